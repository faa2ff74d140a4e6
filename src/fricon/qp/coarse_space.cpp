#include "fricon/qp/coarse_space.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"

namespace fricon::qp {

namespace {
// A row direction of G whose squared length is below this share of the largest acts on no
// unknown (theory.md §4.6).
constexpr double kRankTolerance = 1e-12;
}  // namespace

CoarseSpace::CoarseSpace(const SparseMatrix& G) : G_(G) {
  const Index m = G_.rows();
  const SparseMatrix S = SparseMatrix(G_ * G_.transpose());
  if (m == 0) return;
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
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig{MatrixXd(S)};
  const double largest = std::max(eig.eigenvalues().maxCoeff(), 0.0);
  std::vector<Index> range, null;
  for (Index i = 0; i < m; ++i)
    (largest > 0.0 && eig.eigenvalues()(i) > kRankTolerance * largest ? range : null).push_back(i);
  rank_ = static_cast<Index>(range.size());
  W_.resize(m, rank_);
  null_.resize(m, static_cast<Index>(null.size()));
  for (std::size_t j = 0; j < range.size(); ++j)
    W_.col(static_cast<Index>(j)) =
        eig.eigenvectors().col(range[j]) / std::sqrt(eig.eigenvalues()(range[j]));
  for (std::size_t j = 0; j < null.size(); ++j)
    null_.col(static_cast<Index>(j)) = eig.eigenvectors().col(null[j]);
}

VectorXd CoarseSpace::solve(const VectorXd& r) const {
  FRICON_CHECK(r.size() == rows(), "coarse solve of " << r.size() << " for " << rows() << " rows");
  ++n_solves_;
  if (rows() == 0) return VectorXd();
  if (sparse_) return factor_.solve(r);
  return W_ * (W_.transpose() * r);
}

VectorXd CoarseSpace::onto_rows(const VectorXd& v) const {
  return G_.transpose() * solve(G_ * v);
}

void CoarseSpace::project(VectorXd& v) const {
  if (rows() > 0) v.noalias() -= onto_rows(v);
}

}  // namespace fricon::qp
