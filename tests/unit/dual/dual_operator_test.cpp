// The dual operators against an independent Q = B K^-1 B^T from a dense Cholesky factor of K, on
// the paper's brick at n = 2 (36 multipliers would need n = 4; n = 2 has 9 and runs in
// milliseconds).
#include "fricon/dual/dual_operator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "fricon/core/error.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"

namespace fricon::dual {
namespace {

struct Brick {
  driver::Problem problem = driver::paper_problem(2, 6e4);
  driver::Model model;
  contact::ContactDiscretization disc;
  MatrixXd Q_dense;  // independent: dense Cholesky of K
  VectorXd h_dense, u0_dense;

  explicit Brick(DualOperatorKind kind) {
    PhaseTimes times;
    model = driver::assemble_model(problem, times);
    disc = driver::discretize_contact(problem, model.mesh, model.dofs);
    driver::factorize_model(model, factorization_request(kind, disc.dofs), times);
    const Eigen::LLT<MatrixXd> llt{MatrixXd(model.K)};
    Q_dense = disc.B * llt.solve(MatrixXd(disc.B.transpose()));
    u0_dense = llt.solve(model.f);
    h_dense = disc.B * u0_dense;
  }
  DualInput input() const { return {model.factor, disc.B, model.f, disc.dofs, {}}; }
};

Real relative(const MatrixXd& a, const MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

class EveryOperator : public ::testing::TestWithParam<DualOperatorKind> {};

INSTANTIATE_TEST_SUITE_P(Kinds, EveryOperator,
                         ::testing::Values(DualOperatorKind::Implicit, DualOperatorKind::Forward,
                                           DualOperatorKind::Schur),
                         [](const ::testing::TestParamInfo<DualOperatorKind>& p) {
                           return std::string(enum_name(p.param));
                         });

TEST_P(EveryOperator, QAndHAgreeWithADenseFactorization) {
  const Brick b(GetParam());
  const auto Q = make_dual_operator(GetParam(), b.input());
  EXPECT_EQ(Q->kind(), GetParam());
  EXPECT_EQ(Q->size(), b.disc.n_dual());
  EXPECT_LT(relative(Q->to_dense(), b.Q_dense), 1e-12);
  EXPECT_LT(relative(Q->h(), b.h_dense), 1e-12);
  EXPECT_LT(relative(Q->u0(), b.u0_dense), 1e-12);
  // Implicit forms nothing; the others keep Q.
  EXPECT_EQ(Q->dense() == nullptr, GetParam() == DualOperatorKind::Implicit);
}

TEST_P(EveryOperator, DisplacementOnTheContactDofsIsTheFullSolveThere) {
  // Both ways of recovering it: a solve per recovery, and (many recoveries expected) whatever the
  // operator forms once for them (the forward operator: the contact rows of K^-1 B^T).
  const Brick b(GetParam());
  const Eigen::LLT<MatrixXd> llt{MatrixXd(b.model.K)};
  for (const long many : {0L, 1000L}) {
    DualInput input = b.input();
    input.expected_recoveries = many;
    const auto Q = make_dual_operator(GetParam(), input);
    EXPECT_LT(relative(Q->to_dense(), b.Q_dense), 1e-12) << "expected_recoveries " << many;
    const VectorXd lambda = VectorXd::LinSpaced(Q->size(), 1e6, 3e6);
    const VectorXd full = Q->displacement(lambda);
    VectorXd w;
    Q->contact_displacement(lambda, w);
    ASSERT_EQ(w.size(), full.size());
    for (Index dof : b.disc.dofs)
      EXPECT_NEAR(w(dof), full(dof), 1e-12 * full.lpNorm<Eigen::Infinity>())
          << "dof " << dof << ", expected_recoveries " << many;
    // And the full solve is w = K^-1 (f - B^T lambda) of the dense factorization.
    EXPECT_LT(relative(full, llt.solve(VectorXd(b.model.f - b.disc.B.transpose() * lambda))),
              1e-12);
  }
}

TEST(DualOperator, ImplicitCountsOneSolvePerProduct) {
  const Brick b(DualOperatorKind::Implicit);
  const auto Q = make_dual_operator(DualOperatorKind::Implicit, b.input());
  const long before = Q->n_kinv();
  VectorXd x = VectorXd::Ones(Q->size()), y(Q->size());
  Q->apply(x, y);
  Q->apply(y, x);
  EXPECT_EQ(Q->n_kinv(), before + 2);
}

TEST(DualOperator, OnlySchurAsksForAnOrderingAndNeedsIt) {
  const std::vector<Index> dofs{3, 4, 5};
  EXPECT_EQ(factorization_request(DualOperatorKind::Schur, dofs).last, dofs);
  for (auto kind : {DualOperatorKind::Auto, DualOperatorKind::Implicit, DualOperatorKind::Forward})
    EXPECT_TRUE(factorization_request(kind, dofs).last.empty());
  // A factor in the default order cannot serve the Schur operator: a clear error, not garbage.
  const Brick b(DualOperatorKind::Forward);
  EXPECT_THROW(make_dual_operator(DualOperatorKind::Schur, b.input()), Error);
}

TEST(DualOperator, AutoFormsQWhileItIsNoLargerThanTheFactor) {
  constexpr auto kOne = FactorLocation::OneProcess;
  EXPECT_EQ(resolve(DualOperatorKind::Auto, kOne, 5000, 1e6), DualOperatorKind::Forward);
  EXPECT_EQ(resolve(DualOperatorKind::Auto, kOne, 7000, 1e6), DualOperatorKind::Implicit);
  EXPECT_EQ(resolve(DualOperatorKind::Auto, kOne, 9000, 1e8), DualOperatorKind::Forward);
  EXPECT_EQ(resolve(DualOperatorKind::Schur, kOne, 7000, 1e6), DualOperatorKind::Schur);
}

TEST(DualOperator, AutoDistributedFormsQAsASchurComplementUpToTheDenseLimit) {
  // The same limit as on one process, the one rule of dual_operator_kind.hpp.
  constexpr auto kMumps = FactorLocation::Distributed;
  EXPECT_EQ(resolve(DualOperatorKind::Auto, kMumps, kDenseDualLimit), DualOperatorKind::Schur);
  EXPECT_EQ(resolve(DualOperatorKind::Auto, kMumps, kDenseDualLimit + 1),
            DualOperatorKind::Implicit);
  EXPECT_EQ(resolve(DualOperatorKind::Implicit, kMumps, 10), DualOperatorKind::Implicit);
}

TEST(DualOperator, PollingStopsTheFormingOfQ) {
  Brick b(DualOperatorKind::Forward);
  DualInput in = b.input();
  in.poll = [] { throw Interrupted("stop"); };
  EXPECT_THROW(make_dual_operator(DualOperatorKind::Forward, in), Interrupted);
}

}  // namespace
}  // namespace fricon::dual
