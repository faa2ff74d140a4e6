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

}  // namespace
}  // namespace fricon::driver
