// driver: validate(Problem), the one place where the values of a problem are checked.
//
// Every message reads "WHERE: KEY: expected PHRASE, got VALUE", WHERE = problem.where(KEY), and
// the phrase is the one the TOML reader uses for the same key's type errors, so that a value is
// described the same way whether the file had the wrong type or the wrong range. The sections
// are checked in the order of the file (docs/problem-file.md), so the first bad value is named.
#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::driver {

namespace {

[[noreturn]] void fail(const Problem& p, std::string_view key, std::string_view what) {
  throw InputError(fmt::format("{}: {}: {}", p.where(key), key, what));
}

[[noreturn]] void fail_expected(const Problem& p, std::string_view key, std::string_view expected,
                                std::string_view got) {
  fail(p, key, fmt::format("expected {}, got {}", expected, got));
}

/// A real must be finite, and satisfy its range (`ok`, computed by the caller).
void check_real(const Problem& p, std::string_view key, Real v, std::string_view expected,
                bool ok) {
  if (!std::isfinite(v))
    fail_expected(p, key, expected, format_real(v) + " (numbers must be finite)");
  if (!ok) fail_expected(p, key, expected, format_real(v));
}

void check_int(const Problem& p, std::string_view key, long long v, std::string_view expected,
               bool ok) {
  if (!ok) fail_expected(p, key, expected, fmt::format("{}", v));
}

/// An enum value outside its spelling table (a cast in code); EnumNames<E>::what is the key.
template <typename E>
void check_enum(const Problem& p, E v) {
  if (enum_is_valid(v)) return;
  fail_expected(
      p, EnumNames<E>::what, enum_choices<E>(),
      fmt::format("{} (a value outside the enum)", static_cast<std::underlying_type_t<E>>(v)));
}

void check_tag(const Problem& p, std::string_view key, const std::string& tag) {
  if (tag.empty()) fail_expected(p, key, "a non-empty boundary tag", "\"\"");
}

void check_vec3(const Problem& p, std::string_view key, const Vec3& v, std::string_view expected) {
  for (int i = 0; i < 3; ++i)
    check_real(p, fmt::format("{}[{}]", key, i), v[i], expected, true);
}

// ---------------------------------------------------------------------------------------------
// The sections.

void validate_brick(const Problem& p) {
  const MeshOptions& m = p.mesh;
  for (std::size_t i = 0; i < 3; ++i)
    check_real(p, fmt::format("mesh.size[{}]", i), m.size[i], "a positive number [m]",
               m.size[i] > 0.0);
  for (std::size_t i = 0; i < 3; ++i)
    check_int(p, fmt::format("mesh.cells[{}]", i), m.cells[i], "an integer >= 1", m.cells[i] >= 1);
  // 5 tetrahedra and about 3 dofs per cube: keep every count far from overflow (and from 32-bit
  // indices in the ordering libraries) instead of failing on allocation later.
  constexpr double kMaxCells = 1e8;
  const double total = static_cast<double>(m.cells[0]) * static_cast<double>(m.cells[1]) *
                       static_cast<double>(m.cells[2]);
  if (total > kMaxCells)
    fail(p, "mesh.cells",
         fmt::format("expected at most {:.0f} cubes in all, got {} x {} x {} = {:.3g}", kMaxCells,
                     m.cells[0], m.cells[1], m.cells[2], total));
}

void validate_gmsh(const Problem& p) {
  const MeshOptions& m = p.mesh;
  if (m.file.empty())
    fail_expected(p, "mesh.file", "a Gmsh file name (.msh or .geo)", "\"\" (mesh.kind = \"gmsh\")");
  if (m.size_factor)
    check_real(p, "mesh.size_factor", *m.size_factor, "a positive number", *m.size_factor > 0.0);
  check_enum(p, m.unit);
}

void validate_mesh(const Problem& p) {
  check_enum(p, p.mesh.kind);
  switch (p.mesh.kind) {
    case MeshKind::Brick:
      validate_brick(p);
      break;
    case MeshKind::Gmsh:
      validate_gmsh(p);
      break;
    case MeshKind::Arrays:
      if (!p.mesh.given)
        fail_expected(p, "mesh.kind", "a mesh given by code with kind = \"arrays\" (fricon.Mesh)",
                      "\"arrays\" without a mesh");
      break;
  }
}

void validate_voigt(const Problem& p, const std::string& key, const MaterialOptions& m) {
  if (!m.voigt)
    fail_expected(p, key + ".voigt",
                  "a 6x6 Hooke matrix [Pa] (material.model = \"anisotropic\" needs one)", "none");
  fe::Voigt6 D;
  for (std::size_t i = 0; i < 6; ++i)
    for (std::size_t j = 0; j < 6; ++j) {
      const Real v = (*m.voigt)[i][j];
      check_real(p, fmt::format("{}.voigt[{}][{}]", key, i, j), v, "a number [Pa]", true);
      D(static_cast<Index>(i), static_cast<Index>(j)) = v;
    }
  // Symmetry and ellipticity (docs/theory.md §1).
  (void)fe::anisotropic(D, fmt::format("{}: {}.voigt", p.where(key + ".voigt"), key));
}

/// One material; `key` is "material" or "material[i]".
void validate_one_material(const Problem& p, const std::string& key, const MaterialOptions& m) {
  check_enum(p, m.model);
  if (m.model == fe::MaterialModel::Anisotropic) {
    validate_voigt(p, key, m);
    return;
  }
  check_real(p, key + ".young", m.young, "a positive number [Pa]", m.young > 0.0);
  check_real(p, key + ".poisson", m.poisson, "a number in (-1, 0.5)",
             m.poisson > -1.0 && m.poisson < 0.5);
}

/// [material], or [[material]] with one distinct region each (that the regions exist is checked
/// against the mesh, driver/model.cpp).
void validate_material(const Problem& p) {
  if (p.materials.empty()) {
    validate_one_material(p, "material", p.material);
    return;
  }
  for (std::size_t i = 0; i < p.materials.size(); ++i) {
    const std::string key = fmt::format("material[{}]", i);
    const MaterialOptions& m = p.materials[i];
    if (m.region.empty())
      fail_expected(p, key + ".region", "a region name (a physical volume of the mesh)", "\"\"");
    for (std::size_t j = 0; j < i; ++j)
      if (p.materials[j].region == m.region)
        fail(p, key + ".region",
             fmt::format("region \"{}\" already has a material (material[{}])", m.region, j));
    validate_one_material(p, key, m);
  }
}

void validate_dirichlet(const Problem& p) {
  for (std::size_t i = 0; i < p.dirichlet.size(); ++i) {
    const DirichletOptions& d = p.dirichlet[i];
    check_tag(p, fmt::format("dirichlet[{}].boundary", i), d.boundary);
    if (!d.components[0] && !d.components[1] && !d.components[2])
      fail_expected(p, fmt::format("dirichlet[{}].components", i),
                    "a string of distinct letters from \"xyz\"", "\"\"");
    const std::string value = fmt::format("dirichlet[{}].value", i);
    check_vec3(p, value, d.value, "a number [m]");
    for (std::size_t c = 0; c < 3; ++c)
      if (!d.components[c] && d.value[static_cast<Index>(c)] != 0.0)
        fail(p, fmt::format("{}[{}]", value, c),
             fmt::format("a value for component {} that dirichlet[{}].components does not fix "
                         "(it would be ignored): add \"{}\" to components or set it to 0",
                         "xyz"[c], i, "xyz"[c]));
  }
}

void validate_traction(const Problem& p) {
  for (std::size_t i = 0; i < p.traction.size(); ++i) {
    const TractionOptions& t = p.traction[i];
    check_tag(p, fmt::format("traction[{}].boundary", i), t.boundary);
    check_vec3(p, fmt::format("traction[{}].value", i), t.value, "a number [Pa]");
  }
}

/// A list of numbers >= 0, at least one ([contact.friction] t and f).
void check_non_negative_list(const Problem& p, std::string_view key, const std::vector<Real>& v,
                             std::string_view expected_elem) {
  if (v.empty()) fail_expected(p, key, "a non-empty array of numbers", "an empty array");
  for (std::size_t i = 0; i < v.size(); ++i)
    check_real(p, fmt::format("{}[{}]", key, i), v[i], expected_elem, v[i] >= 0.0);
}

void validate_table_law(const Problem& p, const FrictionOptions& fr) {
  check_non_negative_list(p, "contact.friction.t", fr.t, "a number >= 0 [m]");
  for (std::size_t i = 1; i < fr.t.size(); ++i)
    if (!(fr.t[i] > fr.t[i - 1]))
      fail(p, fmt::format("contact.friction.t[{}]", i),
           fmt::format("expected slips in strictly increasing order, got {} after {}",
                       format_real(fr.t[i]), format_real(fr.t[i - 1])));
  check_non_negative_list(p, "contact.friction.f", fr.f, "a number >= 0");
  if (fr.f.size() != fr.t.size())
    fail(p, "contact.friction.f",
         fmt::format("expected as many values as contact.friction.t ({}), got {}", fr.t.size(),
                     fr.f.size()));
}

/// kinks (>= 0, strictly increasing) and quadrature_rtol (in (0, 1)) of the expression and
/// function laws.
void validate_quadrature_keys(const Problem& p, const FrictionOptions& fr) {
  for (std::size_t i = 0; i < fr.kinks.size(); ++i) {
    const std::string key = fmt::format("contact.friction.kinks[{}]", i);
    check_real(p, key, fr.kinks[i], "a number >= 0 [m]", fr.kinks[i] >= 0.0);
    if (i > 0 && !(fr.kinks[i] > fr.kinks[i - 1]))
      fail(p, key,
           fmt::format("expected slips in strictly increasing order, got {} after {}",
                       format_real(fr.kinks[i]), format_real(fr.kinks[i - 1])));
  }
  check_real(p, "contact.friction.quadrature_rtol", fr.quadrature_rtol, "a number in (0, 1)",
             fr.quadrature_rtol > 0.0 && fr.quadrature_rtol < 1.0);
}

void validate_friction(const Problem& p, const FrictionOptions& fr) {
  check_enum(p, fr.law);
  switch (fr.law) {
    case contact::FrictionLawKind::Paper:
      check_real(p, "contact.friction.param", fr.param, "a positive number [1/m]", fr.param > 0.0);
      break;
    case contact::FrictionLawKind::Constant:
      check_real(p, "contact.friction.value", fr.value, "a number >= 0", fr.value >= 0.0);
      break;
    case contact::FrictionLawKind::Table:
      validate_table_law(p, fr);
      break;
    case contact::FrictionLawKind::Expression:
      if (fr.expression.empty())
        fail_expected(p, "contact.friction.expression", "a formula in the slip t [m]", "\"\"");
      validate_quadrature_keys(p, fr);
      break;
    case contact::FrictionLawKind::Function:
      if (!fr.function)
        fail(p, "contact.friction.law",
             "law \"function\" needs a function given from code (FrictionLawSpec::function)");
      validate_quadrature_keys(p, fr);
      break;
  }
}

void validate_obstacle(const Problem& p, const ObstacleOptions& o) {
  check_enum(p, o.kind);
  check_vec3(p, "contact.obstacle.point", o.point, "a number [m]");
  check_vec3(p, "contact.obstacle.normal", o.normal, "a number");
  if (!(o.normal.norm() > 0.0))
    fail(p, "contact.obstacle.normal",
         "expected a non-zero vector (the plane's normal, pointing towards the body), got [0, 0, "
         "0]");
}

void validate_contact(const Problem& p) {
  if (!p.contact) return;
  const ContactOptions& c = *p.contact;
  check_tag(p, "contact.boundary", c.boundary);
  check_enum(p, c.model);
  check_real(p, "contact.slip_bound", c.slip_bound, "a number >= 0 [Pa]", c.slip_bound >= 0.0);
  if (c.start_slip_bound) {
    check_real(p, "contact.start_slip_bound", *c.start_slip_bound, "a number >= 0 [Pa]",
               *c.start_slip_bound >= 0.0);
    if (c.model != contact::FrictionModel::Coulomb)
      fail(p, "contact.start_slip_bound",
           "only used by model \"coulomb\" (the Tresca problem it starts from)");
  }
  check_enum(p, c.patches);
  if (c.patch_size) {
    check_real(p, "contact.patch_size", *c.patch_size, "a positive number [m]",
               *c.patch_size > 0.0);
    if (c.patches != contact::PatchKind::Agglomerate)
      fail(p, "contact.patch_size",
           fmt::format("only used by patches = \"agglomerate\" (patches is \"{}\")",
                       enum_name(c.patches)));
  }
  if (c.obstacle) validate_obstacle(p, *c.obstacle);
  validate_friction(p, c.friction);
}

void validate_solver(const Problem& p) {
  const SolverOptions& s = p.solver;
  check_real(p, "solver.outer_tol", s.outer_tol, "a positive number", s.outer_tol > 0.0);
  check_int(p, "solver.outer_max", s.outer_max, "an integer >= 1", s.outer_max >= 1);
  check_real(p, "solver.qp_rtol", s.qp_rtol, "a number in (0, 1)",
             s.qp_rtol > 0.0 && s.qp_rtol < 1.0);
  check_int(p, "solver.qp_max", s.qp_max, "an integer >= 1", s.qp_max >= 1);
  check_enum(p, s.dual_operator);
  check_enum(p, s.acceleration);
  check_enum(p, s.qp_variant);
  check_enum(p, s.qp_expansion);
  check_enum(p, s.dual_scaling);
  check_enum(p, s.contact_search);
  check_real(p, "solver.contact_search_margin", s.contact_search_margin, "a number >= 0",
             s.contact_search_margin >= 0.0);
  check_enum(p, s.backend);
  check_enum(p, s.partition);
  if (s.backend == parallel::Backend::Petsc && !parallel::petsc_available())
    fail(p, "solver.backend",
         "\"petsc\": this fricon was built without PETSc; install Debian's petsc-dev (`make deps` "
         "or scripts/install-deps.sh does) and rebuild (`make build`: CMake finds it), then run "
         "`mpirun -n P fricon solve ...` (docs/parallel.md)");
  if (s.backend == parallel::Backend::Petsc && s.dual_operator == dual::DualOperatorKind::Forward)
    fail(p, "solver.dual_operator",
         "\"forward\" sweeps a CHOLMOD factor; with backend = \"petsc\" use \"auto\", \"schur\" "
         "(Q from MUMPS's Schur complement) or \"implicit\" (a distributed solve per product)");
  if (s.memory_per_rank) {
    check_real(p, "solver.memory_per_rank", *s.memory_per_rank, "a positive number [MiB]",
               *s.memory_per_rank > 0.0);
    if (s.backend != parallel::Backend::Petsc)
      fail(p, "solver.memory_per_rank",
           fmt::format("limits the MUMPS factorization of backend = \"petsc\" (backend is \"{}\")",
                       enum_name(s.backend)));
  }
  check_int(p, "solver.anderson_depth", s.anderson_depth, "an integer in [1, 20]",
            s.anderson_depth >= 1 && s.anderson_depth <= 20);
}

void validate_output(const Problem& p) {
  if (p.output.dir.empty()) fail_expected(p, "output.dir", "a non-empty folder name", "\"\"");
}

/// The contact face must keep some free dofs: the Dirichlet entries on it may not fix all of
/// x, y and z.
void validate_contact_not_clamped(const Problem& p) {
  if (!p.contact) return;
  std::array<bool, 3> fixed{false, false, false};
  for (const auto& d : p.dirichlet)
    if (d.boundary == p.contact->boundary)
      for (std::size_t i = 0; i < 3; ++i)
        fixed[i] = fixed[i] || d.components[i];
  if (fixed[0] && fixed[1] && fixed[2])
    fail(p, "contact.boundary",
         fmt::format("contact and Dirichlet on the same face \"{}\": [[dirichlet]] fixes all of "
                     "x, y, z there, so no contact node would be left",
                     p.contact->boundary));
}

}  // namespace

void validate(const Problem& p) {
  validate_mesh(p);
  validate_material(p);
  check_vec3(p, "volume_force", p.volume_force, "a number [N/m^3]");
  validate_dirichlet(p);
  validate_traction(p);
  validate_contact(p);
  validate_solver(p);
  validate_output(p);
  validate_contact_not_clamped(p);
}

}  // namespace fricon::driver
