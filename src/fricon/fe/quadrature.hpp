#pragma once
// fe: quadrature rules on the simplices: the small symmetric rules of the elements' stiffness
// and mass (fe/element.hpp), and Gauss-Legendre and conical-product (collapsed-coordinate) rules
// for higher degrees and integrals that are not polynomial (manufactured loads, error norms).

#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::fe {

struct QuadratureRule {
  /// Points in barycentric coordinates (one column per point, entries sum to 1).
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> points;
  /// Weights as fractions of the simplex measure (they sum to 1).
  VectorXd weights;
};

/// Gauss-Legendre rule with n points on [0, 1] (points as a 2 x n barycentric (1-s, s) matrix).
QuadratureRule gauss_legendre(int n);

/// Collapsed Gauss rule on the tetrahedron with n points per direction (n^3 points); exact for
/// polynomials of total degree <= 2n - 3 at least.
QuadratureRule tet_rule(int n);

/// Collapsed Gauss rule on the triangle with n points per direction (n^2 points); exact for
/// polynomials of total degree <= 2n - 2.
QuadratureRule triangle_rule(int n);

/// The centroid of the tetrahedron (degree 1).
QuadratureRule tet_centroid_rule();
/// The symmetric 4-point rule on the tetrahedron (degree 2).
QuadratureRule tet_degree2_rule();
/// The 3-point rule on the triangle at the points (2/3, 1/6, 1/6) and permutations (degree 2).
QuadratureRule triangle_degree2_rule();

}  // namespace fricon::fe
