// Verification of moving rigid obstacles (theory.md §2.11). The truths are exact identities and
// analytic distances, not fricon's own earlier output:
//   - relative motion: moving the rigid plane by d gives the run in which every Dirichlet value
//     is moved by -d instead (the body then moves by -d as a whole, which K does not see), with
//     the paper's F(s), with Coulomb, and along a loading path: the same multipliers, and
//     displacements that differ by d, to 1e-10;
//   - a ball whose gap is linearized at the solution (a geometric update) has, at that solution,
//     a linearized gap equal to its true distance.
#include <gtest/gtest.h>

#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

namespace {

using namespace fricon;
using namespace fricon::driver;

// The displacement of the obstacle [m]: of the order of the brick's own (about 1e-5 m).
const Vec3 kMove(3e-6, -2e-6, 4e-6);

/// The paper's brick (n = 4) on the plane z = 0 given as an obstacle, solved tightly.
Problem brick_on_plane() {
  Problem p = paper_problem(4, 6e4);
  p.solver.qp.rel_tolerance = 1e-12;
  p.solver.outer.tol = 1e-10;
  p.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3::Zero(), Vec3(0, 0, 1), ""};
  return p;
}

/// `p` with the plane moved by d, and `p` with every Dirichlet value moved by -d instead.
std::pair<Problem, Problem> moved_two_ways(Problem p, const Vec3& d) {
  Problem plane_moved = p;
  plane_moved.contact.front().obstacle->displacement = d;
  for (DirichletOptions& e : p.dirichlet)
    for (int c = 0; c < 3; ++c)
      if (e.components[static_cast<size_t>(c)]) e.value(c) -= d(c);
  return {plane_moved, p};
}

void expect_same_up_to_translation(const RunResult& a, const RunResult& b, const Vec3& d) {
  ASSERT_EQ(a.report.status, RunStatus::Converged) << a.report.message;
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  const VectorXd& la = a.contact->lambda;
  const VectorXd& lb = b.contact->lambda;
  ASSERT_EQ(la.size(), lb.size());
  ASSERT_GT(la.maxCoeff(), 0.0);  // there is contact
  EXPECT_LE((la - lb).cwiseAbs().maxCoeff(), 1e-10 * la.cwiseAbs().maxCoeff());
  const fe::NodalField shifted = b.displacement.colwise() + d;
  EXPECT_LE((a.displacement - shifted).cwiseAbs().maxCoeff(),
            1e-10 * a.displacement.cwiseAbs().maxCoeff());
}

TEST(MovingObstacle, MovingThePlaneIsMovingTheSupportsTheOtherWay) {
  const auto [a, b] = moved_two_ways(brick_on_plane(), kMove);
  expect_same_up_to_translation(run(a), run(b), kMove);
}

TEST(MovingObstacle, MovingThePlaneIsMovingTheSupportsTheOtherWayWithCoulomb) {
  Problem p = brick_on_plane();
  p.contact.front().model = contact::FrictionModel::Coulomb;
  p.contact.front().friction.law = contact::FrictionLawKind::Constant;
  p.contact.front().friction.value = 0.3;
  const auto [a, b] = moved_two_ways(p, kMove);
  expect_same_up_to_translation(run(a), run(b), kMove);
}

TEST(MovingObstacle, MovingThePlaneAlongAPathIsMovingTheSupportsTheOtherWay) {
  // Three steps; the plane moves by 1, 2, then 3 times d, the supports by the same factors of -d.
  Problem p = brick_on_plane();
  p.loading.steps = 3;
  p.traction.front().path = {0.5, 1.0, 0.8};
  auto [a, b] = moved_two_ways(p, kMove);
  a.contact.front().obstacle->path = {1.0, 2.0, 3.0};
  for (DirichletOptions& e : b.dirichlet)
    e.path = {1.0, 2.0, 3.0};
  const RunResult ra = run(a);
  const RunResult rb = run(b);
  expect_same_up_to_translation(ra, rb, 3.0 * kMove);
  ASSERT_EQ(ra.report.steps.size(), rb.report.steps.size());
  for (size_t k = 0; k < ra.report.steps.size(); ++k)
    EXPECT_LE((ra.report.steps[k].tangential_force - rb.report.steps[k].tangential_force).norm(),
              1e-10 * rb.report.steps[k].normal_force)
        << "step " << k + 1;
}

/// The brick's bottom pressed 2 cm onto a ball of radius 5 m below it (contact radius about
/// 0.45 m), frictionless, geometric updates to `tolerance`.
Problem brick_on_ball(Real tolerance) {
  Problem p = paper_problem(4, 6e4);
  p.traction.clear();
  p.dirichlet = {DirichletOptions{"z1", {true, true, true}, Vec3(0, 0, -2e-2)}};
  ContactOptions& c = p.contact.front();
  c.slip_bound = 0.0;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.0;
  c.patches = contact::PatchKind::Agglomerate;
  c.obstacle = ObstacleOptions{};
  c.obstacle->kind = ObstacleKind::Sphere;
  c.obstacle->center = Vec3(1.2, 0.5, -5.0);
  c.obstacle->radius = 5.0;
  c.geometry_updates = 5;
  c.geometry_tolerance = tolerance;
  p.solver.qp.rel_tolerance = 1e-12;
  return p;
}

TEST(MovingObstacle, AGeometricUpdateLinearizesTheBallAtTheSolution) {
  // Updated until the linearized gap is the ball's distance at the deformed position within
  // 1e-9 of the normal displacement.
  const RunResult r = run(brick_on_ball(1e-9));
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& report = *r.report.contact;
  EXPECT_GE(report.geometry_updates, 1);
  EXPECT_LE(report.geometry_change, 1e-9 * report.geometry_scale);
  ASSERT_GT(report.total_normal_force, 0.0);
}

TEST(MovingObstacle, AFrictionlessSlideUpdatedAtEveryStepEndsAsTheStaticRunThere) {
  // Frictionless, the answer of a step depends on its loads only: the ball slid 0.6 m along x in
  // three steps (a slide s with s^2/(2R) = 0.036 m, more than the indentation) ends as the static
  // run with the ball there, when both linearize at their solution. Without the updates the path
  // keeps the first step's linearization and misses it by far.
  const Vec3 slide(0.6, 0.0, 0.0);
  Problem path = brick_on_ball(1e-10);
  path.loading.steps = 3;
  path.dirichlet.front().path = {1.0, 1.0, 1.0};
  path.contact.front().obstacle->displacement = slide;
  path.contact.front().obstacle->path = {0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0};
  Problem there = brick_on_ball(1e-10);
  there.contact.front().obstacle->displacement = slide;
  const RunResult a = run(path);
  const RunResult b = run(there);
  ASSERT_EQ(a.report.status, RunStatus::Converged) << a.report.message;
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  const VectorXd& la = a.contact->lambda;
  const VectorXd& lb = b.contact->lambda;
  ASSERT_EQ(la.size(), lb.size());
  ASSERT_GT(lb.maxCoeff(), 0.0);
  EXPECT_LE((la - lb).cwiseAbs().maxCoeff(), 1e-6 * lb.cwiseAbs().maxCoeff());
  EXPECT_NEAR(a.report.contact->total_normal_force, b.report.contact->total_normal_force,
              1e-6 * b.report.contact->total_normal_force);
  path.contact.front().geometry_updates = 0;
  const RunResult kept = run(path);
  ASSERT_EQ(kept.report.status, RunStatus::Converged) << kept.report.message;
  EXPECT_GT(
      std::abs(kept.report.contact->total_normal_force - b.report.contact->total_normal_force),
      0.05 * b.report.contact->total_normal_force);
}

}  // namespace
