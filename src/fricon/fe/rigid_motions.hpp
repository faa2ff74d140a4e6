#pragma once
// fe: whether Dirichlet conditions hold each body (theory.md §2.1). The stiffness matrix of one
// connected body (mesh/bodies.hpp) over its free dofs is singular exactly when a rigid motion
// r(x) = a + w x (x - c) vanishes at every fixed dof of that body; K of the whole mesh is block
// diagonal over its bodies, so it is positive definite exactly when every body is held. This is
// checked before assembly so that the message can name the problem's keys and the free body.

#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

struct RigidMotionCheck {
  Index n_free = 0;        ///< rigid motions (of six) the fixed dofs leave free
  std::string loose_axes;  ///< components fixed nowhere, e.g. "x or y" (empty if none)
  Index n_fixed = 0;       ///< fixed dofs among the nodes checked (0: nothing holds them)
};

/// The rigid motions of the nodes `nodes` (one body, e.g. mesh::Bodies::nodes[b]; indices into
/// mesh.nodes) that `fixed` (3 n_nodes flags over the whole mesh, node-major) leaves free: the
/// null space of the 6x6 Gram matrix of the rigid modes at the fixed dofs of those nodes (their
/// coordinates centred and scaled by their bounding box, accumulated in long double; eigenvalues
/// below 1e-12 of the largest count as zero). With no fixed dof, all six are free.
RigidMotionCheck free_rigid_motions(const mesh::TetMesh& mesh, const std::vector<Index>& nodes,
                                    const std::vector<bool>& fixed);

/// free_rigid_motions of each body of `bodies` (found on `mesh`): one check per body, in order.
std::vector<RigidMotionCheck> free_rigid_motions(const mesh::TetMesh& mesh,
                                                 const mesh::Bodies& bodies,
                                                 const std::vector<bool>& fixed);

}  // namespace fricon::fe
