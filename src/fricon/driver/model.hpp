#pragma once
// driver: the discrete elastic model of a problem, built phase by phase in data-flow order:
// mesh -> dofs (Dirichlet elimination) -> K and f (assembly) -> Cholesky factor of K.
// Everything later (contact, the dual QP, the outer loop) reads this model and never changes it.

#include <functional>
#include <string>
#include <vector>

#include "fricon/core/timer.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::driver {

struct Model {
  mesh::TetMesh mesh;
  fe::Material material;
  fe::DofMap dofs{0};
  SparseMatrix K;                 ///< stiffness over the free dofs [N/m]
  VectorXd f;                     ///< load vector over the free dofs [N]
  linalg::CholeskyFactor factor;  ///< Cholesky factor of K
};

/// Builds the mesh the problem describes and checks it. Throws InputError on bad input.
mesh::TetMesh make_mesh(const Problem& problem);

/// The dofs left free by the problem's Dirichlet conditions. Throws InputError when a boundary
/// tag does not exist on the mesh or nothing is left free.
fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh);

/// Builds the whole model: mesh, material, dofs, K, f and the factor of K. Times the phases
/// "mesh", "assembly" and "factorize" into `times`. Throws InputError when a boundary tag named
/// by the problem does not exist on the mesh, and NumericalError when K is singular.
/// The model up to the factorization: mesh, material, dofs, K and f (phases "mesh", "assembly").
Model assemble_model(const Problem& problem, PhaseTimes& times,
                     const std::function<void(const std::string&)>& on_phase_start = {});

/// Factorizes K (phase "factorize"); with `last` non-empty, those dofs are ordered last so that
/// the factor's trailing block is the Cholesky factor of the Schur complement onto them.
void factorize_model(Model& model, PhaseTimes& times,
                     const std::function<void(const std::string&)>& on_phase_start = {},
                     const std::vector<Index>& last = {});

/// assemble_model then factorize_model.
/// `on_phase_start`, if set, is called with each phase's name as it starts.
Model build_model(const Problem& problem, PhaseTimes& times,
                  const std::function<void(const std::string&)>& on_phase_start = {});

/// Sum of all applied forces [N] (tractions and volume force), including the parts acting on
/// fixed dofs, in each direction.
Vec3 applied_force_total(const Problem& problem, const mesh::TetMesh& mesh);

/// Reaction forces [N] at the fixed dofs for a displacement field u (3 x n_nodes): the internal
/// force minus the applied load there, summed over the mesh.
Vec3 reaction_total(const Model& model, const Problem& problem, const fe::NodalField& u);

}  // namespace fricon::driver
