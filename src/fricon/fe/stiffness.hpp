#pragma once
// fe: the element stiffness of linear elasticity, K_e = int_T B^T D B dV, for any element of
// fe/element.hpp, by its stiffness points (exact on straight-sided cells; theory.md §2.1,
// §2.12).

#include "fricon/core/types.hpp"
#include "fricon/fe/element.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::fe {

/// Strain-displacement matrix at a point: Voigt strain (engineering shears) = B * (u of node 0
/// x, y, z, node 1, ...), from the shape functions' gradients along x, y, z (n_nodes x 3).
using StrainMatrix = Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, kMaxElementDofs>;
StrainMatrix strain_matrix(const ShapeDerivatives& grad);

/// Element stiffness matrix [N/m] of the cell with node coordinates x (in `element`'s node
/// order), ordered as strain_matrix's columns. Throws NumericalError where the map's determinant
/// is not positive (check_jacobians names the tetrahedron first).
ElementMatrix element_stiffness(const Element& element, const ElementNodes& x,
                                const Material& material);

}  // namespace fricon::fe
