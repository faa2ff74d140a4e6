// The scaled QP (qp/scaling.hpp, theory.md §4.5) and the stopping test on the resisted part of b
// (§4.2), checked against references computed here: a FISTA solve of the unscaled problem
// (qp_test_problems.hpp) and KKT residuals from the matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fricon/core/error.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/scaling.hpp"
#include "qp_test_problems.hpp"

using namespace fricon;
using namespace fricon::qp;
using fricon::qp::testing::dense_operator;

namespace {

// A contact QP whose patches live on very different scales, as a graded mesh's do: M = S M0 S
// with S the patch factors s_p = 10^u_p, u uniform in [-1, 1] (so the diagonal of M spans
// four decades), b = S b0, and radii of the scaled size.
struct GradedProblem {
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
  SeparableConstraints c;
  Eigen::VectorXd patch_factor;  ///< 1 / s_p: the factor that undoes the grading
};

GradedProblem graded_problem(Index n_patches, unsigned seed) {
  std::mt19937 rng(seed);
  const Eigen::MatrixXd M0 = qp::testing::random_spd(3 * n_patches, 30.0, rng);
  const Eigen::VectorXd b0 = qp::testing::random_vector(3 * n_patches, rng);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd s(3 * n_patches);
  GradedProblem p;
  p.patch_factor.resize(2 * n_patches);
  for (Index k = 0; k < n_patches; ++k) {
    const double sk = std::pow(10.0, U(rng));
    s.segment<3>(3 * k).setConstant(sk);
    p.patch_factor(2 * k) = p.patch_factor(2 * k + 1) = 1.0 / sk;
  }
  p.M = s.asDiagonal() * M0 * s.asDiagonal();
  p.b = s.cwiseProduct(b0);
  p.c = qp::testing::random_contact_constraints(p.M, p.b, rng);
  return p;
}

MpgpOptions tight(double rtol) {
  MpgpOptions o;
  o.rel_tolerance = rtol;
  return o;
}

}  // namespace

TEST(BlockScaling, ScaledConstraintsKeepBoundsAndShrinkDiscsByTheirFactor) {
  SeparableConstraints c = SeparableConstraints::contact_layout(2);
  c.set_disc_radii(Eigen::Vector2d(3.0, 0.0));
  const BlockScaling D = BlockScaling::per_block(c, Eigen::Vector4d(2.0, 2.0, 5.0, 5.0));
  EXPECT_EQ(D.d(), (Eigen::VectorXd(6) << 2, 2, 2, 5, 5, 5).finished());
  const SeparableConstraints s = D.scaled(c);
  EXPECT_DOUBLE_EQ(s.radius(0), 0.0);  // the bound block keeps no radius
  EXPECT_DOUBLE_EQ(s.radius(1), 1.5);
  EXPECT_DOUBLE_EQ(s.radius(3), 0.0);
  const Eigen::VectorXd x = (Eigen::VectorXd(6) << 1, 2, 3, 4, 5, 6).finished();
  EXPECT_EQ(D.from_scaled(D.to_scaled(x)), x);
}

TEST(BlockScaling, RejectsFactorsThatAreNotPositiveOrDoNotMatchTheBlocks) {
  const SeparableConstraints c = SeparableConstraints::contact_layout(1);
  EXPECT_THROW(BlockScaling::per_block(c, Eigen::Vector2d(1.0, 0.0)), InputError);
  EXPECT_THROW(BlockScaling::per_block(c, Eigen::Vector2d(1.0, NAN)), InputError);
  EXPECT_THROW(BlockScaling::per_block(c, Eigen::Vector3d(1.0, 1.0, 1.0)), InputError);
}

TEST(BlockScaling, ScaledSolveReachesTheSameMinimizerInFewerProducts) {
  const GradedProblem p = graded_problem(12, 5);
  const BlockScaling D = BlockScaling::per_block(p.c, p.patch_factor);
  // The reference: FISTA on the well-conditioned scaled problem, mapped back.
  const Eigen::MatrixXd M_scaled = D.d().asDiagonal() * p.M * D.d().asDiagonal();
  const Eigen::VectorXd y_reference =
      qp::testing::reference_solve(M_scaled, D.dual_to_scaled(p.b), D.scaled(p.c), 1e-14);
  Eigen::VectorXd x_scaled = Eigen::VectorXd::Zero(p.b.size());
  const MpgpReport scaled =
      solve_mpgp_scaled(dense_operator(p.M), p.b, p.c, D, tight(1e-10), x_scaled);
  Eigen::VectorXd x_plain = Eigen::VectorXd::Zero(p.b.size());
  const MpgpReport plain = solve_mpgp_scaled(
      dense_operator(p.M), p.b, p.c, BlockScaling::identity(p.b.size()), tight(1e-10), x_plain);
  ASSERT_EQ(scaled.termination, QpTermination::Converged) << scaled.full();
  ASSERT_EQ(plain.termination, QpTermination::Converged) << plain.full();
  // The same point, each patch on its own scale (in the scaled variables).
  const double y_scale = y_reference.lpNorm<Eigen::Infinity>();
  EXPECT_LT((D.to_scaled(x_scaled) - y_reference).lpNorm<Eigen::Infinity>(), 1e-7 * y_scale);
  EXPECT_LT((D.to_scaled(x_plain) - y_reference).lpNorm<Eigen::Infinity>(), 1e-4 * y_scale);
  EXPECT_LT(scaled.n_products, plain.n_products);
  // The KKT residuals of the scaled problem, from the matrix, are at the tolerance.
  const Eigen::VectorXd g = p.M * x_scaled - p.b;
  EXPECT_LT(scaled_kkt_residuals(x_scaled, g, p.b, p.c, D, StopReference::Resisted).max(), 1e-8);
}

// A preconditioner M ~ A^-1 of the unscaled problem becomes D^-1 M D^-1: the exact inverse stays
// the exact inverse of D A D.
TEST(BlockScaling, APreconditionerIsScaledAsTheInverseOfTheHessian) {
  const GradedProblem p = graded_problem(5, 12);
  const BlockScaling D = BlockScaling::per_block(p.c, p.patch_factor);
  const Eigen::MatrixXd A_inv = p.M.inverse();
  MpgpOptions opt;
  opt.preconditioner = dense_operator(A_inv);
  const MpgpOptions scaled = D.scaled(opt);
  ASSERT_TRUE(scaled.preconditioner);
  const Operator A = dense_operator(p.M);
  const Operator DAD = D.scaled(A);
  std::mt19937 rng(3);
  const Eigen::VectorXd y = qp::testing::random_vector(p.b.size(), rng);
  Eigen::VectorXd Ay(y.size()), back(y.size());
  DAD(y, Ay);
  scaled.preconditioner(Ay, back);
  EXPECT_LE((back - y).norm(), 1e-9 * y.norm());
  EXPECT_FALSE(D.scaled(MpgpOptions{}).preconditioner);  // none stays none
}

TEST(ResistedPart, KeepsThePositiveNormalEntriesAndTheDiscsOfPositiveRadius) {
  SeparableConstraints c = SeparableConstraints::contact_layout(3);
  c.set_disc_radii(Eigen::Vector3d(1.0, 0.0, 2.0));
  const Eigen::VectorXd b = (Eigen::VectorXd(9) << 4, 1, 2, -7, 3, 4, -1e9, 5, 6).finished();
  EXPECT_EQ(resisted_part(b, c), (Eigen::VectorXd(9) << 4, 1, 2, 0, 0, 0, 0, 5, 6).finished());
}

// On a Free block nothing but the equality multiplier resists b_i: all of it counts, whatever
// its sign.
TEST(ResistedPart, KeepsAllOfBOnFreeBlocks) {
  SeparableConstraints c = SeparableConstraints::contact_layout(1);
  c.set_disc_radii(Eigen::VectorXd::Constant(1, 1.0));
  c.append_free(3);
  const Eigen::VectorXd b = (Eigen::VectorXd(6) << -4, 1, 2, -3, 5, 0).finished();
  EXPECT_EQ(resisted_part(b, c), (Eigen::VectorXd(6) << 0, 1, 2, -3, 5, 0).finished());
}

TEST(ResistedPart, FarPatchesDoNotLoosenTheStoppingTest) {
  // A frictionless contact QP plus patches far from the obstacle: b_n hugely negative there (a
  // gap that the free displacement does not close). Relative to ||b|| the test would stop far
  // from the solution of the patches in contact; relative to ||b_R|| it does not.
  std::mt19937 rng(11);
  const Index n_near = 8, n_far = 8, n = 3 * (n_near + n_far);
  const Eigen::MatrixXd M = qp::testing::random_spd(n, 100.0, rng);
  Eigen::VectorXd b = qp::testing::random_vector(n, rng);
  for (Index k = n_near; k < n_near + n_far; ++k)
    b(3 * k) = -1e6;
  SeparableConstraints c = SeparableConstraints::contact_layout(n_near + n_far);
  c.set_disc_radii(Eigen::VectorXd::Zero(n_near + n_far));
  const Eigen::VectorXd reference = qp::testing::reference_solve(M, b, c, 1e-15, 2000000);
  const double scale = reference.lpNorm<Eigen::Infinity>();
  ASSERT_GT(scale, 0.0);
  MpgpOptions o = tight(1e-6);
  o.reference = StopReference::Resisted;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  ASSERT_EQ(solve_mpgp(dense_operator(M), b, c, o, x).termination, QpTermination::Converged);
  EXPECT_LT((x - reference).lpNorm<Eigen::Infinity>(), 1e-4 * scale);
  EXPECT_GT(resisted_part(b, c).norm(), 0.0);
  EXPECT_LT(resisted_part(b, c).norm(), 1e-3 * b.norm());
}
