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

/// The coefficients of a rigid motion over the six modes: translations along x, y, z [m] and
/// rotations about the axes x, y, z through a centre [rad], r(x) = t + w x (x - centre).
using MotionCoefficients = Eigen::Matrix<Real, 6, 1>;

struct RigidMotionCheck {
  Index n_free = 0;            ///< rigid motions (of six) the fixed dofs leave free
  std::string loose_axes;      ///< components fixed nowhere, e.g. "x or y" (empty if none)
  Index n_fixed = 0;           ///< fixed dofs among the nodes checked (0: nothing holds them)
  Vec3 centre = Vec3::Zero();  ///< the centre of the rotations [m]: of the nodes' bounding box
  /// The free motions, n_free columns of MotionCoefficients about `centre`, in reduced echelon
  /// form over the modes in the order tx, ty, tz, rx, ry, rz: a translation or rotation that is
  /// free alone is a unit column (theory.md §2.10).
  Eigen::Matrix<Real, 6, Eigen::Dynamic> free;
};

/// A free motion in words: "translation z", "rotation about x", or its coefficients for a
/// combination ("0.71 tx + 0.71 ty").
std::string describe_motion(const MotionCoefficients& c);

/// The displacement [m] of the rigid motion `c` about `centre` at the point x [m].
Vec3 motion_at(const MotionCoefficients& c, const Vec3& centre, const Vec3& x);

/// The rigid motions of the nodes `nodes` (one body, e.g. mesh::Bodies::nodes[b]; indices into
/// mesh.nodes) that `fixed` (3 n_nodes flags over the whole mesh, node-major) leaves free: the
/// null space of the 6x6 Gram matrix of the rigid modes at the fixed dofs of those nodes (their
/// coordinates centred and scaled by their bounding box, accumulated in long double; eigenvalues
/// below 1e-12 of the largest count as zero). With no fixed dof, all six are free. The null
/// space's basis is returned in RigidMotionCheck::free.
RigidMotionCheck free_rigid_motions(const mesh::TetMesh& mesh, const std::vector<Index>& nodes,
                                    const std::vector<bool>& fixed);

/// free_rigid_motions of each body of `bodies` (found on `mesh`): one check per body, in order.
std::vector<RigidMotionCheck> free_rigid_motions(const mesh::TetMesh& mesh,
                                                 const mesh::Bodies& bodies,
                                                 const std::vector<bool>& fixed);

}  // namespace fricon::fe
