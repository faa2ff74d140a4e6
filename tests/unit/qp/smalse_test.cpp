// qp::solve_smalse (theory.md §4.6) on small dense QPs with bounds, discs and equalities, checked
// from outside the solver: the KKT conditions of the whole problem (the Lagrangian's gradient
// A x - b + G^T mu in the normal cone of Omega, qp::kkt_residuals) and G x = e; infeasible
// equalities are reported with a certificate d (d^T e > sup over Omega of d^T G x, checked here by
// brute force over the blocks), not as a solver that runs out of steps.
#include <gtest/gtest.h>

#include <cmath>

#include "fricon/qp/coarse_space.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/smalse.hpp"

using namespace fricon;
using namespace fricon::qp;

namespace {

// A random SPD matrix of order n (fixed seed through Eigen's Random after srand).
Eigen::MatrixXd spd(Index n, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd M = Eigen::MatrixXd::Random(n, n);
  return M * M.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
}

// G x = e with a dense G, written entry by entry in the tests; the solver takes it sparse.
struct DenseEquality {
  Eigen::MatrixXd G;
  Eigen::VectorXd e;
  operator EqualityConstraint() const { return {G.sparseView(), e}; }
};

Operator dense(const Eigen::MatrixXd& A) {
  return [&A](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = A * x; };
}

MpgpOptions tight() {
  MpgpOptions o;
  o.rel_tolerance = 1e-10;
  return o;
}

// sup over Omega of g^T x, by the blocks: infinite if a bound has g_i > 0.
double support_of(const Eigen::VectorXd& g, const SeparableConstraints& c) {
  double s = 0.0;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Block& b = c.blocks[k];
    if (b.kind == BlockKind::Disc)
      s += c.radius(static_cast<Index>(k)) * g.segment<2>(b.offset).norm();
    else if (g(b.offset) > 1e-9 * g.norm())
      return INFINITY;
  }
  return s;
}

// Six patches with discs of radius 0.4 and two rows: the sum of the normal multipliers, and of
// the first tangential ones; e reachable.
struct TwoRowProblem {
  SeparableConstraints c;
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  DenseEquality eq;
};

TwoRowProblem two_row_problem() {
  const Index patches = 6, n = 3 * patches;
  TwoRowProblem q;
  q.c = SeparableConstraints::contact_layout(patches);
  q.c.set_disc_radii(Eigen::VectorXd::Constant(patches, 0.4));
  q.A = spd(n, 7);
  std::srand(11);
  q.b = Eigen::VectorXd::Random(n);
  q.eq = {Eigen::MatrixXd::Zero(2, n), Eigen::VectorXd(2)};
  for (Index p = 0; p < patches; ++p) {
    q.eq.G(0, 3 * p) = 1.0;
    q.eq.G(1, 3 * p + 1) = 1.0 + 0.1 * static_cast<double>(p);
  }
  q.eq.e << 3.0, 0.5;
  return q;
}

// x (with the equality's multiplier mu) meets G x = e and the KKT conditions of the whole problem.
void expect_whole_kkt(const TwoRowProblem& q, const Eigen::VectorXd& x, const Eigen::VectorXd& mu) {
  EXPECT_LE((q.eq.G * x - q.eq.e).norm(), 1e-8 * q.eq.e.norm());
  const Eigen::VectorXd g = q.A * x - q.b + q.eq.G.transpose() * mu;
  const KktResiduals k = kkt_residuals(x, g, q.c, 1.0, q.b.norm());
  EXPECT_LE(k.max(), 1e-7) << k.feasibility << " " << k.stationarity << " " << k.complementarity;
}

TEST(Smalse, MeetsTheEqualityAndTheKktConditionsOfTheWholeProblem) {
  const TwoRowProblem q = two_row_problem();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(q.b.size()), mu;
  const SmalseReport r = solve_smalse(dense(q.A), q.b, q.c, q.eq, SmalseOptions{}, tight(), x, mu);
  ASSERT_EQ(r.termination, QpTermination::Converged) << r.message;
  expect_whole_kkt(q, x, mu);
}

// Gaps alone and no load (e = 0, b < 0 on the bounds and 0 elsewhere, a body driven by prescribed
// displacements that are zero): x = 0 and mu = 0 meet the KKT conditions exactly, and the solver
// returns them exactly from a warm start, without steps, with and without the projector.
TEST(Smalse, GapsAloneWithNoLoadGiveZeroExactly) {
  TwoRowProblem q = two_row_problem();
  q.eq.e.setZero();
  q.b.setZero();
  for (Index p = 0; p < q.b.size() / 3; ++p)
    q.b(3 * p) = -0.1 - 0.05 * static_cast<double>(p);
  for (const bool projector : {true, false}) {
    SmalseOptions opt;
    opt.projector = projector;
    Eigen::VectorXd x = Eigen::VectorXd::Constant(q.b.size(), 0.2), mu;
    const SmalseReport r = solve_smalse(dense(q.A), q.b, q.c, q.eq, opt, tight(), x, mu);
    ASSERT_EQ(r.termination, QpTermination::Converged) << r.message;
    EXPECT_EQ(r.iterations, 0);
    EXPECT_EQ(x.lpNorm<Eigen::Infinity>(), 0.0);
    EXPECT_EQ(mu.lpNorm<Eigen::Infinity>(), 0.0);
    expect_whole_kkt(q, x, mu);
  }
}

// The inner solves preconditioned in face (with the projector, P M P + Q / rho): the same KKT
// point of the whole problem, with M = A^-1 and with a poor M.
TEST(Smalse, APreconditionedInnerSolveMeetsTheSameConditions) {
  const TwoRowProblem q = two_row_problem();
  const Eigen::MatrixXd good = q.A.inverse(), poor = spd(q.b.size(), 3);
  for (const Eigen::MatrixXd* M : {&good, &poor}) {
    MpgpOptions inner = tight();
    inner.preconditioner = dense(*M);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(q.b.size()), mu;
    const SmalseReport r = solve_smalse(dense(q.A), q.b, q.c, q.eq, SmalseOptions{}, inner, x, mu);
    ASSERT_EQ(r.termination, QpTermination::Converged) << r.message;
    EXPECT_GT(r.n_preconditioner, 0);
    expect_whole_kkt(q, x, mu);
  }
}

TEST(Smalse, AnEqualityOmegaCannotMeetIsCertifiedInfeasible) {
  const Index patches = 4, n = 3 * patches;
  SeparableConstraints c = SeparableConstraints::contact_layout(patches);
  c.set_disc_radii(Eigen::VectorXd::Constant(patches, 1.0));
  const Eigen::MatrixXd A = spd(n, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  // The tangential multipliers can sum to at most 4 (four unit discs); ask for 6.
  DenseEquality eq{Eigen::MatrixXd::Zero(1, n), Eigen::VectorXd::Constant(1, 6.0)};
  for (Index p = 0; p < patches; ++p)
    eq.G(0, 3 * p + 1) = 1.0;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), mu;
  const SmalseReport r = solve_smalse(dense(A), b, c, eq, SmalseOptions{}, tight(), x, mu);
  ASSERT_TRUE(r.infeasible) << r.message;
  const Infeasibility& cert = r.infeasibility;
  EXPECT_NEAR(cert.applied / cert.direction(0), 6.0, 1e-6);
  EXPECT_NEAR(cert.carried / cert.direction(0), 4.0, 1e-6);
  // The certificate holds: d^T e exceeds the most Omega gives along d, found here by blocks.
  EXPECT_GT(cert.direction.dot(eq.e), support_of(eq.G.transpose() * cert.direction, c));
}

TEST(Smalse, ANegativeResultantOfBoundsIsInfeasible) {
  const Index patches = 3, n = 3 * patches;
  const SeparableConstraints c = SeparableConstraints::contact_layout(patches);
  const Eigen::MatrixXd A = spd(n, 5);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  DenseEquality eq{Eigen::MatrixXd::Zero(1, n), Eigen::VectorXd::Constant(1, -2.0)};
  for (Index p = 0; p < patches; ++p)
    eq.G(0, 3 * p) = 1.0;  // lambda_n >= 0 sum to -2?
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), mu;
  const SmalseReport r = solve_smalse(dense(A), b, c, eq, SmalseOptions{}, tight(), x, mu);
  ASSERT_TRUE(r.infeasible) << r.message;
  EXPECT_NEAR(r.infeasibility.carried, 0.0, 1e-9 * std::abs(r.infeasibility.applied));
  EXPECT_GT(r.infeasibility.applied, 0.0);
}

TEST(Smalse, ARowOnPinnedDiscsOnlyIsUndeterminedAndMustCarryNoLoad) {
  const Index patches = 3, n = 3 * patches;
  const SeparableConstraints c = SeparableConstraints::contact_layout(patches);  // radii 0
  const Eigen::MatrixXd A = spd(n, 9);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  DenseEquality eq{Eigen::MatrixXd::Zero(2, n), Eigen::VectorXd::Zero(2)};
  for (Index p = 0; p < patches; ++p) {
    eq.G(0, 3 * p) = 1.0;      // the normal resultant
    eq.G(1, 3 * p + 1) = 1.0;  // a tangential one, on pinned discs
  }
  eq.e << 2.0, 0.0;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), mu;
  SmalseReport r = solve_smalse(dense(A), b, c, eq, SmalseOptions{}, tight(), x, mu);
  ASSERT_EQ(r.termination, QpTermination::Converged) << r.message;
  ASSERT_EQ(r.undetermined.cols(), 1);
  EXPECT_NEAR(std::abs(r.undetermined(1, 0)), 1.0, 1e-12);
  EXPECT_NEAR(mu(1), 0.0, 1e-12);  // least norm: no multiplier on the undetermined row
  // A load on that row cannot be carried, unless it is dropped (Coulomb's first step).
  eq.e(1) = 1.0;
  x.setZero();
  mu.resize(0);
  r = solve_smalse(dense(A), b, c, eq, SmalseOptions{}, tight(), x, mu);
  EXPECT_TRUE(r.infeasible);
  SmalseOptions drop;
  drop.drop_unresisted_load = true;
  x.setZero();
  mu.resize(0);
  r = solve_smalse(dense(A), b, c, eq, drop, tight(), x, mu);
  EXPECT_EQ(r.termination, QpTermination::Converged) << r.message;
  EXPECT_NEAR((eq.G.row(0) * x)(0), 2.0, 1e-8);
}

}  // namespace

namespace {

TEST(BalanceCertificate, DecidesFeasibilityWithoutTheHessian) {
  const Index patches = 4, n = 3 * patches;
  SeparableConstraints c = SeparableConstraints::contact_layout(patches);
  c.set_disc_radii(Eigen::VectorXd::Constant(patches, 1.0));
  // Row 0: the tangential resultant (at most 4 in Omega); row 1: the normal one (any >= 0).
  DenseEquality eq{Eigen::MatrixXd::Zero(2, n), Eigen::VectorXd(2)};
  for (Index p = 0; p < patches; ++p) {
    eq.G(0, 3 * p + 1) = 1.0;
    eq.G(1, 3 * p) = 1.0;
  }
  eq.e << 3.5, 2.0;
  EXPECT_FALSE(balance_certificate(eq, c, 1e-8));
  eq.e << 6.0, 2.0;
  const auto tangential = balance_certificate(eq, c, 1e-8);
  ASSERT_TRUE(tangential);
  EXPECT_GT(tangential->direction.dot(eq.e),
            support_of(eq.G.transpose() * tangential->direction, c));
  eq.e << 1.0, -2.0;  // a pull: the normal multipliers cannot give a negative resultant
  const auto pull = balance_certificate(eq, c, 1e-8);
  ASSERT_TRUE(pull);
  EXPECT_NEAR(pull->carried, 0.0, 1e-9 * pull->applied);
}

}  // namespace

namespace {

// Beyond kDenseCoarseLimit rows the coarse problem is factored by sparse Cholesky (Total FETI's
// many subdomains): the same QP, rows made of pairs of unknowns (x_2i - x_2i+1 = e_i, a gluing
// of free unknowns), checked from outside by its KKT conditions, G x = e and the unconstrained
// solution of the equality-constrained problem by the Lagrangian's linear system.
TEST(Smalse, ManyEqualityRowsOnFreeUnknownsUseTheSparseCoarseProblem) {
  const Index m = kDenseCoarseLimit + 30, n = 2 * m;
  SeparableConstraints c;
  c.append_free(n);
  // A diagonally dominant tridiagonal SPD A.
  std::vector<Eigen::Triplet<double, SparseIndex>> t;
  for (Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0 + 0.001 * static_cast<double>(i % 7));
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  t.clear();
  Eigen::VectorXd e(m), b(n);
  for (Index i = 0; i < m; ++i) {
    t.emplace_back(i, 2 * i, 1.0);
    t.emplace_back(i, 2 * i + 1, -1.0);
    e(i) = std::sin(0.1 * static_cast<double>(i));
  }
  for (Index i = 0; i < n; ++i)
    b(i) = std::cos(0.37 * static_cast<double>(i));
  EqualityConstraint eq;
  eq.G.resize(m, n);
  eq.G.setFromTriplets(t.begin(), t.end());
  eq.e = e;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), mu;
  const Operator op = [&A](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = A * v; };
  const SmalseReport r = solve_smalse(op, b, c, eq, SmalseOptions{}, tight(), x, mu);
  ASSERT_EQ(r.termination, QpTermination::Converged) << r.message;
  EXPECT_LE((eq.G * x - e).norm(), 1e-7 * e.norm());
  // The KKT system [A G^T; G 0] (x, mu) = (b, e), solved directly.
  const Eigen::MatrixXd Ad(A), Gd(eq.G);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = Ad;
  K.topRightCorner(n, m) = Gd.transpose();
  K.bottomLeftCorner(m, n) = Gd;
  Eigen::VectorXd rhs(n + m);
  rhs << b, e;
  const Eigen::VectorXd exact = K.partialPivLu().solve(rhs);
  EXPECT_LE((x - exact.head(n)).norm(), 1e-6 * exact.head(n).norm());
}

}  // namespace
