#pragma once
// core: the range of a numeric setting, and require(), the one range check of fricon.
//
// A Range knows whether it holds a value and how to say what it holds: "a positive number [Pa]",
// "an integer in [1, 20]". The problem file's option tables (driver/problem_options.cpp), their
// validation and the option structs of the solver stages (outer::OuterOptions, ...) all check
// their values through require(), so that a range is written once and described the same way in
// every message:
//   WHERE: KEY: expected a positive number [Pa], got -1.0

#include <limits>
#include <string>
#include <string_view>

namespace fricon {

struct Range {
  bool integer = false;  ///< integers only (the phrase says "an integer")
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = true;  ///< lo itself is excluded
  bool hi_open = true;
  std::string_view unit;  ///< shown in brackets after the phrase ("Pa", "m", "1/m"); may be empty

  /// Whether v lies in the range; a real must also be finite.
  bool contains(double v) const;
  /// "a number", "a positive number", "a number >= 0", "a number in (0, 1)", "an integer >= 1",
  /// "an integer in [1, 20]", each followed by " [unit]" when there is a unit.
  std::string phrase() const;
  /// The same range in another unit.
  constexpr Range in(std::string_view u) const {
    Range r = *this;
    r.unit = u;
    return r;
  }
};

/// Any finite real.
constexpr Range any_number(std::string_view unit = {}) {
  return Range{false,
               -std::numeric_limits<double>::infinity(),
               std::numeric_limits<double>::infinity(),
               true,
               true,
               unit};
}
/// A real > 0.
constexpr Range positive(std::string_view unit = {}) {
  return Range{false, 0.0, std::numeric_limits<double>::infinity(), true, true, unit};
}
/// A real >= 0.
constexpr Range non_negative(std::string_view unit = {}) {
  return Range{false, 0.0, std::numeric_limits<double>::infinity(), false, true, unit};
}
/// A real in the open interval (lo, hi).
constexpr Range open_interval(double lo, double hi, std::string_view unit = {}) {
  return Range{false, lo, hi, true, true, unit};
}
/// An integer >= lo.
constexpr Range integer_at_least(double lo) {
  return Range{true, lo, std::numeric_limits<double>::infinity(), false, true, {}};
}
/// An integer in [lo, hi].
constexpr Range integer_in(double lo, double hi) {
  return Range{true, lo, hi, false, false, {}};
}

/// Throws InputError "CONTEXT: expected PHRASE, got VALUE" (with " (numbers must be finite)"
/// for nan and inf) unless `range` contains `value`. CONTEXT names the value: "WHERE: KEY" for a
/// problem's key, "OuterOptions::tol" for a field set by code.
void require(std::string_view context, double value, const Range& range);

}  // namespace fricon
