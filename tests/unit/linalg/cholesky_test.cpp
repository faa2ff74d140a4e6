// The CHOLMOD wrapper against dense algebra, and its failure on a singular K.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;

namespace {
SparseMatrix random_spd(Index n, unsigned seed) {
  std::srand(seed);
  const MatrixXd R = MatrixXd::Random(n, n);
  const MatrixXd A = R * R.transpose() + static_cast<Real>(n) * MatrixXd::Identity(n, n);
  return A.sparseView().cast<Real>();
}

// A steel brick of edge lengths `size` and `cells` clamped at x0: its dofs and stiffness matrix.
struct ClampedSteel {
  mesh::TetMesh m;
  fe::DofMap dofs{0};
  SparseMatrix K;
};
ClampedSteel clamped_steel(const Vec3& size, const std::array<Index, 3>& cells) {
  ClampedSteel b;
  b.m = mesh::make_brick({size, cells});
  b.dofs = test::clamped_dofs(b.m);
  b.K = fe::assemble_stiffness(b.m, fe::isotropic(2e11, 0.3), b.dofs);
  return b;
}
}  // namespace

TEST(Cholesky, AgreesWithDenseSolve) {
  const SparseMatrix A = random_spd(40, 3);
  linalg::CholeskyFactor chol;
  chol.factorize(A);
  const VectorXd b = VectorXd::LinSpaced(40, -1.0, 2.0);
  const VectorXd x = chol.solve(b);
  const VectorXd x_dense = MatrixXd(A).llt().solve(b);
  EXPECT_NEAR((x - x_dense).norm() / x_dense.norm(), 0.0, 1e-13);
  const MatrixXd B = MatrixXd::Random(40, 5);
  EXPECT_NEAR((chol.solve(B) - MatrixXd(A).llt().solve(B)).norm(), 0.0, 1e-12);
  EXPECT_EQ(chol.n_solves(), 6);
  EXPECT_EQ(chol.info().n, 40);
}

TEST(Cholesky, UnclampedStiffnessIsReportedAsNotPositiveDefinite) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(1, 1, 1), {2, 2, 2}});
  const fe::DofMap free_body(m.n_nodes());
  const SparseMatrix K = fe::assemble_stiffness(m, fe::isotropic(1e9, 0.3), free_body);
  linalg::CholeskyFactor chol;
  try {
    chol.factorize(K);
    FAIL() << "singular K accepted";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos) << e.what();
    // linalg cannot tell a free rigid motion from ill-conditioning: the driver, which has
    // checked the rigid motions (driver::make_dofs), names the cause (driver::factorize_model).
    EXPECT_EQ(std::string(e.what()).find("clamped"), std::string::npos) << e.what();
  }
}

namespace {
// L22 L22^T of a factor of K with the dofs `last` last must equal the Schur complement
// S = K22 - K21 K11^-1 K12 computed with dense algebra, and its solves K's.
void expect_trailing_schur_complement(const SparseMatrix& K, const std::vector<Index>& last) {
  linalg::CholeskyFactor chol;
  chol.factorize(K, last);
  const auto& order = chol.trailing_order();
  ASSERT_EQ(order.size(), last.size());
  const MatrixXd L22 = chol.trailing_factor();

  const Index n = K.rows(), mlast = static_cast<Index>(order.size());
  std::vector<bool> is_last(static_cast<size_t>(n), false);
  for (Index k : order)
    is_last[static_cast<size_t>(k)] = true;
  std::vector<Index> first;
  for (Index k = 0; k < n; ++k)
    if (!is_last[static_cast<size_t>(k)]) first.push_back(k);
  const MatrixXd Kd(K);
  auto block = [&](const std::vector<Index>& r, const std::vector<Index>& c) {
    MatrixXd M(static_cast<Index>(r.size()), static_cast<Index>(c.size()));
    for (size_t i = 0; i < r.size(); ++i)
      for (size_t j = 0; j < c.size(); ++j)
        M(static_cast<Index>(i), static_cast<Index>(j)) = Kd(r[i], c[j]);
    return M;
  };
  const MatrixXd S = block(order, order) -
                     block(order, first) * block(first, first).llt().solve(block(first, order));
  EXPECT_EQ(L22.rows(), mlast);
  EXPECT_NEAR((L22 * L22.transpose() - S).norm() / S.norm(), 0.0, 1e-12);
  // Solves with the constrained factor agree with dense algebra too.
  const VectorXd b = VectorXd::LinSpaced(n, -1.0, 1.0);
  EXPECT_NEAR((chol.solve(b) - Kd.llt().solve(b)).norm() / Kd.llt().solve(b).norm(), 0.0, 1e-12);
}
}  // namespace

TEST(Cholesky, TrailingBlockIsTheFactorOfTheSchurComplement) {
  // The dofs of the bottom face last.
  const auto [m, dofs, K] = clamped_steel(Vec3(2, 1, 1), {4, 2, 2});
  expect_trailing_schur_complement(K, dofs.free_dofs(m.nodes_with_tag("z0")));
}

TEST(Cholesky, TrailingBlockOverTwoBodiesIsTheFactorOfTheSchurComplement) {
  // Two bricks that share no node, both bottoms last (the contact dofs of two bodies): K is block
  // diagonal, its elimination tree a forest, and the trailing block spans two of its trees
  // (postordering them would interleave the bodies' dofs).
  mesh::TetMesh b = mesh::make_brick({Vec3(1, 1, 1), {2, 2, 2}});
  b.nodes.colwise() += Vec3(3, 0, 0);
  const mesh::TetMesh m =
      mesh::disjoint_union({mesh::make_brick({Vec3(2, 1, 1), {4, 2, 2}}), b}, {"a_", "b_"});
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (const char* tag : {"a_x0", "b_x0"})
    for (Index a : m.nodes_with_tag(tag))
      for (int c = 0; c < 3; ++c)
        fixed[static_cast<size_t>(3 * a + c)] = true;
  const fe::DofMap dofs(fixed);
  const SparseMatrix K = fe::assemble_stiffness(m, fe::isotropic(2e11, 0.3), dofs);
  std::vector<Index> last = dofs.free_dofs(m.nodes_with_tag("a_z0"));
  const std::vector<Index> second = dofs.free_dofs(m.nodes_with_tag("b_z0"));
  last.insert(last.end(), second.begin(), second.end());
  expect_trailing_schur_complement(K, last);
}

namespace {
// Columns touching a few dofs of the bottom face, like the rows of the contact operator.
SparseMatrix bottom_columns(const mesh::TetMesh& m, const fe::DofMap& dofs, Index n_cols) {
  const auto bottom = m.nodes_with_tag("z0");
  std::vector<Eigen::Triplet<Real, SparseIndex>> t;
  for (Index j = 0; j < n_cols; ++j)
    for (int k = 0; k < 3; ++k) {
      const Index dof = dofs.dof(bottom[static_cast<size_t>((7 * j + 5 * k + 3) % 65)], k);
      if (dof >= 0) t.emplace_back(dof, j, 1.0 + 0.1 * static_cast<Real>(j + k));
    }
  SparseMatrix B(dofs.n_free(), n_cols);
  B.setFromTriplets(t.begin(), t.end());
  return B;
}
}  // namespace

TEST(Cholesky, InverseGramOnTheReachIsTheDualHessian) {
  // B^T K^-1 B from the forward sweep over the reach of B, against dense solves with K.
  const auto [m, dofs, K] = clamped_steel(Vec3(3, 1, 1), {12, 4, 4});
  const SparseMatrix B = bottom_columns(m, dofs, 10);
  linalg::CholeskyFactor chol;
  chol.factorize(K);
  const MatrixXd Q = chol.inverse_gram(B);
  const MatrixXd Qref = MatrixXd(B.transpose()) * chol.solve(MatrixXd(B));
  EXPECT_NEAR((Q - Qref).norm() / Qref.norm(), 0.0, 1e-12);
  EXPECT_EQ(Q, Q.transpose());
  // The reach of the bottom face is a part of the factor, not all of it.
  EXPECT_LT(static_cast<Index>(chol.reach(dofs.free_dofs(m.nodes_with_tag("z0"))).rows.size()),
            K.rows());
  // A poll that throws interrupts the sweep.
  EXPECT_THROW(chol.inverse_gram(B, [] { throw Interrupted("stop"); }), Interrupted);
}

TEST(Cholesky, SolveOnTheReachIsExactOnItsDofs) {
  const auto [m, dofs, K] = clamped_steel(Vec3(3, 1, 1), {12, 4, 4});
  const std::vector<Index> surface = dofs.free_dofs(m.nodes_with_tag("z0"));
  linalg::CholeskyFactor chol;
  chol.factorize(K);
  const auto reach = chol.reach(surface);
  VectorXd b = VectorXd::Zero(K.rows());
  for (size_t i = 0; i < surface.size(); ++i)
    b(surface[i]) = std::sin(1.0 + static_cast<Real>(i));
  const VectorXd exact = chol.solve(b);
  VectorXd x = b;
  chol.solve_on_reach(reach, x);
  for (Index d : surface)
    EXPECT_NEAR(x(d), exact(d), 1e-12 * exact.cwiseAbs().maxCoeff()) << "dof " << d;
  // Off the reach nothing is computed.
  EXPECT_LE(x.cwiseAbs().cwiseSign().sum(), static_cast<Real>(reach.rows.size()));
  // From the reach, the backward substitution over the whole factor: exact everywhere.
  VectorXd y = b;
  chol.solve_from_reach(reach, y);
  EXPECT_LE((y - exact).norm(), 1e-12 * exact.norm());
  EXPECT_GT(y.cwiseAbs().cwiseSign().sum(), static_cast<Real>(reach.rows.size()));
}

TEST(Cholesky, RowsOfTheInverseOnTheReachAreThoseOfFullSolves) {
  // Q and the rows of K^-1 B on the surface dofs, from one forward sweep carried back over the
  // reach in blocks of columns, against dense solves with K; more columns than one block, so that
  // the blocks' seams are crossed.
  const auto [m, dofs, K] = clamped_steel(Vec3(3, 1, 1), {12, 4, 4});
  const std::vector<Index> surface = dofs.free_dofs(m.nodes_with_tag("z0"));
  const SparseMatrix B = bottom_columns(m, dofs, 150);
  linalg::CholeskyFactor chol;
  chol.factorize(K);
  const auto reach = chol.reach(surface);
  const auto both = chol.inverse_gram_and_rows(B, reach, surface);
  const MatrixXd exact = chol.solve(MatrixXd(B));
  const MatrixXd Qref = MatrixXd(B.transpose()) * exact;
  EXPECT_NEAR((both.gram - Qref).norm() / Qref.norm(), 0.0, 1e-12);
  ASSERT_EQ(both.rows.rows(), static_cast<Index>(surface.size()));
  ASSERT_EQ(both.rows.cols(), B.cols());
  for (size_t i = 0; i < surface.size(); ++i)
    EXPECT_LE((both.rows.row(static_cast<Index>(i)) - exact.row(surface[i])).norm(),
              1e-12 * exact.norm())
        << "dof " << surface[i];
  // A row off the reach is refused; a poll that throws interrupts.
  const std::vector<Index> top = dofs.free_dofs(m.nodes_with_tag("z1"));
  EXPECT_THROW(chol.inverse_gram_and_rows(B, reach, top), Error);
  EXPECT_THROW(chol.inverse_gram_and_rows(B, reach, surface, [] { throw Interrupted("stop"); }),
               Interrupted);
}
