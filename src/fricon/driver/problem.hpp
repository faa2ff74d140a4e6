#pragma once
// driver: the description of one problem, as the library uses it. The TOML reader (io/) fills it,
// and so may code (tests, benchmarks, the Python module); every entry point then calls
// validate(), the one place where values are checked against their ranges. Every field documents
// its unit, default and range; the key path in the problem file is given in brackets and spelt
// the same (docs/problem-file.md). Choices are enums, spelt by their EnumNames tables.

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fricon/contact/candidates.hpp"
#include "fricon/contact/dual_scaling.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/contact/slip_bounds.hpp"
#include "fricon/core/enum_names.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/types.hpp"
#include "fricon/driver/positions.hpp"
#include "fricon/dual/dual_operator_kind.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/io/vtu_encoding.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/parallel/backend.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::mesh {
struct TetMesh;
}  // namespace fricon::mesh

namespace fricon::driver {

/// Where the mesh comes from ([mesh] kind).
enum class MeshKind {
  Brick,   ///< the structured box generator (the paper's mesh)
  Gmsh,    ///< a Gmsh file: a mesh (.msh, MSH 2.2 or 4.1) or a geometry meshed on the fly (.geo)
  Arrays,  ///< a mesh given by code (MeshOptions::given; fricon.Mesh in Python), not by a file
};

/// The length unit of a mesh file's coordinates ([mesh] unit); fricon computes in metres.
enum class LengthUnit {
  Metre,       ///< "m" (default)
  Centimetre,  ///< "cm"
  Millimetre,  ///< "mm" (CAD and Gmsh models are often drawn in millimetres)
};

/// Metres per unit: 1, 0.01, 0.001.
Real metres_per(LengthUnit unit);

/// The orders of the elements ([mesh] order, theory.md §2.12): linear (4-node tetrahedra) and
/// quadratic (10-node).
inline constexpr int kLinearOrder = 1;
inline constexpr int kQuadraticOrder = 2;

/// The keys of [mesh] that `kind` uses (besides kind).
std::span<const std::string_view> mesh_parameters(MeshKind kind);

/// [mesh]
struct MeshOptions {
  MeshKind kind = MeshKind::Brick;          ///< [mesh.kind]
  std::array<Real, 3> size{3.0, 1.0, 1.0};  ///< [mesh.size] box edge lengths [m], > 0 (brick)
  /// [mesh.cells] cubes per direction, >= 1 each, at most 1e8 in all (brick)
  std::array<Index, 3> cells{12, 4, 4};
  /// [mesh.file] the Gmsh file (gmsh); the reader resolves a relative path against the problem
  /// file's folder, so this is the path as the program opens it.
  std::string file;
  /// [mesh.size_factor] Gmsh's Mesh.MeshSizeFactor for a .geo file, > 0 (gmsh, optional).
  std::optional<Real> size_factor;
  /// [mesh.unit] the unit of the file's coordinates (gmsh): they are multiplied by
  /// metres_per(unit) on reading. Default metres.
  LengthUnit unit = LengthUnit::Metre;
  /// [mesh.order] the order of the elements, kLinearOrder or kQuadraticOrder (brick, gmsh): a
  /// .geo file is meshed at it by Gmsh (curved edges on curved surfaces at 2); at 2 the brick and
  /// a linear .msh file get straight edge midpoints (mesh::add_edge_midpoints); a quadratic .msh
  /// file is refused at 1. Unset: the file's own order (a .msh file's elements, a .geo file's
  /// Mesh.ElementOrder), linear for the brick.
  std::optional<int> order;
  /// The mesh itself (arrays): built and checked by code (mesh::mesh_from_arrays), shared, never
  /// modified; required for kind = arrays, unused otherwise.
  std::shared_ptr<const mesh::TetMesh> given;
};

/// [material], or one table of [[material]]
struct MaterialOptions {
  /// [material.region] with [[material]]: the region (a Gmsh physical volume's name) this
  /// material fills; empty for the one [material] table, which fills the whole body.
  std::string region;
  fe::MaterialModel model = fe::MaterialModel::Isotropic;  ///< [material.model]
  Real young = 21.19e10;  ///< [material.young] Young's modulus [Pa], > 0 (isotropic)
  Real poisson = 0.277;   ///< [material.poisson] Poisson's ratio, in (-1, 0.5) (isotropic)
  /// [material.voigt] 6x6 Hooke matrix [Pa] (order 11,22,33,23,13,12, engineering shears);
  /// required for model = anisotropic, symmetric positive definite.
  std::optional<std::array<std::array<Real, 6>, 6>> voigt;
};

/// [[dirichlet]]: prescribed displacement of some components on a tagged boundary.
struct DirichletOptions {
  std::string boundary;                              ///< [dirichlet.boundary] boundary tag
  std::array<bool, 3> components{true, true, true};  ///< [dirichlet.components] subset of "xyz"
  /// [dirichlet.value] the displacement [m] of the fixed components (the others must be 0),
  /// finite; default zero (a clamp). Nodes in several [[dirichlet]] sets must get one value.
  Vec3 value = Vec3::Zero();
  /// [dirichlet.path] with [loading] steps > 1: the factor of `value` at each step (steps
  /// finite values); empty: the value is constant over the steps.
  std::vector<Real> path{};
};

/// [[traction]]: constant surface traction on a tagged boundary.
struct TractionOptions {
  std::string boundary;       ///< [traction.boundary] boundary tag
  Vec3 value = Vec3::Zero();  ///< [traction.value] traction vector [Pa], finite
  /// [traction.path] with [loading] steps > 1: the factor of `value` at each step (steps finite
  /// values); empty: the traction is constant over the steps.
  std::vector<Real> path{};
};

/// [contact.friction]: the coefficient of friction F(t), t = ||u_t|| [m].
using FrictionOptions = contact::FrictionLawSpec;

/// What the contact surface touches ([contact.obstacle] kind).
enum class ObstacleKind {
  Plane,     ///< a rigid plane (half-space)
  Body,      ///< another surface of the mesh, usually of another elastic body (theory.md §2.8)
  Sphere,    ///< a rigid ball (theory.md §2.11)
  Cylinder,  ///< a rigid infinite circular cylinder
  Surface,   ///< a rigid surface of the mesh file that no elastic body carries
};

/// The keys of [contact.obstacle] that `kind` uses (besides kind).
std::span<const std::string_view> obstacle_parameters(ObstacleKind kind);

/// [contact.obstacle]: what the contact surface (the slave) may touch.
struct ObstacleOptions {
  ObstacleKind kind = ObstacleKind::Plane;  ///< [contact.obstacle.kind]
  Vec3 point = Vec3::Zero();                ///< [contact.obstacle.point] a point of the plane [m]
  /// [contact.obstacle.normal] the plane's normal, pointing out of the obstacle towards the body;
  /// non-zero (it is normalized).
  Vec3 normal = Vec3(0.0, 0.0, 1.0);
  /// [contact.obstacle.boundary] kind body: the tag of the master surface, a boundary of the same
  /// mesh, facing the contact surface; kind surface: the tag of the rigid surface.
  std::string boundary;
  Vec3 center = Vec3::Zero();  ///< [contact.obstacle.center] kind sphere: its centre [m]
  Real radius = 0.0;           ///< [contact.obstacle.radius] sphere and cylinder [m], > 0
  Vec3 axis = Vec3::UnitZ();   ///< [contact.obstacle.axis] cylinder: its axis, non-zero
  /// [contact.obstacle.displacement] every kind but body: the obstacle's translation [m].
  Vec3 displacement = Vec3::Zero();
  /// [contact.obstacle.path] with [loading] steps > 1: the factor of `displacement` at each step
  /// (steps values), or of each of its components ([fx, fy, fz] per step, 3 steps values);
  /// empty: the displacement holds at every step.
  std::vector<Real> path{};
};

/// Whether the obstacle is rigid (any kind but body).
inline bool is_rigid(const ObstacleOptions& o) {
  return o.kind != ObstacleKind::Body;
}

/// The obstacle's translation [m] at step k (1-based) of a loading path of `steps` steps (k = 0,
/// or no path: its displacement).
Vec3 obstacle_displacement(const ObstacleOptions& o, int k, int steps);

/// [contact.geometry_updates] and [contact.geometry_tolerance] by default: enough for the
/// examples in examples/obstacles (docs/benchmarks.md shows what each update changes).
inline constexpr int kDefaultGeometryUpdates = 3;
inline constexpr Real kDefaultGeometryTolerance = 1e-3;

/// [contact] or one table of [[contact]]: one contact pair, a tagged boundary (the slave, which
/// carries the patches and the multipliers) against a rigid plane or another surface.
struct ContactOptions {
  std::string boundary = "z0";  ///< [contact.boundary] tag of the contact surface
  /// [contact.obstacle] a rigid obstacle or the master surface; absent: the plane of a flat
  /// contact surface, at zero gap (the paper's setting).
  std::optional<ObstacleOptions> obstacle;
  /// [contact.search_distance] with obstacle kind body: how far along the slave's normal the
  /// master is looked for [m], > 0; absent: a tenth of the slave surface's diameter.
  std::optional<Real> search_distance;
  /// [contact.model] Tresca (slip bound F g) or Coulomb (slip bound F times the pressure).
  contact::FrictionModel model = contact::FrictionModel::Tresca;
  Real slip_bound = 2.0e7;  ///< [contact.slip_bound] g [Pa], >= 0 (Tresca only)
  /// [contact.start_slip_bound] g0 [Pa], >= 0 (Coulomb only): start the successive
  /// approximations from the Tresca solution with g = g0 instead of the frictionless one.
  std::optional<Real> start_slip_bound;
  /// [contact.patches] partition of the contact surface for the multipliers.
  contact::PatchKind patches = contact::PatchKind::Chessboard;
  /// [contact.patch_size] target patch diameter [m] of patches = "agglomerate", > 0; absent:
  /// chosen from the mesh (the stars of an independent set of vertices).
  std::optional<Real> patch_size;
  FrictionOptions friction;  ///< [contact.friction]
  /// [contact.geometry_updates] against a curved rigid obstacle: at most this many times (per step
  /// of a path) gap and normal are evaluated again at the deformed position and the problem
  /// solved again (theory.md §2.11), >= 0.
  int geometry_updates = kDefaultGeometryUpdates;
  /// [contact.geometry_tolerance] the updates stop when the linearized gap is within this share
  /// of the normal displacement of the true gap at every node in contact, > 0.
  Real geometry_tolerance = kDefaultGeometryTolerance;
};

/// The MPGP options of a run before its [solver] keys: turned discs (theory.md §4.7).
inline qp::MpgpOptions run_qp_defaults() {
  qp::MpgpOptions o;
  o.active_discs = qp::MpgpDiscFace::Turned;
  return o;
}

/// [solver] (driver/problem_options.cpp documents each key, its range and default).
struct SolverOptions {
  /// The successive approximations (theory.md §5): [solver.outer_tol] tol, [solver.outer_max]
  /// max_iterations, [solver.acceleration], [solver.anderson_depth]; the loop takes them as
  /// they are.
  outer::OuterOptions outer;
  /// Each QP (theory.md §4): [solver.qp_rtol] rel_tolerance, [solver.qp_max] max_iterations,
  /// [solver.qp_variant] variant, [solver.qp_active_discs] active_discs; its expansion is
  /// qp_expansion's (mpgp()). Its other fields are settings for code only; the driver sets
  /// norm_A and the monitor of each solve. A run's default differs from MpgpOptions' (the
  /// paper's MPGP): the CG steps turn active discs (theory.md §4.7).
  qp::MpgpOptions qp = run_qp_defaults();
  /// [solver.qp_expansion]; absent: the backend's, ProjectedCG under Total FETI, Fixed on one
  /// factor of K (theory.md §4.7).
  std::optional<qp::MpgpExpansion> qp_expansion;
  bool warm_start = true;       ///< [solver.warm_start]
  Real certificate_tol = 1e-6;  ///< [solver.certificate_tol]
  dual::DualOperatorKind dual_operator = dual::DualOperatorKind::Auto;  ///< [solver.dual_operator]
  contact::DualScaling dual_scaling = contact::DualScaling::Patch;      ///< [solver.dual_scaling]
  contact::ContactSearch contact_search = contact::ContactSearch::Gap;  ///< [solver.contact_search]
  Real contact_search_margin = 0.0;                        ///< [solver.contact_search_margin]
  parallel::Backend backend = parallel::Backend::Cholmod;  ///< [solver.backend]
  parallel::PartitionKind partition = parallel::PartitionKind::Graph;  ///< [solver.partition]
  std::optional<Real> memory_per_rank;  ///< [solver.memory_per_rank] [MiB]; absent: no limit
  /// [solver.subdomains] backend "tfeti": the number of subdomains over all bodies; absent: from
  /// subdomain_size.
  std::optional<int> subdomains;
  int subdomain_size = static_cast<int>(feti::kDefaultSubdomainSize);  ///< [solver.subdomain_size]
  feti::RowScaling tfeti_scaling = feti::RowScaling::Stiffness;        ///< [solver.tfeti_scaling]
  /// [solver.tfeti_preconditioner]
  feti::FetiPreconditioner tfeti_preconditioner = feti::kDefaultPreconditioner;
  int tfeti_neck_cuts = static_cast<int>(feti::kDefaultNeckCuts);  ///< [solver.tfeti_neck_cuts]

  /// The options of this run's contact QPs: qp with the expansion of qp_expansion, or the
  /// backend's where it is absent.
  qp::MpgpOptions mpgp() const {
    qp::MpgpOptions o = qp;
    o.expansion =
        qp_expansion.value_or(backend == parallel::Backend::Tfeti ? qp::MpgpExpansion::ProjectedCG
                                                                  : qp::MpgpExpansion::Fixed);
    return o;
  }
};

/// The number of load steps of a path ([loading] steps).
inline constexpr Range kLoadStepsRange = integer_in(1, 100000);

/// [loading]: a quasi-static loading path (theory.md §2.9). Step k solves the contact problem
/// for the loads of step k, each load's value times its path's k-th factor, with friction on the
/// slip increment from step k - 1 and the coefficient of the accumulated slip.
struct LoadingOptions {
  int steps = 1;  ///< [loading.steps] >= 1; 1: the static problem
  /// [loading.volume_force_path] the factor of volume_force at each step (steps finite values);
  /// empty: the volume force is constant over the steps.
  std::vector<Real> volume_force_path;
};

/// [output]
struct OutputOptions {
  std::string dir = "results";  ///< [output.dir] results folder, non-empty
  /// [output.step_files_every] along a loading path: the files of every k-th step (k, 2k, ...)
  /// are written into steps/ (and those of the last step always); 1: every step.
  int step_files_every = 1;
  /// [output.step_files] along a loading path: the steps whose files are written (strictly
  /// increasing, 1 ... loading.steps; the last step's always); empty: step_files_every decides.
  std::vector<int> step_files;
  /// [output.vtu_encoding] how the .vtu files store their arrays: binary (appended raw, exact)
  /// or ASCII text.
  io::VtuEncoding vtu_encoding = io::VtuEncoding::Binary;
};

struct Problem {
  /// What the problem was read from or built by (a file name, "paper(n = 4, ...)"), for messages.
  std::string source = "<memory>";
  /// Where each value was given: key path ("material.young", "dirichlet[0].boundary",
  /// "contact.friction.t[2]") -> "file:line:col" or "--set KEY=VALUE". Filled by the reader;
  /// empty for a problem built in code. Read it through where(). Copies of the problem share
  /// it (a path's steps copy the problem once each; driver/positions.hpp).
  Positions positions;

  std::string title;  ///< [title] free text, optional
  MeshOptions mesh;
  /// [material] the material of the whole body, used when `materials` is empty.
  MaterialOptions material;
  /// [[material]] one material per region (each with its region), replacing `material`.
  std::vector<MaterialOptions> materials;
  Vec3 volume_force = Vec3::Zero();  ///< [volume_force] body force [N/m^3], finite
  std::vector<DirichletOptions> dirichlet;
  std::vector<TractionOptions> traction;
  /// [contact] (one pair) or [[contact]] (one entry per pair); empty: linear elasticity.
  std::vector<ContactOptions> contact;
  LoadingOptions loading;
  SolverOptions solver;
  OutputOptions output;

  /// Where `key` was given, for the start of a message: its own position, else that of the
  /// closest enclosing key ("dirichlet[0]", "dirichlet"), else `source`.
  std::string where(std::string_view key) const;
  /// Throws InputError "WHERE: KEY: WHAT" with WHERE = where(KEY): a bad value of `key`.
  [[noreturn]] void fail(std::string_view key, std::string_view what) const;
  /// The key path of contact pair i: "contact" for the one pair of [contact], "contact[i]" for
  /// an entry of [[contact]] (also when the file gives one pair as [[contact]]: the record
  /// holds its keys as "contact[0]...").
  std::string contact_key(std::size_t i) const;
  /// Whether the record holds the entries of `key` (an array of tables that may also be one
  /// table, [contact]) as an array: "KEY[0]" was given ([[contact]] in the file, or
  /// --set contact.0.KEY=...).
  bool given_as_array(std::string_view key) const;
};

/// The problem of step `k` (1-based, <= loading.steps) of its loading path: every load with a
/// path has its value multiplied by the path's k-th factor; the rest is unchanged.
Problem at_step(const Problem& problem, int k);

/// The problem with the value of the i-th load with a path (path_loads order) multiplied by
/// factors[i] and that of every other load by `rest`: the loads are linear in these factors
/// (at_step is scaled_loads with the step's factors and rest = 1).
Problem scaled_loads(const Problem& problem, const std::vector<Real>& factors, Real rest);

/// A load that carries a path: its key ("traction[0]", "dirichlet[1]", "volume_force") and its
/// factors.
struct PathLoad {
  std::string key;
  const std::vector<Real>* factors = nullptr;
  /// The boundary tag it acts on; empty for the volume force.
  std::string boundary;
};

/// The loads of the problem that carry a path, in the order [[traction]], [[dirichlet]],
/// volume_force.
std::vector<PathLoad> path_loads(const Problem& problem);

/// The factor of each of `loads` (path_loads) at step k (1-based).
std::vector<Real> step_factors(const std::vector<PathLoad>& loads, int k);

/// Checks every value of the problem against its range and the consistency of the values with
/// one another that needs no mesh (e.g. contact on a face that Dirichlet conditions clamp
/// entirely). Every entry point calls it: the TOML reader after --set, code before run().
/// Throws InputError "WHERE: KEY: expected ..., got VALUE" with WHERE = problem.where(KEY).
void validate(const Problem& problem);

}  // namespace fricon::driver

FRICON_ENUM_NAMES(fricon::driver::MeshKind, "mesh.kind", {driver::MeshKind::Brick, "brick"},
                  {driver::MeshKind::Gmsh, "gmsh"}, {driver::MeshKind::Arrays, "arrays"});
FRICON_ENUM_NAMES(fricon::driver::LengthUnit, "mesh.unit", {driver::LengthUnit::Metre, "m"},
                  {driver::LengthUnit::Centimetre, "cm"}, {driver::LengthUnit::Millimetre, "mm"});
FRICON_ENUM_NAMES(fricon::driver::ObstacleKind, "contact.obstacle.kind",
                  {driver::ObstacleKind::Plane, "plane"}, {driver::ObstacleKind::Body, "body"},
                  {driver::ObstacleKind::Sphere, "sphere"},
                  {driver::ObstacleKind::Cylinder, "cylinder"},
                  {driver::ObstacleKind::Surface, "surface"});
