// dual: Q from a factor of K ordered with the contact dofs last (theory.md §3.3): the trailing
// block L22 of the factor is the Cholesky factor of the Schur complement S of K onto the contact
// dofs, so Q = Y^T Y with Y = L22^-1 Bc^T (Bc: the contact columns of B, in pivot order), and
// the contact displacement is w_c = u0_c - L22^-T Y lambda. The outer loop never touches the
// volume. The constraint on the ordering costs fill (docs/benchmarks.md).
#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::dual {

namespace {

class SchurOperator final : public FactorDualOperator {
 public:
  explicit SchurOperator(const DualInput& input)
      : FactorDualOperator(input), order_(in_.factor.trailing_order()) {
    if (order_.size() != in_.contact_dofs.size())
      throw Error(fmt::format(
          "dual operator schur needs K factored with the {} contact dofs last (factor has {})",
          in_.contact_dofs.size(), order_.size()));
    L22_ = in_.factor.trailing_factor();
    Y_ = contact_columns_in_pivot_order();
    linalg::solve_lower(L22_, Y_);
    Q_ = MatrixXd::Zero(in_.B.rows(), in_.B.rows());
    linalg::add_gram_lower(Y_, Q_);
    Q_ = Q_.selfadjointView<Eigen::Lower>();
    load_changed();
  }
  DualOperatorKind kind() const override { return DualOperatorKind::Schur; }
  const MatrixXd* dense() const override { return &Q_; }

  void apply(const VectorXd& x, VectorXd& y) const override { linalg::symmetric_product(Q_, x, y); }

  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    const VectorXd wc = u0_c_ - L22_.transpose().triangularView<Eigen::Upper>().solve(Y_ * lambda);
    if (w.size() != u0_.size()) w = VectorXd::Zero(u0_.size());
    for (size_t k = 0; k < order_.size(); ++k)
      w(order_[k]) = wc(static_cast<Index>(k));
  }

 private:
  // Bc^T (contact dofs x n_dual), rows in the factor's pivot order.
  MatrixXd contact_columns_in_pivot_order() const {
    const Index nc = static_cast<Index>(order_.size());
    std::vector<Index> position(static_cast<size_t>(in_.B.cols()), -1);
    for (Index k = 0; k < nc; ++k)
      position[static_cast<size_t>(order_[static_cast<size_t>(k)])] = k;
    MatrixXd BcT = MatrixXd::Zero(nc, in_.B.rows());
    for (Index col = 0; col < in_.B.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(in_.B, col); it; ++it) {
        FRICON_CHECK(position[static_cast<size_t>(col)] >= 0,
                     "B touches dof " << col << " outside the contact dofs");
        BcT(position[static_cast<size_t>(col)], it.row()) = it.value();
      }
    return BcT;
  }

  void load_changed() override {
    u0_c_.resize(static_cast<Index>(order_.size()));
    for (size_t k = 0; k < order_.size(); ++k)
      u0_c_(static_cast<Index>(k)) = u0_(order_[k]);
  }

  std::vector<Index> order_;  // the contact dofs in pivot order (L22's rows)
  MatrixXd L22_, Y_, Q_;
  VectorXd u0_c_;
};

}  // namespace

std::unique_ptr<DualOperator> make_schur_operator(const DualInput& input) {
  return std::make_unique<SchurOperator>(input);
}

}  // namespace fricon::dual
