// dual: Q formed once by a forward sweep over the part of the factor the contact dofs reach
// (theory.md §3.3): with K = P^T L L^T P, Q = Y^T Y for Y = L^-1 P B^T, and each column of B^T
// is carried only along its own path of the elimination tree (CholeskyFactor::inverse_gram).
// Inside the outer loop the displacement is recovered on that reach only (solve_on_reach), or,
// when many recoveries are coming (DualInput::expected_recoveries), by a product with the contact
// rows
// C = E K^-1 B^T of K^-1 B^T, carried back from the forward sweep's Y with Q (theory.md §3.3).
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

// Forming C carries the n_dual columns of Y back over the reach in blocks (the BLAS's level 3);
// per column that costs about this fraction of one recovery by a solve over the reach (the paper's
// brick at n = 16: its 576 columns in about the time of 30 one-column solves).
constexpr double kBlockedColumnCost = 1.0 / 16.0;

// Whether to form the contact rows C: cheaper than the recoveries expected, and the forward
// sweep's Y kept for them (at most reach rows x n_dual numbers) no larger than the factor itself.
bool form_contact_rows(const DualInput& in, const linalg::CholeskyFactor::Reach& reach) {
  const double n_dual = static_cast<double>(in.B.rows());
  const bool pays = static_cast<double>(in.expected_recoveries) > kBlockedColumnCost * n_dual;
  const double kept = static_cast<double>(reach.rows.size()) * n_dual;
  return pays && kept <= in.factor.info().nnz_L;
}

class ForwardOperator final : public FactorDualOperator {
 public:
  explicit ForwardOperator(const DualInput& input)
      : FactorDualOperator(input), reach_(in_.factor.reach(in_.contact_dofs)) {
    const SparseMatrix Bt = in_.B.transpose();
    if (form_contact_rows(in_, reach_)) {
      linalg::CholeskyFactor::GramAndRows both =
          in_.factor.inverse_gram_and_rows(Bt, reach_, in_.contact_dofs, in_.poll);
      Q_ = std::move(both.gram);
      C_ = std::move(both.rows);
      n_kinv_ += in_.B.rows();  // a backward substitution per multiplier
    } else {
      Q_ = in_.factor.inverse_gram(Bt, in_.poll);
    }
    n_kinv_ += nonzero_rows(in_.B);  // a zero row is carried nowhere
  }
  DualOperatorKind kind() const override { return DualOperatorKind::Forward; }
  const MatrixXd* dense() const override { return &Q_; }

  void apply(const VectorXd& x, VectorXd& y) const override { linalg::symmetric_product(Q_, x, y); }

  // u0 - K^-1 B^T lambda: B^T lambda lives on the contact dofs, so the forward substitution runs
  // over their reach only (the linear residual of the result is checked by the driver).
  VectorXd displacement(const VectorXd& lambda) const override {
    VectorXd x = in_.B.transpose() * lambda;
    in_.factor.solve_from_reach(reach_, x);
    ++n_kinv_;
    return u0_ - x;
  }

  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    if (w.size() != u0_.size()) w = VectorXd::Zero(u0_.size());
    if (C_.size() > 0) {
      VectorXd x;
      linalg::product(C_, lambda, x);
      for (size_t i = 0; i < in_.contact_dofs.size(); ++i)
        w(in_.contact_dofs[i]) = u0_(in_.contact_dofs[i]) - x(static_cast<Index>(i));
      return;
    }
    VectorXd x = in_.B.transpose() * lambda;
    in_.factor.solve_on_reach(reach_, x);
    ++n_kinv_;
    for (Index dof : in_.contact_dofs)
      w(dof) = u0_(dof) - x(dof);
  }

 private:
  linalg::CholeskyFactor::Reach reach_;
  MatrixXd Q_;
  MatrixXd C_;  ///< E K^-1 B^T, the contact dofs' rows [m/Pa], if formed (else empty)
};

}  // namespace

std::unique_ptr<DualOperator> make_forward_operator(const DualInput& input) {
  return std::make_unique<ForwardOperator>(input);
}

}  // namespace fricon::dual
