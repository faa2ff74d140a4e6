// Unit tests of the MPGP solver. Every solution is checked against truth obtained without the
// solver: hand computations, diagonal problems, an active-set enumeration, a secular equation,
// problems built around a chosen optimum, and an independent FISTA reference.

#include "fricon/qp/mpgp.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "fricon/core/error.hpp"
#include "fricon/qp/kkt.hpp"
#include "qp_test_problems.hpp"

namespace fricon::qp {
namespace {

using testing::dense_operator;
using testing::objective;
using testing::random_spd;
using testing::random_vector;

MpgpOptions tight() {
  MpgpOptions o;
  o.rel_tolerance = 1e-10;
  return o;
}

const std::vector<MpgpVariant> kVariants = {MpgpVariant::Paper, MpgpVariant::BarzilaiBorwein};
const std::vector<MpgpExpansion> kExpansions = {MpgpExpansion::Fixed, MpgpExpansion::Optimal,
                                                MpgpExpansion::ProjectedCG};

// An algorithm of solve_mpgp: a variant with an expansion move, its CG steps holding or turning
// the active discs.
struct Algorithm {
  MpgpVariant variant;
  MpgpExpansion expansion;
  MpgpDiscFace active_discs = MpgpDiscFace::Held;
};

std::vector<Algorithm> all_algorithms() {
  std::vector<Algorithm> out;
  for (const auto v : kVariants)
    for (const auto e : kExpansions)
      for (const auto d : {MpgpDiscFace::Held, MpgpDiscFace::Turned})
        out.push_back({v, e, d});
  return out;
}

// The tests that check solutions, counters and failures run once per variant and expansion:
// inside them, options() and tight() carry both.
class MpgpVariants : public ::testing::TestWithParam<Algorithm> {
 protected:
  MpgpOptions options() const {
    MpgpOptions o;
    o.variant = GetParam().variant;
    o.expansion = GetParam().expansion;
    o.active_discs = GetParam().active_discs;
    return o;
  }
  MpgpOptions tight() const {
    MpgpOptions o = options();
    o.rel_tolerance = qp::tight().rel_tolerance;
    return o;
  }
  /// Turned discs make CG steps that are monotone to second order only (theory.md §4.7).
  bool monotone() const { return GetParam().active_discs == MpgpDiscFace::Held; }
};

INSTANTIATE_TEST_SUITE_P(All, MpgpVariants, ::testing::ValuesIn(all_algorithms()),
                         [](const ::testing::TestParamInfo<Algorithm>& param_info) {
                           return std::string(enum_name(param_info.param.variant)) + "_" +
                                  std::string(enum_name(param_info.param.expansion)) +
                                  (param_info.param.active_discs == MpgpDiscFace::Turned ? "_turn"
                                                                                         : "");
                         });

SeparableConstraints all_bounds(Index n) {
  SeparableConstraints c;
  for (Index i = 0; i < n; ++i)
    c.blocks.push_back({BlockKind::Bound, i});
  c.radius = Eigen::VectorXd::Zero(n);
  return c;
}

SeparableConstraints all_discs(const Eigen::VectorXd& rho) {
  SeparableConstraints c;
  for (Index i = 0; i < rho.size(); ++i)
    c.blocks.push_back({BlockKind::Disc, 2 * i});
  c.radius = rho;
  return c;
}

// KKT residuals with g computed here from the matrix, default scales.
KktResiduals kkt(const Eigen::MatrixXd& M, const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                 const SeparableConstraints& c) {
  const Eigen::VectorXd g = M * x - b;
  const auto s = default_kkt_scales(x, b, c);
  return kkt_residuals(x, g, c, s.x, s.g);
}

struct Problem {
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
  SeparableConstraints c;
};

Problem random_contact_problem(Index n_patches, double cond, unsigned seed) {
  std::mt19937 rng(seed);
  Problem p;
  p.M = random_spd(3 * n_patches, cond, rng, 3.0);
  p.b = random_vector(3 * n_patches, rng);
  p.c = testing::random_contact_constraints(p.M, p.b, rng);
  return p;
}

// ---------------------------------------------------------------------------------------------
// Options, enums, report

TEST(MpgpOptions, DefaultsAreValid) {
  EXPECT_NO_THROW(MpgpOptions{}.validate());
}

TEST(MpgpOptions, ValidateRejectsOutOfRangeFields) {
  auto bad = [](auto mutate) {
    MpgpOptions o;
    mutate(o);
    return o;
  };
  const std::vector<MpgpOptions> cases = {
      bad([](MpgpOptions& o) { o.rel_tolerance = -1e-6; }),
      bad([](MpgpOptions& o) { o.rel_tolerance = NAN; }),
      bad([](MpgpOptions& o) { o.abs_tolerance = -1.0; }),
      bad([](MpgpOptions& o) { o.max_iterations = -1; }),
      bad([](MpgpOptions& o) { o.gamma = 0.0; }),
      bad([](MpgpOptions& o) { o.step_factor = 0.0; }),
      bad([](MpgpOptions& o) { o.step_factor = 2.01; }),
      bad([](MpgpOptions& o) { o.norm_A = -1.0; }),
      bad([](MpgpOptions& o) { o.norm_A = INFINITY; }),
      bad([](MpgpOptions& o) { o.power_iterations = 0; }),
      bad([](MpgpOptions& o) { o.power_tolerance = 0.0; }),
      bad([](MpgpOptions& o) { o.active_tolerance = -1e-12; }),
      bad([](MpgpOptions& o) { o.active_tolerance = 0.5; }),
      bad([](MpgpOptions& o) { o.variant = static_cast<MpgpVariant>(9); }),
      bad([](MpgpOptions& o) { o.expansion = static_cast<MpgpExpansion>(9); }),
      bad([](MpgpOptions& o) { o.expansion_length_factor = 0.0; }),
      bad([](MpgpOptions& o) { o.expansion_length_factor = 2.5; }),
      bad([](MpgpOptions& o) { o.expansion_length_factor = NAN; }),
  };
  for (const auto& o : cases)
    EXPECT_THROW(o.validate(), InputError);
  try {
    bad([](MpgpOptions& o) { o.gamma = -2.0; }).validate();
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("gamma"), std::string::npos) << msg;
    EXPECT_NE(msg.find("-2"), std::string::npos) << msg;
  }
}

TEST(MpgpEnums, SpellingsRoundTrip) {
  EXPECT_EQ(enum_name(QpTermination::Converged), "converged");
  EXPECT_EQ(enum_name(QpTermination::MaxIterations), "max_iterations");
  EXPECT_EQ(enum_name(QpTermination::NumericalFailure), "numerical_failure");
  EXPECT_EQ(enum_name(QpTermination::UserStopped), "user_stopped");
  EXPECT_EQ(enum_name(MpgpVariant::Paper), "paper");
  EXPECT_EQ(enum_name(MpgpVariant::BarzilaiBorwein), "bb");
  for (auto v : kVariants) {
    EXPECT_EQ(parse_enum<MpgpVariant>(enum_name(v)), v);
  }
  EXPECT_EQ(MpgpOptions{}.variant, MpgpVariant::BarzilaiBorwein);  // the program's default
  EXPECT_THROW(parse_enum<MpgpVariant>("BB"), InputError);
  try {
    parse_enum<MpgpVariant>("spg");  // removed
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "solver.qp_variant = \"spg\" is not one of \"paper\", \"bb\"");
  }
  EXPECT_EQ(enum_name(MpgpExpansion::Fixed), "fixed");
  EXPECT_EQ(enum_name(MpgpExpansion::Optimal), "opt");
  EXPECT_EQ(enum_name(MpgpExpansion::ProjectedCG), "projcg");
  for (auto e : kExpansions) {
    EXPECT_EQ(parse_enum<MpgpExpansion>(enum_name(e)), e);
  }
  EXPECT_EQ(MpgpOptions{}.expansion, MpgpExpansion::Fixed);  // today's algorithm
  try {
    parse_enum<MpgpExpansion>("bb");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "solver.qp_expansion = \"bb\" is not one of \"fixed\", \"opt\", \"projcg\"");
  }
}

// ---------------------------------------------------------------------------------------------
// Problems with hand-checkable optima

TEST_P(MpgpVariants, DiagonalBoundProblemGivesClippedUnconstrainedSolution) {
  const Eigen::VectorXd d = (Eigen::VectorXd(5) << 1.0, 2.0, 4.0, 0.5, 3.0).finished();
  const Eigen::VectorXd b = (Eigen::VectorXd(5) << 1.0, -2.0, 2.0, -0.1, 0.0).finished();
  const Eigen::MatrixXd M = d.asDiagonal();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
  const auto rep = solve_mpgp(dense_operator(M), b, all_bounds(5), tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  const Eigen::VectorXd expected = (Eigen::VectorXd(5) << 1.0, 0.0, 0.5, 0.0, 0.0).finished();
  EXPECT_LE((x - expected).norm(), 1e-12) << x.transpose();  // CG ends exactly on a face
}

TEST_P(MpgpVariants, BlockScalarDiscProblemGivesProjectedUnconstrainedSolution) {
  // A = diag(c_k I_2): the problem splits per disc and the optimum is P_disc(b_k / c_k).
  const Eigen::Vector3d ck(2.0, 0.5, 1.0), rho(1.0, 4.0, 0.0);
  Eigen::VectorXd d(6), b(6);
  d << ck(0), ck(0), ck(1), ck(1), ck(2), ck(2);
  b << 6.0, 8.0, 0.3, -0.4, 1.0, 1.0;
  const Eigen::MatrixXd M = d.asDiagonal();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
  const auto rep = solve_mpgp(dense_operator(M), b, all_discs(rho), tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  Eigen::VectorXd expected(6);
  expected << 0.6, 0.8,  // (3, 4) scaled onto radius 1
      0.6, -0.8,         // (0.6, -0.8) is inside radius 4
      0.0, 0.0;          // pinned
  EXPECT_LE((x - expected).norm(), 1e-10) << x.transpose();
}

TEST_P(MpgpVariants, CoupledTwoByTwoBoundProblemMatchesHandSolution) {
  // A = [2 1; 1 2], b = (1, -2): the unconstrained optimum (4/3, -5/3) is infeasible; with x2 = 0,
  // x1 = b1 / 2 = 1/2 and g2 = 1/2 + 2 = 5/2 >= 0, so x = (1/2, 0).
  const Eigen::Matrix2d M{{2.0, 1.0}, {1.0, 2.0}};
  const Eigen::MatrixXd Md = M;
  Eigen::VectorXd x = Eigen::Vector2d(3.0, 3.0);
  const auto rep =
      solve_mpgp(dense_operator(Md), Eigen::Vector2d(1.0, -2.0), all_bounds(2), tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_NEAR(x(0), 0.5, 1e-12);
  EXPECT_NEAR(x(1), 0.0, 1e-12);
  EXPECT_NEAR(rep.objective, 0.5 * 2 * 0.25 - 0.5, 1e-12);
}

TEST_P(MpgpVariants, CoupledTwoByTwoDiscProblemMatchesHandSolution) {
  // A = [2 1; 1 2], b = (3, 3), rho = 1: A^-1 b = (1, 1) lies outside; at x = (1, 1)/sqrt 2 the
  // gradient (3/sqrt 2 - 3)(1, 1) is a negative multiple of the outward normal: optimal.
  const Eigen::MatrixXd M = Eigen::Matrix2d{{2.0, 1.0}, {1.0, 2.0}};
  Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0);
  const auto rep = solve_mpgp(dense_operator(M), Eigen::Vector2d(3.0, 3.0),
                              all_discs(Eigen::VectorXd::Ones(1)), tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_NEAR(x(0), std::sqrt(0.5), 1e-10);
  EXPECT_NEAR(x(1), std::sqrt(0.5), 1e-10);
}

TEST_P(MpgpVariants, AnisotropicDiscMatchesSecularEquation) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd M = random_spd(2, 1.0 + 50.0 * trial, rng);
    const Eigen::Vector2d b = random_vector(2, rng);
    const double rho = 0.05 + 0.1 * trial * M.llt().solve(b).norm() / 20.0;
    const Eigen::Vector2d expected = testing::trust_region_2d(M, b, rho);
    Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0);
    const auto rep =
        solve_mpgp(dense_operator(M), b, all_discs(Eigen::VectorXd::Constant(1, rho)), tight(), x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_LE((x - expected).norm(), 1e-8 * std::max(rho, 1.0)) << "trial " << trial;
  }
}

TEST_P(MpgpVariants, BoundProblemsMatchActiveSetEnumeration) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 24; ++trial) {
    const Index n = 2 + trial % 7;
    const double cond = std::pow(10.0, trial % 4);
    const Eigen::MatrixXd M = random_spd(n, cond, rng);
    const Eigen::VectorXd b = random_vector(n, rng);
    const Eigen::VectorXd expected = testing::enumerate_bound_solution(M, b);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    const auto rep = solve_mpgp(dense_operator(M), b, all_bounds(n), tight(), x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_LE((x - expected).norm(), 1e-10 * cond * std::max(1.0, expected.norm()))
        << "trial " << trial << " n " << n << " cond " << cond;
  }
}

// A = I, b = (1, 0), x0 = (0, 1): g = (-1, 1), the bound x_1 = 0 is active with beta = (-1, 0),
// phi = (0, 1) and phitilde^T phi = min(1, 1 / alpha_bar) < ||beta||^2 = 1, so the first step is a
// proportioning step. Paper's (14(b)) moves to P(x0 - alpha_bar g) = (1.95, 0) with alpha_bar =
// 1.95.
TEST(Mpgp, ProportioningStepMatchesHandComputation) {
  const Eigen::MatrixXd M = Eigen::Matrix2d::Identity();
  auto opt = tight();
  opt.variant = MpgpVariant::Paper;
  opt.norm_A = 1.0;
  opt.max_iterations = 1;
  opt.record_history = true;
  Eigen::VectorXd x = Eigen::Vector2d(0.0, 1.0);
  const auto rep = solve_mpgp(dense_operator(M), Eigen::Vector2d(1.0, 0.0), all_bounds(2), opt, x);
  ASSERT_EQ(rep.history.size(), 2u);
  EXPECT_EQ(rep.history[1].step, 'p');
  EXPECT_DOUBLE_EQ(rep.history[1].alpha, 1.95);
  EXPECT_LE((x - Eigen::Vector2d(1.95, 0.0)).norm(), 1e-15);
}

// The same start with the spectral moves (norm_A = 1, so the first trial length is alpha_bar =
// 1.95): d = P(x0 - 1.95 g) - x0 = (1.95, -1), g^T d = -2.95, d^T A d = 1.95^2 + 1, so the exact
// line search gives t = 2.95 / 4.8025 and x1 = x0 + t d. For A = I both Barzilai-Borwein lengths
// are 1, so the second move is x1 - g(x1) = b = (1, 0), the solution.
TEST(Mpgp, SpectralStepsMatchHandComputation) {
  const Eigen::MatrixXd M = Eigen::Matrix2d::Identity();
  const double t = 2.95 / (1.95 * 1.95 + 1.0);
  const Eigen::Vector2d x1(1.95 * t, 1.0 - t);
  auto opt = tight();
  opt.variant = MpgpVariant::BarzilaiBorwein;
  opt.norm_A = 1.0;
  opt.record_history = true;
  Eigen::VectorXd x = Eigen::Vector2d(0.0, 1.0);
  const auto rep = solve_mpgp(dense_operator(M), Eigen::Vector2d(1.0, 0.0), all_bounds(2), opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  ASSERT_GE(rep.history.size(), 2u);
  const auto& h = rep.history[1];
  EXPECT_EQ(h.step, 'p');
  EXPECT_NEAR(h.alpha, 1.95 * t, 1e-15);
  EXPECT_NEAR(h.objective, objective(M, Eigen::Vector2d(1.0, 0.0), x1), 1e-15);
  EXPECT_LE((x - Eigen::Vector2d(1.0, 0.0)).norm(), 1e-15) << x.transpose();
}

// BarzilaiBorwein updates g recursively and recomputes it before it stops: the reported ||g^P|| is
// that of the exact gradient, computed here independently.
TEST(Mpgp, BarzilaiBorweinCertifiesTheStoppingTestWithTheExactGradient) {
  const Problem p = random_contact_problem(15, 1000.0, 31);
  auto opt = tight();
  opt.variant = MpgpVariant::BarzilaiBorwein;
  opt.rel_tolerance = 1e-8;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  const Eigen::VectorXd g = p.M * x - p.b;
  double gp2 = 0.0;  // docs/theory.md §4.1 with exact active tests
  for (Index i = 0; i < 15; ++i) {
    const double gn = g(3 * i);
    gp2 += x(3 * i) > 0.0 ? gn * gn : std::min(gn, 0.0) * std::min(gn, 0.0);
    const Eigen::Vector2d xt = x.segment<2>(3 * i + 1), gt = g.segment<2>(3 * i + 1);
    const double rho = p.c.radius(2 * i + 1);
    if (rho == 0.0) continue;
    if (xt.norm() < rho * (1.0 - 1e-12)) {
      gp2 += gt.squaredNorm();
    } else {
      const Eigen::Vector2d eta = xt.normalized();
      gp2 += (gt - std::min(eta.dot(gt), 0.0) * eta).squaredNorm();
    }
  }
  EXPECT_NEAR(std::sqrt(gp2), rep.norm_gp, 1e-6 * rep.norm_gp);
  EXPECT_LE(std::sqrt(gp2), 1e-8 * p.b.norm() * (1.0 + 1e-6));
}

// Near a very tight solution the exact line search of a spectral move drowns in rounding (the
// normal forces times the rounding of points on the circles); the move is then Paper's fixed one
// and the solver still reaches the tolerance.
TEST(Mpgp, SpectralMovesFallBackToFixedStepsAtTheRoundingLevel) {
  const Problem p = random_contact_problem(5, 10.0, 1);
  auto opt = tight();
  opt.variant = MpgpVariant::BarzilaiBorwein;
  opt.rel_tolerance = 1e-13;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_GT(rep.n_fallbacks, 0) << rep.full();
  EXPECT_EQ(rep.n_objective_increases, 0) << rep.full();
  EXPECT_LE(kkt(p.M, p.b, x, p.c).max(), 1e-12) << rep.full();
}

// A = I, b = (1, -1), x0 = (0.5, 0.5), both bounds: g = (-0.5, 1.5) = phi = p, a_cg = 1 and
// a_f = 0.5 / 1.5 = 1/3 < a_cg, so the first step is an expansion. At the boundary point
// x_b = (2/3, 0), g_b = (-1/3, 1): the second bound is active (beta = 0), gr = phi = (-1/3, 0).
// Optimal: a = g^T gr / gr^T gr = 1 and x_b - gr = (1, 0) is feasible (no projection, 2 products);
// ProjectedCG: P(x0 - p) = P(1, -1) = (1, 0) and g recomputed (2 products). Both land on the
// solution (1, 0) in one step; Fixed (alpha_bar = 1.95) goes to (2/3 + 0.65, 0) and needs more.
TEST(Mpgp, OptimalAndProjectedCgExpansionsMatchHandComputation) {
  const Eigen::MatrixXd M = Eigen::Matrix2d::Identity();
  const Eigen::Vector2d b(1.0, -1.0);
  for (const auto variant : kVariants) {
    for (const auto expansion : {MpgpExpansion::Optimal, MpgpExpansion::ProjectedCG}) {
      auto opt = tight();
      opt.variant = variant;
      opt.expansion = expansion;
      opt.norm_A = 1.0;
      opt.record_history = true;
      Eigen::VectorXd x = Eigen::Vector2d(0.5, 0.5);
      const auto rep = solve_mpgp(dense_operator(M), b, all_bounds(2), opt, x);
      const std::string where = std::string(enum_name(expansion)) + "\n" + rep.full();
      ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
      ASSERT_EQ(rep.iterations, 1) << where;
      EXPECT_EQ(rep.history[1].step, 'e') << where;
      EXPECT_DOUBLE_EQ(rep.history[1].alpha, expansion == MpgpExpansion::Optimal ? 1.0 / 3.0 : 1.0);
      EXPECT_EQ(rep.n_expansion_products, 2) << where;
      EXPECT_EQ(rep.n_expansion_fallbacks, 0) << where;
      EXPECT_LE((x - Eigen::Vector2d(1.0, 0.0)).norm(), 1e-15) << x.transpose();
      EXPECT_NEAR(rep.objective, -0.5, 1e-15);
    }
  }
  auto opt = tight();
  opt.variant = MpgpVariant::Paper;
  opt.norm_A = 1.0;
  opt.max_iterations = 1;
  Eigen::VectorXd x = Eigen::Vector2d(0.5, 0.5);
  solve_mpgp(dense_operator(M), b, all_bounds(2), opt, x);
  EXPECT_LE((x - Eigen::Vector2d(2.0 / 3.0 + 0.65, 0.0)).norm(), 1e-15) << x.transpose();
}

// The hand computation above with the second unknown a Free block: A = I, b = (-1, -1.25),
// x0 = (0.5, 0.25): g = p = (1.5, 1.5), a_cg = 1 and a_f = 1/3 from the bound alone (the free
// unknown sets no limit, though it decreases), so the first step is an expansion. At x_b = (0,
// -0.25), g_b = (1, 1): the bound is active (beta = 0), the free unknown is not, gr = (0, 1).
// Optimal: a = 1 and x_b - gr = (0, -1.25) is feasible; ProjectedCG: P(x0 - p) = P(-1, -1.25) =
// (0, -1.25), the free unknown kept negative. Both land on the solution (0, -1.25) in one step.
TEST(Mpgp, ExpansionsMoveFreeUnknownsAsHandComputed) {
  const Eigen::MatrixXd M = Eigen::Matrix2d::Identity();
  const Eigen::Vector2d b(-1.0, -1.25);
  SeparableConstraints c = all_bounds(1);
  c.append_free(1);
  for (const auto variant : kVariants) {
    for (const auto expansion : {MpgpExpansion::Optimal, MpgpExpansion::ProjectedCG}) {
      auto opt = tight();
      opt.variant = variant;
      opt.expansion = expansion;
      opt.norm_A = 1.0;
      opt.record_history = true;
      Eigen::VectorXd x = Eigen::Vector2d(0.5, 0.25);
      const auto rep = solve_mpgp(dense_operator(M), b, c, opt, x);
      const std::string where = std::string(enum_name(expansion)) + "\n" + rep.full();
      ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
      ASSERT_EQ(rep.iterations, 1) << where;
      EXPECT_EQ(rep.history[1].step, 'e') << where;
      EXPECT_DOUBLE_EQ(rep.history[1].alpha, expansion == MpgpExpansion::Optimal ? 1.0 / 3.0 : 1.0);
      EXPECT_EQ(rep.n_expansion_products, 2) << where;
      EXPECT_LE((x - Eigen::Vector2d(0.0, -1.25)).norm(), 1e-15) << x.transpose();
      EXPECT_NEAR(rep.objective, 0.5 * 1.25 * 1.25 - 1.25 * 1.25, 1e-15);
    }
  }
}

// A move that would increase q is replaced by the fixed-length one. With the length factor 2
// (PERMON's default) the Optimal move overshoots by construction, so fallbacks occur, and
// ProjectedCG's steps past the boundary raise q on these problems too; along every history q still
// decreases and the solution is the Fixed expansion's.
TEST(Mpgp, ExpansionMovesThatWouldIncreaseQFallBack) {
  for (const auto variant : kVariants) {
    for (const auto& [expansion, factor] :
         {std::pair{MpgpExpansion::Optimal, 2.0}, std::pair{MpgpExpansion::ProjectedCG, 1.0}}) {
      int fallbacks = 0;
      for (unsigned seed = 1; seed <= 10; ++seed) {
        const Problem p = random_contact_problem(20, 1000.0, 4000 + seed);
        auto opt = tight();
        opt.variant = variant;
        opt.expansion = expansion;
        opt.expansion_length_factor = factor;
        opt.record_history = true;
        Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
        const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
        const std::string where = std::string(enum_name(variant)) + "/" +
                                  std::string(enum_name(expansion)) + " seed " +
                                  std::to_string(seed) + "\n" + rep.full();
        ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
        fallbacks += rep.n_expansion_fallbacks;
        for (std::size_t k = 1; k < rep.history.size(); ++k) {
          EXPECT_LE(rep.history[k].objective,
                    rep.history[k - 1].objective + 1e-13 * std::abs(rep.history[k].objective))
              << where << "step " << k;
        }
        EXPECT_EQ(rep.n_objective_increases, 0) << where;
        auto fixed = tight();
        fixed.variant = variant;
        Eigen::VectorXd x_fixed = Eigen::VectorXd::Zero(p.b.size());
        solve_mpgp(dense_operator(p.M), p.b, p.c, fixed, x_fixed);
        EXPECT_LE((x - x_fixed).norm(), 1e-10 * p.b.norm()) << where;
      }
      EXPECT_GT(fallbacks, 0) << enum_name(variant) << "/" << enum_name(expansion);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Random contact-layout problems

struct RandomLayout {
  Index n_patches;
  double cond;
  unsigned seed;
};

std::vector<RandomLayout> random_cases() {
  std::vector<RandomLayout> cases;
  unsigned seed = 100;
  for (Index n_patches : {1, 2, 3, 5, 8, 13, 20}) {
    for (double cond : {1.0, 10.0, 100.0, 1000.0})
      cases.push_back({n_patches, cond, seed++});
  }
  return cases;
}

TEST_P(MpgpVariants, RandomContactProblemsSatisfyKktToTightTolerance) {
  for (const auto& rc : random_cases()) {
    const Problem p = random_contact_problem(rc.n_patches, rc.cond, rc.seed);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, tight(), x);
    const std::string where = "n " + std::to_string(3 * rc.n_patches) + " cond " +
                              std::to_string(rc.cond) + "\n" + rep.full();
    ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
    EXPECT_LE(rep.rel_gp, 1e-10) << where;
    const auto r = kkt(p.M, p.b, x, p.c);
    EXPECT_LE(r.feasibility, 1e-14) << where;
    EXPECT_LE(r.stationarity, 1e-9) << where;
    EXPECT_LE(r.complementarity, 1e-9) << where;
    EXPECT_EQ(rep.n_objective_increases, 0) << where;
  }
}

TEST_P(MpgpVariants, RandomContactProblemsMatchReferenceSolver) {
  for (const auto& rc : random_cases()) {
    if (rc.cond > 100.0 || rc.n_patches > 8) continue;  // keeps the FISTA reference fast
    const Problem p = random_contact_problem(rc.n_patches, rc.cond, rc.seed + 1000);
    const Eigen::VectorXd ref = testing::reference_solve(p.M, p.b, p.c);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, tight(), x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    const double q = objective(p.M, p.b, x), q_ref = objective(p.M, p.b, ref);
    EXPECT_LE(q, q_ref + 1e-12 * std::abs(q_ref)) << "n " << p.b.size() << " cond " << rc.cond;
    EXPECT_LE((x - ref).norm(), 1e-8 * std::max(1.0, ref.norm()))
        << "n " << p.b.size() << " cond " << rc.cond;
  }
}

// Each expansion move solves the random problems to the same point as the variant's Fixed move, to
// the tolerance, and that point satisfies the KKT conditions computed here from the matrix.
TEST_P(MpgpVariants, RandomContactProblemsAgreeWithTheFixedExpansion) {
  for (const auto& rc : random_cases()) {
    const Problem p = random_contact_problem(rc.n_patches, rc.cond, rc.seed + 3000);
    auto fixed = tight();
    fixed.expansion = MpgpExpansion::Fixed;
    Eigen::VectorXd x_fixed = Eigen::VectorXd::Zero(p.b.size());
    ASSERT_EQ(solve_mpgp(dense_operator(p.M), p.b, p.c, fixed, x_fixed).termination,
              QpTermination::Converged);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, tight(), x);
    const std::string where = "n " + std::to_string(3 * rc.n_patches) + " cond " +
                              std::to_string(rc.cond) + "\n" + rep.full();
    ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
    // ||x - x*|| <= ||g^P|| / lambda_min, lambda_min = 3 here, for both solutions.
    EXPECT_LE((x - x_fixed).norm(), 1e-10 * p.b.norm()) << where;
    EXPECT_LE(kkt(p.M, p.b, x, p.c).max(), 1e-9) << where;
    EXPECT_EQ(rep.n_objective_increases, 0) << where;
  }
}

TEST_P(MpgpVariants, LargerGammaSolvesRandomContactProblems) {
  for (const auto& rc : random_cases()) {
    if (rc.n_patches > 8) continue;
    const Problem p = random_contact_problem(rc.n_patches, rc.cond, rc.seed + 2000);
    auto opt = tight();
    opt.gamma = 2.0;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_LE(kkt(p.M, p.b, x, p.c).max(), 1e-9) << "cond " << rc.cond;
  }
}

// Builds b around a chosen optimum x*: per block pick a state, x*_i and g*_i satisfying the KKT
// conditions, and set b = A x* - g*. Strict convexity makes x* the unique solution.
TEST_P(MpgpVariants, ManufacturedOptimumIsRecovered) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const Index n_patches = 4 + seed % 9;
    const double cond = std::pow(10.0, seed % 4);
    const Eigen::MatrixXd M = random_spd(3 * n_patches, cond, rng);
    auto c = SeparableConstraints::contact_layout(n_patches);
    Eigen::VectorXd rho(n_patches), xs(3 * n_patches), gs(3 * n_patches);
    for (Index i = 0; i < n_patches; ++i) {
      const double u = U(rng);  // normal: free / active / degenerate (x = g = 0)
      xs(3 * i) = u < 0.4 ? 0.5 + U(rng) : 0.0;
      gs(3 * i) = u < 0.4 ? 0.0 : (u < 0.8 ? 0.2 + U(rng) : 0.0);
      const double v = U(rng);
      const double phi = 2.0 * std::numbers::pi * U(rng);
      const Eigen::Vector2d eta(std::cos(phi), std::sin(phi));
      rho(i) = v < 0.1 ? 0.0 : 0.5 + U(rng);
      Eigen::Vector2d xt = Eigen::Vector2d::Zero(), gt = Eigen::Vector2d::Zero();
      if (rho(i) == 0.0) {
        gt = Eigen::Vector2d(U(rng) - 0.5, U(rng) - 0.5);  // any reaction
      } else if (v < 0.45) {
        xt = 0.8 * U(rng) * rho(i) * eta;  // interior, g = 0
      } else if (v < 0.9) {
        xt = rho(i) * eta;  // on the circle with a positive multiplier
        gt = -(0.2 + U(rng)) * eta;
      } else {
        xt = rho(i) * eta;  // on the circle, zero multiplier (degenerate)
      }
      xs.segment<2>(3 * i + 1) = xt;
      gs.segment<2>(3 * i + 1) = gt;
    }
    c.set_disc_radii(rho);
    const Eigen::VectorXd b = M * xs - gs;
    auto opt = tight();
    opt.rel_tolerance = 1e-12;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    const auto rep = solve_mpgp(dense_operator(M), b, c, opt, x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_LE((x - xs).norm(), 1e-9 * cond * xs.norm()) << "seed " << seed << " cond " << cond;
  }
}

TEST_P(MpgpVariants, AllInactiveProblemGivesUnconstrainedSolution) {
  std::mt19937 rng(3);
  const Index n_patches = 10;
  const Eigen::MatrixXd M = random_spd(3 * n_patches, 10.0, rng);
  // x* strictly inside Omega: positive normals, tangential parts well inside the discs.
  Eigen::VectorXd xs = random_vector(3 * n_patches, rng);
  for (Index i = 0; i < n_patches; ++i)
    xs(3 * i) = 1.0 + std::abs(xs(3 * i));
  auto c = SeparableConstraints::contact_layout(n_patches);
  Eigen::VectorXd rho(n_patches);
  for (Index i = 0; i < n_patches; ++i)
    rho(i) = 2.0 * xs.segment<2>(3 * i + 1).norm() + 0.1;
  c.set_disc_radii(rho);
  const Eigen::VectorXd b = M * xs;
  auto opt = tight();
  opt.rel_tolerance = 1e-13;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  const auto rep = solve_mpgp(dense_operator(M), b, c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_LE((x - M.llt().solve(b)).norm(), 1e-10 * xs.norm());
}

TEST_P(MpgpVariants, AllActiveProblemGivesBoundaryValues) {
  std::mt19937 rng(4);
  const Index n_patches = 10;
  const Eigen::MatrixXd M = random_spd(3 * n_patches, 100.0, rng);
  auto c = SeparableConstraints::contact_layout(n_patches);
  Eigen::VectorXd rho(n_patches), xs = Eigen::VectorXd::Zero(3 * n_patches);
  Eigen::VectorXd gs = Eigen::VectorXd::Zero(3 * n_patches);
  for (Index i = 0; i < n_patches; ++i) {
    rho(i) = 0.5 + 0.1 * static_cast<double>(i);
    const double phi = 0.7 * static_cast<double>(i);
    const Eigen::Vector2d eta(std::cos(phi), std::sin(phi));
    xs.segment<2>(3 * i + 1) = rho(i) * eta;
    gs(3 * i) = 1.0 + 0.1 * static_cast<double>(i);  // normal pressed against its bound
    gs.segment<2>(3 * i + 1) = -(1.0 + 0.2 * static_cast<double>(i)) * eta;
  }
  c.set_disc_radii(rho);
  const Eigen::VectorXd b = M * xs - gs;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  const auto rep = solve_mpgp(dense_operator(M), b, c, tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_LE((x - xs).norm(), 1e-9 * xs.norm());
  for (Index i = 0; i < n_patches; ++i) {
    EXPECT_EQ(x(3 * i), 0.0);
    EXPECT_NEAR(x.segment<2>(3 * i + 1).norm(), rho(i), 1e-12);
  }
}

// ---------------------------------------------------------------------------------------------
// Free blocks: unconstrained unknowns (the equality multipliers of domain decomposition) in one QP
// with the bounds and discs of contact

// The KKT conditions of x for min 1/2 x^T M x - b^T x over Omega, checked block by block from
// their definitions (not by kkt_residuals), gradients to tol ||b|| and positions to tol times the
// scale of x:
//   Bound  x_i >= 0, g_i >= 0, and x_i = 0 or g_i = 0
//   Disc   ||x_i|| <= rho; on the circle g_i = -s eta with s >= 0, inside g_i = 0 (rho = 0: any)
//   Free   g_i = 0
void expect_kkt_by_definition(const Eigen::MatrixXd& M, const Eigen::VectorXd& b,
                              const Eigen::VectorXd& x, const SeparableConstraints& c, double tol) {
  const Eigen::VectorXd g = M * x - b;
  const double tol_g = tol * b.norm();
  const double tol_x = tol * std::max(x.lpNorm<Eigen::Infinity>(), c.max_radius());
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Index o = c.blocks[k].offset;
    switch (c.blocks[k].kind) {
      case BlockKind::Free:
        EXPECT_LE(std::abs(g(o)), tol_g) << "free block " << k << " x " << x(o);
        break;
      case BlockKind::Bound:
        EXPECT_GE(x(o), -tol_x) << "bound block " << k;
        EXPECT_GE(g(o), -tol_g) << "bound block " << k;
        EXPECT_TRUE(std::abs(x(o)) <= tol_x || std::abs(g(o)) <= tol_g)
            << "bound block " << k << " x " << x(o) << " g " << g(o);
        break;
      case BlockKind::Disc: {
        const double rho = c.radius(static_cast<Index>(k));
        const Eigen::Vector2d xi = x.segment<2>(o), gi = g.segment<2>(o);
        EXPECT_LE(xi.norm(), rho + tol_x) << "disc block " << k;
        if (rho == 0.0) break;
        if (xi.norm() >= rho - tol_x) {
          const Eigen::Vector2d eta = xi.normalized();
          const double s = -eta.dot(gi);
          EXPECT_GE(s, -tol_g) << "disc block " << k;
          EXPECT_LE((gi + s * eta).norm(), tol_g) << "disc block " << k;
        } else {
          EXPECT_LE(gi.norm(), tol_g) << "disc block " << k;
        }
        break;
      }
    }
  }
}

// With every bound and disc inactive at the solution, the constraints play no part: x = A^-1 b,
// computed here by Eigen's LDLT. The free unknowns of x* include large negative values, which a
// solver treating them as bounds would clip and one leaving them at their start would miss.
TEST_P(MpgpVariants, InactiveContactWithFreeUnknownsGivesUnconstrainedSolution) {
  constexpr Index kPatches = 5, kFree = 7;
  constexpr double kCond = 30.0;
  std::mt19937 rng(21);
  const Index n = 3 * kPatches + kFree;
  const Eigen::MatrixXd M = random_spd(n, kCond, rng);
  Eigen::VectorXd xs = random_vector(n, rng);
  Eigen::VectorXd rho(kPatches);
  for (Index i = 0; i < kPatches; ++i) {
    xs(3 * i) = 1.0 + std::abs(xs(3 * i));  // normal well inside x >= 0
    rho(i) = 2.0 * xs.segment<2>(3 * i + 1).norm() + 0.1;
  }
  xs.tail(kFree) << -12.0, 3.0, -0.5, 8.0, -4.0, 0.0, 6.5;
  auto c = SeparableConstraints::contact_layout(kPatches);
  c.set_disc_radii(rho);
  c.append_free(kFree);
  const Eigen::VectorXd b = M * xs;
  const Eigen::VectorXd truth = M.ldlt().solve(b);
  auto opt = tight();
  opt.rel_tolerance = 1e-13;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const auto rep = solve_mpgp(dense_operator(M), b, c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_LE((x - truth).norm(), 1e-10 * truth.norm()) << (x - truth).transpose();
  EXPECT_EQ(rep.n_objective_increases, 0) << rep.full();
}

// Bounds pressed against their limit, discs on their circle and free unknowns of either sign,
// the Free blocks interleaved with the contact blocks (not only appended): b is built around a
// chosen optimum x* (b = A x* - g* with g* in the normal cone), which strict convexity makes
// unique, and the solver's x is checked by the KKT conditions computed here and against x*.
// Bounds, discs and free unknowns with a manufactured optimum xs: per group a free unknown, a
// bound (active with a positive multiplier in two groups of three) and a disc (on its circle,
// pushed outward, in every other group), b = M xs - gs with gs in the normal cone at xs.
struct ManufacturedMixed {
  SeparableConstraints c;
  Eigen::MatrixXd M;
  Eigen::VectorXd b, xs;
  Index n_active_bounds = 0;
};

ManufacturedMixed bounds_discs_and_free(Index groups, double cond, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Index n = 4 * groups;  // per group: a bound, a disc and a free unknown, 4 unknowns
  ManufacturedMixed m;
  SeparableConstraints& c = m.c;
  for (Index i = 0; i < groups; ++i) {
    c.blocks.push_back({BlockKind::Free, 4 * i});
    c.blocks.push_back({BlockKind::Bound, 4 * i + 1});
    c.blocks.push_back({BlockKind::Disc, 4 * i + 2});
  }
  c.radius = Eigen::VectorXd::Zero(3 * groups);
  Eigen::VectorXd xs = Eigen::VectorXd::Zero(n), gs = Eigen::VectorXd::Zero(n);
  for (Index i = 0; i < groups; ++i) {
    const Index o = 4 * i;
    xs(o) = (i % 2 == 0 ? -1.0 : 1.0) * (1.0 + 2.0 * U(rng));  // free, g* = 0
    if (i % 3 != 2) {  // bound active with a positive multiplier
      gs(o + 1) = 0.2 + U(rng);
      ++m.n_active_bounds;
    } else {
      xs(o + 1) = 0.5 + U(rng);
    }
    const double rho = 0.5 + U(rng);
    const double phi = 2.0 * std::numbers::pi * U(rng);
    const Eigen::Vector2d eta(std::cos(phi), std::sin(phi));
    c.radius(3 * i + 2) = rho;
    if (i % 2 == 0) {  // on the circle, pushed outward
      xs.segment<2>(o + 2) = rho * eta;
      gs.segment<2>(o + 2) = -(0.2 + U(rng)) * eta;
    } else {
      xs.segment<2>(o + 2) = 0.5 * rho * eta;
    }
  }
  m.M = random_spd(n, cond, rng);
  m.b = m.M * xs - gs;
  m.xs = xs;
  return m;
}

TEST_P(MpgpVariants, ActiveBoundsAndDiscsWithFreeUnknownsSatisfyKkt) {
  constexpr double kCond = 100.0;
  const ManufacturedMixed m = bounds_discs_and_free(6, kCond, 22);
  ASSERT_NO_THROW(m.c.validate());
  ASSERT_GE(m.n_active_bounds, 2);
  // The active bounds matter: the unconstrained minimiser is infeasible.
  const Eigen::VectorXd unconstrained = m.M.ldlt().solve(m.b);
  ASSERT_GT((unconstrained - testing::reference_project(m.c, unconstrained)).norm(), 1e-3);
  auto opt = tight();
  opt.rel_tolerance = 1e-12;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(m.b.size());
  const auto rep = solve_mpgp(dense_operator(m.M), m.b, m.c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  expect_kkt_by_definition(m.M, m.b, x, m.c, 1e-9);
  EXPECT_LE((x - m.xs).norm(), 1e-9 * kCond * m.xs.norm()) << (x - m.xs).transpose();
}

// ---------------------------------------------------------------------------------------------
// Preconditioning in face (MpgpOptions::preconditioner, docs/theory.md §4.2)

// With M = A^-1 and no constraint, the first CG step from any point is the solution.
TEST_P(MpgpVariants, PreconditionerThatIsTheInverseSolvesAnUnconstrainedProblemInOneCgStep) {
  constexpr Index kN = 30;
  std::mt19937 rng(5);
  const Eigen::MatrixXd A = random_spd(kN, 1e4, rng);
  const Eigen::MatrixXd A_inv = A.inverse();
  const Eigen::VectorXd b = testing::random_vector(kN, rng);
  SeparableConstraints c;
  c.append_free(kN);
  auto opt = options();
  opt.rel_tolerance = 1e-10;
  Eigen::VectorXd plain = Eigen::VectorXd::Zero(kN);
  const auto rep_plain = solve_mpgp(dense_operator(A), b, c, opt, plain);
  opt.preconditioner = dense_operator(A_inv);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kN);
  const auto rep = solve_mpgp(dense_operator(A), b, c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_EQ(rep.n_cg, 1);
  EXPECT_GE(rep.n_preconditioner, 1);
  EXPECT_GT(rep_plain.n_cg, 10);  // the condition number 1e4 needs many plain CG steps
  const Eigen::VectorXd exact = A.ldlt().solve(b);
  EXPECT_LE((x - exact).norm(), 1e-8 * exact.norm());
}

// With active bounds and discs the preconditioner acts in the face only (restricted to the free
// blocks): the same manufactured optimum, by a good and by a poor approximation of A^-1.
TEST_P(MpgpVariants, PreconditionedInFaceReachesTheManufacturedOptimum) {
  constexpr double kCond = 1e3;
  const ManufacturedMixed m = bounds_discs_and_free(8, kCond, 31);
  const Index n = m.b.size();
  std::mt19937 rng(77);
  const Eigen::MatrixXd good = m.M.inverse();
  const Eigen::MatrixXd poor = random_spd(n, 50.0, rng);  // SPD, unrelated to M
  for (const Eigen::MatrixXd* P : {&good, &poor}) {
    auto opt = options();
    opt.rel_tolerance = 1e-12;
    opt.preconditioner = dense_operator(*P);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    const auto rep = solve_mpgp(dense_operator(m.M), m.b, m.c, opt, x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_GT(rep.n_preconditioner, 0);
    EXPECT_EQ(rep.n_objective_increases, 0);
    expect_kkt_by_definition(m.M, m.b, x, m.c, 1e-9);
    EXPECT_LE((x - m.xs).norm(), 1e-9 * kCond * m.xs.norm()) << (x - m.xs).transpose();
  }
}

// A load only on the free unknowns: the part of b that the bounds and discs resist is 0, but x = 0
// is no solution (g = -b on the free unknowns); the stopping test must refer to that load.
TEST_P(MpgpVariants, LoadOnFreeUnknownsAloneIsSolved) {
  constexpr Index kPatches = 3, kFree = 4;
  std::mt19937 rng(23);
  const Index n = 3 * kPatches + kFree;
  const Eigen::MatrixXd M = random_spd(n, 10.0, rng);
  auto c = SeparableConstraints::contact_layout(kPatches);
  c.set_disc_radii(Eigen::VectorXd::Constant(kPatches, 0.5));
  c.append_free(kFree);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  // All negative: neither a bound's max(b_i, 0) nor a pinned disc's 0 would see this load.
  b.tail(kFree) << -1.0, -2.0, -0.5, -3.0;
  auto opt = tight();
  opt.rel_tolerance = 1e-12;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const auto rep = solve_mpgp(dense_operator(M), b, c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_GT(rep.iterations, 0) << rep.full();
  EXPECT_GT(x.tail(kFree).norm(), 0.0);
  expect_kkt_by_definition(M, b, x, c, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Counters, history, monitor, termination

TEST_P(MpgpVariants, ProductCountMatchesOperatorCalls) {
  const Problem p = random_contact_problem(12, 300.0, 7);
  for (bool given_norm : {false, true}) {
    long calls = 0;
    auto opt = tight();
    if (given_norm) {
      opt.norm_A = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p.M).eigenvalues().maxCoeff();
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    const auto rep = solve_mpgp(dense_operator(p.M, &calls), p.b, p.c, opt, x);
    ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
    EXPECT_EQ(rep.variant, opt.variant);
    EXPECT_EQ(rep.iterations, rep.n_cg + rep.n_expansion + rep.n_proportioning);
    // All three step kinds occur, so the formula below tests each coefficient.
    EXPECT_GT(rep.n_cg, 0);
    EXPECT_GT(rep.n_expansion, 0);
    EXPECT_GT(rep.n_proportioning, 0);
    long expected = 1 + rep.n_cg + rep.n_expansion_products + rep.n_proportioning;
    if (opt.variant == MpgpVariant::Paper && monotone()) {
      EXPECT_EQ(rep.n_fallbacks + rep.n_refreshes, 0);
    } else {
      expected += rep.n_refreshes;
    }
    EXPECT_EQ(rep.n_products, expected) << rep.full();
    EXPECT_EQ(rep.expansion, opt.expansion);
    if (opt.expansion == MpgpExpansion::Fixed) {
      EXPECT_EQ(rep.n_expansion_products, 2L * rep.n_expansion);
      EXPECT_EQ(rep.n_expansion_fallbacks, 0);
    } else {
      EXPECT_GE(rep.n_expansion_products, rep.n_expansion);
      EXPECT_LE(rep.n_expansion_products, 3L * rep.n_expansion);
    }
    EXPECT_EQ(calls, rep.n_products + rep.n_power_products);
    EXPECT_EQ(rep.norm_A_estimated, !given_norm);
    if (given_norm) {
      EXPECT_EQ(rep.n_power_products, 0);
      EXPECT_EQ(rep.norm_A_used, opt.norm_A);
    } else {
      EXPECT_GT(rep.n_power_products, 1);
    }
    EXPECT_DOUBLE_EQ(rep.alpha_bar_used, opt.step_factor / rep.norm_A_used);
  }
}

TEST_P(MpgpVariants, ObjectiveDecreasesMonotonicallyAlongHistory) {
  const Problem p = random_contact_problem(15, 1000.0, 8);
  auto opt = tight();
  opt.record_history = true;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  ASSERT_EQ(rep.history.size(), static_cast<std::size_t>(rep.iterations) + 1);
  EXPECT_EQ(rep.history.front().step, 's');
  EXPECT_EQ(rep.history.front().objective, 0.0);  // q(0)
  int counts[3] = {0, 0, 0};
  for (std::size_t k = 1; k < rep.history.size(); ++k) {
    const auto& h = rep.history[k];
    EXPECT_EQ(h.iteration, static_cast<int>(k));
    if (monotone()) {  // else the steps are not compared with exact values of q (§4.7)
      EXPECT_LE(h.objective, rep.history[k - 1].objective + 1e-13 * std::abs(h.objective))
          << "step " << k << " (" << h.step << ")";
    }
    EXPECT_GT(h.alpha, 0.0);
    ASSERT_TRUE(h.step == 'c' || h.step == 'e' || h.step == 'p');
    ++counts[h.step == 'c' ? 0 : h.step == 'e' ? 1 : 2];
  }
  EXPECT_EQ(counts[0], rep.n_cg);
  EXPECT_EQ(counts[1], rep.n_expansion);
  EXPECT_EQ(counts[2], rep.n_proportioning);
  EXPECT_EQ(rep.n_objective_increases, 0);
  const double q = objective(p.M, p.b, x);
  EXPECT_NEAR(rep.history.back().objective, q, 1e-12 * std::abs(q));
  EXPECT_NEAR(rep.objective, q, 1e-12 * std::abs(q));
  // Turned discs: the last step's ||g^P|| is that of the recursive gradient, which the stopping
  // test recomputed.
  EXPECT_NEAR(rep.history.back().norm_gp, rep.norm_gp, monotone() ? 0.0 : 0.01 * rep.norm_gp);
}

TEST_P(MpgpVariants, MonitorReturningFalseStopsWithUserStopped) {
  const Problem p = random_contact_problem(10, 100.0, 9);
  int seen = 0;
  auto opt = tight();
  opt.monitor = [&seen](const MpgpIteration& it) {
    EXPECT_EQ(it.iteration, seen);
    ++seen;
    return it.iteration < 3;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  EXPECT_EQ(rep.termination, QpTermination::UserStopped) << rep.full();
  EXPECT_EQ(rep.iterations, 3);
  EXPECT_EQ(seen, 4);  // start + 3 steps
  EXPECT_FALSE(rep.message.empty());
}

TEST_P(MpgpVariants, MaxIterationsIsReportedWithMessage) {
  const Problem p = random_contact_problem(10, 1000.0, 10);
  auto opt = tight();
  opt.max_iterations = 5;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  EXPECT_EQ(rep.termination, QpTermination::MaxIterations);
  EXPECT_EQ(rep.iterations, 5);
  EXPECT_NE(rep.message.find("max_iterations = 5"), std::string::npos) << rep.message;
  EXPECT_GT(rep.rel_gp, 1e-10);
  EXPECT_LE(kkt(p.M, p.b, x, p.c).feasibility, 0.0);  // the last iterate stays feasible
  EXPECT_NE(rep.brief().find("max_iterations"), std::string::npos);
  EXPECT_NE(rep.full().find("n_expansion"), std::string::npos);
}

TEST_P(MpgpVariants, WarmStartAtSolutionTakesNoStep) {
  const Problem p = random_contact_problem(6, 10.0, 11);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  solve_mpgp(dense_operator(p.M), p.b, p.c, tight(), x);
  auto opt = tight();
  opt.rel_tolerance = 1e-6;
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  EXPECT_EQ(rep.termination, QpTermination::Converged);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_EQ(rep.n_products, 1);
}

// ---------------------------------------------------------------------------------------------
// Regression pin

// The exact behaviour of both variants on three fixed problems (12, 30 and 60 unknowns, bounds
// and discs, some of each active; the second from an infeasible start), recorded from the code
// as it was before MPGP was restructured into named steps and required to stay the same: the
// product counts of Paper are what reproduces the n_mult column of the paper's Table 1 (`fricon
// paper`), so a change that alters them, even by one product, changes the reproduced results.
// Change these numbers only with an intended change of the algorithm, after re-checking `fricon
// paper`. The problems are drawn through std::normal_distribution and
// std::uniform_real_distribution, whose algorithms the standard leaves to the library: the numbers
// are those of libstdc++, and the test is skipped with another standard library.
struct PinnedCounts {
  int iterations, n_cg, n_expansion, n_proportioning;
  long n_products;
  int n_fallbacks, n_refreshes;
};

struct PinnedRun {
  PinnedCounts counts;
  std::vector<double> x;  // the final iterate
};

struct PinnedProblem {
  Index n_patches;  // random_contact_problem(n_patches, cond, seed)
  double cond;
  unsigned seed;
  double rel_tolerance;
  bool infeasible_start;  // start from 2 N(0, 1) (std::mt19937 seed 7) instead of 0
};

struct PinnedCase {
  PinnedProblem problem;
  PinnedRun paper, bb;
};

// Counts: iterations, n_cg, n_expansion, n_proportioning, n_products, n_fallbacks, n_refreshes.
const std::vector<PinnedCase>& pinned_cases() {
  // clang-format off
  static const std::vector<PinnedCase> cases = {
      {{4, 100.0, 41u, 1e-10, false},
       {{219, 5, 3, 211, 223, 0, 0},
        {0.013592065402163053, -0.031334696914938898, 0.036270360239960525, 0.012209626792763353,
         0.050712951241713003, -0.081146166146292997, 0, -0.0097499888099906312,
         -0.01839047255865223, 0, -0.079207062243079343, -0.021365074539348362}},
       {{167, 19, 13, 135, 181, 64, 0},
        {0.013592065401309198, -0.031334696914568597, 0.036270360240280443, 0.01220962679196516,
         0.050712951242313793, -0.081146166145917534, 0, -0.0097499888092873674,
         -0.018390472559025074, 0, -0.07920706224277245, -0.021365074539351898}}},
      {{10, 1000.0, 44u, 1e-6, true},
       {{288, 163, 12, 113, 301, 0, 0},
        {0, -0.0067336991118499938, -0.013172353328159908, 0.016413057860587301,
         0.0091120814938779066, 0.0042653952479856042, 0.0016098888999979721, -0.015713371379424863,
         -0.01729780771807142, 0, 0.024951758351422285, 0.0027314807011256268,
         0, 0.016427836123637667, -0.013363482701378352, 0.023392592175033148,
         -0.0031189379482196742, 0.0036970554882001399, 0, 0.0085001492983828811,
         -0.0035823550666708899, 0, -0.0063864133113011, -0.015480133104304215,
         0.024681335101465092, 0.0090564779305192227, -0.0183408365084262, 0,
         0.0057714368926852144, -0.0085977769754733008}},
       {{287, 145, 33, 109, 322, 0, 1},
        {0, -0.0067337204465824129, -0.013172310774276639, 0.016413120841271243,
         0.0091120777073582793, 0.0042654033370450083, 0.0016098181976651551, -0.015713293460335391,
         -0.01729782934255306, 0, 0.02495166425614569, 0.0027315334581215528,
         0, 0.016427773676458986, -0.013363496823376907, 0.023392479691008362,
         -0.0031189977583822226, 0.0036970080902406209, 0, 0.0085001611124037018,
         -0.0035823574007082717, 0, -0.0063863787691796391, -0.015480189478890937,
         0.024681305821627097, 0.0090564642989892138, -0.018340883121287076, 0,
         0.0057713558487327574, -0.0085977541528970726}}},
      {{20, 300.0, 43u, 1e-8, false},
       {{345, 130, 8, 207, 354, 0, 0},
        {0, 0.05079275441067263, 0.088554204310152984, 0.015527233065237773,
         -0.055466200615592105, -0.026167612016039492, 0.052899058940591555, 0.12102066635723328,
         -0.018995995832536649, 0, 0, -0,
         0.021889334253405932, -0.062961965781190177, 0.029293380019950809, 0.085439831611032385,
         0.029231313566599752, -0.0087659196063732386, 0.080652523100748288, -0.010003414033616083,
         0.020776925779796663, 0.0054317634676112978, 0.088295105419983561, 0.087459173239374424,
         0.09056985574851964, -0.023991169653818704, 0.015623428471014311, 0.082452754018527724,
         -0.023827122819724749, 0.071098784434423204, 0, 0.07159120341829775,
         -0.061268265574446749, 0.056221142380910021, -0.035332806484322951, 0.04781096514392686,
         0, 0.04723438243684179, 0.023498641222315025, 0.07515473005394864,
         -0.039958867220385483, 0.0053325686988983136, 0.054136964605605985, 0,
         -0, 0, -0.17842746288460506, 0.0029610149809449768,
         0.054084175716934683, -0, -0, 0.046547926277291818,
         0.12117521806326625, 0.023093177441188679, 0.033948583010627253, -0,
         -0, 0, 0.016384707381765031, 0.043113123534926114}},
       {{307, 125, 44, 138, 352, 10, 0},
        {0, 0.050792754304301517, 0.088554204219854979, 0.015527233111967634,
         -0.055466200634591831, -0.026167611975766711, 0.052899058802712673, 0.12102066619495266,
         -0.018995995649747396, 0, 0, -0,
         0.021889334189401439, -0.062961965721496913, 0.029293380148253029, 0.085439831365253446,
         0.02923131379833321, -0.0087659193909059088, 0.080652523162155154, -0.010003413873086356,
         0.02077692588141155, 0.0054317637139090344, 0.088295105060943999, 0.087459173336886992,
         0.090569856006722751, -0.023991169705305109, 0.015623428176990506, 0.082452753519131686,
         -0.023827122704215012, 0.071098784385519628, 0, 0.07159120333532365,
         -0.061268265642687295, 0.056221141976495428, -0.035332806347186024, 0.047810964963830006,
         0, 0.047234382436666916, 0.023498641222666532, 0.075154729956132427,
         -0.039958867222562117, 0.0053325686825880132, 0.054136964455948788, 0,
         -0, 0, -0.17842746231685583, 0.0029610149862943774,
         0.054084176131113486, -0, -0, 0.046547926211886997,
         0.12117521803736105, 0.02309317737692625, 0.033948582819534223, -0,
         -0, 0, 0.016384707436888281, 0.043113123506921314}}}};
  // clang-format on
  return cases;
}

TEST(MpgpRegression, CountsAndIteratesArePinned) {
#ifndef __GLIBCXX__
  GTEST_SKIP() << "the pinned problems are those drawn by libstdc++'s distributions";
#endif
  for (const auto& [k, paper, bb] : pinned_cases()) {
    const Problem prob = random_contact_problem(k.n_patches, k.cond, k.seed);
    const Index n = prob.b.size();
    for (const auto& [variant, pin] :
         {std::pair{MpgpVariant::Paper, &paper}, std::pair{MpgpVariant::BarzilaiBorwein, &bb}}) {
      MpgpOptions opt;
      opt.variant = variant;
      opt.expansion = MpgpExpansion::Fixed;  // the expansion the counts were pinned with
      opt.rel_tolerance = k.rel_tolerance;
      opt.reference = StopReference::Whole;  // the test the counts were pinned with
      Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
      if (k.infeasible_start) {
        std::mt19937 rng(7);
        x = 2.0 * random_vector(n, rng);
      }
      const auto rep = solve_mpgp(dense_operator(prob.M), prob.b, prob.c, opt, x);
      const std::string where = "n " + std::to_string(n) + " seed " + std::to_string(k.seed) +
                                (variant == MpgpVariant::Paper ? " paper\n" : " bb\n") + rep.full();
      ASSERT_EQ(rep.termination, QpTermination::Converged) << where;
      const PinnedCounts& c = pin->counts;
      EXPECT_EQ(rep.iterations, c.iterations) << where;
      EXPECT_EQ(rep.n_cg, c.n_cg) << where;
      EXPECT_EQ(rep.n_expansion, c.n_expansion) << where;
      EXPECT_EQ(rep.n_proportioning, c.n_proportioning) << where;
      EXPECT_EQ(rep.n_products, c.n_products) << where;
      EXPECT_EQ(rep.n_fallbacks, c.n_fallbacks) << where;
      EXPECT_EQ(rep.n_refreshes, c.n_refreshes) << where;
      ASSERT_EQ(static_cast<Index>(pin->x.size()), n);
      const Eigen::Map<const Eigen::VectorXd> x_pin(pin->x.data(), n);
      EXPECT_LE((x - x_pin).lpNorm<Eigen::Infinity>(), 1e-12 * x_pin.lpNorm<Eigen::Infinity>())
          << where;
      // The pinned iterate is a solution by a measure independent of the solver: its KKT
      // residuals, computed here from the matrix, are at the requested tolerance.
      EXPECT_LT(kkt(prob.M, prob.b, x, prob.c).max(), 10 * k.rel_tolerance) << where;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Edge cases and failures

TEST_P(MpgpVariants, ZeroRightHandSideGivesZeroSolution) {
  const Problem p = random_contact_problem(4, 10.0, 12);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(p.b.size(), 0.3);
  const auto rep =
      solve_mpgp(dense_operator(p.M), Eigen::VectorXd::Zero(p.b.size()), p.c, options(), x);
  EXPECT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_EQ(x, Eigen::VectorXd::Zero(p.b.size()));
  EXPECT_EQ(rep.rel_gp, 0.0);
  EXPECT_EQ(rep.objective, 0.0);
  EXPECT_TRUE(std::isfinite(rep.alpha_bar_used));
}

TEST_P(MpgpVariants, InfeasibleInitialGuessIsProjectedFirst) {
  const Problem p = random_contact_problem(8, 100.0, 13);
  std::mt19937 rng(1);
  const Eigen::VectorXd x0 = 10.0 * random_vector(p.b.size(), rng);
  Eigen::VectorXd x = x0;
  auto opt = tight();
  opt.record_history = true;
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, opt, x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  EXPECT_LE(kkt(p.M, p.b, x, p.c).max(), 1e-9);
  // The starting objective is that of the projected guess.
  const Eigen::VectorXd px = testing::reference_project(p.c, x0);
  EXPECT_NEAR(rep.history.front().objective, objective(p.M, p.b, px),
              1e-12 * std::abs(objective(p.M, p.b, px)));
}

TEST_P(MpgpVariants, ZeroRadiusPinsTangentialUnknowns) {
  Problem p = random_contact_problem(6, 10.0, 14);
  p.c.set_disc_radii(Eigen::VectorXd::Zero(6));  // frictionless
  Eigen::VectorXd x = Eigen::VectorXd::Ones(p.b.size());
  const auto rep = solve_mpgp(dense_operator(p.M), p.b, p.c, tight(), x);
  ASSERT_EQ(rep.termination, QpTermination::Converged) << rep.full();
  for (Index i = 0; i < 6; ++i)
    EXPECT_EQ(x.segment<2>(3 * i + 1), Eigen::Vector2d::Zero());
  // Independent truth: the bound problem on the normal unknowns alone.
  Eigen::MatrixXd Mn(6, 6);
  Eigen::VectorXd bn(6), xn(6);
  for (Index i = 0; i < 6; ++i) {
    bn(i) = p.b(3 * i);
    xn(i) = x(3 * i);
    for (Index j = 0; j < 6; ++j)
      Mn(i, j) = p.M(3 * i, 3 * j);
  }
  EXPECT_LE((xn - testing::enumerate_bound_solution(Mn, bn)).norm(), 1e-9);
}

TEST(Mpgp, NonFiniteOrMismatchedInputsThrow) {
  const Problem p = random_contact_problem(3, 10.0, 15);
  const auto A = dense_operator(p.M);
  const Index n = p.b.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd b_nan = p.b;
  b_nan(2) = NAN;
  EXPECT_THROW(solve_mpgp(A, b_nan, p.c, MpgpOptions{}, x), Error);
  Eigen::VectorXd x_inf = Eigen::VectorXd::Zero(n);
  x_inf(0) = INFINITY;
  EXPECT_THROW(solve_mpgp(A, p.b, p.c, MpgpOptions{}, x_inf), Error);
  auto c_nan = p.c;
  c_nan.radius(1) = NAN;
  EXPECT_THROW(solve_mpgp(A, p.b, c_nan, MpgpOptions{}, x), Error);
  Eigen::VectorXd x_short = Eigen::VectorXd::Zero(n - 1);
  EXPECT_THROW(solve_mpgp(A, p.b, p.c, MpgpOptions{}, x_short), InputError);
  MpgpOptions bad;
  bad.gamma = -1.0;
  EXPECT_THROW(solve_mpgp(A, p.b, p.c, bad, x), InputError);
  EXPECT_THROW(solve_mpgp(Operator{}, p.b, p.c, MpgpOptions{}, x), InputError);
}

TEST_P(MpgpVariants, IndefiniteOperatorReportsNumericalFailure) {
  // A = -I: the power method finds ||A|| = 1, then p^T A p < 0 at the first CG step.
  const Operator A = [](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = -v; };
  auto c = SeparableConstraints::contact_layout(2);
  c.set_disc_radii(Eigen::Vector2d(1.0, 1.0));
  Eigen::VectorXd x = Eigen::VectorXd::Constant(6, 0.1);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(6, 1.0);
  const auto rep = solve_mpgp(A, b, c, options(), x);
  EXPECT_EQ(rep.termination, QpTermination::NumericalFailure) << rep.full();
  EXPECT_NE(rep.message.find("CG step"), std::string::npos) << rep.message;
  // The failed step is counted: its product was spent.
  EXPECT_EQ(rep.n_cg, 1);
  EXPECT_EQ(rep.iterations, 1);
  EXPECT_EQ(rep.n_products, 2);
}

TEST_P(MpgpVariants, OperatorProducingNanReportsNumericalFailure) {
  const Operator A = [](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    y = v;
    if (v(0) != 0.0) y(0) = NAN;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Constant(3, 0.5);
  MpgpOptions opt = options();
  opt.norm_A = 1.0;
  const auto rep =
      solve_mpgp(A, Eigen::Vector3d(1, 1, 1), SeparableConstraints::contact_layout(1), opt, x);
  EXPECT_EQ(rep.termination, QpTermination::NumericalFailure) << rep.full();
}

TEST(Mpgp, ZeroNormOperatorThrowsNumericalError) {
  const Operator A = [](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y.setZero(v.size()); };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(solve_mpgp(A, Eigen::Vector3d(1, 1, 1), SeparableConstraints::contact_layout(1),
                          MpgpOptions{}, x),
               NumericalError);
}

// ---------------------------------------------------------------------------------------------
// Power method

TEST(EstimateNorm, ApproachesLargestEigenvalueFromBelow) {
  std::mt19937 rng(21);
  for (Index n : {1, 5, 40}) {
    const Eigen::MatrixXd M = random_spd(n, 50.0, rng, 2.0);
    const double lmax = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().maxCoeff();
    long count = 0;
    const double est = estimate_norm(dense_operator(M), n, 1000, 1e-12, &count);
    EXPECT_LE(est, lmax * (1 + 1e-14));
    EXPECT_GE(est, lmax * (1 - 1e-6)) << "n " << n;
    EXPECT_GE(count, 1);
  }
  EXPECT_EQ(estimate_norm(dense_operator(Eigen::MatrixXd(0, 0)), 0, 10, 1e-8), 0.0);
}

TEST(EstimateNorm, CountsProductsExactly) {
  const Eigen::MatrixXd M = Eigen::VectorXd::LinSpaced(30, 1.0, 30.0).asDiagonal();
  long calls = 0, counted = 5;  // the counter is added to, not overwritten
  estimate_norm(dense_operator(M, &calls), 30, 7, 1e-30, &counted);
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(counted, 12);
}

}  // namespace
}  // namespace fricon::qp
