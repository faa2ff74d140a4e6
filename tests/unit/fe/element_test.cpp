// The P1 tetrahedron: gradients, symmetry, rigid-body kernel, quadrature exactness.
#include <gtest/gtest.h>

#include <cmath>

#include "fricon/fe/p1_element.hpp"
#include "fricon/fe/quadrature.hpp"

using namespace fricon;
using namespace fricon::fe;

namespace {
TetVertices skewed_tet() {
  TetVertices x;
  x << 0.1, 1.3, 0.2, 0.4,  //
      0.0, 0.2, 0.9, 0.3,   //
      0.05, 0.1, 0.2, 1.1;
  return x;
}

// The six rigid motions at the four vertices, as 12-vectors.
Eigen::Matrix<Real, 12, 6> rigid_modes(const TetVertices& x) {
  Eigen::Matrix<Real, 12, 6> R = Eigen::Matrix<Real, 12, 6>::Zero();
  for (int a = 0; a < 4; ++a) {
    for (int c = 0; c < 3; ++c)
      R(3 * a + c, c) = 1.0;
    for (int r = 0; r < 3; ++r) {
      Vec3 axis = Vec3::Zero();
      axis(r) = 1.0;
      R.block<3, 1>(3 * a, 3 + r) = axis.cross(Vec3(x.col(a)));
    }
  }
  return R;
}
}  // namespace

TEST(P1Element, GradientsReproduceLinearFunctions) {
  const TetVertices x = skewed_tet();
  const P1Gradients g = p1_gradients(x);
  const Vec3 slope(0.3, -1.2, 2.5);
  Eigen::Matrix<Real, 4, 1> values;
  for (int a = 0; a < 4; ++a)
    values(a) = slope.dot(x.col(a)) + 7.0;
  EXPECT_NEAR((g.grad * values - slope).norm(), 0.0, 1e-13);
  EXPECT_GT(g.volume, 0.0);
}

TEST(P1Element, StiffnessIsSymmetricWithRigidKernelOfRankSix) {
  const TetVertices x = skewed_tet();
  const ElementMatrix K = element_stiffness(x, isotropic(2e11, 0.3));
  EXPECT_NEAR((K - K.transpose()).norm() / K.norm(), 0.0, 1e-15);
  EXPECT_NEAR((K * rigid_modes(x)).norm() / K.norm(), 0.0, 1e-14);
  Eigen::SelfAdjointEigenSolver<ElementMatrix> eig(K);
  // Exactly six zero eigenvalues, six positive ones.
  for (int i = 0; i < 6; ++i)
    EXPECT_LT(std::abs(eig.eigenvalues()(i)), 1e-6 * K.norm());
  for (int i = 6; i < 12; ++i)
    EXPECT_GT(eig.eigenvalues()(i), 1e-6 * K.norm());
}

TEST(P1Element, EnergyOfUniformStrainMatchesHandValue) {
  // A uniform extension u = (e x, 0, 0) stores |T| (lambda + 2 mu) e^2 / 2.
  const TetVertices x = skewed_tet();
  const Real E = 1e9, nu = 0.25, e = 1e-3;
  const ElementMatrix K = element_stiffness(x, isotropic(E, nu));
  Eigen::Matrix<Real, 12, 1> u = Eigen::Matrix<Real, 12, 1>::Zero();
  for (int a = 0; a < 4; ++a)
    u(3 * a) = e * x(0, a);
  const auto [lambda, mu] = lame(E, nu);
  EXPECT_NEAR(0.5 * u.dot(K * u), 0.5 * p1_gradients(x).volume * (lambda + 2 * mu) * e * e,
              1e-12 * E * e * e);
}

TEST(Quadrature, GaussLegendreIsExact) {
  for (int n = 1; n <= 8; ++n) {
    const QuadratureRule r = gauss_legendre(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      Real sum = 0;
      for (int q = 0; q < n; ++q)
        sum += r.weights(q) * std::pow(r.points(1, q), p);
      EXPECT_NEAR(sum, 1.0 / (p + 1), 1e-14) << "n = " << n << ", degree " << p;
    }
  }
}

TEST(Quadrature, TetRuleIntegratesMonomials) {
  // Over the unit simplex, the mean of l1^a l2^b l3^c is a! b! c! 3! / (a+b+c+3)!.
  const QuadratureRule r = tet_rule(4);
  EXPECT_NEAR(r.weights.sum(), 1.0, 1e-14);
  auto fact = [](int k) { return std::tgamma(k + 1.0); };
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; b <= 3 - a; ++b)
      for (int c = 0; c <= 3 - a - b; ++c) {
        Real sum = 0;
        for (Index q = 0; q < r.weights.size(); ++q)
          sum += r.weights(q) * std::pow(r.points(1, q), a) * std::pow(r.points(2, q), b) *
                 std::pow(r.points(3, q), c);
        EXPECT_NEAR(sum, fact(a) * fact(b) * fact(c) * 6.0 / fact(a + b + c + 3), 1e-14);
      }
}
