// Unit tests of the KKT residuals against values worked out by hand.

#include "fricon/qp/kkt.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "fricon/core/error.hpp"

namespace fricon::qp {
namespace {

SeparableConstraints one_bound() {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Bound, 0}};
  c.radius = Eigen::VectorXd::Zero(1);
  return c;
}

SeparableConstraints one_disc(double rho) {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Disc, 0}};
  c.radius = Eigen::VectorXd::Constant(1, rho);
  return c;
}

SeparableConstraints one_free() {
  SeparableConstraints c;
  c.append_free(1);
  return c;
}

KktResiduals free_unknown(double x, double g) {
  return kkt_residuals(Eigen::VectorXd::Constant(1, x), Eigen::VectorXd::Constant(1, g), one_free(),
                       1.0, 1.0);
}

KktResiduals bound(double x, double g) {
  return kkt_residuals(Eigen::VectorXd::Constant(1, x), Eigen::VectorXd::Constant(1, g),
                       one_bound(), 1.0, 1.0);
}

KktResiduals disc(double rho, double x1, double x2, double g1, double g2) {
  return kkt_residuals(Eigen::Vector2d(x1, x2), Eigen::Vector2d(g1, g2), one_disc(rho), 1.0, 1.0);
}

void expect_kkt(const KktResiduals& r, double feas, double stat, double comp) {
  EXPECT_NEAR(r.feasibility, feas, 1e-14);
  EXPECT_NEAR(r.stationarity, stat, 1e-14);
  EXPECT_NEAR(r.complementarity, comp, 1e-14);
}

TEST(KktResiduals, BoundBlockHandValues) {
  expect_kkt(bound(0.0, 2.0), 0, 0, 0);    // active, g >= 0: optimal
  expect_kkt(bound(1.5, 0.0), 0, 0, 0);    // free, g = 0: optimal
  expect_kkt(bound(0.0, -3.0), 0, 3, 0);   // could increase x: stationarity violated
  expect_kkt(bound(2.0, 0.5), 0, 0, 1.0);  // free with a multiplier: complementarity
  expect_kkt(bound(-0.5, 2.0), 0.5, 0, 1.0);
}

TEST(KktResiduals, DiscBlockHandValues) {
  // On the circle of radius 5 at (3, 4); outward normal (0.6, 0.8).
  expect_kkt(disc(5, 3, 4, -1.2, -1.6), 0, 0, 0);  // g = -2 eta: optimal
  expect_kkt(disc(5, 3, 4, 0.8, -0.6), 0, 1, 0);   // tangential g
  expect_kkt(disc(5, 3, 4, 1.2, 1.6), 0, 2, 0);    // -g points inward: not a normal-cone element
  // g = -2 eta + tangential 0.5: the tangential part is the distance to the ray.
  expect_kkt(disc(5, 3, 4, -1.2 + 0.4, -1.6 - 0.3), 0, 0.5, 0);
  // Interior point (0.3, 0.4) with g = -2 eta: multiplier 2 times gap 4.5.
  expect_kkt(disc(5, 0.3, 0.4, -1.2, -1.6), 0, 0, 9.0);
  expect_kkt(disc(5, 0.3, 0.4, 0, 0), 0, 0, 0);
  // Centre of a disc with rho > 0: the normal cone is {0}.
  expect_kkt(disc(5, 0, 0, 1, 1), 0, std::sqrt(2.0), 0);
  // Outside: (6, 8) has norm 10 > 5; g = -eta: multiplier 1 times |5 - 10|.
  expect_kkt(disc(5, 6, 8, -0.6, -0.8), 5, 0, 5);
  // Pinned disc: any gradient is balanced by the constraint.
  expect_kkt(disc(0, 0, 0, 3, -7), 0, 0, 0);
}

TEST(KktResiduals, FreeBlockHandValues) {
  // No constraint: every x is feasible, the optimum needs g = 0 whatever the sign of x, and there
  // is no multiplier for a complementarity residual.
  expect_kkt(free_unknown(-3.0, 0.0), 0, 0, 0);
  expect_kkt(free_unknown(2.0, 0.0), 0, 0, 0);
  expect_kkt(free_unknown(-3.0, 0.5), 0, 0.5, 0);  // a bound would see x < 0 and x g != 0
  expect_kkt(free_unknown(2.0, -1.5), 0, 1.5, 0);
  expect_kkt(free_unknown(0.0, 4.0), 0, 4, 0);  // a bound at 0 with g > 0 would be optimal
}

// A contact patch followed by two Free blocks: the free stationarity enters the maximum, the free
// unknowns neither feasibility nor complementarity.
TEST(KktResiduals, FreeBlocksAmongContactBlocks) {
  auto c = SeparableConstraints::contact_layout(1);
  c.set_disc_radii(Eigen::VectorXd::Constant(1, 1.0));
  c.append_free(2);
  Eigen::VectorXd x(5), g(5);
  x << 1.0, 0.0, 0.0, -50.0, 7.0;  // bound inactive, disc centre, free anything
  g << 0.0, 0.0, 0.0, 0.25, -3.0;
  const auto r = kkt_residuals(x, g, c, 2.0, 10.0);
  EXPECT_EQ(r.feasibility, 0.0);
  EXPECT_NEAR(r.stationarity, 3.0 / 10.0, 1e-15);
  EXPECT_EQ(r.complementarity, 0.0);
  // At g = 0 on the free unknowns the point is optimal.
  g.tail<2>().setZero();
  EXPECT_EQ(kkt_residuals(x, g, c, 2.0, 10.0).max(), 0.0);
}

TEST(KktResiduals, MaximaAreScaled) {
  const auto c = SeparableConstraints::contact_layout(2);
  auto cc = c;
  cc.set_disc_radii(Eigen::Vector2d(1.0, 1.0));
  // Patch 0: bound stationarity 3; patch 1: disc on the circle with tangential g 4.
  Eigen::VectorXd x(6), g(6);
  x << 0, 0, 0, 2.0, 1, 0;
  g << -3, 0, 0, 0.5, 0, 4;
  const auto r = kkt_residuals(x, g, cc, 2.0, 10.0);
  EXPECT_NEAR(r.feasibility, 0.0, 1e-15);
  EXPECT_NEAR(r.stationarity, 4.0 / 10.0, 1e-15);
  EXPECT_NEAR(r.complementarity, 1.0 / 20.0, 1e-15);  // |2 * 0.5| / (2 * 10)
  EXPECT_NEAR(r.max(), 0.4, 1e-15);
}

TEST(KktResiduals, DefaultScalesAndConvenienceOverload) {
  auto c = SeparableConstraints::contact_layout(1);
  c.set_disc_radii(Eigen::VectorXd::Constant(1, 3.0));
  const Eigen::Vector3d x(0.5, 0.0, 0.0), b(4.0, 0.0, 3.0);
  const auto s = default_kkt_scales(x, b, c);
  EXPECT_EQ(s.x, 3.0);
  EXPECT_EQ(s.g, 5.0);
  const auto s0 = default_kkt_scales(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                     SeparableConstraints::contact_layout(1));
  EXPECT_EQ(s0.x, 1.0);
  EXPECT_EQ(s0.g, 1.0);
  // A = 2 I: optimum x = (2, 0, 1.5) (b/2 is inside the disc); check zero residuals.
  const Operator A = [](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = 2.0 * v; };
  const auto r = kkt_residuals(A, b, Eigen::Vector3d(2.0, 0.0, 1.5), c);
  EXPECT_LE(r.max(), 1e-15);
  const auto r2 = kkt_residuals(A, b, Eigen::Vector3d(2.0, 0.0, 1.0), c);
  // x_t = (0, 1) is inside the disc but g_t = (0, -1) pushes outward: multiplier 1 times gap 2
  // shows up as complementarity (g_t is on the ray {-s eta}, so stationarity is 0).
  EXPECT_NEAR(r2.stationarity, 0.0, 1e-15);
  EXPECT_NEAR(r2.complementarity, 2.0 / 15.0, 1e-15);
}

TEST(KktResiduals, RejectsBadScalesAndSizes) {
  const auto c = one_bound();
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(kkt_residuals(v, v, c, 0.0, 1.0), InputError);
  EXPECT_THROW(kkt_residuals(v, v, c, 1.0, NAN), InputError);
  EXPECT_THROW(kkt_residuals(Eigen::VectorXd::Zero(2), v, c, 1.0, 1.0), InputError);
}

}  // namespace
}  // namespace fricon::qp
