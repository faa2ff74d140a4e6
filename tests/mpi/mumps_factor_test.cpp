// parallel::MumpsFactor on the ranks of an MPI job (run under mpirun -n 1 and -n 2; label mpi),
// against dense Eigen on the same small matrices: the Schur complement of K in [[K, B^T], [B, 0]],
// distributed solves with K (each rank gives rows and gets back its own), what DistributedSolves
// brings to rank 0 (Q x, the displacement everywhere and on the contact dofs), and the failures
// that must end every rank with the same error (a singular matrix, a memory limit below the
// analysis's estimate). Each rank gives the entries of its own share of the rows, so the matrix
// MUMPS factors is a sum over ranks as in a distributed run.

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/command_channel.hpp"
#include "fricon/parallel/mpi/distributed_solves.hpp"
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

TEST(MumpsFactor, SchurComplementIsMinusQ) {
  const MatrixXd K = stiffness(), B = constraints();
  const MumpsFactor factor(world(), kN, kM, share(K, &B));
  EXPECT_EQ(factor.info().n, kN + kM);
  if (world_rank() != 0) return;
  const MatrixXd Q = B * K.llt().solve(B.transpose());
  ASSERT_EQ(factor.schur().rows(), kM);
  EXPECT_LT((factor.schur() + Q).norm(), kAgree * Q.norm());
}

// Distributed solves: each rank gives the rows i % size == rank of two right-hand sides and
// gets back its own rows of the solution; together the ranks hold every free dof once.
void expect_distributed_solve(const MumpsFactor& factor, const MatrixXd& K) {
  const int rank = world_rank(), size = world_size();
  MatrixXd b(kN, 2);
  for (Index i = 0; i < kN; ++i) {
    b(i, 0) = std::cos(static_cast<double>(i));
    b(i, 1) = static_cast<double>(i % 3) - 1.0;
  }
  std::vector<Index> rows;
  for (Index i = rank; i < kN; i += size)
    rows.push_back(i);
  const MatrixXd x = factor.solve_distributed(rows, b(rows, Eigen::all), 2);
  const MatrixXd truth = K.llt().solve(b);
  const std::vector<Index>& mine = factor.solution_rows();
  ASSERT_EQ(x.rows(), static_cast<Index>(mine.size()));
  std::vector<int> held(static_cast<std::size_t>(kN), 0);
  for (std::size_t k = 0; k < mine.size(); ++k) {
    ++held[static_cast<std::size_t>(mine[k])];
    EXPECT_LT((x.row(static_cast<Index>(k)) - truth.row(mine[k])).norm(), kAgree * truth.norm());
  }
  MPI_Allreduce(MPI_IN_PLACE, held.data(), static_cast<int>(kN), MPI_INT, MPI_SUM, world());
  for (Index i = 0; i < kN; ++i)
    EXPECT_EQ(held[static_cast<std::size_t>(i)], 1) << "dof " << i;
}

TEST(MumpsFactor, DistributedSolvesWithK) {
  const MatrixXd K = stiffness();
  const MumpsFactor factor(world(), kN, 0, share(K, nullptr));
  expect_distributed_solve(factor, K);
}

TEST(MumpsFactor, DistributedInteriorSolvesOfTheSchurFactor) {
  const MatrixXd K = stiffness(), B = constraints();
  const MumpsFactor factor(world(), kN, kM, share(K, &B));
  expect_distributed_solve(factor, K);
  expect_distributed_solve(factor, K);  // again, with the same factor
}

// DistributedSolves on both factors: what rank 0 receives against dense Eigen.
void expect_distributed_steps(const MumpsFactor& factor, const MatrixXd& K, const MatrixXd& B) {
  const SparseMatrix B_sparse = B.sparseView();
  const VectorXd f = VectorXd::LinSpaced(kN, 1.0, -0.5);
  // The contact dofs in descending order (position() must not rely on their order), and the
  // coupling built on rank 0 alone: the others have it from broadcast().
  std::vector<Index> contact_dofs;
  for (Index j = kN - 1; j >= 0; --j)
    if (B.col(j).squaredNorm() > 0.0) contact_dofs.push_back(j);
  ContactCoupling contact =
      world_rank() == 0 ? ContactCoupling::of(B_sparse, contact_dofs) : ContactCoupling{};
  contact.broadcast(world());
  ASSERT_EQ(contact.dofs, contact_dofs);
  ASSERT_EQ(contact.B.rows(), kM);
  const CommandChannel channel(world());
  // Every rank gives f / size on every row: MUMPS sums the rows that several ranks give.
  const int size = world_size();
  std::vector<Index> all_rows(static_cast<std::size_t>(kN));
  std::iota(all_rows.begin(), all_rows.end(), Index{0});
  const DistributedSolves solves(factor, channel, &contact, LoadPart{all_rows, f / size});
  if (world_rank() != 0) {
    EXPECT_EQ(solves.follow(), 7);
    return;
  }
  const Eigen::LLT<MatrixXd> llt(K);
  const VectorXd x = VectorXd::LinSpaced(kM, -2.0, 3.0);
  const VectorXd Qx = B * llt.solve(B.transpose() * x);
  EXPECT_LT((solves.apply(x) - Qx).norm(), kAgree * Qx.norm());
  const VectorXd w = llt.solve(f - B.transpose() * x);
  EXPECT_LT((solves.displacement(x) - w).norm(), kAgree * w.norm());
  VectorXd w_c = VectorXd::Constant(kN, 99.0);
  solves.contact_displacement(x, w_c);
  for (Index j = 0; j < kN; ++j) {
    const bool on_contact = B.col(j).squaredNorm() > 0.0;
    EXPECT_NEAR(w_c(j), on_contact ? w(j) : 99.0, kAgree * w.norm()) << "dof " << j;
  }
  channel.finish(7);
}

TEST(DistributedSolves, OnTheFactorOfK) {
  const MatrixXd K = stiffness(), B = constraints();
  const MumpsFactor factor(world(), kN, 0, share(K, nullptr));
  expect_distributed_steps(factor, K, B);
}

TEST(DistributedSolves, OnTheSchurFactor) {
  const MatrixXd K = stiffness(), B = constraints();
  const MumpsFactor factor(world(), kN, kM, share(K, &B));
  expect_distributed_steps(factor, K, B);
}

TEST(MumpsFactor, SingularMatrixFailsOnEveryRank) {
  MatrixXd K = stiffness();
  K.row(kN / 2).setZero();  // a dof with no stiffness
  K.col(kN / 2).setZero();
  std::string message;
  try {
    const MumpsFactor factor(world(), kN, 0, share(K, nullptr));
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
  }
  const MemoryLimit limit{0.5, "test.toml:3:1", "solver.memory_per_rank"};
  std::string message;
  try {
    const MumpsFactor factor(world(), n, 0, laplacian_share(), {}, limit);
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
