// Verification of meshes of several bodies that share no node (theory.md §2.1), each held by its
// own [[dirichlet]] conditions. K is block diagonal over the bodies, so the truth is exact:
//   - the paper's brick (n = 4, with its contact on the plane) beside a second, loaded brick: each
//     body's displacement is that of the same body solved alone, to the solver's tolerance;
//   - two separate blocks of a Gmsh file (tests/bad_input/115-two-bodies-one-free.geo), both
//     clamped: the run converges, the unloaded block does not move, global equilibrium holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

namespace {

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

}  // namespace
