#pragma once
// io: how the arrays of a .vtu file are stored ([output] vtu_encoding). A choice of its own
// header so that the problem's options (driver/problem.hpp) can name it without the writer.

#include "fricon/core/enum_names.hpp"

namespace fricon::io {

/// The encoding of a .vtu file's arrays.
enum class VtuEncoding {
  /// VTK's appended raw data: each array's bytes (little endian) after the XML, behind a 64-bit
  /// byte count. Exact, less than half the size of the text, and read by ParaView and meshio
  /// without parsing text: the default.
  Binary,
  /// Every value as text, doubles with round-trip precision: readable, and several times larger.
  Ascii,
};

}  // namespace fricon::io

FRICON_ENUM_NAMES(fricon::io::VtuEncoding, "output.vtu_encoding",
                  {fricon::io::VtuEncoding::Binary, "binary"},
                  {fricon::io::VtuEncoding::Ascii, "ascii"});
