# Warning flags for fricon's own targets (not for third-party headers, which are SYSTEM includes).
add_library(fricon_warnings INTERFACE)
target_compile_options(fricon_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wno-unknown-pragmas)
if(FRICON_WERROR)
  target_compile_options(fricon_warnings INTERFACE -Werror)
endif()
