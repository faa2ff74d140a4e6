// io: --set KEY=VALUE, applied to the parsed document before it is read (docs/problem-file.md).
#include <algorithm>
#include <charconv>
#include <functional>
#include <memory>
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

using driver::join_key;

namespace {

/// `origin`: how messages name the override, "--set KEY=VALUE" (Context::override_origin and
/// the override's text).
[[noreturn]] void fail_override(const std::string& origin, std::string_view what) {
  throw InputError(fmt::format("{}: {}", origin, what));
}

bool is_index(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool is_bare_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

/// "traction[1].value" or "traction.1.value" -> {"traction", "1", "value"}.
std::vector<std::string> split_key(const std::string& origin, std::string_view key) {
  std::string dotted;
  for (std::size_t i = 0; i < key.size(); ++i) {
    if (key[i] == '[') {
      const auto close = key.find(']', i);
      if (close == std::string_view::npos || !is_index(key.substr(i + 1, close - i - 1)))
        fail_override(origin, fmt::format("invalid key '{}': write an index as [N] or .N", key));
      dotted += '.';
      dotted += key.substr(i + 1, close - i - 1);
      i = close;
    } else {
      dotted += key[i];
    }
  }
  std::vector<std::string> parts;
  std::string_view rest = dotted;
  while (true) {
    const auto dot = rest.find('.');
    const std::string_view part = rest.substr(0, dot);
    if (part.empty() || !std::all_of(part.begin(), part.end(), is_bare_key_char))
      fail_override(origin, fmt::format("invalid key '{}': expected dotted names such as "
                                        "material.young or traction.1.value",
                                        key));
    parts.emplace_back(part);
    if (dot == std::string_view::npos) break;
    rest = rest.substr(dot + 1);
  }
  return parts;
}

/// A one-key table {v = VALUE}: VALUE in TOML syntax, or a bare word taken as a string.
toml::table parse_override_value(const std::string& origin, std::string_view value) {
  if (value.empty()) fail_override(origin, "missing value after '='");
  try {
    toml::table holder = toml::parse(fmt::format("v = {}", value), std::string_view("--set"));
    if (holder.size() != 1 || holder.get("v") == nullptr)
      fail_override(origin, "expected a single TOML value after '='");
    return holder;
  } catch (const toml::parse_error& e) {
    const bool bare = value.find_first_of("\"'[]{},=# \t\r\n") == std::string_view::npos;
    if (!bare)
      fail_override(origin, fmt::format("invalid TOML value '{}': {}", value, e.description()));
    toml::table holder;
    holder.insert("v", std::string(value));
    return holder;
  }
}

void for_each_node(const toml::node& n, const std::function<void(const toml::node&)>& fn) {
  fn(n);
  if (const auto* t = n.as_table())
    for (const auto& [k, v] : *t)
      for_each_node(v, fn);
  if (const auto* a = n.as_array())
    for (const auto& v : *a)
      for_each_node(v, fn);
}

}  // namespace

void apply_override(Context& ctx, toml::table& root, const std::string& text) {
  const auto origin = std::make_shared<const std::string>(ctx.override_origin + " " + text);
  const auto eq = text.find('=');
  if (eq == std::string::npos) fail_override(*origin, "expected KEY=VALUE");
  const auto path = split_key(*origin, trim(std::string_view(text).substr(0, eq)));
  toml::table holder = parse_override_value(*origin, trim(std::string_view(text).substr(eq + 1)));
  toml::node& value = *holder.get("v");

  const auto prefix = [&](std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i)
      s = join_key(s, path[i]);
    return s;
  };
  const auto index_of = [&](const toml::array& a, std::size_t i) {
    if (!is_index(path[i]))
      fail_override(*origin, fmt::format("'{}' is an array: address its entries as {}.0, {}.1, ...",
                                         prefix(i), prefix(i), prefix(i)));
    // Digits only (is_index); an index too large for size_t is out of range like any other.
    std::size_t idx = 0;
    const auto [end, ec] = std::from_chars(path[i].data(), path[i].data() + path[i].size(), idx);
    if (ec != std::errc{} || idx > a.size())
      fail_override(*origin, fmt::format("index {} out of range: '{}' has {} entries", path[i],
                                         prefix(i), a.size()));
    return idx;  // == size appends a new entry
  };
  const auto unregister = [&](const toml::node& old) {
    for_each_node(old, [&](const toml::node& n) { ctx.origins.erase(&n); });
  };

  std::vector<const toml::node*> created;
  toml::node* cur = &root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (auto* t = cur->as_table()) {
      toml::node* child = t->get(path[i]);
      if (child == nullptr) {
        child = is_index(path[i + 1]) ? &t->insert_or_assign(path[i], toml::array{}).first->second
                                      : &t->insert_or_assign(path[i], toml::table{}).first->second;
        created.push_back(child);
      }
      cur = child;
    } else if (auto* a = cur->as_array()) {
      const std::size_t idx = index_of(*a, i);
      if (idx == a->size()) {
        a->push_back(toml::table{});
        created.push_back(&a->back());
      }
      cur = a->get(idx);
    } else {
      fail_override(*origin, fmt::format("'{}' is {}, not a table", prefix(i), describe(*cur)));
    }
  }

  const std::size_t last = path.size() - 1;
  toml::node* placed = nullptr;
  if (auto* t = cur->as_table()) {
    if (const auto* old = t->get(path[last])) unregister(*old);
    placed = &t->insert_or_assign(path[last], std::move(value)).first->second;
  } else if (auto* a = cur->as_array()) {
    const std::size_t idx = index_of(*a, last);
    if (idx == a->size()) {
      a->push_back(std::move(value));
    } else {
      unregister(*a->get(idx));
      a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(idx), std::move(value));
    }
    placed = a->get(idx);
  } else {
    fail_override(*origin, fmt::format("'{}' is {}, not a table", prefix(last), describe(*cur)));
  }
  for (const auto* n : created)
    ctx.origins[n] = origin;
  for_each_node(*placed, [&](const toml::node& n) { ctx.origins[&n] = origin; });

  // A selector (friction law, material model) changed from the command line makes the file's
  // parameters of the other choices meaningless: drop them, so that e.g.
  // --set contact.friction.law=constant --set contact.friction.value=0.2 works on a file
  // written for the paper's law. Parameters given by overrides are kept (and then rejected).
  const auto* choice = placed->as_string();
  auto* table = cur->as_table();
  if (choice == nullptr || table == nullptr) return;
  for (const driver::OptionTable* t : driver::all_option_tables()) {
    if (t->selector.empty() || prefix(path.size()) != join_key(t->name, t->selector)) continue;
    for (const auto& [name, used] : t->selector_choices) {
      if (name == choice->get()) continue;
      for (const auto param : used) {
        const toml::node* old = table->get(param);
        if (old != nullptr && !ctx.origins.contains(old)) table->erase(param);
      }
    }
  }
}

}  // namespace fricon::io::detail
