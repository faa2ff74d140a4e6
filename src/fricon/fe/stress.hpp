#pragma once
// fe: stresses of a displacement field, per cell and recovered at the nodes (theory.md §2.12).

#include "fricon/core/types.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

using VoigtField = Eigen::Matrix<Real, 6, Eigen::Dynamic>;

struct StressField {
  /// Per tetrahedron: the stress at its centroid in Voigt order 11,22,33,23,13,12 [Pa],
  /// 6 x n_tets (the element's constant stress for 4-node tetrahedra).
  VoigtField stress;
  VectorXd von_mises;  ///< per tetrahedron, of `stress` [Pa]
  /// Per node: the stress recovered at the nodes, the mean over the elements that share the node
  /// of each element's stress evaluated there (6 x n_nodes) [Pa]. Unweighted averaging: exact
  /// for a field that the element reproduces (linear stress at order 2, constant at order 1).
  VoigtField nodal_stress;
  VectorXd nodal_von_mises;  ///< per node, of nodal_stress [Pa]
};

/// sigma = D eps(u) on every tetrahedron and recovered at the nodes, with the von Mises
/// equivalents, for a nodal displacement u (3 x n_nodes) [m].
StressField compute_stresses(const mesh::TetMesh& mesh, Materials materials, const NodalField& u);

/// The von Mises equivalent of a Voigt stress [Pa].
Real von_mises(const Eigen::Matrix<Real, 6, 1>& s);

}  // namespace fricon::fe
