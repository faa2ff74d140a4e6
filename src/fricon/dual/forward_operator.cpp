// dual: Q formed once by a forward sweep over the part of the factor the contact dofs reach
// (theory.md §3.3): with K = P^T L L^T P, Q = Y^T Y for Y = L^-1 P B^T, and each column of B^T
// is carried only along its own path of the elimination tree (CholeskyFactor::inverse_gram).
// Inside the outer loop the displacement is recovered on that reach only (solve_on_reach).
#include "fricon/dual/dual_operator.hpp"

#include "fricon/linalg/blas.hpp"

namespace fricon::dual {

namespace {

class ForwardOperator final : public FactorDualOperator {
 public:
  explicit ForwardOperator(const DualInput& input)
      : FactorDualOperator(input),
        Q_(in_.factor.inverse_gram(SparseMatrix(in_.B.transpose()), in_.poll)),
        reach_(in_.factor.reach(in_.contact_dofs)) {
    n_kinv_ += in_.B.rows();
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
