// fe::free_rigid_motions per connected body (theory.md §2.1): on a mesh of two bodies that share
// no node, each body's count of free rigid motions is that of its own Dirichlet conditions, and
// their sum is the dimension of the kernel of K over the free dofs, computed independently
// (dense eigenvalues). A check of the whole mesh as one body would miss a free body.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "fricon/fe/assembly.hpp"
#include "fricon/fe/rigid_motions.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::fe;

namespace {

constexpr Real kYoung = 1e9;    // Pa
constexpr Real kPoisson = 0.3;  // -
// An eigenvalue of K below this fraction of the largest is in its kernel (round-off is ~1e-16).
constexpr Real kKernelTolerance = 1e-10;

// Brick a ([0, 2] x [0, 1] x [0, 1]) and brick b, far away ([1e3, 1e3 + 1] x ...): tags
// "a_x0", ..., "b_x0", ...
mesh::TetMesh two_bricks() {
  mesh::TetMesh b = mesh::make_brick({Vec3(1, 1, 1), {1, 1, 1}});
  b.nodes.colwise() += Vec3(1e3, 0, 0);
  return mesh::disjoint_union({mesh::make_brick({Vec3(2, 1, 1), {2, 1, 1}}), b}, {"a_", "b_"});
}

// Components `components` (e.g. "xyz") fixed on the nodes of `tag`, added to `fixed`.
void fix(const mesh::TetMesh& m, const std::string& tag, const std::string& components,
         std::vector<bool>& fixed) {
  for (Index a : m.nodes_with_tag(tag))
    for (char c : components)
      fixed[static_cast<size_t>(3 * a + (c - 'x'))] = true;
}

// The dimension of the kernel of K over the free dofs of `fixed`.
Index kernel_dimension(const mesh::TetMesh& m, const std::vector<bool>& fixed) {
  const DofMap dofs(fixed);
  const MatrixXd K(assemble_stiffness(m, isotropic(kYoung, kPoisson), dofs));
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(K, Eigen::EigenvaluesOnly);
  const Real lmax = eig.eigenvalues().maxCoeff();
  return (eig.eigenvalues().array() < kKernelTolerance * lmax).count();
}

struct BodiesCase {
  std::vector<std::pair<std::string, std::string>> conditions;  // (tag, components)
  Index free_a, free_b;
  std::string loose_b;  // RigidMotionCheck::loose_axes of body b
};

TEST(RigidMotions, EachBodyCountsItsOwnConditionsAndTheSumIsTheKernelOfK) {
  const mesh::TetMesh m = two_bricks();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  ASSERT_EQ(bodies.n_bodies(), 2);
  const std::vector<BodiesCase> cases{
      {{{"a_x0", "xyz"}}, 0, 6, "x, y or z"},              // b held by nothing
      {{{"a_x0", "xyz"}, {"b_z0", "z"}}, 0, 3, "x or y"},  // b on a roller
      {{{"a_x0", "xyz"}, {"b_x0", "xyz"}}, 0, 0, ""},      // both clamped
      {{{"a_z0", "z"}, {"b_x1", "xyz"}}, 3, 0, ""},        // a on a roller
      {{{"b_x0", "x"}}, 6, 3, "y or z"},                   // b: x and two rotations held
  };
  for (const BodiesCase& c : cases) {
    std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
    std::string name;
    for (const auto& [tag, components] : c.conditions) {
      fix(m, tag, components, fixed);
      name += tag + ":" + components + " ";
    }
    const std::vector<RigidMotionCheck> checks = free_rigid_motions(m, bodies, fixed);
    ASSERT_EQ(checks.size(), 2u);
    EXPECT_EQ(checks[0].n_free, c.free_a) << name;
    EXPECT_EQ(checks[1].n_free, c.free_b) << name;
    EXPECT_EQ(checks[1].loose_axes, c.loose_b) << name;
    EXPECT_EQ(kernel_dimension(m, fixed), c.free_a + c.free_b) << name;
  }
}

// The whole mesh checked as one body (what fricon did before issue 23, defect 8): the clamped
// body's fixed dofs span the six modes, and the free body goes unnoticed.
TEST(RigidMotions, TheWholeMeshAsOneBodyMissesAFreeBody) {
  const mesh::TetMesh m = two_bricks();
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  fix(m, "a_x0", "xyz", fixed);
  std::vector<Index> all(static_cast<size_t>(m.n_nodes()));
  for (Index a = 0; a < m.n_nodes(); ++a)
    all[static_cast<size_t>(a)] = a;
  EXPECT_EQ(free_rigid_motions(m, all, fixed).n_free, 0);
  EXPECT_EQ(kernel_dimension(m, fixed), 6);
}

TEST(RigidMotions, ABodyWithoutFixedDofsHasSixFreeMotionsAndNothingFixed) {
  const mesh::TetMesh m = two_bricks();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  fix(m, "a_x0", "xyz", fixed);
  const std::vector<RigidMotionCheck> checks = free_rigid_motions(m, bodies, fixed);
  EXPECT_EQ(checks[0].n_fixed, 3 * static_cast<Index>(m.nodes_with_tag("a_x0").size()));
  EXPECT_EQ(checks[1].n_fixed, 0);
  EXPECT_EQ(checks[1].n_free, 6);
}

}  // namespace
