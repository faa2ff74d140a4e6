#pragma once
// parallel/mpi: one MUMPS factorization shared by the ranks of a distributed run (docs/theory.md
// §3.3, docs/parallel.md). The ranks give the entries of the lower triangle they assembled; MUMPS
// sums them, orders, factors across the ranks, and
//   - without Schur variables: factors K (symmetric positive definite);
//   - with m Schur variables: factors the augmented matrix A = [[K, B^T], [B, 0]] (symmetric
//     indefinite) and returns the Schur complement of K in A, S = -B K^-1 B^T = -Q, dense on rank
//     0; solves with K are the "interior" solves of the same factor (ICNTL(26) = 0).
// Solves take and return distributed right-hand sides and solutions (each rank its rows); what
// rank 0 needs of them is DistributedSolves's business. Every call here is collective unless it
// says "rank 0".

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/parallel/mpi/session.hpp"

namespace fricon::parallel {

/// Entries (row >= col, 0-based, duplicates allowed and summed) that one rank gives.
struct LocalEntries {
  std::vector<int> rows, cols;
  std::vector<double> values;
  void add(Index row, Index col, double value) {
    rows.push_back(static_cast<int>(row));
    cols.push_back(static_cast<int>(col));
    values.push_back(value);
  }
  std::size_t size() const { return values.size(); }
};

/// What the factorization reports: sizes and cost (global), and this rank's memory.
struct MumpsInfo {
  Index n = 0;              ///< order of the factored matrix (n_free + n_schur)
  Index n_schur = 0;        ///< Schur variables (the multipliers), 0 for K alone
  double nnz_A = 0.0;       ///< entries given by all ranks
  double nnz_factor = 0.0;  ///< entries of the factors (INFOG(29))
  double flops = 0.0;       ///< operations of the elimination (RINFOG(3))
  std::string ordering;     ///< the fill-reducing ordering used (given, or MUMPS's INFOG(7))
  double memory_mib = 0.0;  ///< memory MUMPS allocated on this rank during factorization (INFO(16))
  double estimate_mib = 0.0;      ///< memory the analysis estimated for this rank (INFO(15))
  double estimate_max_mib = 0.0;  ///< the largest rank's estimate (INFOG(16))
  double analysis_s = 0.0;        ///< wall time of the analysis (ordering, symbolic) [s]
  double factorization_s = 0.0;   ///< wall time of the numerical factorization [s]
};

/// A bound on the memory of the factorization on every rank.
struct MemoryLimit {
  double mib = 0.0;   ///< the most MUMPS may allocate on one rank [MiB]; 0: no limit
  std::string where;  ///< where the limit was given (for the message), e.g. "f.toml:12:1"
  std::string key;    ///< its name, e.g. "solver.memory_per_rank"
};

class MumpsFactor {
 public:
  /// Collective. Factors the matrix of order n_free + n_schur whose lower-triangle entries the
  /// ranks give (`entries`, moved in and freed after the factorization); the last n_schur
  /// variables are the Schur variables. `order` (read on rank 0; empty: MUMPS chooses) is the
  /// elimination order of the first n_free variables, the Schur variables following. Throws
  /// NumericalError on every rank if MUMPS fails (with its INFOG(1), INFOG(2) and their meaning),
  /// or, before the numerical factorization, if the analysis estimates more memory on some rank
  /// than `limit` allows (the limit also bounds MUMPS's allocations, ICNTL(23)).
  MumpsFactor(MPI_Comm comm, Index n_free, Index n_schur, LocalEntries entries,
              const std::vector<Index>& order = {}, const MemoryLimit& limit = {});
  /// Collective (MUMPS releases its memory on every rank).
  ~MumpsFactor();
  MumpsFactor(const MumpsFactor&) = delete;
  MumpsFactor& operator=(const MumpsFactor&) = delete;

  int rank() const { return rank_; }
  Index n_free() const { return n_free_; }
  const MumpsInfo& info() const { return info_; }

  /// Rank 0: the Schur complement S = -B K^-1 B^T (n_schur x n_schur, both triangles) [m^3/Pa].
  const MatrixXd& schur() const { return schur_; }

  /// Collective, every rank: K X = R with distributed right-hand sides and solution. This rank
  /// gives the rows `rows` of R (0-based free dofs; no row is given by two ranks, and rows no rank
  /// gives are zero) as `rhs` (rows.size() x n_rhs); it gets back its share of X: the rows
  /// solution_rows() (the pivots MUMPS holds here; every free dof on exactly one rank) x n_rhs.
  /// Throws NumericalError on every rank if MUMPS fails.
  MatrixXd solve_distributed(const std::vector<Index>& rows, MatrixXd rhs, int n_rhs) const;
  /// The free dofs whose solution solve_distributed() returns on this rank (0-based, in its row
  /// order), known after the first call.
  const std::vector<Index>& solution_rows() const { return solution_rows_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  MPI_Comm comm_;
  int rank_ = 0;
  Index n_free_ = 0;
  MumpsInfo info_;
  MatrixXd schur_;
  mutable std::vector<Index> solution_rows_;
};

}  // namespace fricon::parallel
