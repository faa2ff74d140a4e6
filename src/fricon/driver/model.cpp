#include "fricon/driver/model.hpp"

#include <algorithm>
#include <string_view>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/floating_bodies.hpp"
#include "fricon/driver/obstacle.hpp"
#include "fricon/driver/option_table.hpp"
#include "fricon/fe/element.hpp"
#include "fricon/fe/rigid_motions.hpp"
#include "fricon/feti/partition.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/gmsh_file.hpp"

namespace fricon::driver {

namespace {

// The triangles of a boundary that must be a surface (a traction's).
std::vector<Index> tagged_faces(const mesh::TetMesh& mesh, const Problem& problem,
                                const std::string& key, const std::string& tag) {
  auto faces = mesh.faces_with_tag(tag);
  if (faces.empty()) problem.fail(key, mesh.no_surface(tag));
  return faces;
}

// The nodes of a [[dirichlet]] boundary: a surface, a curve or a point of the mesh.
std::vector<Index> tagged_nodes(const mesh::TetMesh& mesh, const Problem& problem,
                                const std::string& key, const std::string& tag) {
  auto nodes = mesh.nodes_with_tag(tag);
  if (nodes.empty())
    problem.fail(key, fmt::format("boundary '{}' does not exist on the mesh (tags: {})", tag,
                                  mesh.tag_list()));
  return nodes;
}

fe::Material make_material(const Problem& problem, const MaterialOptions& m,
                           const std::string& key) {
  const std::string where = problem.where(key) + ": " + key;
  if (m.model == fe::MaterialModel::Anisotropic) {
    FRICON_CHECK(m.voigt.has_value(), "anisotropic material without voigt matrix");
    fe::Voigt6 D;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        D(i, j) = (*m.voigt)[i][j];
    return fe::anisotropic(D, where);
  }
  return fe::isotropic(m.young, m.poisson, where);
}

std::string region_name(const mesh::TetMesh& mesh, int r) {
  return mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<size_t>(r)];
}

std::string region_list(const mesh::TetMesh& mesh) {
  std::string s;
  for (int r = 0; r < mesh.n_regions(); ++r)
    s += fmt::format("{}\"{}\"", r == 0 ? "" : ", ", region_name(mesh, r));
  return s;
}

// The applied loads (tractions and volume force) over the free dofs of `dofs`. With all
// 3 n_nodes components as `dofs` it gives the totals and reactions.
VectorXd applied_load(const Problem& problem, const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                      Extent extent = Extent::Whole) {
  VectorXd f = VectorXd::Zero(dofs.n_free());
  for (size_t i = 0; i < problem.traction.size(); ++i) {
    const auto& t = problem.traction[i];
    // A part of the body (a rank's) may hold none of a tag's triangles; the whole body must.
    const std::vector<Index> faces =
        extent == Extent::Part
            ? mesh.faces_with_tag(t.boundary)
            : tagged_faces(mesh, problem, fmt::format("traction[{}].boundary", i), t.boundary);
    fe::add_traction(mesh, dofs, faces, t.value, f);
  }
  if (problem.volume_force.squaredNorm() > 0)
    fe::add_volume_force(mesh, dofs, problem.volume_force, f);
  return f;
}

// The [[dirichlet]] entries that fix a component of some node of body b, as
// `dirichlet[0] ("base")`, comma-separated (empty if none).
std::string entries_on_body(const Problem& problem, const mesh::TetMesh& mesh,
                            const mesh::Bodies& bodies, Index b) {
  std::string s;
  for (size_t i = 0; i < problem.dirichlet.size(); ++i) {
    const auto& d = problem.dirichlet[i];
    if (!d.components[0] && !d.components[1] && !d.components[2]) continue;
    const std::vector<Index> nodes = mesh.nodes_with_tag(d.boundary);
    if (std::any_of(nodes.begin(), nodes.end(),
                    [&](Index a) { return bodies.node_body[static_cast<size_t>(a)] == b; }))
      s += fmt::format("{}dirichlet[{}] (\"{}\")", s.empty() ? "" : ", ", i, d.boundary);
  }
  return s;
}

// The rigid-motion check of fe, per body, with a message that names the problem's keys and, for
// a mesh of several bodies, the first body that is not held.
void check_rigid_motions(const Problem& problem, const mesh::TetMesh& mesh,
                         const mesh::Bodies& bodies, const std::vector<bool>& fixed) {
  const std::vector<fe::RigidMotionCheck> checks = fe::free_rigid_motions(mesh, bodies, fixed);
  std::vector<Index> loose;  // the bodies not held
  for (Index b = 0; b < bodies.n_bodies(); ++b)
    if (checks[static_cast<size_t>(b)].n_free > 0) loose.push_back(b);
  if (loose.empty()) return;
  const fe::RigidMotionCheck& check = checks[static_cast<size_t>(loose.front())];
  if (bodies.n_bodies() == 1)
    throw InputError(fmt::format(
        "{}: dirichlet: {} leave {} rigid motion(s) of the body free{}, so the stiffness matrix "
        "would be singular (not positive definite); fix enough components to hold the body, "
        "e.g. a [[dirichlet]] entry with components = \"xyz\" on one face",
        problem.where("dirichlet"),
        problem.dirichlet.empty() ? "there is no [[dirichlet]] entry: the conditions"
                                  : "the [[dirichlet]] conditions",
        check.n_free,
        check.loose_axes.empty()
            ? ""
            : fmt::format(" (no {} component is fixed anywhere)", check.loose_axes)));
  const Index b = loose.front();
  const std::string entries = entries_on_body(problem, mesh, bodies, b);
  std::string others;  // the other bodies not held
  for (size_t i = 1; i < loose.size(); ++i)
    others += fmt::format("{}{}", i == 1 ? "" : ", ", loose[i]);
  throw InputError(fmt::format(
      "{}: dirichlet: the mesh has {} separate bodies (0 to {}, sharing no node) and {} is not "
      "held: {} {} rigid motion(s) of it free{}, so the stiffness matrix would be singular (not "
      "positive definite); give each body [[dirichlet]] conditions of its own, e.g. components = "
      "\"xyz\" on one face of it: contact alone does not hold a body (floating bodies are not "
      "solved yet){}",
      problem.where("dirichlet"), bodies.n_bodies(), bodies.n_bodies() - 1,
      mesh::describe_body(mesh, bodies, b),
      entries.empty() ? "no [[dirichlet]] entry fixes any of its nodes, which leaves"
                      : fmt::format("the [[dirichlet]] entries on it, {}, leave", entries),
      check.n_free,
      check.n_fixed == 0 || check.loose_axes.empty()
          ? ""
          : fmt::format(" (no {} component is fixed on it)", check.loose_axes),
      loose.size() == 1   ? ""
      : loose.size() == 2 ? fmt::format("; body {} is not held either", others)
                          : fmt::format("; bodies {} are not held either", others)));
}

// K_free,fixed times the prescribed displacements [N]: moved to the right-hand side.
VectorXd prescribed_load(const Model& model) {
  if (model.prescribed.isZero(0.0)) return VectorXd::Zero(model.dofs.n_free());
  return model.dofs.from_nodal(fe::internal_forces(model.mesh, model.materials, model.prescribed));
}

}  // namespace

fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh) {
  return make_dofs(problem, mesh, mesh::find_bodies(mesh));
}

fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh,
                     const mesh::Bodies& bodies) {
  std::vector<bool> fixed(static_cast<size_t>(3 * mesh.n_nodes()), false);
  for (size_t i = 0; i < problem.dirichlet.size(); ++i) {
    const auto& d = problem.dirichlet[i];
    for (Index a :
         tagged_nodes(mesh, problem, fmt::format("dirichlet[{}].boundary", i), d.boundary))
      for (int c = 0; c < 3; ++c)
        if (d.components[c]) fixed[static_cast<size_t>(3 * a + c)] = true;
  }
  fe::DofMap dofs(fixed);
  if (dofs.n_free() == 0)
    throw InputError(fmt::format(
        "{}: dirichlet: the [[dirichlet]] conditions fix every displacement component of the "
        "mesh: nothing to solve",
        problem.where("dirichlet")));
  // With contact, a body that its conditions leave free floats (check_model).
  if (problem.contact.empty()) check_rigid_motions(problem, mesh, bodies, fixed);
  return dofs;
}

std::vector<fe::Material> make_materials(const Problem& problem, const mesh::TetMesh& mesh) {
  if (problem.materials.empty()) return {make_material(problem, problem.material, "material")};
  for (size_t i = 0; i < problem.materials.size(); ++i) {
    const std::string key = fmt::format("material[{}].region", i);
    if (mesh.find_region(problem.materials[i].region) < 0)
      problem.fail(key, fmt::format("the mesh has no region \"{}\" (its regions: {})",
                                    problem.materials[i].region, region_list(mesh)));
  }
  std::vector<fe::Material> materials;
  for (int r = 0; r < mesh.n_regions(); ++r) {
    const std::string name = region_name(mesh, r);
    const auto it = std::find_if(problem.materials.begin(), problem.materials.end(),
                                 [&](const MaterialOptions& m) { return m.region == name; });
    if (it == problem.materials.end())
      throw InputError(fmt::format(
          "{}: material: region \"{}\" of the mesh has no [[material]] (give one per region: {})",
          problem.where("material"), name, region_list(mesh)));
    materials.push_back(
        make_material(problem, *it, fmt::format("material[{}]", it - problem.materials.begin())));
  }
  return materials;
}

fe::NodalField make_prescribed(const Problem& problem, const mesh::TetMesh& mesh,
                               std::vector<int>* owners) {
  fe::NodalField u = fe::NodalField::Zero(3, mesh.n_nodes());
  // Which [[dirichlet]] entry set each component, to name both of two that disagree.
  std::vector<int> set_by(static_cast<size_t>(3 * mesh.n_nodes()), -1);
  for (size_t i = 0; i < problem.dirichlet.size(); ++i) {
    const auto& d = problem.dirichlet[i];
    for (Index a : mesh.nodes_with_tag(d.boundary))
      for (int c = 0; c < 3; ++c) {
        if (!d.components[c]) continue;
        int& owner = set_by[static_cast<size_t>(3 * a + c)];
        if (owner >= 0 && u(c, a) != d.value(c))
          throw InputError(
              fmt::format("{}: dirichlet[{}].value: node {} (at {:.6g}, {:.6g}, {:.6g}) is also on "
                          "dirichlet[{}].boundary = \"{}\", which prescribes {} = {} there, not {}",
                          problem.where(fmt::format("dirichlet[{}].value", i)), i, a,
                          mesh.nodes(0, a), mesh.nodes(1, a), mesh.nodes(2, a), owner,
                          problem.dirichlet[static_cast<size_t>(owner)].boundary, "xyz"[c], u(c, a),
                          d.value(c)));
        owner = static_cast<int>(i);
        u(c, a) = d.value(c);
      }
  }
  if (owners) *owners = std::move(set_by);
  return u;
}

namespace {

mesh::TetMesh make_brick_mesh(const Problem& problem) {
  mesh::BrickSpec spec;
  spec.size = Vec3(problem.mesh.size[0], problem.mesh.size[1], problem.mesh.size[2]);
  spec.cells = problem.mesh.cells;
  mesh::TetMesh m = mesh::make_brick(spec);
  if (problem.mesh.order == kQuadraticOrder) mesh::add_edge_midpoints(m);  // straight edges
  // A brick's elements can only be degenerate through its sizes and cell counts.
  mesh::check_mesh(m, fmt::format("{}: mesh.size = [{}, {}, {}], mesh.cells = [{}, {}, {}]",
                                  problem.where("mesh"), spec.size(0), spec.size(1), spec.size(2),
                                  spec.cells[0], spec.cells[1], spec.cells[2]));
  return m;
}

/// The Gmsh file's mesh, at the order of mesh.order (read_gmsh: a .geo file meshed at it, a linear
/// .msh file raised to it, a quadratic one refused at order 1); its errors (which name the mesh
/// file and element) are prefixed with the position of mesh.file.
mesh::TetMesh read_gmsh_mesh(const Problem& problem) {
  try {
    mesh::TetMesh mesh =
        mesh::read_gmsh(problem.mesh.file, problem.mesh.size_factor, problem.mesh.order);
    mesh::scale_lengths(mesh, metres_per(problem.mesh.unit));  // uniform: keeps every check
    fe::check_jacobians(mesh, problem.mesh.file);              // curved elements that fold
    return mesh;
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: mesh.file: {}", problem.where("mesh.file"), e.what()));
  }
}

}  // namespace

mesh::TetMesh make_mesh(const Problem& problem) {
  switch (problem.mesh.kind) {
    case MeshKind::Brick:
      return make_brick_mesh(problem);
    case MeshKind::Gmsh:
      return read_gmsh_mesh(problem);
    case MeshKind::Arrays:
      // Checked when it was built (mesh::mesh_from_arrays), but for curved elements that fold.
      fe::check_jacobians(*problem.mesh.given, "the mesh given by code");
      return *problem.mesh.given;
  }
  FRICON_CHECK(false, "make_mesh: invalid mesh kind");
  return {};
}

namespace {

Model assemble(const Problem& problem, PhaseTimes& times, const PhaseCallback& on_phase_start,
               bool with_stiffness) {
  Model model;
  if (on_phase_start) on_phase_start("mesh");
  {
    ScopedPhase phase(times, "mesh");
    model.mesh = make_mesh(problem);
    model.bodies = mesh::find_bodies(model.mesh);
    model.materials = make_materials(problem, model.mesh);
  }
  if (on_phase_start) on_phase_start("assembly");
  {
    ScopedPhase phase(times, "assembly");
    model.dofs = make_dofs(problem, model.mesh, model.bodies);
    model.floating = fe::find_floating_bodies(model.mesh, model.bodies, model.dofs);
    model.prescribed = make_prescribed(problem, model.mesh);
    if (with_stiffness) model.K = fe::assemble_stiffness(model.mesh, model.materials, model.dofs);
    model.f = load_vector(problem, model, Extent::Whole);
  }
  return model;
}

}  // namespace

Model assemble_loads(const Problem& problem, PhaseTimes& times,
                     const PhaseCallback& on_phase_start) {
  return assemble(problem, times, on_phase_start, false);
}

Model assemble_model(const Problem& problem, PhaseTimes& times,
                     const PhaseCallback& on_phase_start) {
  return assemble(problem, times, on_phase_start, true);
}

VectorXd load_vector(const Problem& problem, const Model& model, Extent extent) {
  return applied_load(problem, model.mesh, model.dofs, extent) - prescribed_load(model);
}

VectorXd stiffness_times(const Model& model, const VectorXd& w) {
  if (model.K.rows() == w.size()) return model.K * w;
  return model.dofs.from_nodal(
      fe::internal_forces(model.mesh, model.materials, model.dofs.to_nodal(w)));
}

namespace {

// A stiffness contrast between materials from which the failure of the factorization is put down
// to it: K's condition number grows with the contrast, and double precision (relative accuracy
// 1e-16) leaves the mesh's own conditioning (~1e4 to 1e8 for h = L/10 to L/100) little room.
constexpr Real kContrastWorthNaming = 1e6;

// The stiffness scale of a material [Pa]: the largest diagonal entry of its Hooke matrix.
Real stiffness_scale(const fe::Material& m) {
  return m.D.diagonal().maxCoeff();
}

// Why K cannot be factorized although make_dofs found every body held: the conditioning, with
// the contrast of the materials when it is large (their positions named).
std::string ill_conditioning(const Problem& problem, const Model& model,
                             const std::string& factor_message) {
  const auto [softest, stiffest] =
      std::minmax_element(model.materials.begin(), model.materials.end(),
                          [](const fe::Material& a, const fe::Material& b) {
                            return stiffness_scale(a) < stiffness_scale(b);
                          });
  const Real contrast = stiffness_scale(*stiffest) / stiffness_scale(*softest);
  const std::string why =
      contrast >= kContrastWorthNaming
          ? fmt::format(
                "the stiffest material (region \"{}\") is {:.1e} times as stiff as the "
                "softest (region \"{}\"), and K's condition number grows with that "
                "contrast: bring the moduli within about {:.0e} of each other (a body "
                "{:.0e} times stiffer than the other already deforms negligibly)",
                region_name(model.mesh, static_cast<int>(stiffest - model.materials.begin())),
                contrast,
                region_name(model.mesh, static_cast<int>(softest - model.materials.begin())),
                kContrastWorthNaming, kContrastWorthNaming)
          : "look for degenerate or badly shaped tetrahedra, or stiffnesses of very different "
            "orders in an anisotropic material";
  return fmt::format(
      "{}: material: the [[dirichlet]] conditions hold every body (no rigid motion is free), yet "
      "{}; K is too ill-conditioned for double precision: {}",
      problem.where("material"), factor_message, why);
}

}  // namespace

void factorize_model(Model& model, const dual::FactorizationRequest& request, PhaseTimes& times,
                     const PhaseCallback& on_phase_start, const Problem* problem) {
  if (on_phase_start) on_phase_start("factorize");
  ScopedPhase phase(times, "factorize");
  try {
    if (model.floating.empty())
      model.factor.factorize(model.K, request.last);
    else
      model.factor.factorize(fe::regularized_stiffness(model.K, model.floating), request.last);
  } catch (const NumericalError& e) {
    // Only K not positive definite (linalg/cholesky.hpp), not a failure for lack of memory.
    const bool not_positive_definite =
        std::string_view(e.what()).find("not positive definite") != std::string_view::npos;
    if (!problem || model.materials.empty() || !not_positive_definite) throw;
    throw NumericalError(ill_conditioning(*problem, model, e.what()));
  }
}

namespace {

// The spec of pair i of the problem, the positions of its keys for messages.
contact::ContactSpec pair_spec(const Problem& problem, std::size_t i, const mesh::TetMesh& mesh,
                               const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  const ContactOptions& c = problem.contact[i];
  const std::string key = problem.contact_key(i);
  // "file:line:col: contact[i].k": the contact module's messages start with the key's position
  // and its name as the file writes it.
  const auto where = [&](std::string_view k) {
    const std::string full = join_key(key, k);
    return problem.where(full) + ": " + full;
  };
  contact::ContactSpec spec;
  spec.key = key;
  spec.boundary = c.boundary;
  spec.patches = c.patches;
  spec.slip_bound = c.slip_bound;
  if (c.patch_size) spec.patch_size = *c.patch_size;
  if (c.obstacle && is_rigid(*c.obstacle)) {
    spec.obstacle = make_obstacle(*c.obstacle, mesh, c.boundary, where("obstacle.boundary"));
    spec.obstacle_displacement = obstacle_displacement(*c.obstacle, 0, problem.loading.steps);
    // A static run evaluates gap and normal where the obstacle is moved; a loading path, whose
    // steps move it, where it rests (theory.md §2.11).
    if (problem.loading.steps == 1) spec.linearized_displacement = spec.obstacle_displacement;
  }
  if (c.obstacle && c.obstacle->kind == ObstacleKind::Body) {
    contact::MasterSpec master;
    master.boundary = c.obstacle->boundary;
    master.search_distance = c.search_distance.value_or(0.0);
    master.node_body = mesh::find_bodies(mesh).node_body;
    master.where_boundary = where("obstacle.boundary");
    spec.master = std::move(master);
  }
  spec.prescribed = prescribed;
  spec.where_boundary = where("boundary");
  spec.where_patches = where("patches");
  spec.where_patch_size = where("patch_size");
  spec.where_obstacle = where("obstacle");
  return spec;
}

}  // namespace

contact::ContactDiscretization discretize_contact(const Problem& problem, const mesh::TetMesh& mesh,
                                                  const fe::DofMap& dofs,
                                                  const fe::NodalField* deformation,
                                                  const std::vector<Vec3>* obstacles) {
  FRICON_CHECK(!problem.contact.empty(), "discretize_contact: the problem has no [contact]");
  const Eigen::Matrix<Real, 3, Eigen::Dynamic> prescribed = make_prescribed(problem, mesh);
  std::vector<contact::ContactDiscretization> pairs;
  for (std::size_t i = 0; i < problem.contact.size(); ++i) {
    contact::ContactSpec spec = pair_spec(problem, i, mesh, prescribed);
    if (deformation != nullptr && spec.obstacle && !spec.obstacle->flat())
      spec.deformation = *deformation;
    if (obstacles != nullptr && spec.obstacle) {
      spec.obstacle_displacement = obstacles->at(i);
      spec.linearized_displacement = obstacles->at(i);
    }
    pairs.push_back(contact::discretize_contact(mesh, dofs, spec));
  }
  return contact::merge_pairs(std::move(pairs));
}

void check_steps(const Problem& problem, const mesh::TetMesh& mesh) {
  if (problem.loading.steps == 1) {
    (void)make_prescribed(problem, mesh);
    return;
  }
  for (int k = 1; k <= problem.loading.steps; ++k)
    try {
      (void)make_prescribed(at_step(problem, k), mesh);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{} (at step {} of the loading path)", e.what(), k));
    }
}

namespace {

// A floating body must touch something: the bodies that carry a contact boundary or a master
// surface of some pair (theory.md §2.10).
void check_floating_bodies_touch(const Problem& problem, const Model& model) {
  if (model.floating.empty()) return;
  std::vector<bool> touches(static_cast<size_t>(model.bodies.n_bodies()), false);
  const auto mark = [&](const std::string& tag) {
    for (Index a : model.mesh.nodes_with_tag(tag))
      touches[static_cast<size_t>(model.bodies.node_body[static_cast<size_t>(a)])] = true;
  };
  for (const ContactOptions& c : problem.contact) {
    mark(c.boundary);
    if (c.obstacle && c.obstacle->kind == ObstacleKind::Body) mark(c.obstacle->boundary);
  }
  for (const fe::FloatingBody& body : model.floating.bodies) {
    if (touches[static_cast<size_t>(body.body)]) continue;
    std::string motions;
    for (Index j = 0; j < body.n_motions(); ++j)
      motions += fmt::format("{}{}", j == 0 ? "" : ", ", body.motion_name(j));
    throw InputError(fmt::format(
        "{}: dirichlet: {} floats: its [[dirichlet]] conditions leave {} rigid motion(s) free "
        "({}), and no [[contact]] surface or master lies on it, so nothing holds it and the "
        "stiffness matrix would be singular; fix enough components of it, or give it a contact "
        "surface (contact.boundary or obstacle.boundary on it)",
        problem.where("dirichlet"), mesh::describe_body(model.mesh, model.bodies, body.body),
        body.n_motions(), motions));
  }
}

}  // namespace

std::optional<contact::ContactDiscretization> check_model(const Problem& problem,
                                                          const Model& model) {
  check_steps(problem, model.mesh);
  check_floating_bodies_touch(problem, model);
  if (problem.solver.backend == parallel::Backend::Tfeti && problem.solver.subdomains)
    feti::check_subdomain_count(model.mesh, *problem.solver.subdomains,
                                problem.where("solver.subdomains"));
  if (problem.contact.empty()) return std::nullopt;
  contact::ContactDiscretization disc = discretize_contact(problem, model.mesh, model.dofs);
  check_balance(problem, model, disc);
  return disc;
}

Model build_model(const Problem& problem, PhaseTimes& times, const PhaseCallback& on_phase_start) {
  Model model = assemble_model(problem, times, on_phase_start);
  factorize_model(model, {}, times, on_phase_start, &problem);
  return model;
}

fe::NodalField applied_forces(const Problem& problem, const mesh::TetMesh& mesh) {
  const fe::DofMap all(mesh.n_nodes());
  return all.to_nodal(applied_load(problem, mesh, all));
}

Vec3 applied_force_total(const Problem& problem, const mesh::TetMesh& mesh) {
  return applied_forces(problem, mesh).rowwise().sum();
}

Real force_magnitude_sum(const fe::NodalField& forces) {
  return forces.colwise().norm().sum();
}

Vec3 reaction_total(const Model& model, const Problem& problem, const fe::NodalField& u) {
  return reaction_forces(model, problem, u).rowwise().sum();
}

fe::NodalField reaction_forces(const Model& model, const Problem& problem,
                               const fe::NodalField& u) {
  const fe::NodalField load = applied_forces(problem, model.mesh);
  // Only the tetrahedra with a fixed dof contribute to the rows the reaction sums.
  std::vector<Index> tets;
  for (Index t = 0; t < model.mesh.n_tets(); ++t) {
    bool fixed = false;
    for (int a = 0; a < model.mesh.nodes_per_tet() && !fixed; ++a)
      for (int c = 0; c < 3 && !fixed; ++c)
        fixed = model.dofs.is_fixed(model.mesh.tet_node(t, a), c);
    if (fixed) tets.push_back(t);
  }
  const fe::NodalField internal = fe::internal_forces(model.mesh, model.materials, u, tets);
  fe::NodalField r = fe::NodalField::Zero(3, model.mesh.n_nodes());
  for (Index a = 0; a < model.mesh.n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      if (model.dofs.is_fixed(a, c)) r(c, a) = internal(c, a) - load(c, a);
  return r;
}

}  // namespace fricon::driver
