// fe::find_floating_bodies and fe::regularized_stiffness (theory.md §2.10): the free motions that
// the Dirichlet conditions leave are in the kernel of K, named by what they are, and the inverse
// of the regularized K is a generalized inverse of K (K K^+ K = K), checked with dense algebra
// independent of CHOLMOD and of the regularization's own formula.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "fricon/fe/assembly.hpp"
#include "fricon/fe/floating.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::fe;

namespace {

constexpr Real kSteelYoung = 2e11;   // Pa
constexpr Real kSteelPoisson = 0.3;  // -

// A 2 x 1 x 0.5 m brick with the components `components` fixed on the faces `tags`.
struct Case {
  std::vector<std::pair<std::string, std::string>> conditions;  // (tag, components)
  std::vector<std::string> motions;                             // the expected names
};

std::vector<bool> fixed_by(const mesh::TetMesh& m, const Case& c) {
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (const auto& [tag, components] : c.conditions)
    for (Index a : m.nodes_with_tag(tag))
      for (char k : components)
        fixed[static_cast<size_t>(3 * a + (k - 'x'))] = true;
  return fixed;
}

const std::vector<Case> kCases{
    {{},
     {"translation x", "translation y", "translation z", "rotation about x", "rotation about y",
      "rotation about z"}},
    {{{"x0", "x"}, {"y0", "y"}}, {"translation z"}},                          // two symmetry planes
    {{{"z0", "z"}}, {"translation x", "translation y", "rotation about z"}},  // on a roller
    {{{"x0", "xyz"}}, {}},                                                    // clamped
};

TEST(FloatingBodies, TheFreeMotionsAreTheKernelOfKAndNamedByWhatTheyAre) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(2.0, 1.0, 0.5), {4, 2, 2}});
  const mesh::Bodies bodies = mesh::find_bodies(m);
  for (const Case& c : kCases) {
    const DofMap dofs(fixed_by(m, c));
    const FloatingBodies f = find_floating_bodies(m, bodies, dofs);
    ASSERT_EQ(f.n_motions(), static_cast<Index>(c.motions.size()));
    if (c.motions.empty()) {
      EXPECT_TRUE(f.empty());
      continue;
    }
    ASSERT_EQ(f.bodies.size(), 1u);
    for (Index j = 0; j < f.n_motions(); ++j)
      EXPECT_EQ(f.bodies[0].motion_name(j), c.motions[static_cast<size_t>(j)]);
    // K R = 0, and the kernel of K has exactly the dimension of R's columns.
    const SparseMatrix K = assemble_stiffness(m, isotropic(kSteelYoung, kSteelPoisson), dofs);
    const MatrixXd R(f.R);
    EXPECT_LE((K * R).norm(), 1e-10 * MatrixXd(K).norm() * R.norm());
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(K), Eigen::EigenvaluesOnly);
    const Real lmax = eig.eigenvalues().maxCoeff();
    EXPECT_EQ((eig.eigenvalues().array() < 1e-10 * lmax).count(), f.n_motions());
  }
}

TEST(FloatingBodies, TheRegularizedFactorIsAGeneralizedInverse) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(2.0, 1.0, 0.5), {4, 2, 2}});
  const mesh::Bodies bodies = mesh::find_bodies(m);
  for (const Case& c : kCases) {
    if (c.motions.empty()) continue;
    const DofMap dofs(fixed_by(m, c));
    const FloatingBodies f = find_floating_bodies(m, bodies, dofs);
    const SparseMatrix K = assemble_stiffness(m, isotropic(kSteelYoung, kSteelPoisson), dofs);
    linalg::CholeskyFactor factor;
    factor.factorize(regularized_stiffness(K, f));
    // K K^+ K = K, column by column (the whole matrix, densely).
    const MatrixXd Kd(K);
    const MatrixXd KpK = factor.solve(Kd);
    EXPECT_LE((Kd * KpK - Kd).norm(), 1e-9 * Kd.norm()) << c.motions.size() << " free motions";
    // The regularization is local: a dense block on a few dofs only.
    EXPECT_LE(regularized_stiffness(K, f).nonZeros(), K.nonZeros() + 81 * f.bodies.size());
  }
}

TEST(FloatingBodies, TwoBodiesEachGetTheirOwnMotions) {
  mesh::TetMesh b = mesh::make_brick({Vec3(1, 1, 1), {1, 1, 1}});
  b.nodes.colwise() += Vec3(5, 0, 0);
  const mesh::TetMesh m =
      mesh::disjoint_union({mesh::make_brick({Vec3(2, 1, 1), {2, 1, 1}}), b}, {"a_", "b_"});
  const mesh::Bodies bodies = mesh::find_bodies(m);
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (Index a : m.nodes_with_tag("a_x0"))
    for (int k = 0; k < 3; ++k)
      fixed[static_cast<size_t>(3 * a + k)] = true;
  const DofMap dofs(fixed);
  const FloatingBodies f = find_floating_bodies(m, bodies, dofs);
  ASSERT_EQ(f.bodies.size(), 1u);
  EXPECT_EQ(f.bodies[0].body, 1);
  EXPECT_EQ(f.n_motions(), 6);
  // R is zero outside body 1.
  const MatrixXd R(f.R);
  for (Index a : bodies.nodes[0])
    for (int k = 0; k < 3; ++k) {
      if (dofs.dof(a, k) < 0) continue;
      EXPECT_EQ(R.row(dofs.dof(a, k)).norm(), 0.0);
    }
}

}  // namespace
