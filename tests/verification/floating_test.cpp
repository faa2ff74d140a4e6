// Floating bodies (theory.md §2.10), against exact solutions and against the same problem with
// the floating motions held by Dirichlet conditions at the values the floating solve found:
//   - a free block (no Dirichlet condition at all) on the rigid frictionless plane under a uniform
//     pressure p: uniaxial compression is the exact solution and lies in the P1 space, so every
//     patch carries lambda_n = p and the stress is -p e_z e_z, to 1e-8;
//   - the same with Coulomb friction and a shear tau < mu p on the top: friction carries exactly
//     the shear's resultant; tau > mu p cannot be carried and is refused (InputError) with both
//     figures;
//   - a block floating only in z (symmetry planes x = 0 and y = 0) equals the block whose one
//     node has the z displacement the floating solve found (u and lambda to 1e-8);
//   - the two-sphere Hertz example with the upper sphere floating, pressed by the nodal forces
//     that its displacement-driven run's support exerted, gives that run's answer (1e-6).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "common/fixtures.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/mesh/brick.hpp"

// A named namespace, not an anonymous one: the unity build compiles several test files as one.
namespace floating_test {

using namespace fricon;
using namespace fricon::driver;
using testing::HasSubstr;

constexpr Real kPressure = 1.0e6;  // [Pa] on the block's top
constexpr Real kExact = 1e-8;      // the solutions that lie in the discrete space

// A block 0.4 x 0.2 x 0.1 m, nu = 0.3, with no Dirichlet condition, on the plane z = 0 (its
// bottom z0), pressed by kPressure on its top z1; frictionless unless changed.
Problem free_block() {
  Problem p;
  p.mesh.size = {0.4, 0.2, 0.1};
  p.mesh.cells = {8, 4, 2};
  p.material.young = 2.0e11;
  p.material.poisson = 0.3;
  p.traction.push_back({"z1", Vec3(0.0, 0.0, -kPressure)});
  ContactOptions c;
  c.slip_bound = 0.0;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.0;
  p.contact = {c};
  p.solver.qp.rel_tolerance = 1e-12;
  p.solver.outer.tol = 1e-10;
  return p;
}

TEST(FloatingBodies, AFreeBlockOnTheFrictionlessPlaneIsInUniaxialCompression) {
  const RunResult r = run(free_block());
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const VectorXd& lambda = r.contact->lambda;
  for (Index p = 0; p < lambda.size() / 3; ++p) {
    EXPECT_NEAR(lambda(3 * p), kPressure, kExact * kPressure) << "patch " << p;
    EXPECT_NEAR(lambda.segment<2>(3 * p + 1).norm(), 0.0, kExact * kPressure);
  }
  Eigen::Matrix<Real, 6, 1> exact;
  exact << 0.0, 0.0, -kPressure, 0.0, 0.0, 0.0;
  for (Index t = 0; t < r.stress.cols(); ++t)
    ASSERT_LE((r.stress.col(t) - exact).cwiseAbs().maxCoeff(), kExact * kPressure) << t;
  // Six free motions; the frictionless plane resists three of them, the others have no amplitude.
  ASSERT_EQ(r.report.bodies.size(), 1u);
  EXPECT_EQ(r.report.bodies[0].free_motions.size(), 6u);
  EXPECT_EQ(r.report.bodies[0].undetermined.size(), 3u);
  const Real scale = r.report.max_displacement;
  for (std::size_t j : {0u, 1u, 5u})  // translation x, y, rotation about z
    EXPECT_LE(std::abs(r.report.bodies[0].amplitudes[j]), 1e-12 * scale);
}

TEST(FloatingBodies, AQuadraticFreeBlockOnTheFrictionlessPlaneIsInUniaxialCompression) {
  // With 10-node tetrahedra the corners of each 6-node contact triangle carry no share of a
  // uniform pressure (int phi_corner dS = 0); the multipliers are patch integrals, so every
  // patch still carries exactly p (theory.md §2.12).
  Problem p = free_block();
  p.mesh.order = kQuadraticOrder;
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(r.model.mesh.order(), 2);
  const VectorXd& lambda = r.contact->lambda;
  constexpr Real kQuadraticExact = 1e-10;  // the bound
  for (Index k = 0; k < lambda.size() / 3; ++k) {
    EXPECT_NEAR(lambda(3 * k), kPressure, kQuadraticExact * kPressure) << "patch " << k;
    EXPECT_NEAR(lambda.segment<2>(3 * k + 1).norm(), 0.0, kQuadraticExact * kPressure);
  }
  Eigen::Matrix<Real, 6, 1> exact;
  exact << 0.0, 0.0, -kPressure, 0.0, 0.0, 0.0;
  for (Index t = 0; t < r.stress.cols(); ++t)
    ASSERT_LE((r.stress.col(t) - exact).cwiseAbs().maxCoeff(), kExact * kPressure) << t;
}

Problem with_coulomb_shear(Real mu, Real tau) {
  Problem p = free_block();
  p.contact.front().model = contact::FrictionModel::Coulomb;
  p.contact.front().friction.value = mu;
  p.traction.front().value = Vec3(tau, 0.0, -kPressure);
  return p;
}

TEST(FloatingBodies, CoulombFrictionCarriesAShearBelowMuPAndRefusesOneAbove) {
  constexpr Real kMu = 0.3;
  const Problem p = with_coulomb_shear(kMu, 0.2 * kPressure);
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const Real area = 0.4 * 0.2;  // [m^2]
  const Vec3 friction = r.report.contact->pairs.front().tangential_force;
  EXPECT_NEAR(friction(0), -0.2 * kPressure * area, kExact * kPressure * area);
  EXPECT_NEAR(friction(1), 0.0, kExact * kPressure * area);
  EXPECT_NEAR(r.report.contact->pairs.front().normal_force, kPressure * area,
              kExact * kPressure * area);
  EXPECT_LE(r.report.contact->equality_residual, r.report.contact->equality_bound);

  const std::string error =
      test::input_error_of([&] { run(with_coulomb_shear(kMu, 0.5 * kPressure)); });
  EXPECT_THAT(error, HasSubstr("floats"));
  EXPECT_THAT(error, HasSubstr("the applied force along (1, 0, 0) is 4e+04 N"));
  EXPECT_THAT(error, HasSubstr("at most 2.4e+04 N"));  // mu p area
}

TEST(FloatingBodies, APullAwayFromTheObstacleIsRefused) {
  Problem p = free_block();
  p.traction.front().value = Vec3(0.0, 0.0, kPressure);
  const std::string error = test::input_error_of([&] { run(p); });
  EXPECT_THAT(error, HasSubstr("the applied force along (0, 0, 1) is 8e+04 N"));
  EXPECT_THAT(error, HasSubstr("at most 0 N"));
}

TEST(FloatingBodies, FloatingInZEqualsTheBlockHeldAtOneNodeWhereTheFloatingSolveFoundIt) {
  // Symmetry planes x = 0 and y = 0; Tresca friction on the plane; a load with shear.
  Problem floating = free_block();
  floating.dirichlet = {{"x0", {true, false, false}}, {"y0", {false, true, false}}};
  floating.traction.front().value = Vec3(2.0e5, 1.0e5, -kPressure);
  floating.contact.front().slip_bound = 2.0e5;
  floating.contact.front().friction.value = 0.5;
  mesh::TetMesh m = mesh::make_brick({Vec3(0.4, 0.2, 0.1), {8, 4, 2}});
  Index corner = 0;  // the top corner (0.4, 0.2, 0.1)
  for (Index a = 0; a < m.n_nodes(); ++a)
    if ((m.nodes.col(a) - Vec3(0.4, 0.2, 0.1)).norm() < 1e-12) corner = a;
  m.node_sets.push_back({"pin", mesh::kPointDimension, {corner}});
  floating.mesh.kind = MeshKind::Arrays;
  floating.mesh.given = std::make_shared<const mesh::TetMesh>(m);
  const RunResult a = run(floating);
  ASSERT_EQ(a.report.status, RunStatus::Converged) << a.report.message;
  ASSERT_EQ(a.report.bodies.front().free_motions, std::vector<std::string>{"translation z"});

  Problem held = floating;
  held.dirichlet.push_back(
      {"pin", {false, false, true}, Vec3(0.0, 0.0, a.displacement(2, corner))});
  const RunResult b = run(held);
  ASSERT_EQ(b.report.status, RunStatus::Converged) << b.report.message;
  EXPECT_TRUE(b.report.bodies.front().free_motions.empty());
  const Real u_scale = a.displacement.cwiseAbs().maxCoeff();
  EXPECT_LE((a.displacement - b.displacement).cwiseAbs().maxCoeff(), kExact * u_scale);
  const Real l_scale = a.contact->lambda.cwiseAbs().maxCoeff();
  EXPECT_LE((a.contact->lambda - b.contact->lambda).cwiseAbs().maxCoeff(), kExact * l_scale);
}

TEST(FloatingBodies, TheUpperHertzSpherePressedByItsSupportsForcesGivesTheDrivenAnswer) {
  Problem driven = io::read_problem(test::source_path("examples/two-bodies/hertz-spheres.toml"),
                                    {"mesh.size_factor=3", "solver.qp_rtol=1e-11"});
  const RunResult a = run(driven);
  ASSERT_EQ(a.report.status, RunStatus::Converged) << a.report.message;
  const fe::NodalField support = reaction_forces(a.model, driven, a.displacement);

  // The same problem without the upper top's prescribed z; its supports' forces as loads.
  Problem pressed = driven;
  ASSERT_EQ(pressed.dirichlet.front().boundary, "upper_top");
  pressed.dirichlet.erase(pressed.dirichlet.begin());
  PhaseTimes times;
  Model m = assemble_model(pressed, times);
  ASSERT_EQ(m.floating.n_motions(), 1);
  for (Index node : m.mesh.nodes_with_tag("upper_top"))
    m.f(m.dofs.dof(node, 2)) += support(2, node);
  const std::optional<contact::ContactDiscretization> disc = check_model(pressed, m);
  ASSERT_TRUE(disc);
  factorize_model(m, {}, times);
  dual::DualInput input{m.factor, disc->B, m.f, disc->dofs, {}, &disc->offset};
  input.R = &m.floating.R;
  const auto Q = dual::make_dual_operator(dual::DualOperatorKind::Implicit, input);
  const ContactOutcome c = solve_contact(pressed, m, *disc, *Q, times, RunOptions{});
  ASSERT_TRUE(c.converged) << c.message;

  const fe::NodalField u = m.dofs.to_nodal(c.w) + m.prescribed;
  const Real u_scale = a.displacement.cwiseAbs().maxCoeff();
  EXPECT_LE((u - a.displacement).cwiseAbs().maxCoeff(), 1e-6 * u_scale);
  const Real l_scale = a.contact->lambda.cwiseAbs().maxCoeff();
  EXPECT_LE((c.fields.lambda - a.contact->lambda).cwiseAbs().maxCoeff(), 1e-6 * l_scale);
}

TEST(FloatingBodies, AFloatingBodyWithoutAContactSurfaceIsRefusedBeforeTheFactorization) {
  // Two blocks side by side, the second held by nothing; contact only under the first.
  mesh::TetMesh b = mesh::make_brick({Vec3(1, 1, 1), {2, 2, 2}});
  b.nodes.colwise() += Vec3(3, 0, 0);
  const mesh::TetMesh m =
      mesh::disjoint_union({mesh::make_brick({Vec3(1, 1, 1), {2, 2, 2}}), b}, {"", "b_"});
  Problem p = free_block();
  p.mesh.kind = MeshKind::Arrays;
  p.mesh.given = std::make_shared<const mesh::TetMesh>(m);
  p.dirichlet = {{"x0", {true, true, true}}};
  const std::string error = test::input_error_of([&] {
    PhaseTimes times;
    (void)check_model(p, assemble_loads(p, times));
  });
  EXPECT_THAT(error, HasSubstr("body 1"));
  EXPECT_THAT(error, HasSubstr("floats"));
  EXPECT_THAT(error, HasSubstr("no [[contact]] surface or master lies on it"));
}

}  // namespace floating_test
