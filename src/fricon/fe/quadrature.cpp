#include "fricon/fe/quadrature.hpp"

#include <cmath>
#include <numbers>

#include "fricon/core/error.hpp"

namespace fricon::fe {

QuadratureRule gauss_legendre(int n) {
  FRICON_CHECK(n >= 1 && n <= 64, "Gauss-Legendre with " << n << " points");
  QuadratureRule rule;
  rule.points.resize(2, n);
  rule.weights.resize(n);
  // Newton's method on the Legendre polynomial P_n from Chebyshev-like starting values.
  for (int i = 0; i < n; ++i) {
    Real x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    Real dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      Real p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const Real p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const Real pn = n == 1 ? x : p1;
      const Real pn1 = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pn1) / (x * x - 1.0);
      const Real dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const Real s = 0.5 * (1.0 - x);  // map [-1,1] to [0,1]
    rule.points(0, i) = 1.0 - s;
    rule.points(1, i) = s;
    rule.weights(i) = 1.0 / ((1.0 - x * x) * dp * dp);  // half the [-1,1] weight 2/((1-x^2)P'^2)
  }
  return rule;
}

QuadratureRule tet_rule(int n) {
  const QuadratureRule g = gauss_legendre(n);
  QuadratureRule rule;
  rule.points.resize(4, n * n * n);
  rule.weights.resize(n * n * n);
  int q = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Real u = g.points(1, i), v = g.points(1, j), w = g.points(1, k);
        // Collapsed coordinates: xi1 = u, xi2 = v(1-u), xi3 = w(1-u)(1-v); Jacobian (1-u)^2(1-v),
        // reference volume 1/6, so the weight as a volume fraction is 6 (1-u)^2 (1-v) w_i w_j w_k.
        const Real x1 = u, x2 = v * (1.0 - u), x3 = w * (1.0 - u) * (1.0 - v);
        rule.points(0, q) = 1.0 - x1 - x2 - x3;
        rule.points(1, q) = x1;
        rule.points(2, q) = x2;
        rule.points(3, q) = x3;
        rule.weights(q) =
            6.0 * (1.0 - u) * (1.0 - u) * (1.0 - v) * g.weights(i) * g.weights(j) * g.weights(k);
        ++q;
      }
  return rule;
}

QuadratureRule triangle_rule(int n) {
  const QuadratureRule g = gauss_legendre(n);
  QuadratureRule rule;
  rule.points.resize(3, n * n);
  rule.weights.resize(n * n);
  int q = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // Collapsed coordinates: xi1 = u, xi2 = v (1 - u); Jacobian (1 - u), reference area 1/2.
      const Real u = g.points(1, i), v = g.points(1, j);
      rule.points(0, q) = 1.0 - u - v * (1.0 - u);
      rule.points(1, q) = u;
      rule.points(2, q) = v * (1.0 - u);
      rule.weights(q) = 2.0 * (1.0 - u) * g.weights(i) * g.weights(j);
      ++q;
    }
  return rule;
}

QuadratureRule tet_centroid_rule() {
  QuadratureRule rule;
  rule.points = MatrixXd::Constant(4, 1, 0.25);
  rule.weights = VectorXd::Ones(1);
  return rule;
}

QuadratureRule tet_degree2_rule() {
  // Points (a, b, b, b) and permutations with b = (5 - sqrt 5) / 20, a = 1 - 3 b; weights 1/4.
  const Real b = (5.0 - std::sqrt(5.0)) / 20.0;
  const Real a = 1.0 - 3.0 * b;
  QuadratureRule rule;
  rule.points = MatrixXd::Constant(4, 4, b);
  rule.points.diagonal().setConstant(a);
  rule.weights = VectorXd::Constant(4, 0.25);
  return rule;
}

QuadratureRule triangle_degree2_rule() {
  constexpr Real kNear = 2.0 / 3.0, kFar = 1.0 / 6.0;
  QuadratureRule rule;
  rule.points = MatrixXd::Constant(3, 3, kFar);
  rule.points.diagonal().setConstant(kNear);
  rule.weights = VectorXd::Constant(3, 1.0 / 3.0);
  return rule;
}

}  // namespace fricon::fe
