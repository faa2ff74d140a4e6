# ASan + UBSan for the whole build when FRICON_SANITIZE=ON (the `make test` sanitizer pass).
if(FRICON_SANITIZE)
  set(_fricon_san -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_compile_options(${_fricon_san})
  add_link_options(${_fricon_san})
endif()
