#pragma once
// qp: the row space of the equality G x = e of SMALSE-M (docs/theory.md §4.6, §8.3): the Gram
// matrix S = G G^T of its rows and S^+, through which the projector
//
//   P = I - G^T S^+ G   (onto the null space of G)
//
// and the least-norm solution x_e = G^T S^+ e are applied. For floating bodies G has a handful of
// dense rows (6 per body); for Total FETI it has 6 rows per subdomain, sparse, and S is the coarse
// problem, thousands of rows in a large mesh. One class for both, with two ways to invert S:
//   dense  the eigenvectors of S scaled to a unit diagonal (any rank, decided whatever the
//          lengths of the rows: a row direction on which G vanishes is reported, so that
//          SMALSE-M can refuse or drop the load along it), for up to kDenseCoarseLimit rows;
//   sparse S = L L^T by CHOLMOD (S must be positive definite), beyond that (PERMON and ESPRESO
//          factor the coarse problem the same way).

#include "fricon/core/types.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/qp/dual_space.hpp"

namespace fricon::qp {

/// Up to this many rows S is decomposed densely (eigenvalues: its rank and null space are known);
/// beyond, it is factored by sparse Cholesky.
inline constexpr Index kDenseCoarseLimit = 1200;

class CoarseSpace {
 public:
  /// The row space of G (m x n): G's columns of the unknowns this process holds in `space` (all
  /// of them by default); G G^T is summed over the processes, every one decomposes it whole.
  /// Collective there, as are times() and every method that applies it. Throws NumericalError
  /// when m > kDenseCoarseLimit and G G^T is not positive definite (rows that are dependent, or
  /// that act on no unknown free to move): the message names the coarse problem.
  explicit CoarseSpace(const SparseMatrix& G, const DualSpace& space = whole_space());

  Index rows() const { return G_.rows(); }
  /// The rank of G (m on the sparse path).
  Index rank() const { return rank_; }
  /// G's columns of this process.
  const SparseMatrix& G() const { return G_; }
  /// G v over the m rows, v this process's part of the unknowns (summed over the processes).
  VectorXd times(const VectorXd& v) const;
  /// G^T r over this process's unknowns, r over the m rows.
  VectorXd transpose_times(const VectorXd& r) const { return G_.transpose() * r; }
  /// Orthonormal directions of the m rows on which G vanishes (m x (m - rank)): loads along them
  /// act on no unknown. None on the sparse path.
  const MatrixXd& null() const { return null_; }
  /// Whether S was factored by sparse Cholesky.
  bool sparse() const { return sparse_; }

  /// S^+ r for r over the m rows.
  VectorXd solve(const VectorXd& r) const;
  /// r^T S^+ r, the squared length of r in the metric of the orthonormalized rows.
  Real norm2(const VectorXd& r) const { return r.dot(solve(r)); }
  /// v <- P v = v - G^T S^+ G v.
  void project(VectorXd& v) const;
  /// G^T S^+ G v (the projector onto the row space).
  VectorXd onto_rows(const VectorXd& v) const;
  /// Solves with S so far.
  long n_solves() const { return n_solves_; }
  /// Wall time of S's decomposition and of the solves so far [s].
  double seconds() const { return seconds_; }

 private:
  /// S = G G^T decomposed: decompose_scaled, or factored by CHOLMOD beyond kDenseCoarseLimit rows.
  void decompose();
  /// S = G G^T, summed over the processes.
  SparseMatrix gram() const;
  /// The dense path: W_, null_ and rank_ from S.
  void decompose_scaled(const MatrixXd& S);

  SparseMatrix G_;
  const DualSpace* space_;
  Index rank_ = 0;
  bool sparse_ = false;
  MatrixXd W_;  ///< dense: S^+ = W W^T (decompose_scaled)
  MatrixXd null_;
  linalg::CholeskyFactor factor_;  ///< sparse: of S
  mutable long n_solves_ = 0;
  mutable double seconds_ = 0.0;
};

}  // namespace fricon::qp
