#pragma once
// core: the spelling of every choice fricon offers (an enum class per choice), written once.
//
// Each enum that a user can name (in a problem file, on the command line, in a report) declares
// its spellings in one specialisation of EnumNames, next to the enum:
//
//   enum class Acceleration { None, Anderson };   // in namespace fricon::outer
//   FRICON_ENUM_NAMES(fricon::outer::Acceleration, "solver.acceleration",
//                     {fricon::outer::Acceleration::None, "none"},
//                     {fricon::outer::Acceleration::Anderson, "anderson"});
//
// at namespace scope, after the enum (it specialises fricon::EnumNames<E>, below),
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

/// The table of spellings of an enum with N values.
template <typename E, std::size_t N>
using EnumTable = std::array<std::pair<E, std::string_view>, N>;

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

/// Declares the spellings of enum E (a fully qualified name): `what` names the choice in messages
/// (its key path, e.g. "solver.acceleration"), then one {E::Value, "spelling"} per value.
#define FRICON_ENUM_NAMES(E, WHAT, ...)                                                         \
  template <>                                                                                   \
  struct fricon::EnumNames<E> {                                                                 \
    static constexpr std::string_view what = WHAT;                                              \
    static constexpr auto table = std::to_array<std::pair<E, std::string_view>>({__VA_ARGS__}); \
  }
