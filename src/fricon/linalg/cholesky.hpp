#pragma once
// linalg: sparse Cholesky factorization K = L L^T through SuiteSparse CHOLMOD (supernodal, with
// the BLAS it is linked to: OpenBLAS). Factorize once, then solve for as many right-hand sides as
// needed: every product with K^-1 in fricon goes through one factor of this class.
// Knows nothing of meshes.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::linalg {

struct CholeskyInfo {
  Index n = 0;             ///< order of K
  Index nnz_K = 0;         ///< stored non-zeros of K (both triangles)
  double nnz_L = 0.0;      ///< non-zeros of the factor L
  double flops = 0.0;      ///< floating-point operations of the numerical factorization
  bool supernodal = true;  ///< CHOLMOD chose the supernodal method
  std::string ordering;    ///< the fill-reducing ordering used
  double rcond = 0.0;      ///< CHOLMOD's reciprocal condition estimate (min/max diag of L)^2
  int blas_threads = 1;    ///< threads of the BLAS during the factorization
};

class CholeskyFactor {
 public:
  CholeskyFactor();
  ~CholeskyFactor();
  CholeskyFactor(const CholeskyFactor&) = delete;
  CholeskyFactor& operator=(const CholeskyFactor&) = delete;
  CholeskyFactor(CholeskyFactor&&) noexcept;
  CholeskyFactor& operator=(CholeskyFactor&&) noexcept;

  /// Symbolic analysis and numerical factorization of the symmetric matrix K (the lower triangle
  /// is read), ordered by nested dissection of its compressed graph (the dofs of a node merged
  /// into one vertex, when both triangles are stored). Throws NumericalError naming the phase, n,
  /// nnz and, if K is not positive definite or singular to working precision (a rigid motion left
  /// free, or ill-conditioning), a message that says "not positive definite" and where the
  /// factorization broke down or its reciprocal condition estimate.
  void factorize(const SparseMatrix& K);

  /// As factorize(K), with the dofs `last` ordered after all others (the others by nested
  /// dissection of their own block), so that the trailing block L22 of the factor is the Cholesky
  /// factor of the Schur complement of K onto those dofs: S = K22 - K21 K11^-1 K12 = L22 L22^T.
  void factorize(const SparseMatrix& K, const std::vector<Index>& last);

  /// The dense trailing block L22 (m x m lower triangular, m = last.size()) of a factor built with
  /// factorize(K, last), rows and columns in trailing_order().
  MatrixXd trailing_factor() const;
  /// The dofs of the trailing block in pivot order (a permutation of `last`).
  const std::vector<Index>& trailing_order() const { return trailing_order_; }

  /// x = K^-1 b. Each call is one forward and one backward substitution.
  VectorXd solve(const VectorXd& b) const;
  /// X = K^-1 B for a block of right-hand sides (one supernodal solve for all columns).
  MatrixXd solve(const MatrixXd& B) const;

  /// B^T K^-1 B (k x k, dense and symmetric) for a sparse B (n x k), e.g. the dual Hessian
  /// Q = B K^-1 B^T from B^T. With K = P^T L L^T P it is Y^T Y, Y = L^-1 P B, and Y is computed by
  /// a supernodal forward substitution that visits only the supernodes B reaches (the paths from
  /// its non-zeros to the root of the elimination tree), each with only the columns of B whose
  /// paths pass through it: a column touching a few dofs costs its path, not the whole factor.
  /// Y^T Y is summed supernode by supernode and Y is never stored whole. Dense blocks go to the
  /// BLAS. `poll`, if set, is called once per supernode visited (it may throw to interrupt).
  /// Counts k solves.
  MatrixXd inverse_gram(const SparseMatrix& B, const std::function<void()>& poll = {}) const;

  /// The part of the factor that a set of dofs reaches: the supernodes on the paths from their
  /// pivots to the root, and the pivot rows these supernodes hold.
  struct Reach {
    std::vector<Index> supernodes;  ///< ascending (children before parents)
    std::vector<Index> rows;        ///< pivot rows of those supernodes
  };
  Reach reach(const std::vector<Index>& dofs) const;

  /// x <- K^-1 x for x that is zero outside the dofs `reach` was built from; the result is exact
  /// on those dofs (and on every dof pivoted on the reach) and zero elsewhere. One forward and one
  /// backward substitution over the reached part of L only. Counts one solve.
  void solve_on_reach(const Reach& reach, VectorXd& x) const;
  /// x <- K^-1 x for x that is zero outside the dofs `reach` was built from, exact everywhere:
  /// the forward substitution over the reach only, the backward one over the whole factor.
  /// Counts one solve.
  void solve_from_reach(const Reach& reach, VectorXd& x) const;

  /// inverse_gram(B) together with the rows `rows` of K^-1 B (rows.size() x k, dense): the
  /// forward sweep's Y = L^-1 P B is kept rather than dropped, then carried back by L^-T over the
  /// reach of B (`reach`, built from dofs that hold every non-zero of B; `rows` among them), in
  /// blocks of columns for the BLAS's level 3. Keeps up to reach.rows.size() x k numbers of Y.
  /// Counts k solves; `poll` as in inverse_gram.
  struct GramAndRows {
    MatrixXd gram;  ///< B^T K^-1 B
    MatrixXd rows;  ///< (K^-1 B)(rows, :)
  };
  GramAndRows inverse_gram_and_rows(const SparseMatrix& B, const Reach& reach,
                                    const std::vector<Index>& rows,
                                    const std::function<void()>& poll = {}) const;

  Index size() const { return info_.n; }
  const CholeskyInfo& info() const { return info_; }
  /// Number of solve() calls (a matrix solve with m columns counts m).
  long n_solves() const { return n_solves_; }

 private:
  struct Impl;
  struct KeptForward;
  void reach_solve(const Reach& reach, VectorXd& x, bool everywhere) const;
  MatrixXd forward_gram(const SparseMatrix& B, const std::function<void()>& poll,
                        KeptForward* kept) const;
  std::unique_ptr<Impl> impl_;
  CholeskyInfo info_;
  mutable long n_solves_ = 0;
  std::vector<Index> trailing_order_;
};

/// The fill-reducing order fricon gives CHOLMOD, for another solver (MUMPS, parallel/mpi/): nested
/// dissection (CHOLMOD's: METIS bisection, CAMD on the leaves) of the symmetric graph whose
/// vertex v is adjacent to adjacent[start[v] .. start[v+1]) (both directions stored, sorted; v
/// itself may be listed). Returns the vertices in elimination order.
std::vector<Index> nested_dissection(const std::vector<SparseIndex>& start,
                                     const std::vector<SparseIndex>& adjacent);

}  // namespace fricon::linalg
