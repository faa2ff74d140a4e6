// dual: the paper's operator (theory.md §3.3): Q is never formed, each product with Q is one
// solve with the factor of K, y = B K^-1 B^T x. Its product count is the paper's n_mult.
#include "fricon/dual/dual_operator.hpp"

namespace fricon::dual {

namespace {

class ImplicitOperator final : public FactorDualOperator {
 public:
  explicit ImplicitOperator(const DualInput& input) : FactorDualOperator(input) {}
  DualOperatorKind kind() const override { return DualOperatorKind::Implicit; }

  void apply(const VectorXd& x, VectorXd& y) const override {
    y = in_.B * in_.factor.solve(VectorXd(in_.B.transpose() * x));
    ++n_kinv_;
  }

  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    w = displacement(lambda);
  }
};

}  // namespace

std::unique_ptr<DualOperator> make_implicit_operator(const DualInput& input) {
  return std::make_unique<ImplicitOperator>(input);
}

}  // namespace fricon::dual
