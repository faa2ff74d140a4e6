#pragma once
// fe: stresses of a P1 displacement, constant per tetrahedron.

#include "fricon/core/types.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

struct StressField {
  /// Per tetrahedron: stress in Voigt order 11,22,33,23,13,12 [Pa], 6 x n_tets.
  Eigen::Matrix<Real, 6, Eigen::Dynamic> stress;
  VectorXd von_mises;  ///< per tetrahedron [Pa]
};

/// sigma = D eps(u) on every tetrahedron, and its von Mises equivalent, for a nodal displacement
/// u (3 x n_nodes) [m].
StressField compute_stresses(const mesh::TetMesh& mesh, Materials materials, const NodalField& u);

}  // namespace fricon::fe
