#pragma once
// core: the spelling of every choice fricon offers (an enum class per choice), written once.
//
// Each enum that a user can name (in a problem file, on the command line, in a report) declares
// its spellings in one specialisation of EnumNames, next to the enum:
//
//   enum class Acceleration { None, Anderson };
//   template <>
//   struct EnumNames<outer::Acceleration> {
//     static constexpr std::string_view what = "acceleration";
//     static constexpr std::array<std::pair<outer::Acceleration, std::string_view>, 2> table{{
//         {outer::Acceleration::None, "none"}, {outer::Acceleration::Anderson, "anderson"}}};
//   };
//
// and every reader, writer and message goes through the functions below, so that the TOML
// reader, --set, the JSON report, the logs and the Python module spell a choice the same way.

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon {

/// Specialised once per user-visible enum (see the file comment); the primary template is
/// undefined so that an enum without spellings does not compile where one is needed.
template <typename E>
struct EnumNames;

/// The spelling of `value` (e.g. "anderson"); "?" for a value outside the table (a cast).
template <typename E>
constexpr std::string_view enum_name(E value) {
  for (const auto& [v, name] : EnumNames<E>::table)
    if (v == value) return name;
  return "?";
}

/// The value spelt `name`, or nothing.
template <typename E>
constexpr std::optional<E> enum_from_name(std::string_view name) {
  for (const auto& [v, n] : EnumNames<E>::table)
    if (n == name) return v;
  return std::nullopt;
}

/// The accepted spellings as a phrase for messages: one of "a", "b", "c".
template <typename E>
std::string enum_choices() {
  std::string s = "one of";
  bool first = true;
  for (const auto& entry : EnumNames<E>::table) {
    s += fmt::format("{} \"{}\"", first ? "" : ",", entry.second);
    first = false;
  }
  return s;
}

/// The value spelt `name`; throws InputError "<what> = "<name>" is not one of ..." otherwise.
template <typename E>
E parse_enum(std::string_view name) {
  if (const auto v = enum_from_name<E>(name)) return *v;
  throw InputError(
      fmt::format("{} = \"{}\" is not {}", EnumNames<E>::what, name, enum_choices<E>()));
}

/// Whether `value` is one of the table's values (false for an out-of-range cast).
template <typename E>
constexpr bool enum_is_valid(E value) {
  return std::any_of(EnumNames<E>::table.begin(), EnumNames<E>::table.end(),
                     [value](const auto& entry) { return entry.first == value; });
}

}  // namespace fricon
