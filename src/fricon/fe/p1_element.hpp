#pragma once
// fe: the linear tetrahedron. Gradients of the barycentric (P1) shape functions, the constant
// strain-displacement matrix and the element stiffness K_e = |T| B^T D B (theory.md §2.1).

#include "fricon/core/types.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::fe {

using ElementMatrix = Eigen::Matrix<Real, 12, 12>;
using Strain6x12 = Eigen::Matrix<Real, 6, 12>;

/// Vertices of one tetrahedron, one column each [m].
using TetVertices = Eigen::Matrix<Real, 3, 4>;

/// Gradients [1/m] of the four P1 shape functions (one column per vertex) and the volume [m^3].
/// Requires a non-degenerate tetrahedron (throws NumericalError otherwise).
struct P1Gradients {
  Eigen::Matrix<Real, 3, 4> grad;
  Real volume = 0.0;
};
P1Gradients p1_gradients(const TetVertices& x);

/// Strain-displacement matrix: Voigt strain (engineering shears) = B * (u of vertex 0 x,y,z, ...).
Strain6x12 strain_matrix(const Eigen::Matrix<Real, 3, 4>& grad);

/// Element stiffness matrix [N/m], ordered as strain_matrix's columns.
ElementMatrix element_stiffness(const TetVertices& x, const Material& material);

}  // namespace fricon::fe
