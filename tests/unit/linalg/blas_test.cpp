// The BLAS kernels against Eigen's own dense algebra, on blocks of larger matrices (strided).
#include <gtest/gtest.h>

#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"

using namespace fricon;

namespace {
MatrixXd well_conditioned_lower(Index n) {
  MatrixXd L = MatrixXd::Random(n, n);
  L.diagonal().array() += static_cast<Real>(n);
  return L.triangularView<Eigen::Lower>();
}
}  // namespace

TEST(Blas, TriangularSolvesMatchEigen) {
  const MatrixXd L = well_conditioned_lower(7);
  const MatrixXd B = MatrixXd::Random(7, 3);
  MatrixXd X = B;
  linalg::solve_lower(L, X);
  EXPECT_LT((L * X - B).norm(), 1e-12 * B.norm());
  X = B;
  linalg::solve_lower(L, X, /*transpose=*/true);
  EXPECT_LT((L.transpose() * X - B).norm(), 1e-12 * B.norm());
  // On a sub-block in place, leaving the rest of the matrix alone; the strict upper part of L
  // is not read.
  MatrixXd big = MatrixXd::Random(10, 5), Lfull = L;
  Lfull.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  const MatrixXd before = big;
  linalg::solve_lower(Lfull, big.block(2, 1, 7, 3));
  EXPECT_LT((L * big.block(2, 1, 7, 3) - before.block(2, 1, 7, 3)).norm(), 1e-12);
  EXPECT_EQ(big.topRows(2), before.topRows(2));
  EXPECT_EQ(big.col(0), before.col(0));
}

TEST(Blas, ProductsMatchEigen) {
  const MatrixXd A = MatrixXd::Random(6, 4), B = MatrixXd::Random(4, 3),
                 C0 = MatrixXd::Random(6, 3);
  MatrixXd C = C0;
  linalg::subtract_product(A, B, C);
  EXPECT_LT((C - (C0 - A * B)).norm(), 1e-13);
  const MatrixXd At = A.transpose();  // 4 x 6: op(At) = At^T = A
  C = C0;
  linalg::subtract_product(At, B, C, /*transpose_a=*/true);
  EXPECT_LT((C - (C0 - A * B)).norm(), 1e-13);

  MatrixXd S = MatrixXd::Random(5, 5);
  S = (S + S.transpose()).eval();
  MatrixXd Slow = S;
  Slow.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);  // only the lower part is read
  const VectorXd x = VectorXd::Random(5);
  VectorXd y;
  linalg::symmetric_product(Slow, x, y);
  EXPECT_LT((y - S * x).norm(), 1e-13);

  const MatrixXd Y = MatrixXd::Random(8, 4);
  MatrixXd G = MatrixXd::Identity(4, 4);
  linalg::add_gram_lower(Y, G);
  const MatrixXd expected = MatrixXd::Identity(4, 4) + Y.transpose() * Y;
  EXPECT_LT((MatrixXd(G.triangularView<Eigen::Lower>()) -
             MatrixXd(expected.triangularView<Eigen::Lower>()))
                .norm(),
            1e-13);
  EXPECT_EQ(G(0, 3), 0.0);  // the strict upper part is untouched
}

TEST(Blas, ShapeMismatchIsAnError) {
  MatrixXd X(3, 2);
  EXPECT_THROW(linalg::solve_lower(MatrixXd::Identity(4, 4), X), Error);
  MatrixXd C(2, 2);
  EXPECT_THROW(linalg::subtract_product(MatrixXd(2, 3), MatrixXd(2, 2), C), Error);
}

TEST(Blas, OneColumnGoesThroughTheLevelTwoRoutinesAlike) {
  // One right-hand side takes dtrsv/dgemv: the same results, on blocks of larger matrices.
  MatrixXd Lbig = MatrixXd::Random(12, 12);
  Lbig.block(3, 2, 7, 7) = well_conditioned_lower(7);
  Lbig.block(3, 2, 7, 7).triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  const MatrixXd L = MatrixXd(Lbig.block(3, 2, 7, 7).triangularView<Eigen::Lower>());
  MatrixXd X = MatrixXd::Random(9, 4);
  const MatrixXd before = X;
  for (const bool transpose : {false, true}) {
    X = before;
    linalg::solve_lower(Lbig.block(3, 2, 7, 7), X.block(1, 2, 7, 1), transpose);
    const MatrixXd op = transpose ? MatrixXd(L.transpose()) : L;
    EXPECT_LT((op * X.block(1, 2, 7, 1) - before.block(1, 2, 7, 1)).norm(), 1e-12);
    EXPECT_EQ(X.col(1), before.col(1));
    EXPECT_EQ(X.row(0), before.row(0));
  }
  const MatrixXd A = MatrixXd::Random(6, 4);
  const VectorXd b4 = VectorXd::Random(4), b6 = VectorXd::Random(6), c0 = VectorXd::Random(6);
  MatrixXd C = c0;
  linalg::subtract_product(A, b4, C);
  EXPECT_LT((C.col(0) - (c0 - A * b4)).norm(), 1e-13);
  MatrixXd Ct = b4;
  linalg::subtract_product(A, b6, Ct, /*transpose_a=*/true);
  EXPECT_LT((Ct.col(0) - (b4 - A.transpose() * b6)).norm(), 1e-13);
  VectorXd y;
  linalg::product(A, b4, y);
  EXPECT_LT((y - A * b4).norm(), 1e-13);
  EXPECT_THROW(linalg::product(A, b6, y), Error);
}
