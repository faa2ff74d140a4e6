// Global assembly: symmetry, rigid-body kernel, the paper's n_p, patch tests, load totals.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "common/fixtures.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::fe;

TEST(Assembly, FreeDofsMatchThePapersNp) {
  // Table 1: n_p = 900, 2646, 5832 for n = 4, 6, 8.
  const std::map<Index, Index> n_p{{4, 900}, {6, 2646}, {8, 5832}};
  for (const auto& [n, expected] : n_p) {
    const mesh::TetMesh m = mesh::make_brick({Vec3(3, 1, 1), {3 * n, n, n}});
    EXPECT_EQ(test::clamped_dofs(m).n_free(), expected) << "n = " << n;
  }
}

TEST(Assembly, UnconstrainedStiffnessHasExactlyTheRigidMotionsInItsKernel) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(2, 1, 1), {2, 1, 1}});
  const DofMap dofs(m.n_nodes());
  const SparseMatrix K = assemble_stiffness(m, isotropic(1e9, 0.3), dofs);
  const MatrixXd Kd(K);
  EXPECT_NEAR((Kd - Kd.transpose()).norm() / Kd.norm(), 0.0, 1e-15);
  NodalField modes[6];
  for (int r = 0; r < 6; ++r) {
    modes[r].resize(3, m.n_nodes());
    for (Index a = 0; a < m.n_nodes(); ++a) {
      const Vec3 x = m.nodes.col(a);
      Vec3 axis = Vec3::Zero();
      axis(r % 3) = 1.0;
      modes[r].col(a) = r < 3 ? axis : axis.cross(x);
    }
    EXPECT_NEAR((K * dofs.from_nodal(modes[r])).norm() / Kd.norm(), 0.0, 1e-14) << "mode " << r;
  }
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(Kd);
  const Real scale = eig.eigenvalues().maxCoeff();
  EXPECT_LT(std::abs(eig.eigenvalues()(5)), 1e-12 * scale);
  EXPECT_GT(eig.eigenvalues()(6), 1e-6 * scale);
}

TEST(Assembly, PatchTestReproducesAnAffineField) {
  // Prescribe an affine displacement on every boundary node and solve for the interior ones:
  // the P1 solution must be the affine field itself, to round-off.
  const mesh::TetMesh m = mesh::make_brick({Vec3(1.5, 1, 0.7), {5, 4, 3}});
  const Material mat = isotropic(7e10, 0.33);
  Mat3 A;
  A << 1e-3, 2e-4, -3e-4, 5e-4, -2e-3, 1e-4, 0, 7e-4, 1.5e-3;
  const Vec3 c(1e-4, -2e-4, 3e-4);
  NodalField u_exact(3, m.n_nodes());
  for (Index a = 0; a < m.n_nodes(); ++a)
    u_exact.col(a) = A * m.nodes.col(a) + c;

  std::vector<bool> on_boundary(static_cast<size_t>(3 * m.n_nodes()), false);
  for (Index f = 0; f < m.n_faces(); ++f)
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k)
        on_boundary[static_cast<size_t>(3 * m.faces(v, f) + k)] = true;
  const DofMap all(m.n_nodes()), interior(on_boundary);
  ASSERT_GT(interior.n_free(), 0);
  const SparseMatrix K = assemble_stiffness(m, mat, all);
  // Interior equations: K_II u_I = -K_IB u_B, i.e. (K u_B)_I with u_I = 0 moved to the right.
  NodalField u_boundary = u_exact;
  for (Index a = 0; a < m.n_nodes(); ++a)
    for (int k = 0; k < 3; ++k)
      if (interior.dof(a, k) >= 0) u_boundary(k, a) = 0.0;
  const NodalField r = all.to_nodal(K * all.from_nodal(u_boundary));
  linalg::CholeskyFactor chol;
  chol.factorize(assemble_stiffness(m, mat, interior));
  const VectorXd u_interior = chol.solve(VectorXd(-interior.from_nodal(r)));
  EXPECT_NEAR((u_interior - interior.from_nodal(u_exact)).lpNorm<Eigen::Infinity>(), 0.0, 1e-14);
}

TEST(Assembly, TractionPatchTestBalancesConstantStress) {
  // For an affine field with constant stress sigma, K u equals the boundary load of the traction
  // sigma n on every face, node by node (interior nodes get zero).
  const mesh::TetMesh m = mesh::make_brick({Vec3(1, 2, 1), {3, 4, 2}});
  const Material mat = isotropic(1e9, 0.2);
  Mat3 A;
  A << 1e-3, 2e-4, 0, -1e-4, 5e-4, 3e-4, 2e-4, 0, -7e-4;
  NodalField u(3, m.n_nodes());
  for (Index a = 0; a < m.n_nodes(); ++a)
    u.col(a) = A * m.nodes.col(a);
  const Mat3 eps = 0.5 * (A + A.transpose());
  Eigen::Matrix<Real, 6, 1> ev;
  ev << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(1, 2), 2 * eps(0, 2), 2 * eps(0, 1);
  const Eigen::Matrix<Real, 6, 1> sv = mat.D * ev;
  Mat3 sigma;
  sigma << sv(0), sv(5), sv(4), sv(5), sv(1), sv(3), sv(4), sv(3), sv(2);
  const DofMap all(m.n_nodes());
  VectorXd f = VectorXd::Zero(all.n_free());
  for (const auto& tag : m.tag_names) {
    const auto faces = m.faces_with_tag(tag);
    add_traction(m, all, faces, sigma * mesh::face_normal(m, faces.front()), f);
  }
  const SparseMatrix K = assemble_stiffness(m, mat, all);
  EXPECT_NEAR((K * all.from_nodal(u) - f).norm() / f.norm(), 0.0, 1e-13);
  EXPECT_NEAR((internal_forces(m, fe::Materials(&mat, 1), u) - all.to_nodal(f)).norm() / f.norm(),
              0.0, 1e-13);
}

TEST(Assembly, LoadTotalsAreExact) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(3, 1, 1), {6, 2, 2}});
  const DofMap all(m.n_nodes());
  VectorXd f = VectorXd::Zero(all.n_free());
  add_traction(m, all, m.faces_with_tag("x1"), Vec3(1e7, 0, 2e7), f);
  add_traction(m, all, m.faces_with_tag("z1"), Vec3(0, 0, -3e7), f);
  add_volume_force(m, all, Vec3(0, 0, -7.8e4), f);
  const NodalField F = all.to_nodal(f);
  const Vec3 total = F.rowwise().sum();
  // x1 has area 1, z1 area 3, volume 3.
  EXPECT_NEAR(total(0), 1e7, 1e-6);
  EXPECT_NEAR(total(1), 0.0, 1e-6);
  EXPECT_NEAR(total(2), 2e7 - 9e7 - 3 * 7.8e4, 1e-6);
}

TEST(Assembly, FieldLoadsIntegrateLinearDataExactly) {
  // Total force of a linear traction p(x) = (x, 0, 0) on z1 of the unit cube is (1/2, 0, 0);
  // first moment: int x * x dS = 1/3 (the test function x is in P1, so exact).
  const mesh::TetMesh m = mesh::make_brick({Vec3(1, 1, 1), {3, 3, 3}});
  const DofMap all(m.n_nodes());
  NodalField p = NodalField::Zero(3, m.n_nodes());
  p.row(0) = m.nodes.row(0);
  VectorXd f = VectorXd::Zero(all.n_free());
  add_traction_field(m, all, m.faces_with_tag("z1"), p, f);
  const NodalField F = all.to_nodal(f);
  EXPECT_NEAR(F.row(0).sum(), 0.5, 1e-14);
  EXPECT_NEAR(F.row(0).dot(m.nodes.row(0)), 1.0 / 3.0, 1e-14);
  VectorXd fv = VectorXd::Zero(all.n_free());
  add_volume_force_field(m, all, p, fv);
  const NodalField Fv = all.to_nodal(fv);
  EXPECT_NEAR(Fv.row(0).sum(), 0.5, 1e-14);
  EXPECT_NEAR(Fv.row(0).dot(m.nodes.row(0)), 1.0 / 3.0, 1e-14);
}

TEST(DofMap, FreeDofsOfNodesSkipTheFixedComponents) {
  // Node 0: x fixed; node 1: free; node 2: all fixed. Numbering is node-major over free dofs.
  std::vector<bool> fixed(9, false);
  fixed[0] = true;
  fixed[6] = fixed[7] = fixed[8] = true;
  const DofMap dofs(fixed);
  EXPECT_EQ(dofs.free_dofs({0, 1, 2}), (std::vector<Index>{0, 1, 2, 3, 4}));
  EXPECT_EQ(dofs.free_dofs({1, 0}), (std::vector<Index>{2, 3, 4, 0, 1}));
  EXPECT_TRUE(dofs.free_dofs({2}).empty());
}
