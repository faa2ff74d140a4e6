#include "fricon/core/range.hpp"

#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"

namespace fricon {

namespace {

std::string bound(double v, bool integer) {
  return integer ? fmt::format("{}", static_cast<long long>(v)) : fmt::format("{}", v);
}

}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (integer && v != std::floor(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::phrase() const {
  const std::string_view noun = integer ? "integer" : "number";
  const std::string_view article = integer ? "an" : "a";
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string s;
  if (has_lo && has_hi) {
    s = fmt::format("{} {} in {}{}, {}{}", article, noun, lo_open ? '(' : '[', bound(lo, integer),
                    bound(hi, integer), hi_open ? ')' : ']');
  } else if (has_lo && lo == 0.0 && lo_open && !integer) {
    s = "a positive number";
  } else if (has_lo) {
    s = fmt::format("{} {} {} {}", article, noun, lo_open ? ">" : ">=", bound(lo, integer));
  } else if (has_hi) {
    s = fmt::format("{} {} {} {}", article, noun, hi_open ? "<" : "<=", bound(hi, integer));
  } else {
    s = fmt::format("{} {}", article, noun);
  }
  if (!unit.empty()) s += fmt::format(" [{}]", unit);
  return s;
}

void require(std::string_view context, double value, const Range& range) {
  if (range.contains(value)) return;
  const std::string got = range.integer && std::isfinite(value)
                              ? fmt::format("{}", static_cast<long long>(value))
                              : format_real(value);
  throw InputError(fmt::format("{}: expected {}, got {}{}", context, range.phrase(), got,
                               std::isfinite(value) ? "" : " (numbers must be finite)"));
}

}  // namespace fricon
