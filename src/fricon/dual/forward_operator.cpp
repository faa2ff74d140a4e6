// dual: Q formed once by a forward sweep over the part of the factor the contact dofs reach
// (theory.md §3.3): with K = P^T L L^T P, Q = Y^T Y for Y = L^-1 P B^T, and each column of B^T
// is carried only along its own path of the elimination tree (CholeskyFactor::inverse_gram).
// Inside the outer loop the displacement is recovered on that reach only (solve_on_reach).
#include "fricon/dual/dual_operator.hpp"

#include <algorithm>
#include <vector>

#include "fricon/linalg/blas.hpp"

namespace fricon::dual {

namespace {

Index nonzero_rows(const SparseMatrix& B) {
  std::vector<char> used(static_cast<size_t>(B.rows()), 0);
  for (Index j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      if (it.value() != 0.0) used[static_cast<size_t>(it.row())] = 1;
  return static_cast<Index>(std::count(used.begin(), used.end(), 1));
}

class ForwardOperator final : public FactorDualOperator {
 public:
  explicit ForwardOperator(const DualInput& input)
      : FactorDualOperator(input),
        Q_(in_.factor.inverse_gram(SparseMatrix(in_.B.transpose()), in_.poll)),
        reach_(in_.factor.reach(in_.contact_dofs)) {
    n_kinv_ += nonzero_rows(in_.B);  // a zero row is carried nowhere
  }
  DualOperatorKind kind() const override { return DualOperatorKind::Forward; }
  const MatrixXd* dense() const override { return &Q_; }

  void apply(const VectorXd& x, VectorXd& y) const override { linalg::symmetric_product(Q_, x, y); }

  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    VectorXd x = in_.B.transpose() * lambda;
    in_.factor.solve_on_reach(reach_, x);
    ++n_kinv_;
    if (w.size() != u0_.size()) w = VectorXd::Zero(u0_.size());
    for (Index dof : in_.contact_dofs)
      w(dof) = u0_(dof) - x(dof);
  }

 private:
  MatrixXd Q_;
  linalg::CholeskyFactor::Reach reach_;
};

}  // namespace

std::unique_ptr<DualOperator> make_forward_operator(const DualInput& input) {
  return std::make_unique<ForwardOperator>(input);
}

}  // namespace fricon::dual
