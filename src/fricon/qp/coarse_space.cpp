#include "fricon/qp/coarse_space.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"

namespace fricon::qp {

namespace {
// A row direction of G whose squared length is below this share of the largest acts on no
// unknown (theory.md §4.6).
constexpr double kRankTolerance = 1e-12;
}  // namespace

CoarseSpace::CoarseSpace(const SparseMatrix& G, const DualSpace& space) : G_(G), space_(&space) {
  const Stopwatch watch;
  decompose();
  seconds_ = watch.seconds();
}

// S = G G^T: its eigenvectors (dense path) or its factor (sparse path).
void CoarseSpace::decompose() {
  const Index m = G_.rows();
  if (m == 0) return;
  const SparseMatrix S = gram();
  if (m > kDenseCoarseLimit) {
    sparse_ = true;
    rank_ = m;
    null_.resize(m, 0);  // definite: no direction of the rows on which G vanishes
    try {
      factor_.factorize(S);
    } catch (const NumericalError& e) {
      throw NumericalError(fmt::format(
          "the coarse problem G G^T ({} rows, the rigid motions of the subdomains) is singular: "
          "a body has a motion that neither its supports nor its contact resist ({})",
          m, e.what()));
    }
    return;
  }
  decompose_scaled(MatrixXd(S));
}

SparseMatrix CoarseSpace::gram() const {
  SparseMatrix S = SparseMatrix(G_ * G_.transpose());
  if (!space_->distributed()) return S;
  // Each process's entries as (row, column, value) triples, added up in rank order: the same
  // sums on every process (indices below 2^53 are exact as doubles).
  VectorXd mine(3 * S.nonZeros());
  Index k = 0;
  for (Index j = 0; j < S.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(S, j); it; ++it) {
      mine(k++) = static_cast<double>(it.row());
      mine(k++) = static_cast<double>(it.col());
      mine(k++) = it.value();
    }
  const VectorXd all = space_->concat(mine);
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  entries.reserve(static_cast<size_t>(all.size() / 3));
  for (Index t = 0; t + 2 < all.size(); t += 3)
    entries.emplace_back(static_cast<SparseIndex>(all(t)), static_cast<SparseIndex>(all(t + 1)),
                         all(t + 2));
  S.setZero();
  S.setFromTriplets(entries.begin(), entries.end());
  S.makeCompressed();
  return S;
}

// S = D^{1/2} S_s D^{1/2}, D = diag(S): the rank is decided on S_s, whose diagonal is 1, so that
// rows of very different lengths (a small subdomain's rotations against a large one's
// translations, theory.md §8.3) are not taken for dependent ones. S^+ is applied as
// W W^T with W = D^{-1/2} V_r diag(1/sqrt(sigma_r)) (V_r, sigma_r of S_s): G^T W W^T G is the
// orthogonal projector onto the row space of G all the same, and W^T G has orthonormal rows.
void CoarseSpace::decompose_scaled(const MatrixXd& S) {
  const Index m = S.rows();
  VectorXd inv_sqrt_d(m);
  for (Index i = 0; i < m; ++i)  // a row that acts on nothing keeps its scale (a null direction)
    inv_sqrt_d(i) = S(i, i) > 0.0 ? 1.0 / std::sqrt(S(i, i)) : 1.0;
  const MatrixXd S_s = inv_sqrt_d.asDiagonal() * S * inv_sqrt_d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(S_s);
  const double largest = std::max(eig.eigenvalues().maxCoeff(), 0.0);
  std::vector<Index> range, null;
  for (Index i = 0; i < m; ++i)
    (largest > 0.0 && eig.eigenvalues()(i) > kRankTolerance * largest ? range : null).push_back(i);
  rank_ = static_cast<Index>(range.size());
  W_.resize(m, rank_);
  for (std::size_t j = 0; j < range.size(); ++j)
    W_.col(static_cast<Index>(j)) = inv_sqrt_d.asDiagonal() * eig.eigenvectors().col(range[j]) /
                                    std::sqrt(eig.eigenvalues()(range[j]));
  // The null directions of S are D^{-1/2} times those of S_s, made orthonormal.
  MatrixXd null_scaled(m, static_cast<Index>(null.size()));
  for (std::size_t j = 0; j < null.size(); ++j)
    null_scaled.col(static_cast<Index>(j)) =
        inv_sqrt_d.asDiagonal() * eig.eigenvectors().col(null[j]);
  null_ = null_scaled.cols() > 0 ? MatrixXd(null_scaled.householderQr().householderQ() *
                                            MatrixXd::Identity(m, null_scaled.cols()))
                                 : MatrixXd(m, 0);
}

VectorXd CoarseSpace::solve(const VectorXd& r) const {
  FRICON_CHECK(r.size() == rows(), "coarse solve of " << r.size() << " for " << rows() << " rows");
  ++n_solves_;
  if (rows() == 0) return VectorXd();
  const Stopwatch watch;
  VectorXd x = sparse_ ? factor_.solve(r) : VectorXd(W_ * (W_.transpose() * r));
  seconds_ += watch.seconds();
  return x;
}

VectorXd CoarseSpace::times(const VectorXd& v) const {
  VectorXd Gv = G_ * v;
  space_->sum(Gv);
  return Gv;
}

VectorXd CoarseSpace::onto_rows(const VectorXd& v) const {
  return transpose_times(solve(times(v)));
}

void CoarseSpace::project(VectorXd& v) const {
  if (rows() > 0) v.noalias() -= onto_rows(v);
}

}  // namespace fricon::qp
