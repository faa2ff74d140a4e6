// Verification of the contact solver on the paper's brick (n = 4, 6) and on a closed-form case.
// Every check compares with something the solver did not compute itself: the paper's table,
// an independent dense solution of the dual QP by another algorithm (accelerated projected
// gradient on Q formed with a dense Cholesky of K), the KKT conditions, global equilibrium,
// the mirror symmetry of the problem, and the fixed point phi = Psi(phi).
#include <gtest/gtest.h>

#include <cmath>

#include "common/fixtures.hpp"
#include "fricon/contact/b_matrix.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/dual/dual_operator.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

// Independent dual data: Q = B K^-1 B^T and h = B K^-1 f with a dense Cholesky of K.
struct DenseDual {
  MatrixXd Q, KinvBt;
  VectorXd h, u0;
};

DenseDual dense_dual(const RunResult& r) {
  const auto& c = *r.contact;
  const SparseMatrix B = contact::assemble_b(r.model.mesh, r.model.dofs, c.surface, c.patches);
  const Eigen::LLT<MatrixXd> llt{MatrixXd(r.model.K)};
  DenseDual d;
  d.KinvBt = llt.solve(MatrixXd(B.transpose()));
  d.Q = B * d.KinvBt;
  d.u0 = llt.solve(r.model.f);
  d.h = B * d.u0;
  return d;
}

// Projection onto {lambda_n >= 0} x {||lambda_t|| <= rho} per patch.
void project(VectorXd& x, const VectorXd& rho) {
  for (Index p = 0; p < rho.size(); ++p) {
    x(3 * p) = std::max(x(3 * p), 0.0);
    const Real t = x.segment<2>(3 * p + 1).norm();
    if (t > rho(p)) x.segment<2>(3 * p + 1) *= rho(p) / t;
  }
}

// FISTA with restart: an algorithm unrelated to MPGP, run to a fixed point of the projected
// gradient map.
VectorXd fista(const MatrixXd& Q, const VectorXd& h, const VectorXd& rho) {
  const Real L =
      Eigen::SelfAdjointEigenSolver<MatrixXd>(Q, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  VectorXd x = VectorXd::Zero(h.size()), y = x, x_old = x;
  Real t = 1.0;
  for (int it = 0; it < 200000; ++it) {
    x_old = x;
    x = y - (Q * y - h) / L;
    project(x, rho);
    const Real t_new = 0.5 * (1 + std::sqrt(1 + 4 * t * t));
    y = x + ((t - 1) / t_new) * (x - x_old);
    if ((Q * x - h).dot(x - x_old) > 0) {  // restart when the objective goes up
      y = x;
      t = 1.0;
    } else {
      t = t_new;
    }
    if ((x - x_old).norm() <= 1e-15 * x.norm()) break;
  }
  return x;
}

Problem tight(Problem p) {
  p.solver.qp.rel_tolerance = 1e-10;
  return p;
}

}  // namespace

TEST(PaperBrick, SizesIterationsAndPenetrationMatchTable1) {
  for (const PaperRow& row : paper_table1()) {
    if (row.n > 6) continue;
    const RunResult r = run(paper_problem(row.n, row.param));
    ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
    const ContactReport& c = *r.report.contact;
    EXPECT_EQ(r.report.n_primal, row.n_p);
    EXPECT_EQ(c.n_dual, row.n_d);
    EXPECT_LE(std::abs(c.outer_iterations - row.it), 1);
    EXPECT_NEAR(c.wn_pos_inf, row.wn_pos_inf, 0.1 * row.wn_pos_inf);
    // Within a factor 1.5 of the paper's count of products with Q (theory.md §7.5).
    EXPECT_LT(static_cast<double>(c.n_mult), 1.5 * static_cast<double>(row.n_mult));
    EXPECT_GT(static_cast<double>(c.n_mult), static_cast<double>(row.n_mult) / 1.5);
    // Figure maxima of the paper (n = 16) are approached already: max ||lambda_t|| = 0.3 g.
    EXPECT_NEAR(c.max_lambda_t, 0.3 * 2e7, 0.01 * 6e6);
    EXPECT_DOUBLE_EQ(c.err_history.front(), 1.0);
    EXPECT_LE(c.err_history.back(), 1e-4);
  }
}

TEST(PaperBrick, TightQpAgreesWithAnIndependentDenseSolution) {
  const RunResult r = run(tight(paper_problem(4, 6e4)));
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& c = *r.report.contact;
  EXPECT_LT(c.kkt.max(), 1e-9);
  const DenseDual d = dense_dual(r);
  const VectorXd lambda = fista(d.Q, d.h, r.contact->radius);
  const VectorXd& ours = r.contact->lambda;
  // A strongly convex QP stopped at ||g^P|| <= eps ||h|| is within about eps ||h|| / lambda_min(Q)
  // of its solution; allow a factor 10 over that bound.
  const Real lambda_min =
      Eigen::SelfAdjointEigenSolver<MatrixXd>(d.Q, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  const Real bound = 10 * 1e-10 * d.h.norm() / lambda_min / lambda.norm();
  EXPECT_LT(bound, 1e-6);  // the comparison below must mean something
  EXPECT_LT((ours - lambda).norm() / lambda.norm(), bound);
  // The displacement recovered from the multipliers, w = K^-1 (f - B^T lambda), also agrees.
  const VectorXd w = d.u0 - d.KinvBt * lambda;
  const VectorXd w_ours = r.model.dofs.from_nodal(r.displacement);
  EXPECT_LT((w_ours - w).norm() / w.norm(), 1e-8);
}

TEST(PaperBrick, GlobalEquilibriumHoldsToRoundOff) {
  const RunResult r = run(paper_problem(4, 6e4));
  const RunReport& rep = r.report;
  EXPECT_LT(rep.equilibrium_residual, 1e-12);
  EXPECT_LT(rep.linear_residual, 1e-12);
  // The body is pushed down (z1: -9e7 N, x1: +2e7 N): the foundation carries most of it.
  EXPECT_GT(rep.contact_force(2), 0.0);
  EXPECT_NEAR(rep.applied_force(2), -7e7, 1e-3);
}

TEST(PaperBrick, SolutionIsSymmetricInY) {
  // The brick, its mesh (n even), the chessboard and the loads are symmetric under y -> 1 - y:
  // lambda_n and lambda_t1 are even, lambda_t2 odd; likewise w_n, w_t1 even and w_t2 odd.
  const RunResult r = run(tight(paper_problem(4, 6e4)));
  const auto& c = *r.contact;
  const Real scale_n = c.lambda.maxCoeff();
  for (Index p = 0; p < c.patches.size(); ++p)
    for (Index q = 0; q < c.patches.size(); ++q) {
      const bool mirror =
          std::abs(c.patches.centroid(0, p) - c.patches.centroid(0, q)) < 1e-12 &&
          std::abs(c.patches.centroid(1, p) + c.patches.centroid(1, q) - 1.0) < 1e-12;
      if (!mirror) continue;
      EXPECT_NEAR(c.lambda(3 * p), c.lambda(3 * q), 1e-8 * scale_n);
      EXPECT_NEAR(c.lambda(3 * p + 1), c.lambda(3 * q + 1), 1e-8 * scale_n);
      EXPECT_NEAR(c.lambda(3 * p + 2), -c.lambda(3 * q + 2), 1e-8 * scale_n);
    }
  const Real scale_w = r.report.max_displacement;
  const auto& nodes = r.model.mesh.nodes;
  for (Index a = 0; a < c.surface.n_nodes(); ++a)
    for (Index b = 0; b < c.surface.n_nodes(); ++b) {
      const Vec3 xa = nodes.col(c.surface.nodes[static_cast<size_t>(a)]);
      const Vec3 xb = nodes.col(c.surface.nodes[static_cast<size_t>(b)]);
      if (std::abs(xa(0) - xb(0)) > 1e-12 || std::abs(xa(1) + xb(1) - 1.0) > 1e-12) continue;
      EXPECT_NEAR(c.wn(a), c.wn(b), 1e-8 * scale_w);
      EXPECT_NEAR(c.wt1(a), c.wt1(b), 1e-8 * scale_w);
      EXPECT_NEAR(c.wt2(a), -c.wt2(b), 1e-8 * scale_w);
    }
}

TEST(PaperBrick, ReturnedSlipIsAFixedPointOfPsi) {
  // Converge the outer loop tightly, then apply Psi once more independently: radii from the
  // returned slip, the dual QP by FISTA on the dense Q, w recovered, phi = ||w_t||.
  Problem p = tight(paper_problem(4, 6e4));
  p.solver.outer.tol = 1e-9;
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const auto& c = *r.contact;
  const VectorXd phi = (c.wt1.array().square() + c.wt2.array().square()).sqrt().matrix();
  const auto law = contact::make_friction_law(p.contact.front().friction);
  const VectorXd rho =
      contact::patch_radii(r.model.mesh, c.surface, c.patches, *law, phi,
                           VectorXd::Constant(phi.size(), p.contact.front().slip_bound));
  const DenseDual d = dense_dual(r);
  const VectorXd w = d.u0 - d.KinvBt * fista(d.Q, d.h, rho);
  VectorXd psi(phi.size());
  for (Index a = 0; a < phi.size(); ++a) {
    Vec3 u = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const Index dof = r.model.dofs.dof(c.surface.nodes[static_cast<size_t>(a)], k);
      if (dof >= 0) u(k) = w(dof);
    }
    psi(a) = std::hypot(u.dot(c.surface.t1), u.dot(c.surface.t2));
  }
  EXPECT_LT((psi - phi).norm() / phi.norm(), 1e-7);
}

TEST(ContactColumn, FrictionlessColumnUnderGravityCarriesHalfItsWeight) {
  // A column (0,1)x(0,1)x(0,2) clamped on top, on rollers at its four sides, under its own weight
  // b = (0, 0, -b0), resting on the foundation at z = 0. The solution depends on z only, u_z is
  // quadratic and vanishes at both ends, so each end carries half the weight: a uniform contact
  // pressure lambda_n = b0 H / 2, and no tangential displacement.
  Problem p = test::gravity_column();
  const Real b0 = test::kColumnWeight, H = test::kColumnHeight;
  ContactOptions c;
  c.boundary = "z0";
  c.slip_bound = 1e5;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.0;
  p.contact = {c};
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const auto& f = *r.contact;
  for (Index q = 0; q < f.patches.size(); ++q) {
    EXPECT_NEAR(f.lambda(3 * q), b0 * H / 2, 1e-6 * b0 * H) << "patch " << q;
    EXPECT_NEAR(f.lambda.segment<2>(3 * q + 1).norm(), 0.0, 1e-9 * b0 * H);
  }
  EXPECT_NEAR(r.report.contact->total_normal_force, b0 * H / 2 * 1.0, 1e-6 * b0 * H);
  EXPECT_LT(r.report.contact->max_wt, 1e-12);
}

TEST(PaperBrick, EveryDualOperatorGivesTheSameSolution) {
  // implicit (solves with K), dense (block solves), schur (constrained factor), forward (sweep
  // over the reach of the surface): the same QP, so the same multipliers to the QP tolerance
  // and the same outer iterations.
  std::vector<RunResult> runs;
  for (const char* mode : {"implicit", "schur", "forward"}) {
    Problem p = tight(paper_problem(4, 6e4));
    p.solver.dual_operator = parse_enum<dual::DualOperatorKind>(mode);
    runs.push_back(run(p));
    ASSERT_EQ(runs.back().report.status, RunStatus::Converged) << mode;
    EXPECT_EQ(enum_name(runs.back().report.contact->dual_operator), mode);
  }
  const VectorXd& ref = runs[0].contact->lambda;
  for (const RunResult& r : runs) {
    EXPECT_LT((r.contact->lambda - ref).norm() / ref.norm(), 1e-8);
    EXPECT_LT((r.displacement - runs[0].displacement).norm() / runs[0].displacement.norm(), 1e-8);
    EXPECT_EQ(r.report.contact->outer_iterations, runs[0].report.contact->outer_iterations);
  }
  // Implicit: every product with Q is a solve with K; schur: only u0 and the final recovery
  // (which the KKT check reuses).
  EXPECT_GT(runs[0].report.contact->n_kinv, runs[0].report.contact->n_mult);
  EXPECT_EQ(runs[1].report.contact->n_kinv, 2);
  // "auto" is the forward sweep at this size.
  Problem p = tight(paper_problem(4, 6e4));
  EXPECT_EQ(enum_name(run(p).report.contact->dual_operator), "forward");
}

TEST(PaperBrick, AndersonMixingReachesTheSameFixedPoint) {
  // The accelerated outer loop must converge to the same slip and multipliers (to the outer
  // tolerance), in no more iterations than the plain successive approximations.
  Problem plain = tight(paper_problem(4, 6e4));
  plain.solver.outer.tol = 1e-8;
  Problem accelerated = plain;
  accelerated.solver.outer.acceleration = outer::Acceleration::Anderson;
  const RunResult a = run(plain), b = run(accelerated);
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  EXPECT_LE(b.report.contact->outer_iterations, a.report.contact->outer_iterations);
  EXPECT_LT((b.contact->lambda - a.contact->lambda).norm() / a.contact->lambda.norm(), 1e-6);
  EXPECT_LT((b.displacement - a.displacement).norm() / a.displacement.norm(), 1e-6);
}

TEST(PaperBrick, BarzilaiBorweinVariantGivesTheSameSolutionWithFewerProducts) {
  Problem paper = tight(paper_problem(4, 6e4));
  Problem fast = paper;
  fast.solver.qp.variant = qp::MpgpVariant::BarzilaiBorwein;
  const RunResult a = run(paper), b = run(fast);
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  EXPECT_LT(b.report.contact->kkt.max(), 1e-9);
  EXPECT_LT(b.report.contact->n_mult, a.report.contact->n_mult / 2);
  // Both stop at err <= 1e-4 of the same fixed point.
  EXPECT_LT((b.displacement - a.displacement).norm() / a.displacement.norm(), 1e-4);
}

TEST(PaperBrick, AnOuterLoopThatDoesNotContractStopsAndSaysSo) {
  // Friction that rises steeply with slip (F from 0 to 3 over 1 micrometre): no slip gives no
  // friction and a large slip, which gives strong friction and little slip, and so on. The
  // successive approximations cycle; the loop must stop as stalled well before outer_max and
  // name the cause. (Which iteration it stops at depends on rounding, hence on the CPU's BLAS
  // kernels and thread count: only what is robust is asserted.)
  Problem p = paper_problem(4, 6e4);
  p.contact.front().friction.law = contact::FrictionLawKind::Table;
  p.contact.front().friction.t = {1.0e-5, 1.1e-5};
  p.contact.front().friction.f = {0.0, 3.0};
  p.solver.outer.max_iterations = 50;
  const RunResult r = run(p);
  EXPECT_EQ(r.report.status, RunStatus::NotConverged);
  EXPECT_EQ(r.report.contact->termination, outer::OuterTermination::Stalled);
  EXPECT_LE(r.report.contact->outer_iterations, 25);
  EXPECT_NE(r.report.message.find("do not contract"), std::string::npos) << r.report.message;
  // The paper's law contracts: the same check never fires there (7 iterations at most).
  const RunResult ok = run(paper_problem(4, 6e4));
  EXPECT_EQ(ok.report.status, RunStatus::Converged) << ok.report.message;
}

namespace {

// A dual operator whose products are off by a relative 1e-3 from B K^-1 B^T (a defect the QP
// cannot see: it solves its own problem to qp_rtol), with the true displacement recovery.
class SkewedOperator final : public dual::FactorDualOperator {
 public:
  explicit SkewedOperator(const dual::DualInput& input)
      : FactorDualOperator(input), exact_(dual::make_forward_operator(input)) {}
  dual::DualOperatorKind kind() const override { return dual::DualOperatorKind::Forward; }
  void apply(const VectorXd& x, VectorXd& y) const override {
    exact_->apply(x, y);
    y *= 1.0 + 1e-3;
  }
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    exact_->contact_displacement(lambda, w);
  }

 private:
  std::unique_ptr<dual::DualOperator> exact_;
};

struct FactoredBrick {
  Problem problem = paper_problem(4, 6e4);
  Model model;
  contact::ContactDiscretization disc;
  FactoredBrick() {
    PhaseTimes times;
    model = assemble_model(problem, times);
    disc = discretize_contact(problem, model.mesh, model.dofs);
    factorize_model(model, {}, times);
  }
  dual::DualInput input() const { return {model.factor, disc.B, model.f, disc.dofs, {}}; }
};

}  // namespace

TEST(Certificate, ARunWhoseFinalKktResidualsExceedTheBoundIsNotConverged) {
  const FactoredBrick b;
  PhaseTimes times;
  const auto exact = dual::make_forward_operator(b.input());
  const ContactOutcome good = solve_contact(b.problem, b.model, b.disc, *exact, times);
  ASSERT_TRUE(good.converged) << good.message;
  EXPECT_EQ(good.report.termination, outer::OuterTermination::Converged);
  EXPECT_LE(good.report.kkt.max(), good.report.kkt_bound);
  EXPECT_EQ(good.report.kkt_bound, kCertificateFactor * b.problem.solver.qp.rel_tolerance);

  const SkewedOperator skewed(b.input());
  const ContactOutcome bad = solve_contact(b.problem, b.model, b.disc, skewed, times);
  EXPECT_FALSE(bad.converged);
  EXPECT_EQ(bad.report.termination, outer::OuterTermination::CertificateFailed);
  EXPECT_GT(bad.report.kkt.max(), bad.report.kkt_bound);
  EXPECT_NE(bad.message.find("certificate"), std::string::npos) << bad.message;
}

TEST(PaperBrick, MpgpMonotonicityIsReportedPerIterationAndInAll) {
  const RunResult r = run(paper_problem(4, 6e4));
  const ContactReport& c = *r.report.contact;
  int sum = 0;
  for (const IterationReport& it : c.history)
    sum += it.n_objective_increases;
  EXPECT_EQ(sum, c.n_objective_increases);
  EXPECT_EQ(c.n_objective_increases, 0);  // alpha_bar = 1.95/||Q||: no step increases q
}

TEST(Symmetry, AHalfBrickOnARollerReproducesTheFullModelOnItsHalf) {
  // The paper's brick (n = 4) is symmetric under y -> 1 - y. Its half y < 1/2 with a roller
  // (u_y = 0) on the cut y = 1/2 is the same discrete problem restricted to symmetric fields:
  // the same mesh and patches on the half, and the roller meets the contact face along an edge
  // whose nodes keep their x and z components (they remain contact nodes).
  Problem full = tight(paper_problem(4, 6e4));
  full.solver.outer.tol = 1e-9;
  Problem half = full;
  half.mesh.size = {3.0, 0.5, 1.0};
  half.mesh.cells = {12, 2, 4};
  half.dirichlet.push_back({"y1", {false, true, false}});
  const RunResult a = run(full), b = run(half);
  ASSERT_EQ(a.report.status, RunStatus::Converged) << a.report.message;
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  // 13 x 3 surface nodes, the 3 on x = 0 clamped: 36 contact nodes, the roller's included.
  EXPECT_EQ(b.report.contact->n_contact_nodes, 36);
  EXPECT_EQ(b.report.contact->n_patches, a.report.contact->n_patches / 2);

  const auto& fa = *a.contact;
  const auto& fb = *b.contact;
  const Real scale_lambda = fa.lambda.cwiseAbs().maxCoeff();
  Index matched = 0;
  for (Index q = 0; q < fb.patches.size(); ++q)
    for (Index p = 0; p < fa.patches.size(); ++p) {
      if ((fa.patches.centroid.col(p) - fb.patches.centroid.col(q)).norm() > 1e-12) continue;
      ++matched;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fb.lambda(3 * q + c), fa.lambda(3 * p + c), 1e-6 * scale_lambda)
            << "patch " << q << " component " << c;
    }
  EXPECT_EQ(matched, fb.patches.size());

  const Real scale_u = a.report.max_displacement;
  Index nodes = 0;
  for (Index j = 0; j < b.model.mesh.n_nodes(); ++j)
    for (Index i = 0; i < a.model.mesh.n_nodes(); ++i) {
      if ((a.model.mesh.nodes.col(i) - b.model.mesh.nodes.col(j)).norm() > 1e-12) continue;
      ++nodes;
      EXPECT_LT((a.displacement.col(i) - b.displacement.col(j)).norm(), 1e-6 * scale_u)
          << "node " << j;
    }
  EXPECT_EQ(nodes, b.model.mesh.n_nodes());
}

TEST(Symmetry, ARollerOnTheContactFaceFixesTheTangentialComponentOnly) {
  // u_y = 0 on the whole contact face: the t2 = e2 multipliers act on nothing and stay zero, the
  // nodes keep their normal and x motion (all 60 remain contact nodes), and the problem is
  // solved and certified like any other.
  Problem p = tight(paper_problem(4, 6e4));
  p.dirichlet.push_back({"z0", {false, true, false}});
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& c = *r.report.contact;
  EXPECT_EQ(c.n_contact_nodes, 60);
  EXPECT_EQ(c.n_inactive_multipliers, c.n_patches);
  for (Index q = 0; q < c.n_patches; ++q)
    EXPECT_EQ(r.contact->lambda(3 * q + 2), 0.0);
  EXPECT_LT(c.kkt.max(), 1e-9);
  for (Index a = 0; a < r.model.mesh.n_nodes(); ++a) {
    if (r.model.mesh.nodes(2, a) == 0.0) {
      EXPECT_EQ(r.displacement(1, a), 0.0);
    }
  }
}
