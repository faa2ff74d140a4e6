// io: the problem file's document -> driver::Problem, walking the option tables
// (driver/problem_options.cpp): for each section the allowed keys, then the selector (the key
// whose choice decides which other keys are used), then each key's type and shape; the required
// keys, and the keys that the section's choices do not use, are errors. The values themselves
// are left to driver::validate. Two sections hold what a file alone cannot: [mesh] kind "arrays"
// and [contact.friction] law "function" take objects given by code (CodeObjects), and a friction
// expression is parsed here, so that its syntax errors point into the file.
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/problem_options.hpp"
#include "fricon/io/problem_file_stages.hpp"
#include "fricon/io/toml_access.hpp"

namespace fricon::io::detail {

namespace {

using driver::Option;
using driver::OptionTable;
using driver::OptionType;
using driver::OptionValue;

/// How many characters open the string value `n` in the file: 3 for a one-line """...""" or
/// '''...''' string, else 1 (a quote). Escapes in a basic string are not accounted for.
int opening_quote_length(const toml::node& n, const std::string& value) {
  const auto& src = n.source();
  if (src.begin.line == 0 || src.begin.line != src.end.line) return 1;
  const auto raw = static_cast<std::size_t>(src.end.column - src.begin.column);
  return raw == value.size() + 6 ? 3 : 1;
}

/// contact.friction.expression parsed once: a syntax error or an unknown name is reported at its
/// line and column in the file (the string's position plus muparser's offset in it).
void check_expression(const Context& ctx, const Field& f, const std::string& expression) {
  const auto problem = contact::check_friction_expression(expression);
  if (!problem) return;
  std::string where = ctx.where(f.node, nullptr);
  const auto& src = f.node->source();
  const auto offset = std::max<std::ptrdiff_t>(problem->position, 0);
  if (ctx.origins.find(f.node) == ctx.origins.end() && src.begin.line > 0) {
    const auto column = static_cast<std::ptrdiff_t>(src.begin.column) +
                        opening_quote_length(*f.node, expression) + offset;
    where = fmt::format("{}:{}:{}", ctx.file, src.begin.line, column);
  }
  throw InputError(fmt::format("{}: {}: {} at column {} of \"{}\": {}", where, f.path,
                               problem->what, offset + 1, expression, problem->detail));
}

void read_section(const Context& ctx, const Field& f, const OptionTable& table, void* section);

/// A number, or an array, a list or a matrix of numbers.
OptionValue read_numbers(const Context& ctx, const Field& f, const Option& o) {
  const bool integer = o.type == OptionType::Integer;
  const std::string one_phrase = o.range.phrase();
  const auto one = [&](const Field& e) {
    return integer ? get_integer(ctx, e, one_phrase, o.integer_max) : get_real(ctx, e, one_phrase);
  };
  if (o.count == 0) return one(f);
  const std::string_view noun = integer ? "integers" : "numbers";
  const std::string unit = o.range.unit.empty() ? "" : fmt::format(" [{}]", o.range.unit);
  std::vector<double> out;
  const auto row_of = [&](const Field& r) {
    const std::string expected = fmt::format("an array of {} {}", o.count, noun);
    const auto& a = get_array(ctx, r, expected);
    if (a.size() != static_cast<std::size_t>(o.count))
      fail(ctx, r, fmt::format("expected {}, got {} element(s)", expected, a.size()));
    for (std::size_t i = 0; i < a.size(); ++i)
      out.push_back(one(element(ctx, r, a, i)));
  };
  if (o.rows > 0) {
    const auto& rows = get_array(
        ctx, f, fmt::format("an array of {} rows of {} {}{}", o.rows, o.count, noun, unit));
    if (rows.size() != static_cast<std::size_t>(o.rows))
      fail(ctx, f,
           fmt::format("expected {} rows of {} {}{}, got {} row(s)", o.rows, o.count, noun, unit,
                       rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
      row_of(element(ctx, f, rows, i));
    return out;
  }
  if (o.count > 0) {
    row_of(f);
    return out;
  }
  const auto& a = get_array(ctx, f, fmt::format("a non-empty array of {}", noun));
  // A list that may be written as rows: [[1, 2, 3], [4, 5, 6]], read flat.
  if (o.list_rows_of > 0 && !a.empty() && a[0].as_array() != nullptr) {
    const std::string expected = fmt::format("an array of {} {}", o.list_rows_of, noun);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Field row = element(ctx, f, a, i);
      const auto& r = get_array(ctx, row, expected);
      if (r.size() != static_cast<std::size_t>(o.list_rows_of))
        fail(ctx, row, fmt::format("expected {}, got {} element(s)", expected, r.size()));
      for (std::size_t j = 0; j < r.size(); ++j)
        out.push_back(one(element(ctx, row, r, j)));
    }
    return out;
  }
  for (std::size_t i = 0; i < a.size(); ++i)
    out.push_back(one(element(ctx, f, a, i)));
  return out;
}

OptionValue read_text(const Context& ctx, const Field& f, const Option& o) {
  std::string s = get_string(ctx, f, o.phrase);
  if (o.accepts && !o.accepts(s)) fail_expected(ctx, f, o.phrase);
  if (o.is_path) s = beside_problem_file(ctx, s);
  return s;
}

OptionValue read_choice(const Context& ctx, const Field& f, const Option& o) {
  const auto* s = f.node->as_string();
  if (s == nullptr || std::find(o.choices.begin(), o.choices.end(), s->get()) == o.choices.end())
    fail_expected(ctx, f, o.choice_phrase);
  return s->get();
}

/// [[name]] (or the array form of [material]): an array of tables, each read by `table`.
void read_entries(const Context& ctx, const Field& f, const Option& o, const OptionTable& table,
                  void* section) {
  const auto& a = get_array(ctx, f, fmt::format("an array of tables [[{}]]", o.key));
  if (o.type == OptionType::TableOrArray && a.empty())
    fail_expected(ctx, f, fmt::format("at least one [[{}]] table", o.key));
  for (std::size_t i = 0; i < a.size(); ++i)
    read_section(ctx, element(ctx, f, a, i), table, o.append(section));
}

void read_option(const Context& ctx, const Field& f, const Option& o, void* section) {
  switch (o.type) {
    case OptionType::Real:
    case OptionType::Integer:
      o.set(section, read_numbers(ctx, f, o));
      return;
    case OptionType::Boolean:
      o.set(section, get_bool(ctx, f));
      return;
    case OptionType::Choice:
      o.set(section, read_choice(ctx, f, o));
      return;
    case OptionType::Text:
      o.set(section, read_text(ctx, f, o));
      return;
    case OptionType::Table:
      read_section(ctx, f, o.table(), o.open(section));
      return;
    case OptionType::TableArray:
      read_entries(ctx, f, o, o.table(), section);
      return;
    case OptionType::TableOrArray:
      if (f.node->is_array()) {
        read_entries(ctx, f, o, o.array_table(), section);
      } else {
        read_section(ctx, f, o.table(), o.open(section));
      }
      return;
  }
}

// What a file alone cannot hold, and what is checked where the file can point at it.

void finish_mesh(const Context& ctx, const TableReader& t, driver::MeshOptions& m) {
  if (m.kind != driver::MeshKind::Arrays) return;
  if (ctx.code == nullptr || !ctx.code->mesh)
    fail(ctx, *t.find("kind"),
         "\"arrays\" is a mesh given by code (fricon.Mesh in Python); a problem file uses "
         "kind = \"brick\" or \"gmsh\"");
  m.given = ctx.code->mesh;
}

void finish_friction(const Context& ctx, const TableReader& t, driver::FrictionOptions& fr) {
  if (fr.law == contact::FrictionLawKind::Expression)
    check_expression(ctx, *t.find("expression"), fr.expression);
  if (fr.law != contact::FrictionLawKind::Function) return;
  if (ctx.code == nullptr || !ctx.code->friction) {
    const auto law = t.find("law");
    fail(ctx, law ? *law : t.self(),
         "law \"function\" is a function given from code (fricon.FrictionLaw.function in "
         "Python); in a problem file write law = \"expression\"");
  }
  fr.function = ctx.code->friction;
  fr.function_name = ctx.code->friction_name;
}

void read_section(const Context& ctx, const Field& f, const OptionTable& table, void* section) {
  const TableReader t(ctx, f, table.expected, table.keys());
  // @sect: the selector first: it decides which other keys are used.
  if (!table.selector.empty())
    if (auto k = t.find(table.selector)) read_option(ctx, *k, *table.find(table.selector), section);
  // @sect: every other key: unused by the choice, missing, or read.
  for (const Option& o : table.options) {
    if (o.key == table.selector) continue;
    const auto k = t.find(o.key);
    const auto unused = table.unused_by_choice(section, o.key);
    if (k && unused) fail(ctx, *k, *unused);
    if (!k) {
      if (o.required && !unused) (void)t.require(o.key, o.required_why);
      continue;
    }
    read_option(ctx, *k, o, section);
  }
  // @sect: keys used only under a condition on other keys, now that all are read.
  for (const Option& o : table.options)
    if (o.unused)
      if (const auto k = t.find(o.key))
        if (auto why = o.unused(section)) fail(ctx, *k, *why);
  if (&table == &driver::mesh_table())
    finish_mesh(ctx, t, *static_cast<driver::MeshOptions*>(section));
  if (&table == &driver::friction_table())
    finish_friction(ctx, t, *static_cast<driver::FrictionOptions*>(section));
}

}  // namespace

void read_document(Context& ctx, const toml::table& root, driver::Problem& p) {
  p.source = ctx.file;
  ctx.positions = &p.positions;
  read_section(ctx, Field{&root, nullptr, ""}, driver::problem_table(), &p);
  ctx.positions = nullptr;
}

}  // namespace fricon::io::detail
