// Verification of meshes of several bodies that share no node (theory.md §2.1), each held by its
// own [[dirichlet]] conditions. K is block diagonal over the bodies, so the truth is exact:
//   - the paper's brick (n = 4, with its contact on the plane) beside a second, loaded brick: each
//     body's displacement is that of the same body solved alone, to the solver's tolerance;
//   - two separate blocks of a Gmsh file (tests/bad_input/115-two-bodies-one-free.geo), both
//     clamped: the run converges, the unloaded block does not move, global equilibrium holds;
//   - two paper bricks, each on its own plane, a contact pair each with its own friction model
//     and law (theory.md §5.7): each brick moves as it does when the other pair's law is replaced
//     by a frictionless one (the same normal response), so each pair follows its own law.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

// A named namespace, not an anonymous one: the unity build compiles several test files as one.
namespace two_bodies_test {

using namespace fricon;
using namespace fricon::driver;

// The second brick: 1 x 1 x 1 m, 4 cubes a side, 10 m beside the paper's brick in y.
const mesh::BrickSpec kSecond{Vec3(1, 1, 1), {4, 4, 4}};
const Vec3 kSecondAt(0.0, 10.0, 0.0);            // [m]
const Vec3 kSecondTraction(0.0, 2.0e7, -1.0e7);  // on its face x = 1 [Pa]
// Both runs solve the same dual problem (up to the order of the dofs), the union's to
// qp_rtol = 1e-10. They take the same steps, so that relative to the largest displacement they
// differ by round-off (3e-14 seen); the bound allows an answer that differs within the tolerance.
constexpr Real kQpTolerance = 1e-10;
constexpr Real kOuterTolerance = 1e-8;
constexpr Real kSameAnswer = 1e-9;
constexpr Real kRoundoff = 1e-12;     // relative
constexpr Real kEquilibrium = 1e-10;  // RunReport::equilibrium_residual, round-off if all is well
// Two runs of a pair with the same friction but other pairs in the merged QP stop their outer
// loops at different iterates, each within outer_tol = 1e-8 of the fixed point; friction moves
// the bricks by far more than this.
constexpr Real kSameFrictionAnswer = 1e-6;  // relative
constexpr Real kFrictionMatters = 1e-3;     // relative
// The last QP's Coulomb radii are F times the pressures of the iterate before: they agree with
// the final pressures to the outer tolerance.
constexpr Real kRadiusTolerance = 1e-6;  // relative to the largest pressure

mesh::TetMesh second_brick() {
  mesh::TetMesh m = mesh::make_brick(kSecond);
  m.nodes.colwise() += kSecondAt;
  return m;
}

Problem tight(Problem p) {
  p.solver.qp.rel_tolerance = kQpTolerance;
  p.solver.outer.tol = kOuterTolerance;
  p.contact.front().patches =
      contact::PatchKind::Mesh;  // the chessboard squares, kept by the union
  return p;
}

// The second brick alone: clamped at x = 0, loaded at x = 1, no contact.
Problem second_alone() {
  Problem p;
  p.mesh.kind = MeshKind::Arrays;
  p.mesh.given = std::make_shared<const mesh::TetMesh>(second_brick());
  p.material = paper_problem(4, 6e4).material;
  p.dirichlet.push_back({"x0", {true, true, true}, Vec3::Zero()});
  p.traction.push_back({"x1", kSecondTraction});
  return p;
}

TEST(TwoBodies, EachBodyOfAUnionMovesAsItDoesAlone) {
  const Problem first = tight(paper_problem(4, 6e4));
  Problem both = first;
  both.mesh.kind = MeshKind::Arrays;
  const mesh::BrickSpec paper{Vec3(first.mesh.size[0], first.mesh.size[1], first.mesh.size[2]),
                              first.mesh.cells};
  both.mesh.given = std::make_shared<const mesh::TetMesh>(
      mesh::disjoint_union({mesh::make_brick(paper), second_brick()}, {"", "b_"}));
  both.dirichlet.push_back({"b_x0", {true, true, true}, Vec3::Zero()});
  both.traction.push_back({"b_x1", kSecondTraction});
  validate(both);

  const RunResult u_both = run(both);
  const RunResult u_first = run(first);
  const RunResult u_second = run(second_alone());
  ASSERT_EQ(u_both.report.status, RunStatus::Converged) << u_both.report.message;
  ASSERT_EQ(u_first.report.status, RunStatus::Converged) << u_first.report.message;
  ASSERT_EQ(u_both.model.bodies.n_bodies(), 2);
  const Index n1 = u_first.displacement.cols(), n2 = u_second.displacement.cols();
  ASSERT_EQ(u_both.displacement.cols(), n1 + n2);
  const Real scale1 = u_first.displacement.cwiseAbs().maxCoeff();
  const Real scale2 = u_second.displacement.cwiseAbs().maxCoeff();
  EXPECT_LT((u_both.displacement.leftCols(n1) - u_first.displacement).cwiseAbs().maxCoeff(),
            kSameAnswer * scale1);
  // The second brick has no contact: one linear solve, the same to round-off.
  EXPECT_LT((u_both.displacement.rightCols(n2) - u_second.displacement).cwiseAbs().maxCoeff(),
            kRoundoff * scale2);
  EXPECT_EQ(u_both.report.contact->n_patches, u_first.report.contact->n_patches);
}

TEST(TwoBodies, TwoClampedBlocksOfAGmshFileRun) {
  Problem p;
  p.source = "two_bodies_test";
  p.mesh.kind = MeshKind::Gmsh;
  p.mesh.file = std::string(FRICON_SOURCE_DIR) + "/tests/bad_input/115-two-bodies-one-free.geo";
  p.material.young = 2.0e11;  // Pa
  p.material.poisson = 0.3;
  p.dirichlet.push_back({"base", {true, true, true}, Vec3::Zero()});
  p.dirichlet.push_back({"loose_base", {true, true, true}, Vec3::Zero()});
  p.traction.push_back({"loose_top", Vec3(0.0, 0.0, -1.0e7)});
  validate(p);
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const mesh::Bodies& bodies = r.model.bodies;
  ASSERT_EQ(bodies.n_bodies(), 2);
  const int held = r.model.mesh.find_region("held");
  ASSERT_GE(held, 0);
  const Index unloaded = bodies.regions[0] == std::vector<int>{held} ? 0 : 1;
  Real loaded_max = 0.0, unloaded_max = 0.0;  // largest |u| on each body [m]
  for (Index a = 0; a < r.model.mesh.n_nodes(); ++a) {
    Real& m = bodies.node_body[static_cast<size_t>(a)] == unloaded ? unloaded_max : loaded_max;
    m = std::max(m, r.displacement.col(a).norm());
  }
  EXPECT_GT(loaded_max, 0.0);
  EXPECT_LE(unloaded_max, kRoundoff * loaded_max);
  EXPECT_LT(r.report.equilibrium_residual, kEquilibrium);
}

// Two paper bricks (n = 4) side by side, 10 m apart in y, each loaded as the paper's and each
// on its own plane: pair 0 ("z0") with `first`'s friction, pair 1 ("b_z0") with `second`'s.
Problem two_paper_bricks(const ContactOptions& first, const ContactOptions& second) {
  Problem p = tight(paper_problem(4, 6e4));
  const mesh::BrickSpec paper{Vec3(p.mesh.size[0], p.mesh.size[1], p.mesh.size[2]), p.mesh.cells};
  mesh::TetMesh other = mesh::make_brick(paper);
  other.nodes.colwise() += kSecondAt;
  p.mesh.kind = MeshKind::Arrays;
  p.mesh.given = std::make_shared<const mesh::TetMesh>(
      mesh::disjoint_union({mesh::make_brick(paper), other}, {"", "b_"}));
  const std::vector<DirichletOptions> dirichlet = p.dirichlet;
  for (DirichletOptions d : dirichlet) {
    d.boundary = "b_" + d.boundary;
    p.dirichlet.push_back(d);
  }
  const std::vector<TractionOptions> traction = p.traction;
  for (TractionOptions t : traction) {
    t.boundary = "b_" + t.boundary;
    p.traction.push_back(t);
  }
  p.contact = {first, second};
  p.contact[0].boundary = "z0";
  p.contact[1].boundary = "b_z0";
  for (ContactOptions& c : p.contact)
    c.patches = contact::PatchKind::Mesh;  // the chessboard squares, kept by the union
  validate(p);
  return p;
}

// A steel-steel Coulomb pair: F = 0.3 times the patch's own pressure.
ContactOptions coulomb_pair() {
  ContactOptions c;
  c.model = contact::FrictionModel::Coulomb;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.3;
  return c;
}

// A Tresca pair with the paper's law (param = 6e4 1/m) and g = 2e7 Pa.
ContactOptions tresca_pair() {
  ContactOptions c;
  c.model = contact::FrictionModel::Tresca;
  c.slip_bound = 2.0e7;
  c.friction.law = contact::FrictionLawKind::Paper;
  c.friction.param = 6e4;
  return c;
}

// The same pair without friction (F = 0): the same non-penetration, no tangential resistance.
ContactOptions frictionless(ContactOptions c) {
  c.friction = {};
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.0;
  return c;
}

// The largest difference of the displacements of body 0 (the first `n0` nodes) or body 1 (the
// rest), relative to the largest displacement of `b` on that body.
Real body_difference(const RunResult& a, const RunResult& b, Index body, Index n0) {
  const Index n = a.displacement.cols();
  const Index first = body == 0 ? 0 : n0, count = body == 0 ? n0 : n - n0;
  const auto ua = a.displacement.middleCols(first, count);
  const auto ub = b.displacement.middleCols(first, count);
  return (ua - ub).cwiseAbs().maxCoeff() / ub.cwiseAbs().maxCoeff();
}

TEST(TwoBodies, EachPairFollowsItsOwnModelAndLaw) {
  const RunResult mixed = run(two_paper_bricks(coulomb_pair(), tresca_pair()));
  const RunResult coulomb_only = run(two_paper_bricks(coulomb_pair(), frictionless(tresca_pair())));
  const RunResult tresca_only = run(two_paper_bricks(frictionless(coulomb_pair()), tresca_pair()));
  const RunResult neither =
      run(two_paper_bricks(frictionless(coulomb_pair()), frictionless(tresca_pair())));
  for (const RunResult* r : {&mixed, &coulomb_only, &tresca_only, &neither})
    ASSERT_EQ(r->report.status, RunStatus::Converged) << r->report.message;
  const Index n0 = mixed.displacement.cols() / 2;  // the bricks have as many nodes

  // Each brick moves as it does with its own pair's law and the other pair frictionless ...
  EXPECT_LT(body_difference(mixed, coulomb_only, 0, n0), kSameFrictionAnswer);
  EXPECT_LT(body_difference(mixed, tresca_only, 1, n0), kSameFrictionAnswer);
  // ... which friction changes: the comparison would pass for no law at all otherwise.
  EXPECT_GT(body_difference(mixed, neither, 0, n0), kFrictionMatters);
  EXPECT_GT(body_difference(mixed, neither, 1, n0), kFrictionMatters);

  // The radii of the Coulomb pair are F times its pressures, those of the Tresca pair F_R g
  // with F_R <= F(0) = 0.3: at most 0.3 g, whatever the pressure.
  const ContactFields& f = *mixed.contact;
  const ContactReport& c = *mixed.report.contact;
  for (Index p = 0; p < f.patches.size(); ++p) {
    const Real lambda_n = f.lambda(3 * p), rho = f.radius(p);
    if (f.patch_pair[static_cast<size_t>(p)] == 0)
      EXPECT_NEAR(rho, 0.3 * lambda_n, kRadiusTolerance * c.max_lambda_n) << "patch " << p;
    else
      EXPECT_LE(rho, 0.3 * 2.0e7 * (1.0 + kRoundoff)) << "patch " << p;
  }

  // The report names each pair's model and law, and certifies the Coulomb pair.
  ASSERT_EQ(c.pairs.size(), 2u);
  EXPECT_TRUE(c.mixed_models);
  EXPECT_EQ(c.pairs[0].model, contact::FrictionModel::Coulomb);
  EXPECT_EQ(c.pairs[1].model, contact::FrictionModel::Tresca);
  EXPECT_EQ(c.pairs[0].friction_law, coulomb_only.report.contact->pairs[0].friction_law);
  EXPECT_NE(c.pairs[0].friction_law, c.pairs[1].friction_law);
  EXPECT_LE(c.coulomb_residual, c.coulomb_bound);
}

}  // namespace two_bodies_test
