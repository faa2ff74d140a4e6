// The friction cone: its projection against the definition (the nearest point of the cone,
// found by search), and the Coulomb residual at points where it must vanish.
#include "fricon/qp/friction_cone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace fricon::qp {
namespace {

// The distance from x to the cone, by a search over its boundary rays (1, mu cos a, mu sin a).
Real distance_by_search(const Vec3& x, Real mu) {
  if (x.tail<2>().norm() <= mu * x(0)) return 0.0;  // inside
  Real best = x.norm();                             // the apex
  for (int i = 0; i <= 400; ++i) {
    const Real a = 2 * std::numbers::pi * i / 400;
    const Vec3 dir(1.0, mu * std::cos(a), mu * std::sin(a));  // a boundary ray
    const Real s = std::max(0.0, x.dot(dir) / dir.squaredNorm());
    best = std::min(best, (x - s * dir).norm());
  }
  return best;
}

TEST(FrictionCone, ProjectionIsTheNearestPointOfTheCone) {
  std::mt19937 rng(5);
  std::normal_distribution<Real> n01;
  for (int k = 0; k < 200; ++k) {
    const Vec3 x(n01(rng), n01(rng), n01(rng));
    const Real mu = std::abs(n01(rng));
    const Vec3 p = project_friction_cone(x, mu);
    EXPECT_LE(p.tail<2>().norm(), mu * p(0) * (1 + 1e-12) + 1e-15);                // in the cone
    EXPECT_LT((project_friction_cone(p, mu) - p).norm(), 1e-12 * (1 + p.norm()));  // idempotent
    EXPECT_LE((x - p).norm(), distance_by_search(x, mu) + 1e-12);  // nearest, to the search
    EXPECT_GE((x - p).norm(), distance_by_search(x, mu) - 1e-3 * (1 + x.norm()));
  }
  EXPECT_EQ(project_friction_cone(Vec3(-1, 0.1, 0), 0.5), Vec3::Zero());  // polar cone
  EXPECT_EQ(project_friction_cone(Vec3(1, 3, 4), 0.0), Vec3(1, 0, 0));    // mu = 0: the ray
}

TEST(FrictionCone, ResidualVanishesAtCoulombSolutions) {
  // One patch each: sticking (l inside the cone, g = 0), sliding (l on the cone, in contact:
  // g_n = 0, and g_t opposite to l_t) and separated (l = 0, g_n + mu ||g_t|| >= mu ||g_t||).
  const Real mu = 0.4;
  VectorXd l(9), g(9);
  l << 2.0, 0.1, -0.2, /**/ 2.0, 0.8 * 0.6, 0.8 * 0.8, /**/ 0.0, 0.0, 0.0;
  g << 0.0, 0.0, 0.0, /**/ 0.0, -5.0 * 0.6, -5.0 * 0.8, /**/ 3.0, 1.0, 1.0;
  const VectorXd m = VectorXd::Constant(3, mu);
  EXPECT_LT(coulomb_residual(l, g, m, 0.7), 1e-15);
  // A sliding patch whose friction points the wrong way is not a solution.
  VectorXd wrong = g;
  wrong.segment<2>(4) *= -1.0;
  EXPECT_GT(coulomb_residual(l, wrong, m, 0.7), 1e-2);
}

}  // namespace
}  // namespace fricon::qp
