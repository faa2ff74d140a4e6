#include "fricon/io/problem_file.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::io {

namespace {

using driver::Problem;

// ---------------------------------------------------------------------------------------------
// Where a value came from, and how messages are built.

/// The file name, the nodes that --set put into the document (with the override's text), and
/// where the positions of the keys read are recorded (Problem::positions).
struct Context {
  std::string file;
  std::unordered_map<const toml::node*, std::string> origins;
  std::map<std::string, std::string, std::less<>>* positions = nullptr;
  std::string override_origin = "--set";  ///< how an override's origin is named
  const CodeObjects* code = nullptr;      ///< objects given by code (may be null)

  /// "file:line:col" of a key (or of the node when the key has no position), "--set K=V" for a
  /// node from an override, or just "file" when toml++ knows no position.
  std::string where(const toml::node* node, const toml::key* key) const {
    if (node != nullptr) {
      const auto it = origins.find(node);
      if (it != origins.end()) return override_origin + " " + it->second;
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
};

/// One value of the document with its key path, e.g. "traction[1].value[2]".
struct Field {
  const toml::node* node = nullptr;
  const toml::key* key = nullptr;  ///< null for array elements and the root
  std::string path;
};

/// Records where `f` was given, under its key path, for driver::validate's messages.
const Field& record(const Context& ctx, const Field& f) {
  if (ctx.positions != nullptr && !f.path.empty())
    (*ctx.positions)[f.path] = ctx.where(f.node, f.key);
  return f;
}

[[noreturn]] void fail(const Context& ctx, const Field& f, std::string_view what) {
  throw InputError(fmt::format("{}: {}: {}", ctx.where(f.node, f.key), f.path, what));
}

/// The value of a node as the user would recognise it, for "got ..." in messages.
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

std::string join_key(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

Field element(const Context& ctx, const Field& f, const toml::array& a, std::size_t i) {
  return record(ctx, Field{a.get(i), nullptr, fmt::format("{}[{}]", f.path, i)});
}

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

// ---------------------------------------------------------------------------------------------
// Typed access. `expected` is the phrase of the message "expected <expected>, got <value>"; the
// reader checks only the type (and that an integer fits its C++ type), driver::validate the range,
// and both use the same phrase for a key.

Real get_real(const Context& ctx, const Field& f, std::string_view expected) {
  if (const auto* i = f.node->as_integer()) return static_cast<Real>(i->get());
  if (const auto* d = f.node->as_floating_point()) return d->get();  // nan and inf: validate
  fail_expected(ctx, f, expected);
}

/// An integer that fits in T (the range is validate's: the same phrase serves both).
template <typename T>
T get_int(const Context& ctx, const Field& f, std::string_view expected) {
  const auto* i = f.node->as_integer();
  if (i == nullptr) {
    if (f.node->is_floating_point())
      fail(ctx, f,
           fmt::format("expected {}, got {} (a float; write an integer without a decimal point)",
                       expected, describe(*f.node)));
    fail_expected(ctx, f, expected);
  }
  if (!std::in_range<T>(i->get())) fail_expected(ctx, f, expected);
  return static_cast<T>(i->get());
}

/// A string, possibly empty (validate rejects the empty ones that are not allowed).
std::string get_string(const Context& ctx, const Field& f, std::string_view expected) {
  const auto* s = f.node->as_string();
  if (s == nullptr) fail_expected(ctx, f, expected);
  return s->get();
}

/// A choice spelt as in the enum's table (core/enum_names.hpp).
template <typename E>
E get_enum(const Context& ctx, const Field& f) {
  const auto* s = f.node->as_string();
  if (s != nullptr)
    if (const auto v = enum_from_name<E>(s->get())) return *v;
  fail_expected(ctx, f, enum_choices<E>());
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

/// An array of exactly N numbers.
template <std::size_t N>
std::array<Real, N> get_reals(const Context& ctx, const Field& f, std::string_view expected_elem) {
  const auto& a = get_array(ctx, f, fmt::format("an array of {} numbers", N));
  if (a.size() != N)
    fail(ctx, f, fmt::format("expected an array of {} numbers, got {} element(s)", N, a.size()));
  std::array<Real, N> out{};
  for (std::size_t i = 0; i < N; ++i)
    out[i] = get_real(ctx, element(ctx, f, a, i), expected_elem);
  return out;
}

Vec3 get_vec3(const Context& ctx, const Field& f, std::string_view expected_elem) {
  const auto v = get_reals<3>(ctx, f, expected_elem);
  return Vec3(v[0], v[1], v[2]);
}

/// An array of numbers (validate requires at least one).
std::vector<Real> get_real_list(const Context& ctx, const Field& f,
                                std::string_view expected_elem) {
  const auto& a = get_array(ctx, f, "a non-empty array of numbers");
  std::vector<Real> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    out[i] = get_real(ctx, element(ctx, f, a, i), expected_elem);
  return out;
}

/// A table of the document with the keys it allows; unknown keys are rejected on construction.
/// Every key that find() finds is recorded in Problem::positions.
class TableReader {
 public:
  TableReader(const Context& ctx, const Field& self, std::string_view expected,
              std::vector<std::string_view> allowed)
      : ctx_(ctx), self_(self), allowed_(std::move(allowed)) {
    table_ = self.node->as_table();
    if (table_ == nullptr) fail_expected(ctx, self, expected);
    reject_unknown_keys();
  }

  const Field& self() const { return self_; }

  std::optional<Field> find(std::string_view key) const {
    const auto it = table_->find(key);
    if (it == table_->end()) return std::nullopt;
    return record(ctx_, Field{&it->second, &it->first, join_key(self_.path, key)});
  }

  Field require(std::string_view key, std::string_view why = {}) const {
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

 private:
  void reject_unknown_keys() const {
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
      if (d < best && (d <= 2 || d <= a.size() / 3) &&
          d < std::min(a.size(), worst->str().size())) {
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

  const Context& ctx_;
  Field self_;
  std::vector<std::string_view> allowed_;
  const toml::table* table_ = nullptr;
};

// ---------------------------------------------------------------------------------------------
// The sections. Only types and shapes are checked here; driver::validate checks the values.

/// Every parameter of every choice of E (a selector: friction law, material model), in the order
/// of its spelling table, each once.
template <typename E, typename ParamsOf>
std::vector<std::string_view> all_parameters(ParamsOf params_of) {
  std::vector<std::string_view> out;
  for (const auto& entry : EnumNames<E>::table)
    for (const auto key : params_of(entry.first))
      if (std::find(out.begin(), out.end(), key) == out.end()) out.push_back(key);
  return out;
}

/// The keys of a table that holds a selector: the selector, then every parameter.
std::vector<std::string_view> with_selector(std::string_view selector,
                                            std::vector<std::string_view> params) {
  params.insert(params.begin(), selector);
  return params;
}

/// The first of `params` (in their order) that the table holds but the choice does not `use`.
std::optional<Field> find_unused(const TableReader& t, const std::vector<std::string_view>& params,
                                 std::span<const std::string_view> used) {
  for (const auto key : params) {
    if (std::find(used.begin(), used.end(), key) != used.end()) continue;
    if (auto k = t.find(key)) return k;
  }
  return std::nullopt;
}

/// `file` as the program opens it: a relative path is taken from the problem file's folder.
std::string beside_problem_file(const Context& ctx, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute()) return file;
  const std::filesystem::path folder = std::filesystem::path(ctx.file).parent_path();
  return (folder / path).lexically_normal().string();
}

std::string_view unused_mesh_key_hint(driver::MeshKind kind) {
  switch (kind) {
    case driver::MeshKind::Brick:
      return "not used by kind \"brick\" (set mesh.kind = \"gmsh\" to read a Gmsh file)";
    case driver::MeshKind::Gmsh:
      return "not used by kind \"gmsh\" (the mesh comes from mesh.file)";
    case driver::MeshKind::Arrays:
      return "not used by kind \"arrays\" (the mesh is given by code)";
  }
  return "not used by this mesh kind";
}

void read_mesh(const Context& ctx, const Field& f, driver::MeshOptions& m) {
  static const auto params = all_parameters<driver::MeshKind>(driver::mesh_parameters);
  const TableReader t(ctx, f, "a table [mesh]", with_selector("kind", params));
  if (auto k = t.find("kind")) m.kind = get_enum<driver::MeshKind>(ctx, *k);
  if (auto k = find_unused(t, params, driver::mesh_parameters(m.kind)))
    fail(ctx, *k, unused_mesh_key_hint(m.kind));
  if (auto k = t.find("size")) m.size = get_reals<3>(ctx, *k, "a positive number [m]");
  if (auto k = t.find("cells")) {
    const auto& a = get_array(ctx, *k, "an array of 3 integers");
    if (a.size() != 3)
      fail(ctx, *k, fmt::format("expected an array of 3 integers, got {} element(s)", a.size()));
    for (std::size_t i = 0; i < 3; ++i)
      m.cells[i] = get_int<Index>(ctx, element(ctx, *k, a, i), "an integer >= 1");
  }
  if (m.kind == driver::MeshKind::Gmsh) {
    const Field k = t.require("file", "mesh.kind = \"gmsh\" reads a .msh or .geo file");
    m.file = beside_problem_file(ctx, get_string(ctx, k, "a Gmsh file name (.msh or .geo)"));
  }
  if (m.kind == driver::MeshKind::Arrays) {
    if (ctx.code == nullptr || !ctx.code->mesh)
      fail(ctx, *t.find("kind"),
           "\"arrays\" is a mesh given by code (fricon.Mesh in Python); a problem file uses "
           "kind = \"brick\" or \"gmsh\"");
    m.given = ctx.code->mesh;
  }
  if (auto k = t.find("size_factor")) m.size_factor = get_real(ctx, *k, "a positive number");
  if (auto k = t.find("unit")) m.unit = get_enum<driver::LengthUnit>(ctx, *k);
}

/// What to do instead, for a key of [material] that `model` does not use.
std::string_view material_hint(fe::MaterialModel model) {
  return model == fe::MaterialModel::Isotropic
             ? "set material.model = \"anisotropic\" to give a Hooke matrix"
             : "the Hooke matrix is material.voigt";
}

void read_material(const Context& ctx, const Field& f, driver::MaterialOptions& m,
                   bool in_array = false) {
  static const auto params = all_parameters<fe::MaterialModel>(fe::material_parameters);
  std::vector<std::string_view> keys = with_selector("model", params);
  if (in_array) keys.push_back("region");
  const TableReader t(ctx, f, in_array ? "a table" : "a table [material]", keys);
  if (in_array)
    m.region = get_string(ctx, t.require("region", "each [[material]] fills one region"),
                          "a region name (a physical volume of the mesh)");
  if (auto k = t.find("model")) m.model = get_enum<fe::MaterialModel>(ctx, *k);
  if (auto k = find_unused(t, params, fe::material_parameters(m.model)))
    fail(ctx, *k,
         fmt::format("not used by model \"{}\" ({})", enum_name(m.model), material_hint(m.model)));
  if (m.model == fe::MaterialModel::Isotropic) {
    if (auto k = t.find("young")) m.young = get_real(ctx, *k, "a positive number [Pa]");
    if (auto k = t.find("poisson")) m.poisson = get_real(ctx, *k, "a number in (-1, 0.5)");
    m.voigt.reset();
    return;
  }
  // anisotropic: the 6x6 Voigt matrix replaces young and poisson.
  const Field k = t.require("voigt", "material.model = \"anisotropic\" needs a 6x6 Hooke matrix");
  const auto& rows = get_array(ctx, k, "an array of 6 rows of 6 numbers [Pa]");
  if (rows.size() != 6)
    fail(ctx, k, fmt::format("expected 6 rows of 6 numbers [Pa], got {} row(s)", rows.size()));
  std::array<std::array<Real, 6>, 6> D{};
  for (std::size_t i = 0; i < 6; ++i)
    D[i] = get_reals<6>(ctx, element(ctx, k, rows, i), "a number [Pa]");
  m.voigt = D;
}

driver::DirichletOptions read_dirichlet(const Context& ctx, const Field& f) {
  const TableReader t(ctx, f, "a table", {"boundary", "components", "value"});
  driver::DirichletOptions d;
  d.boundary = get_string(ctx, t.require("boundary"), "a non-empty boundary tag");
  if (auto k = t.find("components")) {
    const std::string s = get_string(ctx, *k, "a string of distinct letters from \"xyz\"");
    d.components = {false, false, false};
    for (const char c : s) {
      const auto pos = std::string_view("xyz").find(c);
      if (pos == std::string_view::npos || d.components[pos])
        fail_expected(ctx, *k, "a string of distinct letters from \"xyz\"");
      d.components[pos] = true;
    }
  }
  if (auto k = t.find("value")) d.value = get_vec3(ctx, *k, "a number [m]");
  return d;
}

driver::TractionOptions read_traction(const Context& ctx, const Field& f) {
  const TableReader t(ctx, f, "a table", {"boundary", "value"});
  driver::TractionOptions tr;
  tr.boundary = get_string(ctx, t.require("boundary"), "a non-empty boundary tag");
  tr.value = get_vec3(ctx, t.require("value"), "a number [Pa]");
  return tr;
}

/// [[name]]: an array of tables, each read by `read_one`.
template <typename T, typename ReadOne>
std::vector<T> read_table_array(const Context& ctx, const Field& f, std::string_view name,
                                ReadOne read_one) {
  const std::string expected = fmt::format("an array of tables [[{}]]", name);
  const auto& a = get_array(ctx, f, expected);
  std::vector<T> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Field e = element(ctx, f, a, i);
    if (!e.node->is_table()) fail_expected(ctx, e, fmt::format("a table (write [[{}]])", name));
    out.push_back(read_one(ctx, e));
  }
  return out;
}

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

/// kinks and quadrature_rtol of the expression (and function) laws.
void read_quadrature_keys(const Context& ctx, const TableReader& t, driver::FrictionOptions& fr) {
  if (auto k = t.find("kinks")) fr.kinks = get_real_list(ctx, *k, "a number >= 0 [m]");
  if (auto k = t.find("quadrature_rtol"))
    fr.quadrature_rtol = get_real(ctx, *k, "a number in (0, 1)");
}

void read_friction(const Context& ctx, const Field& f, driver::FrictionOptions& fr) {
  static const auto params =
      all_parameters<contact::FrictionLawKind>(contact::friction_law_parameters);
  const TableReader t(ctx, f, "a table [contact.friction]", with_selector("law", params));
  if (auto k = t.find("law")) fr.law = get_enum<contact::FrictionLawKind>(ctx, *k);
  const auto used = contact::friction_law_parameters(fr.law);
  if (auto k = find_unused(t, params, used)) {
    std::string takes;
    for (const auto u : used)
      takes += fmt::format("{}{}", takes.empty() ? "" : ", ", u);
    fail(ctx, *k, fmt::format("not used by law \"{}\" (it takes: {})", enum_name(fr.law), takes));
  }
  switch (fr.law) {
    case contact::FrictionLawKind::Paper:
      if (auto k = t.find("param")) fr.param = get_real(ctx, *k, "a positive number [1/m]");
      break;
    case contact::FrictionLawKind::Constant:
      if (auto k = t.find("value")) fr.value = get_real(ctx, *k, "a number >= 0");
      break;
    case contact::FrictionLawKind::Table: {
      const Field kt = t.require("t", "law \"table\" needs slips t [m] and coefficients f");
      const Field kf = t.require("f", "law \"table\" needs slips t [m] and coefficients f");
      fr.t = get_real_list(ctx, kt, "a number >= 0 [m]");
      fr.f = get_real_list(ctx, kf, "a number >= 0");
      break;
    }
    case contact::FrictionLawKind::Expression: {
      const Field k =
          t.require("expression", "law \"expression\" needs a formula in the slip t [m]");
      fr.expression = get_string(ctx, k, "a formula in the slip t [m], e.g. \"0.3 - 100*t\"");
      check_expression(ctx, k, fr.expression);
      read_quadrature_keys(ctx, t, fr);
      break;
    }
    case contact::FrictionLawKind::Function: {
      if (ctx.code == nullptr || !ctx.code->friction) {
        const auto law = t.find("law");
        fail(ctx, law ? *law : f,
             "law \"function\" is a function given from code (fricon.FrictionLaw.function in "
             "Python); in a problem file write law = \"expression\"");
      }
      fr.function = ctx.code->friction;
      fr.function_name = ctx.code->friction_name;
      read_quadrature_keys(ctx, t, fr);
      break;
    }
  }
}

void read_obstacle(const Context& ctx, const Field& f, driver::ObstacleOptions& o) {
  const TableReader t(ctx, f,
                      "a table { kind = \"plane\", point = [x, y, z], normal = [nx, ny, nz] }",
                      {"kind", "point", "normal"});
  if (auto k = t.find("kind")) o.kind = get_enum<driver::ObstacleKind>(ctx, *k);
  o.point = get_vec3(ctx, t.require("point", "a point of the plane [m]"), "a number [m]");
  o.normal = get_vec3(ctx, t.require("normal", "the plane's normal, towards the body"), "a number");
}

void read_contact(const Context& ctx, const Field& f, driver::ContactOptions& c) {
  static const auto params =
      all_parameters<contact::FrictionModel>(contact::friction_model_parameters);
  std::vector<std::string_view> keys = with_selector("model", params);
  keys.insert(keys.end(), {"boundary", "obstacle", "patches", "patch_size", "friction"});
  const TableReader t(ctx, f, "a table [contact]", keys);
  if (auto k = t.find("model")) c.model = get_enum<contact::FrictionModel>(ctx, *k);
  if (auto k = find_unused(t, params, contact::friction_model_parameters(c.model)))
    fail(ctx, *k,
         c.model == contact::FrictionModel::Coulomb
             ? "not used by model \"coulomb\": its slip bound is F times the contact pressure "
               "of each patch (start_slip_bound sets the Tresca problem it starts from)"
             : "only used by model \"coulomb\" (the Tresca problem it starts from)");
  if (auto k = t.find("boundary")) c.boundary = get_string(ctx, *k, "a non-empty boundary tag");
  if (auto k = t.find("slip_bound")) c.slip_bound = get_real(ctx, *k, "a number >= 0 [Pa]");
  if (auto k = t.find("start_slip_bound"))
    c.start_slip_bound = get_real(ctx, *k, "a number >= 0 [Pa]");
  if (auto k = t.find("obstacle")) read_obstacle(ctx, *k, c.obstacle.emplace());
  if (auto k = t.find("patches")) c.patches = get_enum<contact::PatchKind>(ctx, *k);
  if (auto k = t.find("patch_size")) c.patch_size = get_real(ctx, *k, "a positive number [m]");
  if (auto k = t.find("friction")) read_friction(ctx, *k, c.friction);
}

void read_solver(const Context& ctx, const Field& f, driver::SolverOptions& s) {
  const TableReader t(
      ctx, f, "a table [solver]",
      {"outer_tol", "outer_max", "qp_rtol", "qp_max", "warm_start", "dual_operator", "acceleration",
       "anderson_depth", "qp_variant", "qp_expansion", "dual_scaling", "contact_search",
       "contact_search_margin", "backend", "partition", "memory_per_rank"});
  if (auto k = t.find("outer_tol")) s.outer_tol = get_real(ctx, *k, "a positive number");
  if (auto k = t.find("outer_max")) s.outer_max = get_int<int>(ctx, *k, "an integer >= 1");
  if (auto k = t.find("qp_rtol")) s.qp_rtol = get_real(ctx, *k, "a number in (0, 1)");
  if (auto k = t.find("qp_max")) s.qp_max = get_int<int>(ctx, *k, "an integer >= 1");
  if (auto k = t.find("warm_start")) s.warm_start = get_bool(ctx, *k);
  if (auto k = t.find("dual_operator")) s.dual_operator = get_enum<dual::DualOperatorKind>(ctx, *k);
  if (auto k = t.find("acceleration")) s.acceleration = get_enum<outer::Acceleration>(ctx, *k);
  if (auto k = t.find("qp_variant")) s.qp_variant = get_enum<qp::MpgpVariant>(ctx, *k);
  if (auto k = t.find("qp_expansion")) s.qp_expansion = get_enum<qp::MpgpExpansion>(ctx, *k);
  if (auto k = t.find("dual_scaling")) s.dual_scaling = get_enum<contact::DualScaling>(ctx, *k);
  if (auto k = t.find("contact_search"))
    s.contact_search = get_enum<contact::ContactSearch>(ctx, *k);
  if (auto k = t.find("contact_search_margin"))
    s.contact_search_margin = get_real(ctx, *k, "a number >= 0");
  if (auto k = t.find("backend")) s.backend = get_enum<parallel::Backend>(ctx, *k);
  if (auto k = t.find("partition")) s.partition = get_enum<parallel::PartitionKind>(ctx, *k);
  if (auto k = t.find("memory_per_rank"))
    s.memory_per_rank = get_real(ctx, *k, "a positive number [MiB]");
  if (auto k = t.find("anderson_depth"))
    s.anderson_depth = get_int<int>(ctx, *k, "an integer in [1, 20]");
}

void read_output(const Context& ctx, const Field& f, driver::OutputOptions& o) {
  const TableReader t(ctx, f, "a table [output]", {"dir"});
  if (auto k = t.find("dir")) o.dir = get_string(ctx, *k, "a non-empty folder name");
}

/// [material] (one material everywhere) or [[material]] (one per region).
void read_materials(const Context& ctx, const Field& f, Problem& p) {
  if (!f.node->is_array()) {
    read_material(ctx, f, p.material);
    return;
  }
  const auto& a = get_array(ctx, f, "a table [material] or an array of tables [[material]]");
  if (a.empty()) fail_expected(ctx, f, "at least one [[material]] table");
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Field e = element(ctx, f, a, i);
    if (!e.node->is_table()) fail_expected(ctx, e, "a table (write [[material]])");
    read_material(ctx, e, p.materials.emplace_back(), true);
  }
}

/// The document -> p, recording the position of every key read in p.positions.
void convert(Context& ctx, const toml::table& root, Problem& p) {
  p.source = ctx.file;
  ctx.positions = &p.positions;
  const TableReader t(ctx, Field{&root, nullptr, ""}, "a table",
                      {"title", "mesh", "material", "volume_force", "dirichlet", "traction",
                       "contact", "solver", "output"});
  if (auto k = t.find("title")) p.title = get_string(ctx, *k, "a string");
  read_mesh(ctx, t.require("mesh", "the [mesh] table is required"), p.mesh);
  read_materials(
      ctx, t.require("material", "a [material] table (or [[material]] per region) is required"), p);
  if (auto k = t.find("volume_force")) p.volume_force = get_vec3(ctx, *k, "a number [N/m^3]");
  if (auto k = t.find("dirichlet"))
    p.dirichlet = read_table_array<driver::DirichletOptions>(ctx, *k, "dirichlet", read_dirichlet);
  if (auto k = t.find("traction"))
    p.traction = read_table_array<driver::TractionOptions>(ctx, *k, "traction", read_traction);
  if (auto k = t.find("contact")) read_contact(ctx, *k, p.contact.emplace());
  if (auto k = t.find("solver")) read_solver(ctx, *k, p.solver);
  if (auto k = t.find("output")) read_output(ctx, *k, p.output);
  ctx.positions = nullptr;
}

// ---------------------------------------------------------------------------------------------
// Overrides (--set KEY=VALUE).

[[noreturn]] void fail_override(const std::string& text, std::string_view what) {
  throw InputError(fmt::format("--set {}: {}", text, what));
}

bool is_index(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool is_bare_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// "traction[1].value" or "traction.1.value" -> {"traction", "1", "value"}.
std::vector<std::string> split_key(const std::string& text, std::string_view key) {
  std::string dotted;
  for (std::size_t i = 0; i < key.size(); ++i) {
    if (key[i] == '[') {
      const auto close = key.find(']', i);
      if (close == std::string_view::npos || !is_index(key.substr(i + 1, close - i - 1)))
        fail_override(text, fmt::format("invalid key '{}': write an index as [N] or .N", key));
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
      fail_override(text, fmt::format("invalid key '{}': expected dotted names such as "
                                      "material.young or traction.1.value",
                                      key));
    parts.emplace_back(part);
    if (dot == std::string_view::npos) break;
    rest = rest.substr(dot + 1);
  }
  return parts;
}

/// A one-key table {v = VALUE}: VALUE in TOML syntax, or a bare word taken as a string.
toml::table parse_override_value(const std::string& text, std::string_view value) {
  if (value.empty()) fail_override(text, "missing value after '='");
  try {
    toml::table holder = toml::parse(fmt::format("v = {}", value), std::string_view("--set"));
    if (holder.size() != 1 || holder.get("v") == nullptr)
      fail_override(text, "expected a single TOML value after '='");
    return holder;
  } catch (const toml::parse_error& e) {
    const bool bare = value.find_first_of("\"'[]{},=# \t\r\n") == std::string_view::npos;
    if (!bare)
      fail_override(text, fmt::format("invalid TOML value '{}': {}", value, e.description()));
    toml::table holder;
    holder.insert("v", std::string(value));
    return holder;
  }
}

/// A key whose value selects which other keys of the same table are used (friction law,
/// material model): its key path and, for each spelling, the parameters that choice takes.
struct Selector {
  std::string_view key;
  std::vector<std::pair<std::string_view, std::span<const std::string_view>>> params;
};

/// The selector of enum E, whose EnumNames<E>::what is the key path.
template <typename E, typename ParamsOf>
Selector selector_of(ParamsOf params_of) {
  Selector s{EnumNames<E>::what, {}};
  for (const auto& [value, name] : EnumNames<E>::table)
    s.params.emplace_back(name, params_of(value));
  return s;
}

const std::vector<Selector>& selectors() {
  static const std::vector<Selector> all = {
      selector_of<contact::FrictionLawKind>(contact::friction_law_parameters),
      selector_of<fe::MaterialModel>(fe::material_parameters),
      selector_of<contact::FrictionModel>(contact::friction_model_parameters),
      selector_of<driver::MeshKind>(driver::mesh_parameters),
  };
  return all;
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

void apply_override(Context& ctx, toml::table& root, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) fail_override(text, "expected KEY=VALUE");
  const auto path = split_key(text, trim(std::string_view(text).substr(0, eq)));
  toml::table holder = parse_override_value(text, trim(std::string_view(text).substr(eq + 1)));
  toml::node& value = *holder.get("v");

  const auto prefix = [&](std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i)
      s = join_key(s, path[i]);
    return s;
  };
  const auto index_of = [&](const toml::array& a, std::size_t i) {
    if (!is_index(path[i]))
      fail_override(text, fmt::format("'{}' is an array: address its entries as {}.0, {}.1, ...",
                                      prefix(i), prefix(i), prefix(i)));
    // Digits only (is_index); an index too large for size_t is out of range like any other.
    std::size_t idx = 0;
    const auto [end, ec] = std::from_chars(path[i].data(), path[i].data() + path[i].size(), idx);
    if (ec != std::errc{} || idx > a.size())
      fail_override(text, fmt::format("index {} out of range: '{}' has {} entries", path[i],
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
      fail_override(text, fmt::format("'{}' is {}, not a table", prefix(i), describe(*cur)));
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
    fail_override(text, fmt::format("'{}' is {}, not a table", prefix(last), describe(*cur)));
  }
  for (const auto* n : created)
    ctx.origins[n] = text;
  for_each_node(*placed, [&](const toml::node& n) { ctx.origins[&n] = text; });

  // A selector (friction law, material model) changed from the command line makes the file's
  // parameters of the other choices meaningless: drop them, so that e.g.
  // --set contact.friction.law=constant --set contact.friction.value=0.2 works on a file
  // written for the paper's law. Parameters given by overrides are kept (and then rejected).
  const auto* choice = placed->as_string();
  auto* table = cur->as_table();
  if (choice == nullptr || table == nullptr) return;
  for (const auto& sel : selectors()) {
    if (prefix(path.size()) != sel.key) continue;
    for (const auto& [name, used] : sel.params) {
      if (name == choice->get()) continue;
      for (const auto param : used) {
        const toml::node* old = table->get(param);
        if (old != nullptr && !ctx.origins.contains(old)) table->erase(param);
      }
    }
  }
}

/// Line `line` (1-based) of `text` without its end of line; empty past the end.
std::string_view line_of(std::string_view text, std::size_t line) {
  std::size_t begin = 0;
  for (std::size_t l = 1; l < line; ++l) {
    begin = text.find('\n', begin);
    if (begin == std::string_view::npos) return {};
    ++begin;
  }
  std::string_view rest = text.substr(std::min(begin, text.size()));
  rest = rest.substr(0, std::min(rest.find('\n'), rest.size()));
  if (!rest.empty() && rest.back() == '\r') rest.remove_suffix(1);
  return rest;
}

/// Whether 1-based `column` is just past the end of `line` (toml++ counts columns in code points
/// or bytes: either is accepted).
bool at_end_of_line(std::string_view line, std::size_t column) {
  const auto code_points =
      static_cast<std::size_t>(std::count_if(line.begin(), line.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      }));
  return column == code_points + 1 || column == line.size() + 1;
}

/// The line of a syntax error as it is shown in the message: trimmed, shortened, control
/// characters replaced by '?'.
std::string quote_line(std::string_view line) {
  line = trim(line);
  constexpr std::size_t kMax = 60;
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    // Cut at a code point boundary.
    if (out.size() >= kMax && (c & 0xC0) != 0x80) return out + "...";
    out += (c < 0x20 || c == 0x7F) ? '?' : static_cast<char>(c);
  }
  return out;
}

nlohmann::json vec_json(const Vec3& v) {
  return nlohmann::json::array({v[0], v[1], v[2]});
}

nlohmann::json material_json(const driver::MaterialOptions& m) {
  nlohmann::json j;
  if (!m.region.empty()) j["region"] = m.region;
  j["model"] = enum_name(m.model);
  if (m.model == fe::MaterialModel::Anisotropic) {
    if (m.voigt) j["voigt"] = *m.voigt;
  } else {
    j["young"] = m.young;
    j["poisson"] = m.poisson;
  }
  return j;
}

}  // namespace

driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const std::vector<std::string>& overrides) {
  ReadOptions options;
  options.overrides = overrides;
  return parse_problem(text, source_name, options);
}

driver::Problem parse_problem(std::string_view text, const std::string& source_name,
                              const ReadOptions& options) {
  Context ctx;
  ctx.file = source_name;
  ctx.override_origin = options.override_origin;
  ctx.code = &options.code;
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    const std::string_view line = line_of(text, b.line);
    // toml++ reports a string left open at the end of its line as a control character (the
    // newline) inside the string.
    const bool open_string = e.description().find("control characters") != std::string_view::npos &&
                             at_end_of_line(line, b.column);
    // The offending line names the key; not when the text is not UTF-8 (it cannot be shown).
    const bool show =
        !trim(line).empty() && e.description().find("utf-8") == std::string_view::npos;
    throw InputError(
        fmt::format("{}:{}:{}: invalid TOML: {}{}{}", source_name, b.line, b.column,
                    e.description(), show ? fmt::format(" in `{}`", quote_line(line)) : "",
                    open_string ? " (is the closing quote of a string missing?)" : ""));
  }
  for (const auto& o : options.overrides)
    apply_override(ctx, root, o);
  Problem problem;
  convert(ctx, root, problem);
  driver::validate(problem);
  return problem;
}

std::string read_problem_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot open the problem file: {}", path, std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the problem file", path));
  return text.str();
}

driver::Problem read_problem(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_problem(read_problem_text(path), path, overrides);
}

nlohmann::json to_json(const driver::Problem& p) {
  using nlohmann::json;
  json j;
  j["title"] = p.title;
  j["mesh"] = {{"kind", enum_name(p.mesh.kind)}};
  switch (p.mesh.kind) {
    case driver::MeshKind::Brick:
      j["mesh"]["size"] = p.mesh.size;
      j["mesh"]["cells"] = p.mesh.cells;
      break;
    case driver::MeshKind::Gmsh:
      j["mesh"]["file"] = p.mesh.file;
      if (p.mesh.size_factor) j["mesh"]["size_factor"] = *p.mesh.size_factor;
      j["mesh"]["unit"] = enum_name(p.mesh.unit);
      break;
    case driver::MeshKind::Arrays:  // the mesh itself is in the results, not in the problem
      break;
  }
  if (p.materials.empty()) {
    j["material"] = material_json(p.material);
  } else {
    j["material"] = json::array();
    for (const auto& m : p.materials)
      j["material"].push_back(material_json(m));
  }
  j["volume_force"] = vec_json(p.volume_force);
  j["dirichlet"] = json::array();
  for (const auto& d : p.dirichlet) {
    std::string comps;
    for (int i = 0; i < 3; ++i)
      if (d.components[i]) comps += "xyz"[i];
    j["dirichlet"].push_back(
        {{"boundary", d.boundary}, {"components", comps}, {"value", vec_json(d.value)}});
  }
  j["traction"] = json::array();
  for (const auto& t : p.traction)
    j["traction"].push_back({{"boundary", t.boundary}, {"value", vec_json(t.value)}});
  if (p.contact) {
    const auto& c = *p.contact;
    json fr = {{"law", enum_name(c.friction.law)}};
    if (c.friction.law == contact::FrictionLawKind::Paper) fr["param"] = c.friction.param;
    if (c.friction.law == contact::FrictionLawKind::Constant) fr["value"] = c.friction.value;
    if (c.friction.law == contact::FrictionLawKind::Table) {
      fr["t"] = c.friction.t;
      fr["f"] = c.friction.f;
    }
    if (c.friction.law == contact::FrictionLawKind::Expression)
      fr["expression"] = c.friction.expression;
    if (c.friction.law == contact::FrictionLawKind::Function) fr["name"] = c.friction.function_name;
    if (c.friction.law == contact::FrictionLawKind::Expression ||
        c.friction.law == contact::FrictionLawKind::Function) {
      fr["kinks"] = c.friction.kinks;
      fr["quadrature_rtol"] = c.friction.quadrature_rtol;
    }
    j["contact"] = {{"boundary", c.boundary},
                    {"model", enum_name(c.model)},
                    {"patches", enum_name(c.patches)},
                    {"friction", fr}};
    if (c.model == contact::FrictionModel::Tresca) j["contact"]["slip_bound"] = c.slip_bound;
    if (c.start_slip_bound) j["contact"]["start_slip_bound"] = *c.start_slip_bound;
    if (c.patch_size) j["contact"]["patch_size"] = *c.patch_size;
    if (c.obstacle)
      j["contact"]["obstacle"] = {{"kind", enum_name(c.obstacle->kind)},
                                  {"point", vec_json(c.obstacle->point)},
                                  {"normal", vec_json(c.obstacle->normal)}};
  }
  const auto& s = p.solver;
  j["solver"] = {{"outer_tol", s.outer_tol},
                 {"outer_max", s.outer_max},
                 {"qp_rtol", s.qp_rtol},
                 {"qp_max", s.qp_max},
                 {"warm_start", s.warm_start},
                 {"dual_operator", enum_name(s.dual_operator)},
                 {"acceleration", enum_name(s.acceleration)},
                 {"anderson_depth", s.anderson_depth},
                 {"qp_variant", enum_name(s.qp_variant)},
                 {"qp_expansion", enum_name(s.qp_expansion)},
                 {"dual_scaling", enum_name(s.dual_scaling)},
                 {"contact_search", enum_name(s.contact_search)},
                 {"contact_search_margin", s.contact_search_margin},
                 {"backend", enum_name(s.backend)},
                 {"partition", enum_name(s.partition)}};
  if (s.memory_per_rank) j["solver"]["memory_per_rank"] = *s.memory_per_rank;
  j["output"] = {{"dir", p.output.dir}};
  return j;
}

namespace {

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

std::string to_toml(const driver::Problem& problem) {
  if (problem.mesh.kind == driver::MeshKind::Arrays)
    throw InputError(
        fmt::format("{}: mesh.kind = \"arrays\": a mesh given by code cannot be "
                    "written to a problem file (write it as a Gmsh file)",
                    problem.where("mesh.kind")));
  if (problem.contact && problem.contact->friction.law == contact::FrictionLawKind::Function)
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
