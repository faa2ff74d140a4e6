#pragma once
// core: how values are shown in messages, the same in every module.

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace fricon {

/// A real as a problem file would show it: with a decimal point or an exponent (so that it reads
/// as a float), or "nan", "inf", "-inf".
inline std::string format_real(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace fricon
