#include "fricon/driver/option_table.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace fricon::driver {

const Option* OptionTable::find(std::string_view key) const {
  for (const Option& o : options)
    if (o.key == key) return &o;
  return nullptr;
}

std::string OptionTable::doc_id() const {
  if (name.empty()) return "top";
  if (expected.find("[[") != std::string::npos) return fmt::format("[[{}]]", name);
  return name;
}

std::vector<std::string_view> OptionTable::keys() const {
  std::vector<std::string_view> out;
  for (const Option& o : options)
    out.push_back(o.key);
  return out;
}

std::optional<std::string> OptionTable::unused_by_choice(const void* section,
                                                         std::string_view key) const {
  if (selector.empty() || key == selector) return std::nullopt;
  if (std::find(selected.begin(), selected.end(), key) == selected.end()) return std::nullopt;
  const std::string choice = std::get<std::string>(find(selector)->get(section));
  for (const auto& [spelling, keys] : selector_choices)
    if (spelling == choice && std::find(keys.begin(), keys.end(), key) != keys.end())
      return std::nullopt;
  return unused_by_selector(section, key);
}

std::optional<std::string> OptionTable::why_unused(const void* section,
                                                   const Option& option) const {
  if (auto why = unused_by_choice(section, option.key)) return why;
  if (option.unused) return option.unused(section);
  return std::nullopt;
}

std::string join_key(std::string_view path, std::string_view key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

std::string Option::value_phrase() const {
  switch (type) {
    case OptionType::Real:
    case OptionType::Integer:
      return range.phrase();
    case OptionType::Boolean:
      return "true or false";
    case OptionType::Choice:
      return choice_phrase;
    case OptionType::Text:
      return std::string(phrase);
    case OptionType::Table:
      return "a table";
    case OptionType::TableArray:
      return "an array of tables";
    case OptionType::TableOrArray:
      return "a table or an array of tables";
  }
  return {};
}

namespace {

std::string number_text(double v, bool integer) {
  if (integer) return fmt::format("{}", static_cast<long long>(v));
  const double a = std::abs(v);
  if (v != 0.0 && (a >= 1e4 || a < 1e-3)) {
    std::string s = fmt::format("{:.6e}", v);  // 2.119000e+11 -> 2.119e11
    const auto e = s.find('e');
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    while (mantissa.back() == '0')
      mantissa.pop_back();
    if (mantissa.back() == '.') mantissa += '0';
    const int ex = std::stoi(exponent);
    return fmt::format("{}e{}", mantissa, ex);
  }
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string type_text(const Option& o) {
  const bool integer = o.type == OptionType::Integer;
  const std::string_view noun = integer ? "integers" : "numbers";
  switch (o.type) {
    case OptionType::Real:
    case OptionType::Integer:
      if (o.rows > 0) return fmt::format("{} arrays of {} {}", o.rows, o.count, noun);
      if (o.count == kList) return fmt::format("array of {}", noun);
      if (o.count > 0) return fmt::format("array of {} {}", o.count, noun);
      return integer ? "integer" : "number";
    case OptionType::Boolean:
      return "boolean";
    case OptionType::Choice:
    case OptionType::Text:
      return "string";
    case OptionType::Table:
      return "table";
    case OptionType::TableArray:
      return "array of tables";
    case OptionType::TableOrArray:
      return "table or array of tables";
  }
  return {};
}

std::string default_text(const Option& o, const void* section) {
  if (!o.shown_default.empty()) return std::string(o.shown_default);
  if (o.required || o.is_nested()) return "—";
  const OptionValue v = o.get(section);
  const bool integer = o.type == OptionType::Integer;
  return std::visit(
      [&](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return "—";
        } else if constexpr (std::is_same_v<T, bool>) {
          return x ? "`true`" : "`false`";
        } else if constexpr (std::is_same_v<T, double>) {
          return fmt::format("`{}`", number_text(x, integer));
        } else if constexpr (std::is_same_v<T, std::string>) {
          return fmt::format("`\"{}\"`", x);
        } else {
          std::string s = "`[";
          const std::size_t per_row = o.rows > 0 ? static_cast<std::size_t>(o.count) : x.size();
          for (std::size_t i = 0; i < x.size(); ++i)
            s += fmt::format("{}{}", i == 0 ? "" : (i % per_row == 0 ? "], [" : ", "),
                             number_text(x[i], integer));
          return s + "]`";
        }
      },
      v);
}

/// "with `kind = "brick"`" for a key that only some choices of the selector use; "" otherwise.
std::string selector_text(const OptionTable& table, const Option& o) {
  if (std::find(table.selected.begin(), table.selected.end(), o.key) == table.selected.end())
    return {};
  std::string choices;
  for (const auto& [spelling, keys] : table.selector_choices)
    if (std::find(keys.begin(), keys.end(), o.key) != keys.end())
      choices += fmt::format("{}`\"{}\"`", choices.empty() ? "" : " or ", spelling);
  return fmt::format("with {} = {}", table.selector, choices);
}

std::string valid_text(const OptionTable& table, const Option& o) {
  std::string s;
  const std::string when = o.used_doc.empty() ? selector_text(table, o) : std::string(o.used_doc);
  const auto add = [&s](std::string_view part) {
    if (part.empty()) return;
    s += s.empty() ? "" : "; ";
    s += part;
  };
  if (o.required) {
    add(when.empty() ? "**required**" : fmt::format("**required** {}", when));
  } else {
    add(when.empty() ? "" : fmt::format("only {}", when));
  }
  switch (o.type) {
    case OptionType::Real:
    case OptionType::Integer: {
      Range r = o.range;
      r.unit = {};
      std::string what = o.count == 0 ? r.phrase() : fmt::format("each {}", r.phrase());
      if (o.non_empty) what += ", at least one";
      add(what);
      break;
    }
    case OptionType::Choice: {
      std::string c;
      for (const auto name : o.choices)
        c += fmt::format("{}`\"{}\"`", c.empty() ? "" : ", ", name);
      add(c);
      break;
    }
    case OptionType::Text:
      add(o.phrase);
      break;
    case OptionType::Boolean:
    case OptionType::Table:
    case OptionType::TableArray:
    case OptionType::TableOrArray:
      break;
  }
  add(o.doc);
  return s;
}

}  // namespace

std::string option_markdown(const OptionTable& table) {
  const std::shared_ptr<void> defaults = table.make();
  std::string s =
      "| key | type | unit | default | valid values |\n"
      "|---|---|---|---|---|\n";
  for (const Option& o : table.options) {
    const std::string unit =
        o.is_number() && !o.range.unit.empty() ? std::string(o.range.unit) : std::string("—");
    s += fmt::format("| `{}` | {} | {} | {} | {} |\n", o.key, type_text(o), unit,
                     default_text(o, defaults.get()), valid_text(table, o));
  }
  return s;
}

}  // namespace fricon::driver
