// qp::CoarseSpace (theory.md §4.6, §8.3) on rows of very different lengths, as Total FETI's G has
// them on a graded mesh (a small subdomain's rotations against a large one's translations),
// checked from outside the class: the rank of G from a construction whose rank is known, P v in
// the null space of G (G P v = 0 against the size of G's terms), the orthonormal rows W^T G and
// the null directions y with G^T y = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "fricon/qp/coarse_space.hpp"

using namespace fricon;
using namespace fricon::qp;

namespace {

// m rows over n unknowns, random, row i scaled by 10^(exponent_i), the exponents spread evenly
// over [-spread/2, spread/2] (fixed seed).
Eigen::MatrixXd rows_of_many_lengths(Index m, Index n, double spread, unsigned seed) {
  std::srand(seed);
  Eigen::MatrixXd G = Eigen::MatrixXd::Random(m, n);
  for (Index i = 0; i < m; ++i)
    G.row(i) *=
        std::pow(10.0, spread * (static_cast<double>(i) / static_cast<double>(m - 1) - 0.5));
  return G;
}

// ||G v|| against the size of its terms, ||G|| ||v||.
double relative_image(const Eigen::MatrixXd& G, const Eigen::VectorXd& v) {
  return (G * v).norm() / (G.cwiseAbs() * v.cwiseAbs()).norm();
}

}  // namespace

// Rows whose squared lengths span 10^16 (S's eigenvalues then span more than 1/kRankTolerance)
// are still independent: full rank, no null direction, and the projector removes every row.
TEST(CoarseSpace, RowsOfVeryDifferentLengthsAreNotTakenForDependentOnes) {
  const Eigen::MatrixXd G = rows_of_many_lengths(12, 40, 8.0, 3);
  const CoarseSpace rows(G.sparseView());
  EXPECT_EQ(rows.rank(), 12);
  EXPECT_EQ(rows.null().cols(), 0);
  std::srand(5);
  Eigen::VectorXd v = Eigen::VectorXd::Random(40);
  rows.project(v);
  EXPECT_LT(relative_image(G, v), 1e-12);
  // The least-norm solution of G x = e meets every row, the shortest as the longest.
  const Eigen::VectorXd e = Eigen::VectorXd::Random(12).cwiseProduct(G.rowwise().norm());
  const Eigen::VectorXd x = G.transpose() * rows.solve(e);
  EXPECT_LT(((G * x - e).array() / e.array().abs()).abs().maxCoeff(), 1e-8);
}

// The metric of the orthonormalized rows: for x in the row space, r = G x has r^T S^+ r = ||x||^2.
TEST(CoarseSpace, TheMetricOfTheRowsIsThatOfOrthonormalRows) {
  const Eigen::MatrixXd G = rows_of_many_lengths(10, 30, 8.0, 7);
  const CoarseSpace rows(G.sparseView());
  std::srand(9);
  const Eigen::VectorXd x = rows.onto_rows(Eigen::VectorXd::Random(30));
  EXPECT_NEAR(rows.norm2(G * x), x.squaredNorm(), 1e-9 * x.squaredNorm());
  // onto_rows is a projector: applied twice it changes nothing.
  EXPECT_LT((rows.onto_rows(x) - x).norm(), 1e-9 * x.norm());
}

// A row that is a multiple of another (1e6 times as long) is dependent whatever its length: rank
// m - 1, and the null direction is a unit vector y with G^T y = 0.
TEST(CoarseSpace, ADependentRowIsFoundAmongRowsOfVeryDifferentLengths) {
  Eigen::MatrixXd G = rows_of_many_lengths(8, 30, 6.0, 11);
  G.row(7) = 1e6 * G.row(0);
  const CoarseSpace rows(G.sparseView());
  EXPECT_EQ(rows.rank(), 7);
  ASSERT_EQ(rows.null().cols(), 1);
  const Eigen::VectorXd y = rows.null().col(0);
  EXPECT_NEAR(y.norm(), 1.0, 1e-12);
  EXPECT_LT((G.transpose() * y).norm() / (G.transpose().cwiseAbs() * y.cwiseAbs()).norm(), 1e-12);
}
