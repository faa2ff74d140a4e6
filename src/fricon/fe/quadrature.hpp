#pragma once
// fe: quadrature rules for integrals that are not polynomial (manufactured loads, error norms).
// Gauss-Legendre on [0,1] and conical-product (collapsed-coordinate) rules on the tetrahedron,
// exact for polynomials up to degree 2 n_points - 1 in each direction.

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

}  // namespace fricon::fe
