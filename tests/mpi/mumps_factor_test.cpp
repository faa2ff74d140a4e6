// parallel::MumpsFactor on the ranks of an MPI job (run under mpirun -n 1 and -n 2; label mpi),
// against dense Eigen on the same small matrices: the solves with K, the Schur complement of K in
// [[K, B^T], [B, 0]], and the failures that must end every rank with the same error (a singular
// matrix, a memory limit below the analysis's estimate). Each rank gives the entries of its own
// share of the rows, so the matrix MUMPS factors is a sum over ranks as in a distributed run.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/mumps_factor.hpp"
#include "fricon/parallel/mpi/session.hpp"

namespace fricon::parallel {
namespace {

constexpr Index kN = 40;          // order of K
constexpr Index kM = 5;           // rows of B (the Schur variables)
constexpr double kAgree = 1e-12;  // relative agreement with the dense solution

// K: a 1D Laplacian with a heavier diagonal and one long-range coupling, SPD (dense, both halves).
MatrixXd stiffness() {
  MatrixXd K = MatrixXd::Zero(kN, kN);
  for (Index i = 0; i < kN; ++i) {
    K(i, i) = 3.0 + 0.01 * static_cast<double>(i);
    if (i + 1 < kN) K(i, i + 1) = K(i + 1, i) = -1.0;
  }
  K(0, kN - 1) = K(kN - 1, 0) = 0.5;
  return K;
}

// B: kM rows, each with three non-zeros.
MatrixXd constraints() {
  MatrixXd B = MatrixXd::Zero(kM, kN);
  for (Index r = 0; r < kM; ++r)
    for (Index k = 0; k < 3; ++k)
      B(r, (7 * r + 3 * k) % kN) =
          1.0 + 0.5 * static_cast<double>(k) - 0.3 * static_cast<double>(r);
  return B;
}

// This rank's share of the lower triangle of A (rows i with i % size == rank, and the block B
// below K on rank 0 when with_b).
LocalEntries share(const MatrixXd& K, const MatrixXd* B) {
  LocalEntries e;
  const int rank = world_rank(), size = world_size();
  for (Index i = 0; i < kN; ++i)
    if (i % size == rank)
      for (Index j = 0; j <= i; ++j)
        if (K(i, j) != 0.0) e.add(i, j, K(i, j));
  if (B != nullptr && rank == 0)
    for (Index r = 0; r < B->rows(); ++r)
      for (Index j = 0; j < kN; ++j)
        if ((*B)(r, j) != 0.0) e.add(kN + r, j, (*B)(r, j));
  return e;
}

// Runs `on_rank_0` with the factor on rank 0 while the other ranks serve its solves.
template <class F>
void drive(const MumpsFactor& factor, F on_rank_0) {
  if (world_rank() != 0) {
    EXPECT_EQ(factor.serve(), 7);
    return;
  }
  on_rank_0();
  factor.finish(7);
}

// The message of the error every rank threw, the same on all ranks.
void expect_same_error_everywhere(const std::string& message, const std::string& fragment) {
  EXPECT_NE(message.find(fragment), std::string::npos) << message;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, world());
  std::string root(static_cast<std::size_t>(length), '\0');
  if (world_rank() == 0) root = message;
  MPI_Bcast(root.data(), length, MPI_CHAR, 0, world());
  EXPECT_EQ(message, root) << "rank " << world_rank();
}

TEST(MumpsFactor, SolvesWithK) {
  const MatrixXd K = stiffness();
  const MumpsFactor factor(world(), kN, 0, share(K, nullptr));
  EXPECT_EQ(factor.info().n, kN);
  drive(factor, [&] {
    MatrixXd b(kN, 2);
    for (Index i = 0; i < kN; ++i) {
      b(i, 0) = std::sin(static_cast<double>(i));
      b(i, 1) = 1.0;
    }
    const MatrixXd x = factor.solve(b);
    const MatrixXd truth = K.llt().solve(b);
    EXPECT_LT((x - truth).norm(), kAgree * truth.norm());
  });
}

TEST(MumpsFactor, SchurComplementIsMinusQ) {
  const MatrixXd K = stiffness(), B = constraints();
  const MumpsFactor factor(world(), kN, kM, share(K, &B));
  drive(factor, [&] {
    const MatrixXd Q = B * K.llt().solve(B.transpose());
    ASSERT_EQ(factor.schur().rows(), kM);
    EXPECT_LT((factor.schur() + Q).norm(), kAgree * Q.norm());
    // The interior solves of the same factor are solves with K.
    const VectorXd b = VectorXd::LinSpaced(kN, -1.0, 2.0);
    const VectorXd truth = K.llt().solve(b);
    EXPECT_LT((factor.solve(b) - truth).norm(), kAgree * truth.norm());
  });
}

TEST(MumpsFactor, SingularMatrixFailsOnEveryRank) {
  MatrixXd K = stiffness();
  K.row(kN / 2).setZero();  // a dof with no stiffness
  K.col(kN / 2).setZero();
  std::string message;
  try {
    const MumpsFactor factor(world(), kN, 0, share(K, nullptr));
    drive(factor, [] {});
  } catch (const NumericalError& e) {
    message = e.what();
  }
  expect_same_error_everywhere(message, "MUMPS factorization failed");
}

// The 7-point Laplacian on a cube of kGrid^3 points (shifted to be definite): large enough for
// MUMPS to estimate megabytes (it counts whole MB).
constexpr Index kGrid = 16;
LocalEntries laplacian_share() {
  LocalEntries e;
  const int rank = world_rank(), size = world_size();
  const auto id = [](Index x, Index y, Index z) { return (z * kGrid + y) * kGrid + x; };
  for (Index z = 0; z < kGrid; ++z)
    for (Index y = 0; y < kGrid; ++y)
      for (Index x = 0; x < kGrid; ++x) {
        const Index i = id(x, y, z);
        if (i % size != rank) continue;
        e.add(i, i, 6.5);
        if (x > 0) e.add(i, id(x - 1, y, z), -1.0);
        if (y > 0) e.add(i, id(x, y - 1, z), -1.0);
        if (z > 0) e.add(i, id(x, y, z - 1), -1.0);
      }
  return e;
}

TEST(MumpsFactor, MemoryLimitBelowTheEstimateFailsOnEveryRank) {
  const Index n = kGrid * kGrid * kGrid;
  {  // without a limit: the estimate the limit is then set below
    const MumpsFactor factor(world(), n, 0, laplacian_share());
    ASSERT_GT(factor.info().estimate_max_mib, 1.0);
    drive(factor, [] {});
  }
  const MemoryLimit limit{0.5, "test.toml:3:1", "solver.memory_per_rank"};
  std::string message;
  try {
    const MumpsFactor factor(world(), n, 0, laplacian_share(), {}, limit);
    drive(factor, [] {});
  } catch (const NumericalError& e) {
    message = e.what();
  }
  expect_same_error_everywhere(message, "test.toml:3:1: solver.memory_per_rank: MUMPS's analysis");
}

}  // namespace
}  // namespace fricon::parallel

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  fricon::parallel::initialize(&argc, &argv);
  return RUN_ALL_TESTS();
}
