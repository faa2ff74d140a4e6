# Warning flags for fricon's own targets (not for third-party headers, which are SYSTEM includes).
add_library(fricon_warnings INTERFACE)
target_compile_options(fricon_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wno-unknown-pragmas)
# In a unity build every source file is #included by the batch's generated file, and GCC then
# warns about a class of one file whose member has a type of that file's anonymous namespace
# (-Wsubobject-linkage), which it accepts in a file compiled on its own.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(fricon_warnings INTERFACE -Wno-subobject-linkage)
endif()
if(FRICON_WERROR)
  target_compile_options(fricon_warnings INTERFACE -Werror)
endif()
