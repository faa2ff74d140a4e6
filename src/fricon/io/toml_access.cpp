#include "fricon/io/toml_access.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/driver/option_table.hpp"

namespace fricon::io::detail {

using driver::join_key;

std::string Context::where(const toml::node* node, const toml::key* key) const {
  if (node != nullptr) {
    const auto it = origins.find(node);
    if (it != origins.end()) return *it->second;
  }
  const toml::source_region* src = nullptr;
  if (key != nullptr && key->source().begin.line > 0) {
    src = &key->source();
  } else if (node != nullptr && node->source().begin.line > 0) {
    src = &node->source();
  }
  if (src == nullptr) return file;
  return fmt::format("{}:{}:{}", file, src->begin.line, src->begin.column);
}

const Field& record(const Context& ctx, const Field& f) {
  if (ctx.positions == nullptr || f.path.empty()) return f;
  if (const auto it = ctx.origins.find(f.node); it != ctx.origins.end()) {
    ctx.positions->set(f.path, it->second);  // shared, not copied per element
  } else {
    ctx.positions->set(f.path, ctx.where(f.node, f.key));
  }
  return f;
}

[[noreturn]] void fail(const Context& ctx, const Field& f, std::string_view what) {
  throw InputError(fmt::format("{}: {}: {}", ctx.where(f.node, f.key), f.path, what));
}

std::string describe(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return fmt::format("\"{}\"", n.as_string()->get());
    case toml::node_type::integer:
      return fmt::format("{}", n.as_integer()->get());
    case toml::node_type::floating_point:
      return format_real(n.as_floating_point()->get());
    case toml::node_type::boolean:
      return n.as_boolean()->get() ? "true" : "false";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      if (n.as_array()->empty()) return "an empty array";
      return fmt::format("an array of {} element(s)", n.as_array()->size());
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

[[noreturn]] void fail_expected(const Context& ctx, const Field& f, std::string_view expected) {
  fail(ctx, f, fmt::format("expected {}, got {}", expected, describe(*f.node)));
}

Field element(const Context& ctx, const Field& f, const toml::array& a, std::size_t i) {
  return record(ctx, Field{a.get(i), nullptr, fmt::format("{}[{}]", f.path, i)});
}

Real get_real(const Context& ctx, const Field& f, std::string_view expected) {
  if (const auto* i = f.node->as_integer()) return static_cast<Real>(i->get());
  if (const auto* d = f.node->as_floating_point()) return d->get();  // nan and inf: validate
  fail_expected(ctx, f, expected);
}

double get_integer(const Context& ctx, const Field& f, std::string_view expected, double max) {
  const auto* i = f.node->as_integer();
  if (i == nullptr) {
    if (f.node->is_floating_point())
      fail(ctx, f,
           fmt::format("expected {}, got {} (a float; write an integer without a decimal point)",
                       expected, describe(*f.node)));
    fail_expected(ctx, f, expected);
  }
  const auto v = static_cast<double>(i->get());
  if (v > max || v < -max - 1.0) fail_expected(ctx, f, expected);
  return v;
}

std::string get_string(const Context& ctx, const Field& f, std::string_view expected) {
  const auto* s = f.node->as_string();
  if (s == nullptr) fail_expected(ctx, f, expected);
  return s->get();
}

bool get_bool(const Context& ctx, const Field& f) {
  const auto* b = f.node->as_boolean();
  if (b == nullptr) fail_expected(ctx, f, "true or false");
  return b->get();
}

const toml::array& get_array(const Context& ctx, const Field& f, std::string_view expected) {
  const auto* a = f.node->as_array();
  if (a == nullptr) fail_expected(ctx, f, expected);
  return *a;
}

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

TableReader::TableReader(const Context& ctx, const Field& self, std::string_view expected,
                         std::vector<std::string_view> allowed)
    : ctx_(ctx), self_(self), allowed_(std::move(allowed)) {
  table_ = self.node->as_table();
  if (table_ == nullptr) fail_expected(ctx, self, expected);
  reject_unknown_keys();
}

std::optional<Field> TableReader::find(std::string_view key) const {
  const auto it = table_->find(key);
  if (it == table_->end()) return std::nullopt;
  return record(ctx_, Field{&it->second, &it->first, join_key(self_.path, key)});
}

Field TableReader::require(std::string_view key, std::string_view why) const {
  auto f = find(key);
  if (!f) {
    const std::string full = join_key(self_.path, key);
    // The root's position (1:1) would point nowhere useful: name just the file there.
    const std::string at = self_.path.empty() ? ctx_.file : ctx_.where(self_.node, self_.key);
    throw InputError(fmt::format("{}: missing required key '{}'{}", at, full,
                                 why.empty() ? "" : fmt::format(" ({})", why)));
  }
  return *f;
}

void TableReader::reject_unknown_keys() const {
  // toml++ keeps keys sorted: report the unknown key that comes first in the file.
  const toml::key* worst = nullptr;
  const toml::node* worst_node = nullptr;
  for (const auto& [k, v] : *table_) {
    if (std::find(allowed_.begin(), allowed_.end(), k.str()) != allowed_.end()) continue;
    const auto pos = [](const toml::key& key) {
      return std::pair(key.source().begin.line, key.source().begin.column);
    };
    if (worst == nullptr || pos(k) < pos(*worst)) {
      worst = &k;
      worst_node = &v;
    }
  }
  if (worst == nullptr) return;
  const std::string name = join_key(self_.path, worst->str());
  std::string hint;
  std::size_t best = SIZE_MAX;
  for (const auto a : allowed_) {
    const std::size_t d = edit_distance(worst->str(), a);
    if (d < best && (d <= 2 || d <= a.size() / 3) && d < std::min(a.size(), worst->str().size())) {
      best = d;
      hint = fmt::format(" (did you mean '{}'?)", join_key(self_.path, a));
    }
  }
  if (hint.empty() && !self_.path.empty() &&
      (worst->str() == "title" || worst->str() == "volume_force"))
    hint = fmt::format(" ('{}' is a top-level key: write it before the first [table] header)",
                       worst->str());
  if (hint.empty()) {
    hint = fmt::format("; {} takes:", self_.path.empty() ? "the top level" : self_.path);
    for (const auto a : allowed_)
      hint += fmt::format(" {}", a);
  }
  throw InputError(
      fmt::format("{}: unknown key '{}'{}", ctx_.where(worst_node, worst), name, hint));
}

std::string beside_problem_file(const Context& ctx, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute()) return file;
  const std::filesystem::path folder = std::filesystem::path(ctx.file).parent_path();
  return (folder / path).lexically_normal().string();
}

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

}  // namespace fricon::io::detail
