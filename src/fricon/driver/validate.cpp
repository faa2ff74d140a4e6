// driver: validate(Problem), the one place where the values of a problem are checked.
//
// It walks the option tables (driver/problem_options.cpp) in the order of the file, so that the
// first bad value is named: every value against its range (core/range.hpp, the phrase the TOML
// reader uses for the same key's type errors), a choice against its enum, a key that the
// section's choices do not use but that was given, then each table's checks between keys. Every
// message reads "WHERE: KEY: expected PHRASE, got VALUE", WHERE = problem.where(KEY).
#include <algorithm>
#include <string>
#include <string_view>
#include <variant>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/driver/problem_options.hpp"

namespace fricon::driver {

namespace {

[[noreturn]] void fail_expected(const Problem& p, const std::string& key, std::string_view expected,
                                std::string_view got) {
  p.fail(key, fmt::format("expected {}, got {}", expected, got));
}

/// The key of value i of a number option: key[i], or key[row][column] for a matrix.
std::string element_key(const std::string& key, const Option& o, std::size_t i) {
  if (o.rows > 0) {
    const auto n = static_cast<std::size_t>(o.count);
    return fmt::format("{}[{}][{}]", key, i / n, i % n);
  }
  return fmt::format("{}[{}]", key, i);
}

void check_numbers(const Problem& p, const std::string& key, const Option& o,
                   const OptionValue& v) {
  if (const auto* x = std::get_if<double>(&v)) {
    require(fmt::format("{}: {}", p.where(key), key), *x, o.range);
    return;
  }
  const auto& xs = std::get<std::vector<double>>(v);
  if (o.non_empty && xs.empty())
    fail_expected(p, key, "a non-empty array of numbers", "an empty array");
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const std::string k = element_key(key, o, i);
    require(fmt::format("{}: {}", p.where(k), k), xs[i], o.range);
  }
}

void check_value(const Problem& p, const std::string& key, const Option& o, const OptionValue& v,
                 const void* section) {
  switch (o.type) {
    case OptionType::Real:
    case OptionType::Integer:
      check_numbers(p, key, o, v);
      break;
    case OptionType::Choice: {
      const auto& name = std::get<std::string>(v);
      if (std::find(o.choices.begin(), o.choices.end(), name) == o.choices.end())
        fail_expected(p, key, o.choice_phrase,
                      fmt::format("{} (a value outside the enum)", o.raw(section)));
      break;
    }
    case OptionType::Text:
      if (!o.may_be_empty && std::get<std::string>(v).empty())
        fail_expected(p, key, o.phrase, "\"\"");
      break;
    case OptionType::Boolean:
    case OptionType::Table:
    case OptionType::TableArray:
    case OptionType::TableOrArray:
      break;
  }
}

void check_section(const Problem& p, const OptionTable& table, const std::string& path,
                   const void* section);

void check_nested(const Problem& p, const std::string& key, const Option& o, const void* section) {
  const auto entries = [&](const OptionTable& t) {
    for (std::size_t i = 0; i < o.size(section); ++i)
      check_section(p, t, fmt::format("{}[{}]", key, i), o.at(section, i));
  };
  switch (o.type) {
    case OptionType::Table:
      if (const void* child = o.child(section)) check_section(p, o.table(), key, child);
      break;
    case OptionType::TableArray:
      entries(o.table());
      break;
    case OptionType::TableOrArray:
      if (o.is_array(section)) {
        entries(o.array_table());
      } else if (const void* child = o.child(section)) {
        // One entry: "contact", or "contact[0]" when the file gave it as [[contact]] (its keys
        // are recorded so, and messages name them as the user wrote them).
        check_section(p, o.table(), p.given_as_array(key) ? key + "[0]" : key, child);
      }
      break;
    default:
      break;
  }
}

void check_section(const Problem& p, const OptionTable& table, const std::string& path,
                   const void* section) {
  for (const Option& o : table.options) {
    const std::string key = join_key(path, o.key);
    if (o.is_nested()) {
      check_nested(p, key, o, section);
      continue;
    }
    const OptionValue v = o.get(section);
    const bool absent = std::holds_alternative<std::monostate>(v);
    const auto unused = table.why_unused(section, o);
    if (unused) {
      // A value that the choices ignore is an error only where its absence can be told.
      if (o.optional && !absent) p.fail(key, *unused);
      continue;
    }
    if (absent) {
      if (o.required)
        fail_expected(p, key,
                      o.required_why.empty()
                          ? o.value_phrase()
                          : fmt::format("{} ({})", o.phrase.empty() ? o.value_phrase() : o.phrase,
                                        o.required_why),
                      "none");
      continue;
    }
    check_value(p, key, o, v, section);
  }
  if (table.check) table.check(p, path, section);
}

}  // namespace

void validate(const Problem& p) {
  check_section(p, problem_table(), "", &p);
}

}  // namespace fricon::driver
