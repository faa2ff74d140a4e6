#pragma once
// fe: the floating bodies of a model (theory.md §2.10): the bodies whose Dirichlet conditions
// leave rigid motions free, their free motions as the columns of R over the free dofs (K R = 0),
// and the regularization of K that makes its factor a generalized inverse K^+ (K K^+ K = K):
//
//   K_reg = K + rho R_I (R_I^T R_I)^-1 R_I^T,
//
// R_I the rows of R at a few dofs I of each floating body (those of three far-apart nodes) and
// zero elsewhere, rho the mean diagonal of K at I (PERMON's MatRegularize; Brzobohaty et al.
// 2011). K_reg is positive definite and sparse (a dense block on I only), and its inverse is a
// generalized inverse of K: K K_reg^-1 K = K.

#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/rigid_motions.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

/// One body whose Dirichlet conditions leave rigid motions free.
struct FloatingBody {
  Index body = 0;              ///< its index in mesh::Bodies
  Vec3 centre = Vec3::Zero();  ///< the centre of its rotations [m]
  /// Its free motions (RigidMotionCheck::free): one column of coefficients per motion.
  Eigen::Matrix<Real, 6, Eigen::Dynamic> motions;
  Index first_column = 0;  ///< the column of R of its first motion
  /// The free dofs where K is regularized (those of three far-apart nodes of the body).
  std::vector<Index> regularization_dofs;

  Index n_motions() const { return motions.cols(); }
  /// Motion j in words (describe_motion).
  std::string motion_name(Index j) const;
};

struct FloatingBodies {
  std::vector<FloatingBody> bodies;
  /// n_free x n_motions: column j is free motion j sampled at the free dofs [m per unit
  /// amplitude: m of a translation, rad of a rotation]; K R = 0.
  SparseMatrix R;

  bool empty() const { return bodies.empty(); }
  Index n_motions() const { return R.cols(); }
};

/// The floating bodies of `mesh` (its connected bodies `bodies`) under the Dirichlet conditions
/// of `dofs`: each body with a free rigid motion (free_rigid_motions), its motions as columns of
/// R and its regularization dofs. Empty when every body is held.
FloatingBodies find_floating_bodies(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                                    const DofMap& dofs);

/// K_reg = K + rho R_I (R_I^T R_I)^-1 R_I^T over the floating bodies (K itself when there is
/// none), K with both triangles stored. Throws Error if the regularization dofs of a body do not
/// determine its motions (R_I^T R_I singular).
SparseMatrix regularized_stiffness(const SparseMatrix& K, const FloatingBodies& floating);

}  // namespace fricon::fe
