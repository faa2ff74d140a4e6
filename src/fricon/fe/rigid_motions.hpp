#pragma once
// fe: whether Dirichlet conditions hold the body. K over the free dofs is singular exactly when
// a rigid motion r(x) = a + w x (x - c) vanishes at every fixed dof (the mesh being connected);
// this is checked before assembly so that the message can name the problem's keys.

#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

struct RigidMotionCheck {
  Index n_free = 0;        ///< rigid motions (of six) the fixed dofs leave free
  std::string loose_axes;  ///< components fixed nowhere, e.g. "x or y" (empty if none)
};

/// The rigid motions that `fixed` (3 n_nodes flags, node-major) leaves free: the null space of
/// the 6x6 Gram matrix of the rigid modes at the fixed dofs (centred and scaled coordinates,
/// accumulated in long double; eigenvalues below 1e-12 of the largest count as zero).
RigidMotionCheck free_rigid_motions(const mesh::TetMesh& mesh, const std::vector<bool>& fixed);

}  // namespace fricon::fe
