// io: driver::Problem -> JSON (the effective problem, every default filled in) and TOML (a
// problem file that reads back to the same Problem), walking the option tables
// (driver/problem_options.cpp): a key that the section's choices do not use, and an optional
// key that is absent, are left out.
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <variant>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/problem_options.hpp"
#include "fricon/io/problem_file.hpp"

namespace fricon::io {

namespace {

using driver::Option;
using driver::OptionTable;
using driver::OptionType;
using driver::OptionValue;

nlohmann::json section_json(const OptionTable& table, const void* section);

nlohmann::json value_json(const Option& o, const OptionValue& v) {
  using nlohmann::json;
  const bool integer = o.type == OptionType::Integer;
  const auto number = [integer](double x) {
    return integer ? json(static_cast<std::int64_t>(x)) : json(x);
  };
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  if (const auto* x = std::get_if<double>(&v)) return number(*x);
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  const auto& xs = std::get<std::vector<double>>(v);
  json out = json::array();
  if (o.rows > 0) {
    for (int r = 0; r < o.rows; ++r) {
      json row = json::array();
      for (int c = 0; c < o.count; ++c)
        row.push_back(number(xs[static_cast<std::size_t>(r * o.count + c)]));
      out.push_back(row);
    }
    return out;
  }
  for (const double x : xs)
    out.push_back(number(x));
  return out;
}

nlohmann::json entries_json(const Option& o, const OptionTable& table, const void* section) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < o.size(section); ++i)
    out.push_back(section_json(table, o.at(section, i)));
  return out;
}

nlohmann::json section_json(const OptionTable& table, const void* section) {
  nlohmann::json j = nlohmann::json::object();
  for (const Option& o : table.options) {
    if (table.why_unused(section, o)) continue;
    switch (o.type) {
      case OptionType::Table:
        if (const void* child = o.child(section))
          j[std::string(o.key)] = section_json(o.table(), child);
        break;
      case OptionType::TableArray:
        j[std::string(o.key)] = entries_json(o, o.table(), section);
        break;
      case OptionType::TableOrArray:
        if (o.is_array(section)) {
          j[std::string(o.key)] = entries_json(o, o.array_table(), section);
        } else if (const void* child = o.child(section)) {
          j[std::string(o.key)] = section_json(o.table(), child);
        }
        break;
      default: {
        const OptionValue v = o.get(section);
        if (!std::holds_alternative<std::monostate>(v)) j[std::string(o.key)] = value_json(o, v);
      }
    }
  }
  return j;
}

// JSON (to_json's output) -> TOML: each JSON value as the TOML node it was read from.
toml::array toml_array(const nlohmann::json& j);
toml::table toml_table(const nlohmann::json& j);

template <typename Container>
void put(Container& c, const std::string& key, const nlohmann::json& v) {
  const auto add = [&](auto&& x) {
    if constexpr (std::is_same_v<Container, toml::table>) {
      c.insert(key, std::forward<decltype(x)>(x));
    } else {
      c.push_back(std::forward<decltype(x)>(x));
    }
  };
  if (v.is_object()) {
    add(toml_table(v));
  } else if (v.is_array()) {
    add(toml_array(v));
  } else if (v.is_boolean()) {
    add(v.get<bool>());
  } else if (v.is_number_integer()) {
    add(v.get<std::int64_t>());
  } else if (v.is_number()) {
    add(v.get<double>());
  } else if (v.is_string()) {
    add(v.get<std::string>());
  }
}

toml::array toml_array(const nlohmann::json& j) {
  toml::array a;
  for (const auto& v : j)
    put(a, "", v);
  return a;
}

toml::table toml_table(const nlohmann::json& j) {
  toml::table t;
  for (const auto& [k, v] : j.items())
    put(t, k, v);
  return t;
}

}  // namespace

nlohmann::json to_json(const driver::Problem& p) {
  nlohmann::json j = section_json(driver::problem_table(), &p);
  // The name a friction law given by code has in reports (not a key of the file).
  for (std::size_t i = 0; i < p.contact.size(); ++i) {
    const auto& fr = p.contact[i].friction;
    if (fr.law != contact::FrictionLawKind::Function) continue;
    auto& entry = p.contact.size() == 1 ? j["contact"] : j["contact"][i];
    entry["friction"]["name"] = fr.function_name;
  }
  return j;
}

std::string to_toml(const driver::Problem& problem) {
  if (problem.mesh.kind == driver::MeshKind::Arrays)
    throw InputError(
        fmt::format("{}: mesh.kind = \"arrays\": a mesh given by code cannot be "
                    "written to a problem file (write it as a Gmsh file)",
                    problem.where("mesh.kind")));
  if (std::any_of(problem.contact.begin(), problem.contact.end(), [](const auto& c) {
        return c.friction.law == contact::FrictionLawKind::Function;
      }))
    throw InputError(
        fmt::format("{}: contact.friction.law = \"function\": a friction law given "
                    "by code cannot be written to a problem file (write it as law = "
                    "\"expression\" or \"table\")",
                    problem.where("contact.friction.law")));
  std::ostringstream out;
  out << toml::toml_formatter(toml_table(to_json(problem))) << '\n';
  return out.str();
}

}  // namespace fricon::io
