// driver: the option tables of the problem file, one per section (driver/option_table.hpp).
//
// Each line is one key: its member, its range (with its unit) and its documentation line, which
// docs/problem-file.md shows as it is (`fricon keys` prints the tables; a test compares them with
// the page). Checks between keys are each table's `check`, run by validate() after every value
// passed its own range.
#include "fricon/driver/problem_options.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::driver {

namespace {

/// Slips (kinks, a table's t) must increase strictly.
void require_increasing(const Problem& p, const std::string& key, const std::vector<Real>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] > v[i - 1]))
      p.fail(fmt::format("{}[{}]", key, i),
             fmt::format("expected slips in strictly increasing order, got {} after {}",
                         format_real(v[i]), format_real(v[i - 1])));
}

std::string_view unused_mesh_key(const MeshOptions& m) {
  switch (m.kind) {
    case MeshKind::Brick:
      return "not used by kind \"brick\" (set mesh.kind = \"gmsh\" to read a Gmsh file)";
    case MeshKind::Gmsh:
      return "not used by kind \"gmsh\" (the mesh comes from mesh.file)";
    case MeshKind::Arrays:
      return "not used by kind \"arrays\" (the mesh is given by code)";
  }
  return "not used by this mesh kind";
}

void check_mesh(const Problem& p, const std::string& path, const MeshOptions& m) {
  if (m.kind == MeshKind::Arrays && !m.given)
    p.fail(join_key(path, "kind"),
           "expected a mesh given by code with kind = \"arrays\" (fricon.Mesh), got \"arrays\" "
           "without a mesh");
  if (m.kind != MeshKind::Brick) return;
  // 5 tetrahedra and about 3 dofs per cube: keep every count far from overflow (and from 32-bit
  // indices in the ordering libraries) instead of failing on allocation later.
  constexpr double kMaxCells = 1e8;
  const double total = static_cast<double>(m.cells[0]) * static_cast<double>(m.cells[1]) *
                       static_cast<double>(m.cells[2]);
  if (total > kMaxCells)
    p.fail(join_key(path, "cells"),
           fmt::format("expected at most {:.0f} cubes in all, got {} x {} x {} = {:.3g}", kMaxCells,
                       m.cells[0], m.cells[1], m.cells[2], total));
}

/// The keys of [material] and of a [[material]] entry (which has its region first).
void material_keys(OptionTableBuilder<MaterialOptions>& b) {
  b.choice("model", &MaterialOptions::model,
           "`\"anisotropic\"` takes a Hooke matrix `voigt` instead of `young` and `poisson`");
  b.selector("model", &MaterialOptions::model, fe::material_parameters,
             [](const MaterialOptions& m, std::string_view) {
               return fmt::format(
                   "not used by model \"{}\" ({})", enum_name(m.model),
                   m.model == fe::MaterialModel::Isotropic
                       ? "set material.model = \"anisotropic\" to give a Hooke matrix"
                       : "the Hooke matrix is material.voigt");
             });
  b.number("young", &MaterialOptions::young, positive("Pa"), "Young's modulus");
  b.number("poisson", &MaterialOptions::poisson, open_interval(-1.0, 0.5), "Poisson's ratio");
  b.number("voigt", &MaterialOptions::voigt, any_number("Pa"),
           "the Hooke matrix D in Voigt order 11, 22, 33, 23, 13, 12 on engineering shears, "
           "symmetric and elliptic (below)")
      .require("material.model = \"anisotropic\" needs one")
      .phrase = "a 6x6 Hooke matrix [Pa]";
}

void check_material(const Problem& p, const std::string& path, const MaterialOptions& m) {
  if (m.model != fe::MaterialModel::Anisotropic || !m.voigt) return;
  fe::Voigt6 D;
  for (std::size_t i = 0; i < 6; ++i)
    for (std::size_t j = 0; j < 6; ++j)
      D(static_cast<Index>(i), static_cast<Index>(j)) = (*m.voigt)[i][j];
  // Symmetry and ellipticity (docs/theory.md §1).
  const std::string key = join_key(path, "voigt");
  (void)fe::anisotropic(D, fmt::format("{}: {}", p.where(key), key));
}

void check_friction(const Problem& p, const std::string& path, const FrictionOptions& fr) {
  switch (fr.law) {
    case contact::FrictionLawKind::Table:
      require_increasing(p, join_key(path, "t"), fr.t);
      if (fr.f.size() != fr.t.size())
        p.fail(join_key(path, "f"), fmt::format("expected as many values as {} ({}), got {}",
                                                join_key(path, "t"), fr.t.size(), fr.f.size()));
      break;
    case contact::FrictionLawKind::Function:
      if (!fr.function)
        p.fail(join_key(path, "law"),
               "law \"function\" needs a function given from code (FrictionLawSpec::function)");
      [[fallthrough]];
    case contact::FrictionLawKind::Expression:
      require_increasing(p, join_key(path, "kinks"), fr.kinks);
      break;
    case contact::FrictionLawKind::Paper:
    case contact::FrictionLawKind::Constant:
      break;
  }
}

/// A load's path (theory.md §2.9): given only with [loading] steps > 1, one factor per step.
void check_path(const Problem& p, const std::string& key, const std::vector<Real>& factors,
                bool per_component = false) {
  if (factors.empty()) return;
  // The step count first: a path is measured against it ([loading] comes later in the file, so
  // its own range check would come after this one).
  require(fmt::format("{}: loading.steps", p.where("loading.steps")), p.loading.steps,
          kLoadStepsRange);
  const auto steps = static_cast<std::size_t>(p.loading.steps);
  if (steps == 1)
    p.fail(key,
           "a path needs [loading] steps > 1 (with steps = 1, the default, the problem is static: "
           "drop the path or set loading.steps)");
  if (per_component && factors.size() == 3 * steps) return;
  if (factors.size() != steps)
    p.fail(key, per_component
                    ? fmt::format("expected one factor per step, loading.steps = {} values, or one "
                                  "[fx, fy, fz] per step ({} values), got {}",
                                  steps, 3 * steps, factors.size())
                    : fmt::format("expected one factor per step, loading.steps = {} values, got {}",
                                  steps, factors.size()));
}

/// The steps whose files a loading path writes: only along a path, within it, increasing.
void check_output(const Problem& p, const std::string& path, const OutputOptions& o) {
  const bool chosen = !o.step_files.empty() || o.step_files_every != 1;
  const std::string key = join_key(path, o.step_files.empty() ? "step_files_every" : "step_files");
  if (chosen && p.loading.steps == 1)
    p.fail(key,
           "chooses the step files of a loading path, but [loading] steps = 1 (the default): a "
           "static run writes no step files");
  for (std::size_t i = 0; i < o.step_files.size(); ++i) {
    const std::string entry = fmt::format("{}[{}]", key, i);
    if (o.step_files[i] > p.loading.steps)
      p.fail(entry, fmt::format("step {} is beyond the path's {} steps (loading.steps)",
                                o.step_files[i], p.loading.steps));
    if (i > 0 && o.step_files[i] <= o.step_files[i - 1])
      p.fail(entry, fmt::format("expected steps in strictly increasing order, got {} after {}",
                                o.step_files[i], o.step_files[i - 1]));
  }
}

void check_solver(const Problem& p, const std::string& path, const SolverOptions& s) {
  if (s.backend == parallel::Backend::Petsc && !parallel::petsc_available())
    p.fail(
        join_key(path, "backend"),
        "\"petsc\": this fricon was built without PETSc; install Debian's petsc-dev (`make deps` "
        "or scripts/install-deps.sh does) and rebuild (`make build`: CMake finds it), then run "
        "`mpirun -n P fricon solve ...` (docs/parallel.md)");
  if (s.backend == parallel::Backend::Tfeti && !feti::metis_available())
    p.fail(
        join_key(path, "backend"),
        "\"tfeti\": this fricon was built without METIS, which cuts the bodies into subdomains; "
        "install Debian's libmetis-dev (`make deps` or scripts/install-deps.sh does) and rebuild "
        "(`make build`)");
  if (s.backend == parallel::Backend::Petsc && s.dual_operator == dual::DualOperatorKind::Forward)
    p.fail(join_key(path, "dual_operator"),
           "\"forward\" sweeps a CHOLMOD factor; with backend = \"petsc\" use \"auto\", \"schur\" "
           "(Q from MUMPS's Schur complement) or \"implicit\" (a distributed solve per product)");
}

/// The contact face must keep some free dofs: the Dirichlet entries on it may not fix all of
/// x, y and z.
void check_contact_not_clamped(const Problem& p, const std::string& key, const ContactOptions& c) {
  std::array<bool, 3> fixed{false, false, false};
  for (const auto& d : p.dirichlet)
    if (d.boundary == c.boundary)
      for (std::size_t i = 0; i < 3; ++i)
        fixed[i] = fixed[i] || d.components[i];
  if (fixed[0] && fixed[1] && fixed[2])
    p.fail(join_key(key, "boundary"),
           fmt::format("contact and Dirichlet on the same face \"{}\": [[dirichlet]] fixes all of "
                       "x, y, z there, so no contact node would be left",
                       c.boundary));
}

/// A pair's master is another surface than its slave (self-contact is not supported).
void check_master(const Problem& p, const std::string& key, const ContactOptions& c) {
  if (!c.obstacle || c.obstacle->kind != ObstacleKind::Body) return;
  if (c.obstacle->boundary == c.boundary)
    p.fail(join_key(key, "obstacle.boundary"),
           fmt::format("expected the tag of another surface than the contact surface, got \"{}\" "
                       "for both: self-contact is not supported",
                       c.boundary));
}

/// Whether pair b is pair a the other way round: a's contact surface is b's master and a's master
/// b's contact surface (one interface, both bodies' sides).
bool reversed_pair(const ContactOptions& a, const ContactOptions& b) {
  const auto against_body = [](const ContactOptions& c) {
    return c.obstacle && c.obstacle->kind == ObstacleKind::Body;
  };
  return against_body(a) && against_body(b) && a.boundary == b.obstacle->boundary &&
         b.boundary == a.obstacle->boundary;
}

/// Every pair: free dofs on its surface, a master of its own, no surface is the contact surface
/// of two pairs, and no interface is given as two pairs (A on B, B on A). Each pair has its own
/// friction model, law and slip bound (theory.md §5.7).
void check_contact_pairs(const Problem& p) {
  for (std::size_t i = 0; i < p.contact.size(); ++i) {
    const ContactOptions& c = p.contact[i];
    const std::string key = p.contact_key(i);
    check_contact_not_clamped(p, key, c);
    check_master(p, key, c);
    for (std::size_t j = 0; j < i; ++j) {
      if (p.contact[j].boundary == c.boundary)
        p.fail(join_key(key, "boundary"),
               fmt::format("expected a surface of its own, got \"{}\", the contact surface of "
                           "contact[{}] too",
                           c.boundary, j));
      if (reversed_pair(p.contact[j], c))
        p.fail(join_key(key, "obstacle.boundary"),
               fmt::format("\"{}\" against \"{}\" is the interface of contact[{}] (\"{}\" "
                           "against \"{}\") given the other way round: each interface is one "
                           "pair (theory.md §2.8), else its contact force would be split between "
                           "the two; keep one of them",
                           c.boundary, c.obstacle->boundary, j, p.contact[j].boundary,
                           p.contact[j].obstacle->boundary));
    }
  }
}

constexpr std::string_view kComponentsPhrase = "a string of distinct letters from \"xyz\"";

std::string components_text(const std::array<bool, 3>& c) {
  std::string s;
  for (std::size_t i = 0; i < 3; ++i)
    if (c[i]) s += "xyz"[i];
  return s;
}

bool components_valid(const std::string& s) {
  std::array<bool, 3> seen{false, false, false};
  for (const char c : s) {
    const auto pos = std::string_view("xyz").find(c);
    if (pos == std::string_view::npos || seen[pos]) return false;
    seen[pos] = true;
  }
  return true;
}

void set_components(const std::string& s, std::array<bool, 3>& c) {
  c = {false, false, false};
  for (const char x : s)
    c[std::string_view("xyz").find(x)] = true;
}

}  // namespace

const OptionTable& problem_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<Problem> b("", "a table");
    b.text("title", &Problem::title, "a string", "any text; shown in the report").allow_empty();
    b.table("mesh", &Problem::mesh, mesh_table, "the mesh: see `[mesh]`")
        .require("the [mesh] table is required");
    b.table_or_tables("material", &Problem::material, material_table, &Problem::materials,
                      material_entry_table,
                      "one `[material]` for the whole body, or one `[[material]]` per region")
        .require("a [material] table (or [[material]] per region) is required");
    b.number("volume_force", &Problem::volume_force, any_number("N/m^3"),
             "a body force per unit volume (gravity of steel: `[0, 0, -7.7e4]`)");
    b.tables("dirichlet", &Problem::dirichlet, dirichlet_table,
             "prescribed displacements: see `[[dirichlet]]`");
    b.tables("traction", &Problem::traction, traction_table,
             "surface tractions: see `[[traction]]`");
    b.table_or_tables("contact", &Problem::contact, contact_table,
                      "frictional contact: one pair `[contact]`, or one `[[contact]]` per pair "
                      "(see `[contact]`); absent: linear elasticity");
    b.table("loading", &Problem::loading, loading_table,
            "a quasi-static loading path: see `[loading]`");
    b.table("solver", &Problem::solver, solver_table, "see `[solver]`");
    b.table("output", &Problem::output, output_table, "see `[output]`");
    b.check([](const Problem& p, const std::string&, const Problem&) { check_contact_pairs(p); });
    return b.build();
  }();
  return table;
}

const OptionTable& mesh_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<MeshOptions> b("mesh", "a table [mesh]");
    b.choice("kind", &MeshOptions::kind,
             "`\"brick\"`: a box cut into cubes of 5 tetrahedra each; `\"gmsh\"`: a mesh from a "
             "Gmsh file; `\"arrays\"`: a mesh given by code (fricon.Mesh in Python), not by a "
             "file");
    b.selector("kind", &MeshOptions::kind, mesh_parameters,
               [](const MeshOptions& m, std::string_view) { return unused_mesh_key(m); });
    b.number("size", &MeshOptions::size, positive("m"),
             "edge lengths along x, y, z; the box is [0, size]");
    b.number("cells", &MeshOptions::cells, integer_at_least(1),
             "cubes along x, y, z, at most 1e8 in all. The paper's n: `[3n, n, n]`. With "
             "`[contact]` and the chessboard patches, the cell counts along the contact face "
             "must be even");
    b.text("file", &MeshOptions::file, "a Gmsh file name (.msh or .geo)",
           "a `.msh` file (MSH 2.2 or 4.1, ASCII or binary) or a `.geo` file, which is meshed in "
           "3D on the fly; a relative path is taken from the problem file's folder")
        .require("mesh.kind = \"gmsh\" reads a .msh or .geo file")
        .path();
    b.number("size_factor", &MeshOptions::size_factor, positive(),
             "with a `.geo` file: Gmsh's `Mesh.MeshSizeFactor` (0.5 halves every element size)");
    b.choice("unit", &MeshOptions::unit,
             "the unit of the file's coordinates. A mesh file is read in metres unless told "
             "otherwise; a model drawn in millimetres needs `unit = \"mm\"` (its coordinates are "
             "multiplied by 0.001 on reading). Every other length of the problem file is in "
             "metres");
    b.number("order", &MeshOptions::order, integer_in(kLinearOrder, kQuadraticOrder),
             "the order of the elements: 1, linear 4-node tetrahedra, or 2, quadratic 10-node "
             "ones (theory.md §2.12). A `.geo` file is meshed at this order (at 2, edges on "
             "curved surfaces are curved); at 2 the brick and a linear `.msh` file get straight "
             "edge midpoints; a quadratic `.msh` file is refused at 1. Unset: the file's own "
             "order (its elements, or a `.geo` file's `Mesh.ElementOrder`), 1 for the brick");
    b.check(check_mesh);
    return b.build();
  }();
  return table;
}

const OptionTable& material_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<MaterialOptions> b("material", "a table [material]");
    material_keys(b);
    b.check(check_material);
    return b.build();
  }();
  return table;
}

const OptionTable& material_entry_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<MaterialOptions> b("material", "a table (write [[material]])");
    b.text("region", &MaterialOptions::region, "a region name (a physical volume of the mesh)",
           "the region this material fills, each region once")
        .require("each [[material]] fills one region");
    material_keys(b);
    b.check([](const Problem& p, const std::string& path, const MaterialOptions& m) {
      // The regions are distinct (that they exist is checked against the mesh).
      const auto i = static_cast<std::size_t>(&m - p.materials.data());
      for (std::size_t j = 0; j < i && i < p.materials.size(); ++j)
        if (p.materials[j].region == m.region)
          p.fail(join_key(path, "region"),
                 fmt::format("region \"{}\" already has a material (material[{}])", m.region, j));
      check_material(p, path, m);
    });
    return b.build();
  }();
  return table;
}

const OptionTable& dirichlet_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<DirichletOptions> b("dirichlet", "a table (write [[dirichlet]])");
    b.text("boundary", &DirichletOptions::boundary, "a non-empty boundary tag",
           "a surface, or a Gmsh physical curve or point (all its nodes)")
        .require();
    b.text_as("components", &DirichletOptions::components, kComponentsPhrase,
              "in any order (`\"z\"`: a roller)", components_text, set_components,
              components_valid);
    b.number("value", &DirichletOptions::value, any_number("m"),
             "the displacement of the fixed components (a non-zero value for a component not in "
             "`components` is an error). A node on two entries must get the same value from "
             "both");
    b.number("path", &DirichletOptions::path, any_number(),
             "with `[loading] steps > 1`: the factor of `value` at each step, one per step "
             "(`[0, 0.5, 1, 1, 0]`); absent: the value holds at every step");
    b.check([](const Problem& p, const std::string& path, const DirichletOptions& d) {
      check_path(p, join_key(path, "path"), d.path);
      for (std::size_t c = 0; c < 3; ++c)
        if (!d.components[c] && d.value[static_cast<Index>(c)] != 0.0)
          p.fail(fmt::format("{}.value[{}]", path, c),
                 fmt::format("a value for component {} that {}.components does not fix (it would "
                             "be ignored): add \"{}\" to components or set it to 0",
                             "xyz"[c], path, "xyz"[c]));
    });
    return b.build();
  }();
  return table;
}

const OptionTable& traction_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<TractionOptions> b("traction", "a table (write [[traction]])");
    b.text("boundary", &TractionOptions::boundary, "a non-empty boundary tag", "").require();
    b.number("value", &TractionOptions::value, any_number("Pa"), "the traction vector in x, y, z")
        .require();
    b.number("path", &TractionOptions::path, any_number(),
             "with `[loading] steps > 1`: the factor of `value` at each step, one per step; "
             "absent: the traction holds at every step");
    b.check([](const Problem& p, const std::string& path, const TractionOptions& t) {
      check_path(p, join_key(path, "path"), t.path);
    });
    return b.build();
  }();
  return table;
}

const OptionTable& contact_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<ContactOptions> b("contact", "a table [contact]");
    b.text("boundary", &ContactOptions::boundary, "a non-empty boundary tag",
           "the tag of the contact surface");
    b.table("obstacle", &ContactOptions::obstacle, obstacle_table,
            "a rigid obstacle (plane, sphere, cylinder, meshed surface; fixed or moving) or the "
            "master surface: see `[contact.obstacle]`; absent: the plane of a flat contact "
            "surface, at zero gap (the paper's setting)");
    b.number("search_distance", &ContactOptions::search_distance, positive("m"),
             "how far along the contact surface's normal the master surface is looked for; "
             "parts of the contact surface farther away carry no multipliers. Absent: a tenth "
             "of the contact surface's diameter");
    b.when(
        [](const ContactOptions& c) {
          return c.obstacle && c.obstacle->kind == ObstacleKind::Body;
        },
        [](const ContactOptions&) {
          return std::string(
              "only used with obstacle kind \"body\" (a rigid plane is "
              "everywhere: its gap is known at every node)");
        },
        "with `obstacle.kind = \"body\"`");
    b.choice("model", &ContactOptions::model,
             "`\"tresca\"`: the slip bound of a patch is F times a given g (the paper's model); "
             "`\"coulomb\"`: F times the patch's own contact pressure, solved by successive "
             "approximations on the slips and the pressures (theory.md §5.6)");
    b.selector("model", &ContactOptions::model, contact::friction_model_parameters,
               [](const ContactOptions& c, std::string_view) -> std::string {
                 if (c.model == contact::FrictionModel::Coulomb)
                   return "not used by model \"coulomb\": its slip bound is F times the contact "
                          "pressure of each patch (start_slip_bound sets the Tresca problem it "
                          "starts from)";
                 return "only used by model \"coulomb\" (the Tresca problem it starts from)";
               });
    b.number("slip_bound", &ContactOptions::slip_bound, non_negative("Pa"), "the slip bound g");
    b.number("start_slip_bound", &ContactOptions::start_slip_bound, non_negative("Pa"),
             "start from the Tresca solution with g = this value instead of the frictionless "
             "one");
    b.choice("patches", &ContactOptions::patches,
             "how the contact surface is cut into the patches that carry the multipliers "
             "(theory.md §2.3): `\"chessboard\"`: 2x2 squares of the brick's surface grid (the "
             "paper's T_H; needs an even number of cells along both edges of the contact face); "
             "`\"mesh\"`: one patch per elementary entity (Gmsh surface) of the contact tag; "
             "`\"agglomerate\"`: fricon builds it from the surface triangles, on any mesh");
    b.number("patch_size", &ContactOptions::patch_size, positive("m"),
             "the target mean patch diameter; a value below the diameter of the finest "
             "partition (the stars, about two mesh edges across) changes nothing. Absent: the "
             "finest partition");
    b.when([](const ContactOptions& c) { return c.patches == contact::PatchKind::Agglomerate; },
           [](const ContactOptions& c) {
             return fmt::format("only used by patches = \"agglomerate\" (patches is \"{}\")",
                                enum_name(c.patches));
           },
           "with `patches = \"agglomerate\"`");
    b.table("friction", &ContactOptions::friction, friction_table,
            "the coefficient of friction: see `[contact.friction]`");
    b.number("geometry_updates", &ContactOptions::geometry_updates, integer_at_least(0),
             "against a curved rigid obstacle: at most this many times gap and "
             "normal are evaluated again at the deformed position and the problem solved again, "
             "while the linearized gap differs from the true one by more than geometry_tolerance "
             "(theory.md §2.11), in a static run and at every step of a loading path");
    b.number("geometry_tolerance", &ContactOptions::geometry_tolerance, open_interval(0.0, 1.0),
             "the geometric updates stop when the linearized gap of every node in contact is "
             "within this share of the largest normal displacement of the true gap");
    return b.build();
  }();
  return table;
}

const OptionTable& obstacle_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<ObstacleOptions> b(
        "contact.obstacle",
        "a table { kind = \"plane\", point = [x, y, z], normal = [nx, ny, nz] }, "
        "{ kind = \"sphere\", center = [x, y, z], radius = r }, { kind = \"cylinder\", point "
        "= [x, y, z], axis = [ax, ay, az], radius = r }, { kind = \"surface\", boundary = "
        "\"tag\" } or { kind = \"body\", boundary = \"tag\" }");
    b.choice("kind", &ObstacleOptions::kind,
             "`\"plane\"`: a rigid plane (half-space); `\"sphere\"`: a rigid ball; "
             "`\"cylinder\"`: a rigid infinite circular cylinder; `\"surface\"`: a rigid "
             "surface of the mesh file that no elastic body carries (theory.md §2.11); "
             "`\"body\"`: a surface of the mesh, usually of another elastic body (theory.md "
             "§2.8)");
    b.selector("kind", &ObstacleOptions::kind, obstacle_parameters,
               [](const ObstacleOptions& o, std::string_view) {
                 return fmt::format("not used by kind \"{}\"", enum_name(o.kind));
               });
    b.number("point", &ObstacleOptions::point, any_number("m"),
             "kind plane: a point of the plane; kind cylinder: a point of its axis")
        .require("a point of the plane, or of the cylinder's axis [m]");
    b.number("normal", &ObstacleOptions::normal, any_number(),
             "the plane's normal, non-zero (normalized by fricon), pointing out of the obstacle, "
             "towards the body")
        .require("the plane's normal, towards the body");
    b.text("boundary", &ObstacleOptions::boundary, "a non-empty boundary tag",
           "kind body: the tag of the master surface, facing the contact surface; kind surface: "
           "the tag of a surface of the mesh file that no tetrahedron carries (a surface-only "
           "physical group, or the surface of a volume left out of the physical groups)")
        .require(
            "the tag of the master surface (kind body) or of the rigid surface (kind surface)");
    b.number("center", &ObstacleOptions::center, any_number("m"), "the ball's centre")
        .require("the ball's centre [m]");
    b.number("radius", &ObstacleOptions::radius, positive("m"),
             "the radius of the ball or of the cylinder")
        .require("the radius [m]");
    b.number("axis", &ObstacleOptions::axis, any_number(),
             "the cylinder's axis, non-zero (normalized by fricon)")
        .require("the cylinder's axis");
    b.number("displacement", &ObstacleOptions::displacement, any_number("m"),
             "the obstacle's translation from where it is given (which the body may not "
             "penetrate); with a path, the value its factors multiply")
        .show_default("[0, 0, 0]");
    b.number("path", &ObstacleOptions::path, any_number(),
             "with `[loading] steps > 1`: the factor of `displacement` at each step, one per "
             "step, or one [fx, fy, fz] per step, the factors of its components (press, then "
             "slide; written flat or as rows, [[fx, fy, fz], ...]); absent: the displacement "
             "holds at every step")
        .or_rows_of(3);
    b.check([](const Problem& p, const std::string& path, const ObstacleOptions& o) {
      // stableNorm: the norm of [0, 0, 1e308] (or of [0, 0, 1e-200]) without overflow or
      // underflow of its square.
      if (o.kind == ObstacleKind::Plane && !(o.normal.stableNorm() > 0.0))
        p.fail(join_key(path, "normal"),
               "expected a non-zero vector (the plane's normal, pointing towards the body), got "
               "[0, 0, 0]");
      if (o.kind == ObstacleKind::Cylinder && !(o.axis.stableNorm() > 0.0))
        p.fail(join_key(path, "axis"),
               "expected a non-zero vector (the cylinder's axis), got [0, 0, 0]");
      check_path(p, join_key(path, "path"), o.path, /*per_component=*/true);
    });
    return b.build();
  }();
  return table;
}

const OptionTable& friction_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<FrictionOptions> b("contact.friction", "a table [contact.friction]");
    b.choice("law", &FrictionOptions::law,
             "`\"function\"` is for code only (a function given by the Python module)");
    b.selector("law", &FrictionOptions::law, contact::friction_law_parameters,
               [](const FrictionOptions& fr, std::string_view) {
                 std::string takes;
                 for (const auto u : contact::friction_law_parameters(fr.law))
                   takes += fmt::format("{}{}", takes.empty() ? "" : ", ", u);
                 return fmt::format("not used by law \"{}\" (it takes: {})", enum_name(fr.law),
                                    takes);
               });
    b.number("param", &FrictionOptions::param, positive("1/m"),
             "the parameter of the paper's law (theory.md §7.1)");
    b.number("value", &FrictionOptions::value, non_negative(), "F for the constant law");
    b.number("t", &FrictionOptions::t, non_negative("m"), "slips, strictly increasing")
        .require("law \"table\" needs slips t [m] and coefficients f")
        .at_least_one();
    b.number("f", &FrictionOptions::f, non_negative(), "F at each slip of `t`, as many as `t`")
        .require("law \"table\" needs slips t [m] and coefficients f")
        .at_least_one();
    b.text("expression", &FrictionOptions::expression,
           "a formula in the slip t [m], e.g. \"0.3 - 100*t\"",
           "F as a formula in the slip `t` (m), e.g. `\"0.1 + 0.4*exp(-t/5e-5)\"` (below)")
        .require("law \"expression\" needs a formula in the slip t [m]");
    b.number("kinks", &FrictionOptions::kinks, non_negative("m"),
             "slips where F is not smooth (a kink or a jump), strictly increasing; the "
             "quadrature of the radii is split there");
    b.number("quadrature_rtol", &FrictionOptions::quadrature_rtol, open_interval(0.0, 1.0),
             "relative accuracy of the radii");
    b.check(check_friction);
    return b.build();
  }();
  return table;
}

namespace {

// The keys of [solver], in the order of the documentation's table, as named groups.
using SolverKeys = OptionTableBuilder<SolverOptions>;

// When the outer loop and each QP stop.
void add_stopping_keys(SolverKeys& b) {
  b.number("outer_tol", at(&SolverOptions::outer, &outer::OuterOptions::tol), outer::kOuterTolRange,
           "the successive approximations stop when err(k) falls below it");
  b.number("outer_max", at(&SolverOptions::outer, &outer::OuterOptions::max_iterations),
           outer::kOuterMaxRange, "at most this many outer iterations");
  b.number("qp_rtol", at(&SolverOptions::qp, &qp::MpgpOptions::rel_tolerance),
           open_interval(0.0, 1.0),
           "a QP stops when ‖projected gradient‖ <= qp_rtol ‖h_R‖ in the scaled variables, "
           "h_R the part of h that the constraints resist (theory.md §4.2); the certificate "
           "allows 100 qp_rtol. At the default the patch pressures of the Hertz and wheel "
           "examples are within 1e-4 of the peak of a solve to 1e-13");
}

// Which variables and which patches the dual QP has.
void add_dual_problem_keys(SolverKeys& b) {
  b.choice("dual_scaling", &SolverOptions::dual_scaling,
           "the variables the dual QP is solved in: `\"patch\"` (each patch's multipliers "
           "divided by one factor from its area and the indentation modulus E/(1−ν²) under "
           "it, so that a graded mesh's patches do not spread the spectrum of Q) or `\"none\"` "
           "(the multipliers themselves, as in the paper). Results are in physical units "
           "either way; theory.md §4.5");
  b.choice("contact_search", &SolverOptions::contact_search,
           "which patches enter the dual QP: `\"gap\"` (those the free displacement K⁻¹f "
           "brings within `contact_search_margin` of closing, grown until no patch left out "
           "penetrates; the certificate covers every patch; under `backend = \"tfeti\"` the "
           "free displacement is that of the gluing alone) or `\"off\"` (every patch). Tresca "
           "friction with a positive `slip_bound`, which acts without pressure, `backend = "
           "\"petsc\"`, and a floating body under `\"tfeti\"` use every patch; theory.md §2.7, "
           "§8.7");
  b.number("contact_search_margin", &SolverOptions::contact_search_margin, non_negative(),
           "a patch is a first candidate when its mean gap at the free displacement is at "
           "most this many times the deepest free penetration (0: the patches the free body "
           "would penetrate)");
}

// How the QPs and the outer loop iterate.
void add_iteration_keys(SolverKeys& b) {
  b.number("qp_max", at(&SolverOptions::qp, &qp::MpgpOptions::max_iterations), integer_at_least(1),
           "at most this many iterations per QP");
  b.number("certificate_tol", &SolverOptions::certificate_tol, open_interval(0.0, 1.0),
           "Coulomb: the largest natural-map residual of a converged run; a fixed point above "
           "it takes further steps at tighter tolerances, else the run is not converged "
           "(theory.md §5.6)");
  b.boolean("warm_start", &SolverOptions::warm_start,
            "start each QP from the previous multipliers");
  b.choice("qp_variant", at(&SolverOptions::qp, &qp::MpgpOptions::variant),
           "inner QP algorithm: `\"bb\"` (MPGP with Barzilai-Borwein lengths for the "
           "expansion and proportioning steps; 5-8x fewer products with Q than `\"paper\"` on "
           "the paper's problems) or `\"paper\"` (the plain MPGP of the paper; `fricon paper` "
           "runs it with `qp_expansion = \"fixed\"` and `qp_active_discs = \"hold\"`, so that "
           "n_mult compares with the paper's); theory.md §4");
  b.choice("qp_expansion", &SolverOptions::qp_expansion,
           "the move of MPGP's expansion step: `\"fixed\"` (to the boundary along the CG "
           "direction, then a projected free-gradient step of the fixed length 1.95/‖Q‖, the "
           "paper's), `\"opt\"` (that step with PERMON's exact line-search length along the "
           "free gradient) or `\"projcg\"` (the full CG step past the boundary, projected). "
           "With the contact search the three need about the same products over whole runs "
           "on one factor of K, where `\"fixed\"` keeps Coulomb's successive approximations "
           "contracting to tighter tolerances; under `backend = \"tfeti\"` `\"projcg\"` needs the "
           "fewest (theory.md §4.2, §4.7)")
      .show_default("\"projcg\" with backend \"tfeti\", else \"fixed\"");
  b.choice("qp_active_discs", at(&SolverOptions::qp, &qp::MpgpOptions::active_discs),
           "what MPGP's CG steps do with a patch whose friction force is on its circle (a "
           "slipping patch): `\"turn\"` (they turn the force along the circle, with the "
           "circle's curvature, and return it to the circle; a very tight circle is held) or "
           "`\"hold\"` (the paper's: only the projected steps turn it, one steepest-descent "
           "move at a time). `\"turn\"` needs fewer products where many patches slip, and "
           "under `backend = \"tfeti\"` keeps their count nearly flat as the mesh grows "
           "(theory.md §4.7)");
  b.choice("acceleration", at(&SolverOptions::outer, &outer::OuterOptions::acceleration),
           "`\"none\"`: the paper's successive approximations phi^k = Psi(phi^(k-1)); "
           "`\"anderson\"`: Anderson mixing of the last `anderson_depth` iterates (the "
           "stopping test still measures err(k) = the relative fixed-point residual)");
  b.number("anderson_depth", at(&SolverOptions::outer, &outer::OuterOptions::anderson_depth),
           outer::kAndersonDepthRange, "iterates kept by Anderson mixing");
}

// How Q is applied and where K is factored.
void add_factorization_keys(SolverKeys& b) {
  b.choice("dual_operator", &SolverOptions::dual_operator,
           "how Q = B K^-1 B^T is applied: `\"implicit\"` (each product with Q is one solve "
           "with K, the paper's way), `\"forward\"` (Q = Y^T Y with Y = L^-1 P B^T, computed "
           "by a forward sweep over the part of the factor that the contact surface reaches; "
           "the outer loop then recovers w on that part only), `\"schur\"` (K factored with "
           "the contact dofs last; Q formed from the factor of the Schur complement onto "
           "them, and the outer loop runs on the contact surface only), or `\"auto\"` "
           "(`\"forward\"` while the dense Q, n_dual^2 entries, is no larger than the factor "
           "of K, or up to 6,000 multipliers; else `\"implicit\"`). All give the same solution "
           "to the QP tolerance; iteration counts can differ by rounding (theory.md §3.3)");
  b.choice("backend", &SolverOptions::backend,
           "where K is factored: `\"cholmod\"` (one process, CHOLMOD) or `\"petsc\"` (the ranks "
           "of an MPI job: `mpirun -n P fricon solve FILE --set solver.backend=petsc`; each "
           "rank assembles its own tetrahedra and MUMPS factors across them). With "
           "`\"petsc\"`, `dual_operator` may be `\"auto\"`, `\"schur\"` or `\"implicit\"`, not "
           "`\"forward\"`. A fricon built without PETSc refuses `\"petsc\"` and says how to "
           "get it. `\"tfeti\"`: Total FETI, each body cut into subdomains that are factored "
           "on their own (on the machine's threads, and under `mpirun` shared out among the "
           "ranks) and glued by multipliers in the same dual QP as the contact ones, for "
           "meshes past one factorization; docs/theory.md §8");
  b.choice("partition", &SolverOptions::partition,
           "with `backend = \"petsc\"`: how the tetrahedra are split among the ranks for "
           "assembly: `\"graph\"` (PT-Scotch through PETSc, on the mesh's dual graph) or "
           "`\"blocks\"` (consecutive blocks in mesh order). It changes who computes what, not "
           "the answer (beyond rounding)");
  b.number("memory_per_rank", &SolverOptions::memory_per_rank, positive("MiB"),
           "the most memory the MUMPS factorization may take on one rank. A run whose "
           "estimate (from MUMPS's analysis) exceeds it on some rank stops before the "
           "numerical factorization, with the estimate in the message; docs/parallel.md")
      .show_default("no limit");
  b.when([](const SolverOptions& s) { return s.backend == parallel::Backend::Petsc; },
         [](const SolverOptions& s) {
           return fmt::format(
               "limits the MUMPS factorization of backend = \"petsc\" (backend is \"{}\")",
               enum_name(s.backend));
         },
         "with `backend = \"petsc\"`");
}

// The subdomains of backend "tfeti", used only with it.
void add_tfeti_keys(SolverKeys& b) {
  const auto tfeti_only = [&b] {
    b.when([](const SolverOptions& s) { return s.backend == parallel::Backend::Tfeti; },
           [](const SolverOptions& s) {
             return fmt::format("sets up the subdomains of backend = \"tfeti\" (backend is \"{}\")",
                                enum_name(s.backend));
           },
           "with `backend = \"tfeti\"`");
  };
  b.number("subdomains", &SolverOptions::subdomains, integer_at_least(1),
           "with `backend = \"tfeti\"`: the number of subdomains over all bodies (each body "
           "gets a share in proportion to its tetrahedra, at least one), cut by METIS on the "
           "bodies' dual graphs; a part that METIS leaves disconnected becomes one subdomain "
           "per connected piece. Absent: from `subdomain_size`; theory.md §8.1")
      .show_default("from subdomain_size");
  tfeti_only();
  b.number("subdomain_size", &SolverOptions::subdomain_size,
           integer_at_least(feti::kMinSubdomainSize),
           "with `backend = \"tfeti\"` and no `subdomains`: the target number of nodes per "
           "subdomain (the default was measured the fastest on the paper's brick, "
           "docs/benchmarks.md)");
  tfeti_only();
  b.choice("tfeti_scaling", &SolverOptions::tfeti_scaling,
           "with `backend = \"tfeti\"`: how the gluing and Dirichlet rows of B are scaled: "
           "`\"stiffness\"` (each by the lumped stiffness of its dofs, so that its diagonal "
           "entry of F is about 1, as the scaled contact rows'; a diagonal preconditioner of "
           "the equality multipliers) or `\"uniform\"` (one factor for all); theory.md §8.5");
  tfeti_only();
  b.choice("tfeti_preconditioner", &SolverOptions::tfeti_preconditioner,
           "with `backend = \"tfeti\"`: what preconditions the gluing and Dirichlet "
           "multipliers in the QP's conjugate gradient steps: `\"none\"` (the row scaling "
           "alone), `\"lumped\"` ((B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1, in face: one "
           "product with every subdomain's stiffness between its interface dofs per step, "
           "which it keeps) or `\"dirichlet\"` (the same with each subdomain's Schur "
           "complement on those dofs: it keeps K_s and a factor of its interior, and a step "
           "costs two products with K_s and a solve with that factor; the default, because on "
           "meshes of flat elements `\"none\"` can need a hundred times its steps); "
           "theory.md §8.5");
  tfeti_only();
  b.number("tfeti_neck_cuts", &SolverOptions::tfeti_neck_cuts, integer_at_least(0),
           "with `backend = \"tfeti\"`: rounds of cutting again, with their neighbours, the "
           "subdomains whose softest deformation is 20 or more times softer than the median "
           "subdomain's (a part joined by a neck, which can double the products with F); each "
           "round factors every subdomain again. 0 keeps METIS's partition as it comes; "
           "theory.md §8.9");
  tfeti_only();
}

}  // namespace

const OptionTable& solver_table() {
  static const OptionTable table = [] {
    SolverKeys b("solver", "a table [solver]");
    add_stopping_keys(b);
    add_dual_problem_keys(b);
    add_iteration_keys(b);
    add_factorization_keys(b);
    add_tfeti_keys(b);
    b.check(check_solver);
    return b.build();
  }();
  return table;
}

const OptionTable& loading_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<LoadingOptions> b("loading", "a table [loading]");
    b.number("steps", &LoadingOptions::steps, kLoadStepsRange,
             "load steps of a quasi-static path (docs/theory.md §2.9); each step starts from the "
             "state the last one left, friction acts on the slip increment and the coefficient "
             "on the accumulated slip. 1: the static problem");
    b.number("volume_force_path", &LoadingOptions::volume_force_path, any_number(),
             "the factor of `volume_force` at each step, one per step; absent: constant");
    b.check([](const Problem& p, const std::string& path, const LoadingOptions& l) {
      check_path(p, join_key(path, "volume_force_path"), l.volume_force_path);
      if (l.steps > 1 && p.solver.backend == parallel::Backend::Petsc)
        p.fail(join_key(path, "steps"),
               "a loading path does not run with backend \"petsc\": use solver.backend = "
               "\"cholmod\" (one factor) or \"tfeti\" (subdomains, also on MPI ranks)");
    });
    return b.build();
  }();
  return table;
}

const OptionTable& output_table() {
  static const OptionTable table = [] {
    OptionTableBuilder<OutputOptions> b("output", "a table [output]");
    b.text("dir", &OutputOptions::dir, "a non-empty folder name",
           "the results folder, relative to the working directory. `--out DIR` on the command "
           "line takes precedence");
    b.number("step_files_every", &OutputOptions::step_files_every, kLoadStepsRange,
             "along a loading path ([loading] steps > 1): write the files of every k-th step "
             "(steps k, 2k, ...) into `steps/`, and those of the last step always; steps.csv "
             "keeps every step, solution.pvd lists the steps written");
    b.when([](const OutputOptions& o) { return o.step_files.empty(); },
           [](const OutputOptions&) {
             return std::string("not used with step_files, which lists the steps to write");
           },
           "without `step_files`");
    b.number("step_files", &OutputOptions::step_files, kLoadStepsRange,
             "along a loading path: write the files of these steps only (strictly increasing, "
             "at most [loading] steps), and those of the last step always; absent: "
             "`step_files_every` decides")
        .show_default("absent");
    b.choice(
        "vtu_encoding", &OutputOptions::vtu_encoding,
        "how solution.vtu, contact.vtu and obstacle.vtu (and the step files) store their "
        "arrays: `\"binary\"`, VTK's appended raw data (exact, less than half the size of "
        "the text, read by ParaView and meshio), or `\"ascii\"`, text with round-trip precision");
    b.check(check_output);
    return b.build();
  }();
  return table;
}

std::vector<const OptionTable*> all_option_tables() {
  return {&problem_table(),   &mesh_table(),     &material_table(), &material_entry_table(),
          &dirichlet_table(), &traction_table(), &contact_table(),  &obstacle_table(),
          &friction_table(),  &loading_table(),  &solver_table(),   &output_table()};
}

}  // namespace fricon::driver
