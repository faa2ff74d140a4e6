# Warning flags for fricon's own targets (not for third-party headers, which are SYSTEM includes).
add_library(fricon_warnings INTERFACE)
target_compile_options(fricon_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wno-unknown-pragmas)
# In a unity build every source file is #included by the batch's generated file, and GCC then
# warns about a class of one file whose member has a type of that file's anonymous namespace
# (-Wsubobject-linkage), which it accepts in a file compiled on its own.
# GCC 12 at -O3 also inlines across a batch's files far enough to report Eigen's packet loads from
# a one-element vector as out of bounds (-Warray-bounds, a known false positive of that version
# with Eigen); the sanitizer build checks the bounds at run time instead.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(fricon_warnings INTERFACE -Wno-subobject-linkage -Wno-array-bounds)
endif()
if(FRICON_WERROR)
  target_compile_options(fricon_warnings INTERFACE -Werror)
endif()
