// Loading paths (theory.md §2.9) against what holds whatever the solver does inside:
//   - the first step of a path is the static problem, and a path of frictionless steps
//     proportional to the final loads ends at the one-step answer (frictionless contact is
//     path-independent);
//   - saturation: a block pressed and then pushed by its top face carries a friction force equal
//     to the reaction of the push (global equilibrium) while it sticks, exactly mu times the
//     normal force once every patch slides, and sticks again when the push reverses;
//   - slip-weakening: with the paper's F of the accumulated slip, the force ratio of the sliding
//     block falls from 0.3 to 0.2 where the law falls (1e-5 to 1e-5 + 2/param);
//   - the contact search along a path (theory.md §2.7, §2.9): leaving out patches that do not
//     press changes no step's answer (the same path with every patch), while the candidates grow
//     with the load.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fricon/contact/friction_law.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

constexpr Real kPress = 1.0e-4;  // downward displacement of the block's top [m]
constexpr Real kMu = 0.3;

// A 1 x 1 x 0.5 m block (Poisson's ratio 0: pressing leaves the bottom without tangential
// motion, so that sliding is along the push only) on a rigid plane, its top pressed down by
// kPress and pushed along x by `push` [m] times each factor of the path.
Problem pushed_block(const std::vector<Real>& push_path, Real push) {
  Problem p;
  p.mesh.size = {1.0, 1.0, 0.5};
  p.mesh.cells = {4, 4, 2};
  p.material.poisson = 0.0;
  DirichletOptions press;
  press.boundary = "z1";
  press.components = {false, true, true};
  press.value = Vec3(0.0, 0.0, -kPress);
  DirichletOptions shear;
  shear.boundary = "z1";
  shear.components = {true, false, false};
  shear.value = Vec3(push, 0.0, 0.0);
  shear.path = push_path;
  p.dirichlet = {press, shear};
  ContactOptions c;
  c.boundary = "z0";
  c.model = contact::FrictionModel::Coulomb;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = kMu;
  p.contact = {c};
  p.loading.steps = static_cast<int>(push_path.size());
  p.solver.qp.rel_tolerance = 1e-10;
  p.solver.outer.tol = 1e-9;
  p.solver.certificate_tol = 1e-9;
  return p;
}

Real relative_difference(const fe::NodalField& a, const fe::NodalField& b) {
  return (a - b).norm() / b.norm();
}

// Every step's result, as RunOptions::on_step reports it.
struct StepRecorder {
  std::vector<fe::NodalField> displacement;
  RunOptions options() {
    RunOptions o;
    o.on_step = [this](const RunResult& r) { displacement.push_back(r.displacement); };
    return o;
  }
};

}  // namespace

TEST(LoadingPath, TheFirstStepIsTheStaticProblem) {
  Problem statics = paper_problem(4, 6e4);
  statics.solver.qp.rel_tolerance = 1e-11;
  statics.solver.outer.tol = 1e-10;
  const RunResult one = run(statics);
  ASSERT_EQ(one.report.status, RunStatus::Converged) << one.report.message;
  // Two steps with the static loads: the first is the static run; the second, with nothing
  // changed, stays there (no slip increment).
  Problem path = statics;
  path.loading.steps = 2;
  path.traction.front().path = {1.0, 1.0};
  StepRecorder steps;
  const RunResult r = run(path, steps.options());
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(steps.displacement.size(), 2u);
  // The same problem, up to the round-off of u0 = K^-1 f summed from the loads' own solutions.
  EXPECT_LE(relative_difference(steps.displacement[0], one.displacement), 1e-12);
  EXPECT_LE(relative_difference(steps.displacement[1], one.displacement), 1e-8);
  ASSERT_EQ(r.report.steps.size(), 2u);
  const Real s1 = r.report.steps[0].max_accumulated_slip;
  EXPECT_NEAR(r.report.steps[1].max_accumulated_slip, s1, 1e-8 * s1)
      << "the second step adds no slip";
}

TEST(LoadingPath, ProportionalFrictionlessStepsEndAtTheOneStepAnswer) {
  Problem statics = paper_problem(4, 6e4);
  statics.contact.front().friction.law = contact::FrictionLawKind::Constant;
  statics.contact.front().friction.value = 0.0;
  statics.solver.qp.rel_tolerance = 1e-11;
  const RunResult one = run(statics);
  ASSERT_EQ(one.report.status, RunStatus::Converged) << one.report.message;
  Problem path = statics;
  path.loading.steps = 4;
  for (TractionOptions& t : path.traction)
    t.path = {0.25, 0.5, 0.75, 1.0};
  StepRecorder steps;
  const RunResult r = run(path, steps.options());
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  EXPECT_LE(relative_difference(r.displacement, one.displacement), 1e-8);
  // Linear in the load as long as the contact zone does not change: a quarter of the load, a
  // quarter of the displacement (the brick touches everywhere at every step here).
  EXPECT_LE(relative_difference(4.0 * steps.displacement[0], one.displacement), 1e-8);
}

TEST(LoadingPath, OverlappingDirichletEntriesThatAgreeCountTheirValueOnce) {
  // The clamped end and the bottom share an edge, and both move it down by the same amount at
  // every step: each step is the static (elastic, linear) problem of its loads, the shared edge
  // moved once, not once per entry.
  Problem statics;
  statics.mesh.size = {3.0, 1.0, 1.0};
  statics.mesh.cells = {6, 2, 2};
  DirichletOptions end, bottom;
  end.boundary = "x0";
  end.components = {true, true, true};
  end.value = Vec3(0.0, 0.0, -1e-4);
  bottom.boundary = "z0";
  bottom.components = {false, false, true};
  bottom.value = Vec3(0.0, 0.0, -1e-4);
  TractionOptions pull;
  pull.boundary = "x1";
  pull.value = Vec3(1e7, 0.0, 0.0);
  statics.dirichlet = {end, bottom};
  statics.traction = {pull};
  const std::vector<Real> factors{0.5, 1.0};
  Problem path = statics;
  path.loading.steps = 2;
  for (DirichletOptions& d : path.dirichlet)
    d.path = factors;
  path.traction.front().path = {1.0, 1.0};
  StepRecorder steps;
  const RunResult r = run(path, steps.options());
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(steps.displacement.size(), factors.size());
  for (size_t k = 0; k < factors.size(); ++k) {
    Problem alone = statics;
    for (DirichletOptions& d : alone.dirichlet)
      d.value *= factors[k];
    const RunResult one = run(alone);
    ASSERT_EQ(one.report.status, RunStatus::Converged) << one.report.message;
    EXPECT_LE(relative_difference(steps.displacement[k], one.displacement), 1e-10) << "step " << k;
  }
}

TEST(LoadingPath, ThePushedBlockSticksThenSlidesAtMuTimesTheNormalForceAndSticksOnReversal) {
  // Push to 1e-5 (stick), to 4e-4 and 6e-4 (past sliding), then back to 5e-4 (reversal).
  const std::vector<Real> path{0.0, 0.1, 4.0, 6.0, 5.0};
  const RunResult r = run(pushed_block(path, 1e-4));
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const std::vector<StepReport>& s = r.report.steps;
  ASSERT_EQ(s.size(), path.size());
  for (const StepReport& step : s) {
    SCOPED_TRACE(step.step);
    // Global equilibrium: the friction force is the reaction of the push (and the normal force
    // that of the press).
    EXPECT_LE(step.equilibrium_residual, 1e-8);
    EXPECT_NEAR(step.tangential_force.x(), -step.reaction_force.x(), 1e-8 * step.normal_force);
    EXPECT_LE(step.tangential_force.norm(), kMu * step.normal_force * (1.0 + 1e-8));
  }
  // Pressed only: no friction. A small push sticks everywhere.
  EXPECT_LE(s[0].tangential_force.norm(), 1e-8 * s[0].normal_force);
  // The friction force on the block opposes the push (along -x).
  const auto resisted = [&s](size_t k) { return -s[k].tangential_force.x(); };
  EXPECT_EQ(s[1].n_slip, 0);
  EXPECT_GT(resisted(1), 0.0);
  // Pushed past sliding: every patch slips, the force is mu N (to the Coulomb fixed point's
  // tolerance).
  for (size_t k : {2, 3}) {
    EXPECT_EQ(s[k].n_stick, 0) << "step " << k + 1;
    EXPECT_NEAR(resisted(k), kMu * s[k].normal_force, 1e-7 * s[k].normal_force);
  }
  // Reversal: it sticks again, and the force falls along the stick slope of the first push (the
  // corner of the loop), not at once to -mu N.
  EXPECT_EQ(s[4].n_slip, 0);
  const Real stick_slope = resisted(1) / (0.1e-4);
  const Real expected = resisted(3) - stick_slope * 1e-4;
  EXPECT_NEAR(resisted(4), expected, 0.02 * std::abs(expected));
}

TEST(LoadingPath, SlipWeakeningFallsFromStaticToKineticWhereThePapersLawFalls) {
  constexpr Real param = 6e4;  // F falls from 0.3 at 1e-5 m to 0.2 at 1e-5 + 2/param m
  // The push [1e-6 m]: fast to the start of sliding, then 2e-6 m per step through the fall (the
  // slip grows by about 2.5 times the push there: the softening slope is below the block's
  // shear stiffness, so that the fall is stable under a prescribed push), then beyond.
  std::vector<Real> path{0.0, 20.0, 40.0, 56.0};
  for (int push = 58; push <= 100; push += 2)
    path.push_back(static_cast<Real>(push));
  path.insert(path.end(), {120.0, 140.0});
  Problem p = pushed_block(path, 1e-6);
  p.contact.front().friction.law = contact::FrictionLawKind::Paper;
  p.contact.front().friction.param = param;
  // Softening slows the successive approximations (contraction about 0.8 inside the fall).
  p.solver.outer.acceleration = outer::Acceleration::Anderson;
  p.solver.outer.max_iterations = 100;
  // Per step, the least and the largest accumulated slip of the surface nodes.
  std::vector<std::pair<Real, Real>> slip;
  RunOptions o;
  o.on_step = [&slip](const RunResult& r) {
    slip.emplace_back(r.contact->slip.minCoeff(), r.contact->slip.maxCoeff());
  };
  const RunResult r = run(p, o);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const auto law = contact::make_friction_law(p.contact.front().friction);
  int before = 0, during = 0, after = 0;
  for (const StepReport& s : r.report.steps) {
    if (s.n_stick > 0 || s.n_separated > 0) continue;  // not sliding everywhere
    SCOPED_TRACE(s.step);
    const Real ratio = -s.tangential_force.x() / s.normal_force;  // it opposes the push
    const auto [least, most] = slip[static_cast<size_t>(s.step - 1)];
    // Each patch's friction is its mean F times its pressure: the ratio lies between F at the
    // most and at the least slip, 0.3 before the fall and 0.2 after it.
    EXPECT_LE(ratio, (*law)(least) + 1e-8);
    EXPECT_GE(ratio, (*law)(most)-1e-8);
    if (most < 1e-5) ++before;
    if (least > 1e-5 + 2.0 / param) {
      ++after;
      EXPECT_NEAR(ratio, 0.2, 1e-8);
    }
    if (least > 1e-5 && most < 1e-5 + 2.0 / param) ++during;
  }
  EXPECT_GT(after, 0) << "the block never slid past the law's fall";
  EXPECT_GT(during, 0) << "no sliding step inside the fall";
  // The force drop of slip-weakening: from the largest ratio to 0.2.
  Real largest = 0.0;
  for (const StepReport& s : r.report.steps)
    largest = std::max(largest, -s.tangential_force.x() / s.normal_force);
  EXPECT_GT(largest, 0.25);
}

// The paper's brick (n = 4) over a plane that falls away towards the loaded free end (2 mm over
// the 3 m), Coulomb friction 0.3, its loads raised to their values in three steps and then
// partly taken off: as the load grows, the free end presses patches that it did not press
// before.
Problem loaded_tilted_brick(contact::ContactSearch search) {
  Problem p = paper_problem(4, 6e4);
  ContactOptions& c = p.contact.front();
  c.model = contact::FrictionModel::Coulomb;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.3;
  c.obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3(0.0, 0.0, -1.0e-5), Vec3(2.0e-3, 0.0, 1.0), ""};
  for (TractionOptions& t : p.traction)
    t.path = {0.3, 0.6, 1.0, 0.7};
  p.loading.steps = 4;
  p.solver.qp.rel_tolerance = 1e-10;
  p.solver.outer.tol = 1e-8;
  p.solver.contact_search = search;
  return p;
}

// Every step's multipliers and the number of patches in its QP.
struct ContactRecorder {
  std::vector<VectorXd> lambda;
  std::vector<Index> candidates;
  RunOptions options() {
    RunOptions o;
    o.on_step = [this](const RunResult& r) {
      lambda.push_back(r.contact->lambda);
      candidates.push_back(r.report.contact->n_candidate_patches);
    };
    return o;
  }
};

TEST(LoadingPath, TheContactSearchChangesNoStepAndItsCandidatesGrowWithTheLoad) {
  ContactRecorder every, searched;
  const RunResult all = run(loaded_tilted_brick(contact::ContactSearch::Off), every.options());
  const RunResult r = run(loaded_tilted_brick(contact::ContactSearch::Gap), searched.options());
  ASSERT_EQ(all.report.status, RunStatus::Converged) << all.report.message;
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(searched.lambda.size(), 4u);
  ASSERT_EQ(every.lambda.size(), 4u);
  const Index n_patches = r.report.contact->n_patches;
  for (std::size_t k = 0; k < 4; ++k) {
    const Real scale = every.lambda[k].maxCoeff();
    EXPECT_LE((searched.lambda[k] - every.lambda[k]).lpNorm<Eigen::Infinity>(), 1e-7 * scale)
        << "step " << k + 1;
    EXPECT_EQ(every.candidates[k], n_patches);
  }
  // Patches are left out, more at the first step than at the full load; the set never shrinks.
  EXPECT_LT(searched.candidates.back(), n_patches);
  EXPECT_LT(searched.candidates.front(), searched.candidates[2]);
  EXPECT_TRUE(std::is_sorted(searched.candidates.begin(), searched.candidates.end()));
  EXPECT_LE(r.report.contact->kkt.max(), r.report.contact->kkt_bound);
}

TEST(LoadingPath, ACoulombPressBroughtBackToZeroEndsWithoutPressure) {
  // The pattern of docs/problem-file.md, [0, 0.5, 1, 1, 0], on the press: released to exactly
  // zero, no load and no gap press the block onto the plane, so the exact answer of the last
  // step is lambda = 0 whatever the history (Poisson's ratio 0.277: the press spreads the
  // bottom and friction locks a tangential state in, which the release undoes).
  Problem p = pushed_block({0.0, 0.0, 0.0, 0.0, 0.0}, 0.0);
  p.material.poisson = 0.277;
  p.dirichlet.front().path = {0.0, 0.5, 1.0, 1.0, 0.0};
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const std::vector<StepReport>& s = r.report.steps;
  ASSERT_EQ(s.size(), 5u);
  const Real pressed = s[3].normal_force;
  ASSERT_GT(pressed, 0.0);
  EXPECT_LE(std::abs(s[4].normal_force), 1e-8 * pressed);
  EXPECT_LE(s[4].tangential_force.norm(), 1e-8 * pressed);
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.contact->lambda.cwiseAbs().maxCoeff(), 1e-8 * r.report.steps[3].normal_force);
  EXPECT_EQ(s[4].n_separated, r.report.contact->n_patches);
}

TEST(LoadingPath, SlipAccumulatesOnlyWhileInContact) {
  // A slip-weakening block (the paper's F: 0.3 up to 1e-5 m of slip, 0.2 beyond 4.3e-5 m) is
  // lifted 0.1 mm off the plane, moved 100 um along x in the air and set down again: it never
  // slid on the plane, so its accumulated slip is zero and its coefficient the static F(0) = 0.3
  // (Poisson's ratio 0: the set-down moves the bottom along the plane by nothing).
  Problem p = pushed_block({0.0, 100.0, 100.0, 100.0}, 1e-6);
  p.dirichlet.front().path = {-1.0, -1.0, 1.0, 1.0};  // lifted, lifted, pressed, pressed
  p.contact.front().friction.law = contact::FrictionLawKind::Paper;
  p.contact.front().friction.param = 6e4;
  std::vector<Real> most_slip;
  RunOptions o;
  o.on_step = [&most_slip](const RunResult& r) { most_slip.push_back(r.contact->slip.maxCoeff()); };
  const RunResult r = run(p, o);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(most_slip.size(), 4u);
  for (size_t k = 0; k < most_slip.size(); ++k)
    EXPECT_LE(most_slip[k], 1e-9) << "step " << k + 1 << ": slip accumulated in the air";
  ASSERT_TRUE(r.contact);
  EXPECT_NEAR(r.contact->F.minCoeff(), 0.3, 1e-12);
  EXPECT_NEAR(r.contact->coefficient.minCoeff(), 0.3, 1e-12);
  // Pressed at steps 3 and 4: in contact, sticking.
  EXPECT_GT(r.report.steps[3].normal_force, 0.0);
}
