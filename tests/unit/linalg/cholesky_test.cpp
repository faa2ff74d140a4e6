// The CHOLMOD wrapper against dense algebra, and its failure on a singular K.
#include <gtest/gtest.h>

#include "fricon/core/error.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;

namespace {
SparseMatrix random_spd(Index n, unsigned seed) {
  std::srand(seed);
  const MatrixXd R = MatrixXd::Random(n, n);
  const MatrixXd A = R * R.transpose() + static_cast<Real>(n) * MatrixXd::Identity(n, n);
  return A.sparseView().cast<Real>();
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
    EXPECT_NE(std::string(e.what()).find("dirichlet"), std::string::npos) << e.what();
  }
}
