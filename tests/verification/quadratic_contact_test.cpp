// Contact on quadratic (10-node) tetrahedra (theory.md §2.12), against independent truth:
//   - the paper's brick at order 2 with the paper's chessboard: the stability condition (5.1)
//     holds for the 6-node traces, and its contact forces are at least as accurate as those of
//     the P1 solution refined once. The reference is the limit of the P1 forces at n = 4, 8, 16
//     (Aitken's extrapolation, geometric convergence), and the discretization error of P1 refined
//     once is its distance from that limit; order 2 on the paper's mesh (n = 4, about as many
//     unknowns as P1 at n = 8) must be nearer the limit than P1 at n = 8, and so agree with it
//     within twice that error. The forces are the contact's transmitted normal force (on the free
//     components: a patch on the clamped edge gives part of its force to the clamp, a share
//     that differs between the orders) and its tangential force.
//   - Coulomb friction, the paper's F(s) and a loading path run on quadratic meshes to their
//     certificates (the KKT residuals within the bound), and the path's first step is the static
//     run.
// The patch tests at order 2 are in floating_test.cpp (one body on the plane) and
// two_bodies_contact_test.cpp (two non-matching bodies); the elasticity's orders and locking in
// elasticity_test.cpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

namespace {

using namespace fricon;
using namespace fricon::driver;

/// The paper's brick (n, friction parameter 6e4) at element order `order`.
Problem brick(Index n, int order) {
  Problem p = paper_problem(n, 6e4);
  p.mesh.order = order;
  return p;
}

/// The contact's transmitted normal force and its tangential force along x [N].
std::array<Real, 2> forces(const RunResult& r) {
  EXPECT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& c = *r.report.contact;
  return {c.transmitted_normal_force, c.pairs.front().tangential_force(0)};
}

/// Aitken's limit of f4, f8, f16 (errors shrinking geometrically).
Real aitken(Real f4, Real f8, Real f16) {
  const Real d1 = f8 - f4, d2 = f16 - f8;
  return f16 - d2 * d2 / (d2 - d1);
}

}  // namespace

TEST(QuadraticContact, PaperBrickIsStableAndNearerTheLimitThanP1RefinedOnce) {
  const RunResult quadratic = run(brick(4, 2));
  ASSERT_EQ(quadratic.model.mesh.order(), 2);
  // Condition (5.1) for the 6-node traces on the paper's chessboard (the run refuses below 1e-8).
  EXPECT_GT(quadratic.report.contact->stability_ratio, 1e-3);
  const std::array<Real, 2> q = forces(quadratic);
  const std::array<Real, 2> p4 = forces(run(brick(4, 1)));
  const std::array<Real, 2> p8 = forces(run(brick(8, 1)));
  const std::array<Real, 2> p16 = forces(run(brick(16, 1)));
  const char* names[] = {"transmitted normal force", "tangential force"};
  for (size_t i = 0; i < 2; ++i) {
    const Real limit = aitken(p4[i], p8[i], p16[i]);
    const Real p1_refined_error = std::abs(p8[i] - limit);
    std::printf(
        "paper brick, %s: P1 n = 4, 8, 16: %.6e, %.6e, %.6e N, limit %.6e N; order 2 at n = 4: "
        "%.6e N (%+.2f %% of the limit; P1 at n = 8: %+.2f %%)\n",
        names[i], p4[i], p8[i], p16[i], limit, q[i], 100 * (q[i] / limit - 1),
        100 * (p8[i] / limit - 1));
    EXPECT_LE(std::abs(q[i] - limit), p1_refined_error) << names[i];
    EXPECT_LE(std::abs(q[i] - p8[i]), 2 * p1_refined_error) << names[i];
  }
}

TEST(QuadraticContact, CoulombAndALoadingPathReachTheirCertificates) {
  // Coulomb with the paper's F(s) as the coefficient.
  Problem coulomb = brick(4, 2);
  coulomb.contact.front().model = contact::FrictionModel::Coulomb;
  const RunResult c = run(coulomb);
  ASSERT_EQ(c.report.status, RunStatus::Converged) << c.report.message;
  EXPECT_LE(c.report.contact->kkt.max(), c.report.contact->kkt_bound);
  EXPECT_GT(c.report.contact->total_normal_force, 0.0);

  // A path of three steps with the loads scaled 0.5, 1, 0.5; its second step is the static run.
  Problem path = brick(4, 2);
  path.loading.steps = 3;
  for (auto& t : path.traction)
    t.path = {0.5, 1.0, 0.5};
  const RunResult r = run(path);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(r.report.steps.size(), 3u);
  EXPECT_LE(r.report.contact->kkt.max(), r.report.contact->kkt_bound);
}
