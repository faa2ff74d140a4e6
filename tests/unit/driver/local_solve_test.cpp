// driver: solve_local (`fricon dual solve`) on local problems built in code, in particular the
// change of variables per contact (LocalSolveOptions::scaling).

#include "fricon/driver/local_solve.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fricon/core/error.hpp"
#include "fricon/qp/friction_cone.hpp"

namespace fricon::driver {
namespace {

// A local problem whose contacts' blocks of W lie orders of magnitude apart: W = S M S with M a
// random SPD matrix of condition number 10 and S = diag(s_a I_3), s_a log-uniform in
// [10^-decades/2, 10^decades/2]; q = -W r0 + u0 with r0 inside the cones (normal 1, tangential up
// to 0.8) and u0 opening about a quarter of the contacts, so that the answer has contacts
// closed and open, sticking and sliding. Coulomb with mu = 0.3, or Tresca with thresholds
// 0.3 r0_n.
qp::LocalProblem scaled_problem(Index n_contacts, double decades, bool coulomb, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Index m = 3 * n_contacts;
  MatrixXd G(m, m);
  for (Index j = 0; j < m; ++j)
    for (Index i = 0; i < m; ++i)
      G(i, j) = N(rng);
  const MatrixXd Qr = Eigen::HouseholderQR<MatrixXd>(G).householderQ();
  VectorXd lam(m);
  for (Index i = 0; i < m; ++i)
    lam(i) = std::pow(10.0, static_cast<double>(i) / static_cast<double>(m - 1));
  VectorXd s(m), r0(m), u0 = VectorXd::Zero(m);
  for (Index a = 0; a < n_contacts; ++a) {
    s.segment<3>(3 * a).setConstant(std::pow(10.0, decades * (U(rng) - 0.5)));
    const double angle = 2.0 * std::numbers::pi * U(rng), t = 0.8 * U(rng);
    r0.segment<3>(3 * a) << 1.0, t * std::cos(angle), t * std::sin(angle);
    if (U(rng) < 0.25) u0(3 * a) = 0.5;
  }
  const MatrixXd M = Qr * lam.asDiagonal() * Qr.transpose();
  const MatrixXd W = s.asDiagonal() * (0.5 * (M + M.transpose())) * s.asDiagonal();
  qp::LocalProblem p;
  p.W = W.sparseView();
  // r0 in the units of S^-1: the reactions of a stiff contact are small and the other way round.
  const VectorXd r = r0.cwiseQuotient(s);
  p.q = -(W * r) + u0.cwiseProduct(s);
  if (coulomb) {
    p.mu = VectorXd::Constant(n_contacts, 0.3);
  } else {
    p.threshold.resize(n_contacts);
    for (Index a = 0; a < n_contacts; ++a)
      p.threshold(a) = 0.3 * r(3 * a);
  }
  p.source = "scaled_problem";
  return p;
}

TEST(ContactScaling, OneFactorPerContactFromTheMeanOfItsDiagonal) {
  VectorXd diagonal(9);
  diagonal << 4.0, 4.0, 4.0,  // mean 4: 1/2
      1.0, 2.0, 6.0,          // mean 3
      0.0, -1.0, 1.0;         // mean 0: not positive, 1
  const qp::BlockScaling D = contact_scaling(diagonal);
  VectorXd expected(9);
  expected << 0.5, 0.5, 0.5, 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0), 1.0,
      1.0, 1.0;
  EXPECT_LE((D.d() - expected).norm(), 1e-15) << D.d().transpose();
  EXPECT_THROW(contact_scaling(VectorXd::Ones(4)), InputError);
}

// With contacts whose blocks of W are 10^4 apart the scaled and the unscaled solve give the same
// reactions to the tolerance, both certified by the natural-map residual of the problem as given;
// the scaled one needs fewer products.
TEST(SolveLocal, ScaledAndUnscaledGiveTheSameReactions) {
  for (const bool coulomb : {false, true}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const qp::LocalProblem p = scaled_problem(12, 2.0, coulomb, seed);
      LocalSolveOptions scaled;
      LocalSolveOptions unscaled;
      unscaled.scaling = false;
      const LocalSolution a = solve_local(p, scaled);
      const LocalSolution b = solve_local(p, unscaled);
      const std::string where = std::string(coulomb ? "Coulomb" : "Tresca") + " seed " +
                                std::to_string(seed) + ": " + a.reason + " / " + b.reason;
      ASSERT_TRUE(a.solved) << where;
      ASSERT_TRUE(b.solved) << where;
      EXPECT_LE((a.r - b.r).norm(), 1e-7 * b.r.norm()) << where;
      EXPECT_LE(a.residual, scaled.residual_tol) << where;
      // The certificate is that of the problem as given, recomputed here.
      const VectorXd u = p.W * a.r + p.q;
      EXPECT_LE((a.u - u).norm(), 1e-12 * u.norm()) << where;
      const Real alpha = 1.0 / a.norm_W;
      EXPECT_DOUBLE_EQ(a.residual, coulomb ? qp::coulomb_residual(a.r, u, p.mu, alpha)
                                           : qp::tresca_residual(a.r, u, p.threshold, alpha))
          << where;
      EXPECT_EQ(b.norm_W_scaled, b.norm_W);
      EXPECT_LT(a.norm_W_scaled, a.norm_W) << where;  // D W D has a diagonal of about 1
      EXPECT_LT(a.n_products, b.n_products) << where;
    }
  }
}

// A problem W = S + A with S SPD (eigenvalues 1..10) and A antisymmetric, ||A|| = asymmetry
// (relative to S's smallest eigenvalue, 1), whose solution r0 is known by construction: per
// contact closed (r_n = 1, u_n = 0) or open (r = 0, u_n = 0.5), sticking (||r_t|| < bound, u_t = 0)
// or sliding (||r_t|| = bound, u_t = -0.7 r_t); q = u0 - W r0. The bound is mu r_n (Coulomb,
// mu = 0.3) or the threshold (Tresca, 0.3). S positive definite makes W strongly monotone and r0
// the only solution of the Tresca problem.
struct KnownSolution {
  qp::LocalProblem p;
  VectorXd r0;
};

KnownSolution nonsymmetric_problem(Index n_contacts, double asymmetry, bool coulomb,
                                   unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Index m = 3 * n_contacts;
  MatrixXd G(m, m), B(m, m);
  for (Index j = 0; j < m; ++j)
    for (Index i = 0; i < m; ++i) {
      G(i, j) = N(rng);
      B(i, j) = N(rng);
    }
  const MatrixXd Qr = Eigen::HouseholderQR<MatrixXd>(G).householderQ();
  VectorXd lam(m);
  for (Index i = 0; i < m; ++i)
    lam(i) = 1.0 + 9.0 * static_cast<double>(i) / static_cast<double>(m - 1);
  MatrixXd S = Qr * lam.asDiagonal() * Qr.transpose();
  S = 0.5 * (S + S.transpose());
  MatrixXd A = B - B.transpose();
  A *= asymmetry / A.jacobiSvd().singularValues()(0);
  const double bound = 0.3;
  VectorXd r0 = VectorXd::Zero(m), u0 = VectorXd::Zero(m);
  for (Index a = 0; a < n_contacts; ++a) {
    const double angle = 2.0 * std::numbers::pi * U(rng);
    const Eigen::Vector2d t(std::cos(angle), std::sin(angle));
    const bool open = a % 4 == 3, slide = a % 2 == 1;
    if (open) {
      u0(3 * a) = 0.5;
      continue;
    }
    r0(3 * a) = 1.0;
    if (slide) {
      r0.segment<2>(3 * a + 1) = bound * t;
      u0.segment<2>(3 * a + 1) = -0.7 * r0.segment<2>(3 * a + 1);
    } else {
      r0.segment<2>(3 * a + 1) = 0.5 * bound * t;
    }
  }
  KnownSolution k;
  const MatrixXd W = S + A;
  k.p.W = W.sparseView();
  k.p.q = u0 - W * r0;
  if (coulomb) {
    k.p.mu = VectorXd::Constant(n_contacts, bound);
  } else {
    k.p.threshold = VectorXd::Constant(n_contacts, bound);
  }
  k.p.source = "nonsymmetric_problem";
  k.r0 = r0;
  return k;
}

TEST(MeasureAsymmetry, LargestDifferenceAndLargestEntry) {
  MatrixXd W(3, 3);
  W << 2, 1, 0, 0.5, -4, 0, 0, 0.25, 1;
  const Asymmetry a = measure_asymmetry(W.sparseView());
  EXPECT_EQ(a.max_difference, 0.5);
  EXPECT_EQ(a.max_entry, 4.0);
  EXPECT_EQ(a.relative(), 0.125);
  EXPECT_THROW(measure_asymmetry(SparseMatrix(3, 2)), InputError);
}

// A non-symmetric W (issue 23: Capsules' W is not symmetric): solved by the splitting W = S + A to
// the solution known by construction, certified against W as given.
TEST(SolveLocal, NonSymmetricWIsSolvedToTheKnownSolution) {
  for (const bool coulomb : {false, true}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const KnownSolution k = nonsymmetric_problem(8, 0.2, coulomb, seed);
      const LocalSolution s = solve_local(k.p);
      const std::string where = std::string(coulomb ? "Coulomb" : "Tresca") + " seed " +
                                std::to_string(seed) + ": " + s.reason;
      ASSERT_TRUE(s.solved) << where;
      EXPECT_TRUE(s.split) << where;
      EXPECT_LE((s.r - k.r0).norm(), 1e-7 * k.r0.norm()) << where;
      EXPECT_LE((s.u - (k.p.W * s.r + k.p.q)).norm(), 1e-12 * s.u.norm()) << where;
      EXPECT_NEAR(s.asymmetry.relative(),
                  measure_asymmetry(k.p.W).max_difference / measure_asymmetry(k.p.W).max_entry,
                  1e-15);
    }
  }
}

// A symmetric W (to round-off) is not split: one Tresca QP, as before.
TEST(SolveLocal, SymmetricWIsNotSplit) {
  const KnownSolution k = nonsymmetric_problem(8, 0.0, false, 4);
  const LocalSolution s = solve_local(k.p);
  ASSERT_TRUE(s.solved) << s.reason;
  EXPECT_FALSE(s.split);
  EXPECT_EQ(s.outer_iterations, 1);
  EXPECT_TRUE(s.last_changes.empty());
  EXPECT_LE((s.r - k.r0).norm(), 1e-7 * k.r0.norm());
}

// An antisymmetric part three times S's smallest eigenvalue: the splitting's iteration matrix
// S^-1 A has eigenvalues +-3i, it does not contract, and the solve is refused with the measured
// ratio, never called solved.
TEST(SolveLocal, NonContractingSplittingIsRefusedWithItsMeasuredRatio) {
  MatrixXd W = MatrixXd::Identity(3, 3);
  W(0, 1) = 3.0;
  W(1, 0) = -3.0;
  qp::LocalProblem p;
  p.W = W.sparseView();
  p.q = (VectorXd(3) << -1.0, 0.05, 0.0).finished();
  p.threshold = VectorXd::Constant(1, 10.0);
  p.source = "antisymmetric";
  const LocalSolution s = solve_local(p);
  EXPECT_FALSE(s.solved);
  EXPECT_TRUE(s.split);
  EXPECT_NE(s.reason.find("observed"), std::string::npos) << s.reason;
  EXPECT_NE(s.reason.find("splitting W = S + A"), std::string::npos) << s.reason;
}

// The spectrum behind a failed solve is that of S = (W + W^T)/2, not of one triangle of W: here
// the lower triangle read as a symmetric matrix has the eigenvalue -1, S is positive semidefinite
// and singular (issue 23: Capsules was called indefinite this way).
TEST(SolveLocal, AFailedSolveReportsTheSpectrumOfTheSymmetricPart) {
  MatrixXd W = MatrixXd::Identity(3, 3);
  W(1, 0) = 2.0;  // S = [[1 1 0] [1 1 0] [0 0 1]]: eigenvalues 0, 1, 2
  qp::LocalProblem p;
  p.W = W.sparseView();
  p.q = (VectorXd(3) << -1.0, 0.5, 0.2).finished();
  p.threshold = VectorXd::Constant(1, 0.1);
  p.source = "triangle";
  LocalSolveOptions o;
  o.qp_max = 1;  // make it fail
  o.outer_max = 1;
  const LocalSolution s = solve_local(p, o);
  ASSERT_FALSE(s.solved);
  EXPECT_EQ(s.reason.find("not positive semidefinite"), std::string::npos) << s.reason;
  EXPECT_NE(s.reason.find("is singular (1 of its 3 eigenvalues are zero"), std::string::npos)
      << s.reason;
}

}  // namespace
}  // namespace fricon::driver
