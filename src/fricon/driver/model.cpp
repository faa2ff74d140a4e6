#include "fricon/driver/model.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"
#include "fricon/mesh/brick.hpp"

namespace fricon::driver {

namespace {

std::vector<Index> tagged_faces(const mesh::TetMesh& mesh, const Problem& problem,
                                const std::string& key, const std::string& tag) {
  auto faces = mesh.faces_with_tag(tag);
  if (faces.empty())
    throw InputError(fmt::format("{}: {}: boundary '{}' does not exist on the mesh (tags: {})",
                                 problem.source, key, tag, mesh.tag_list()));
  return faces;
}

fe::Material make_material(const Problem& problem) {
  const std::string where = problem.source + ": material";
  if (problem.material.model == "anisotropic") {
    FRICON_CHECK(problem.material.voigt.has_value(), "anisotropic material without voigt matrix");
    fe::Voigt6 D;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        D(i, j) = (*problem.material.voigt)[i][j];
    return fe::anisotropic(D, where);
  }
  return fe::isotropic(problem.material.young, problem.material.poisson, where);
}

// Loads on all 3 n_nodes components (fixed ones included), for totals and reactions.
VectorXd full_load(const Problem& problem, const mesh::TetMesh& mesh, const fe::DofMap& dofs) {
  VectorXd f = VectorXd::Zero(dofs.n_free());
  for (size_t i = 0; i < problem.traction.size(); ++i) {
    const auto& t = problem.traction[i];
    fe::add_traction(
        mesh, dofs,
        tagged_faces(mesh, problem, fmt::format("traction[{}].boundary", i), t.boundary), t.value,
        f);
  }
  if (problem.volume_force.squaredNorm() > 0)
    fe::add_volume_force(mesh, dofs, problem.volume_force, f);
  return f;
}

// K over the free dofs is singular exactly when a rigid motion r(x) = a + w x (x - c) vanishes at
// every fixed dof (the mesh is connected). Checked here, before any assembly, so that the message
// can name the file and the key. G = sum over fixed dofs of the rigid modes' values there (6x6,
// Gram matrix, in centred and scaled coordinates, accumulated in long double).
void check_rigid_motions(const Problem& problem, const mesh::TetMesh& mesh,
                         const std::vector<bool>& fixed) {
  const Vec3 lo = mesh.nodes.rowwise().minCoeff(), hi = mesh.nodes.rowwise().maxCoeff();
  const Vec3 centre = 0.5 * (lo + hi);
  const Real scale = std::max((hi - lo).maxCoeff(), std::numeric_limits<Real>::min());
  Eigen::Matrix<long double, 6, 6> gram = Eigen::Matrix<long double, 6, 6>::Zero();
  for (Index a = 0; a < mesh.n_nodes(); ++a) {
    const Vec3 x = (mesh.nodes.col(a) - centre) / scale;
    for (int c = 0; c < 3; ++c) {
      if (!fixed[static_cast<size_t>(3 * a + c)]) continue;
      // Component c of the translations e_0..e_2 and of the rotations e_k x x.
      Eigen::Matrix<long double, 6, 1> r = Eigen::Matrix<long double, 6, 1>::Zero();
      r(c) = 1.0L;
      for (int k = 0; k < 3; ++k)
        r(3 + k) = static_cast<long double>(Vec3::Unit(k).cross(x)(c));
      gram += r * r.transpose();
    }
  }
  const Eigen::Matrix<Real, 6, 6> g = gram.cast<Real>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, 6, 6>> eig(g, Eigen::EigenvaluesOnly);
  const Real lmax = eig.eigenvalues().maxCoeff();
  Index n_free = 0;
  for (Index i = 0; i < 6; ++i)
    n_free += eig.eigenvalues()(i) <= 1e-12 * lmax ? 1 : 0;
  if (n_free == 0) return;
  std::vector<char> loose;  // components fixed nowhere
  for (int c = 0; c < 3; ++c)
    if (g(c, c) == 0.0) loose.push_back("xyz"[c]);
  std::string axes;
  for (size_t i = 0; i < loose.size(); ++i)
    axes += fmt::format("{}{}", i == 0 ? "" : i + 1 == loose.size() ? " or " : ", ", loose[i]);
  throw InputError(fmt::format(
      "{}: dirichlet: {} leave {} rigid motion(s) of the body free{}, so the stiffness matrix "
      "would be singular (not positive definite); fix enough components to hold the body, e.g. "
      "a [[dirichlet]] entry with components = \"xyz\" on one face",
      problem.source,
      problem.dirichlet.empty() ? "there is no [[dirichlet]] entry: the conditions"
                                : "the [[dirichlet]] conditions",
      n_free, axes.empty() ? "" : fmt::format(" (no {} component is fixed anywhere)", axes)));
}

}  // namespace

fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh) {
  std::vector<bool> fixed(static_cast<size_t>(3 * mesh.n_nodes()), false);
  for (size_t i = 0; i < problem.dirichlet.size(); ++i) {
    const auto& d = problem.dirichlet[i];
    for (Index f :
         tagged_faces(mesh, problem, fmt::format("dirichlet[{}].boundary", i), d.boundary))
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c)
          if (d.components[c]) fixed[static_cast<size_t>(3 * mesh.faces(v, f) + c)] = true;
  }
  fe::DofMap dofs(fixed);
  if (dofs.n_free() == 0)
    throw InputError(fmt::format(
        "{}: dirichlet: the [[dirichlet]] conditions fix every displacement component of the "
        "mesh: nothing to solve",
        problem.source));
  check_rigid_motions(problem, mesh, fixed);
  return dofs;
}

mesh::TetMesh make_mesh(const Problem& problem) {
  if (problem.mesh.kind != "brick")
    throw InputError(
        fmt::format("{}: mesh.kind: unknown kind '{}'", problem.source, problem.mesh.kind));
  mesh::BrickSpec spec;
  spec.size = Vec3(problem.mesh.size[0], problem.mesh.size[1], problem.mesh.size[2]);
  spec.cells = problem.mesh.cells;
  mesh::TetMesh m = mesh::make_brick(spec);
  // A brick's elements can only be degenerate through its sizes and cell counts.
  mesh::check_mesh(m, fmt::format("{}: mesh.size = [{}, {}, {}], mesh.cells = [{}, {}, {}]",
                                  problem.source, spec.size(0), spec.size(1), spec.size(2),
                                  spec.cells[0], spec.cells[1], spec.cells[2]));
  return m;
}

Model assemble_model(const Problem& problem, PhaseTimes& times,
                     const std::function<void(const std::string&)>& on_phase_start) {
  Model model;
  if (on_phase_start) on_phase_start("mesh");
  {
    ScopedPhase phase(times, "mesh");
    model.mesh = make_mesh(problem);
    model.material = make_material(problem);
  }
  if (on_phase_start) on_phase_start("assembly");
  {
    ScopedPhase phase(times, "assembly");
    model.dofs = make_dofs(problem, model.mesh);
    model.K = fe::assemble_stiffness(model.mesh, model.material, model.dofs);
    model.f = full_load(problem, model.mesh, model.dofs);
  }
  return model;
}

void factorize_model(Model& model, PhaseTimes& times,
                     const std::function<void(const std::string&)>& on_phase_start,
                     const std::vector<Index>& last) {
  if (on_phase_start) on_phase_start("factorize");
  ScopedPhase phase(times, "factorize");
  model.factor.factorize(model.K, last);
}

Model build_model(const Problem& problem, PhaseTimes& times,
                  const std::function<void(const std::string&)>& on_phase_start) {
  Model model = assemble_model(problem, times, on_phase_start);
  factorize_model(model, times, on_phase_start);
  return model;
}

Vec3 applied_force_total(const Problem& problem, const mesh::TetMesh& mesh) {
  const fe::DofMap all(mesh.n_nodes());
  return all.to_nodal(full_load(problem, mesh, all)).rowwise().sum();
}

Vec3 reaction_total(const Model& model, const Problem& problem, const fe::NodalField& u) {
  const fe::DofMap all(model.mesh.n_nodes());
  const fe::NodalField load = all.to_nodal(full_load(problem, model.mesh, all));
  const fe::NodalField internal = fe::internal_forces(model.mesh, model.material, u);
  Vec3 r = Vec3::Zero();
  for (Index a = 0; a < model.mesh.n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      if (model.dofs.is_fixed(a, c)) r(c) += internal(c, a) - load(c, a);
  return r;
}

}  // namespace fricon::driver
