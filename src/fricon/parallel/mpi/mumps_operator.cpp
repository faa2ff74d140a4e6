#include "fricon/parallel/mpi/mumps_operator.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::parallel {

namespace {

// What both operators share: u0, h and the displacement by solves with the MUMPS factor.
class MumpsOperator : public dual::DualOperator {
 public:
  MumpsOperator(const MumpsFactor& factor, const SparseMatrix& B, const VectorXd& f,
                const VectorXd* offset)
      : factor_(factor), B_(B), f_(f) {
    set_free_solution(factor_.solve(f_), B_, offset);
    ++n_kinv_;
  }
  VectorXd displacement(const VectorXd& lambda) const override {
    ++n_kinv_;
    return factor_.solve(VectorXd(f_ - B_.transpose() * lambda));
  }
  /// One distributed solve gives w everywhere; the contact dofs are among them.
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    w = displacement(lambda);
  }

 protected:
  const MumpsFactor& factor_;
  const SparseMatrix& B_;
  const VectorXd& f_;
};

class MumpsSchurOperator final : public MumpsOperator {
 public:
  MumpsSchurOperator(const MumpsFactor& factor, const SparseMatrix& B, const VectorXd& f,
                     const VectorXd* offset)
      : MumpsOperator(factor, B, f, offset), Q_(-factor.schur()) {
    if (Q_.rows() != B.rows())
      throw Error(fmt::format("the MUMPS Schur complement has order {}, expected n_dual = {}",
                              Q_.rows(), B.rows()));
  }
  dual::DualOperatorKind kind() const override { return dual::DualOperatorKind::Schur; }
  const MatrixXd* dense() const override { return &Q_; }
  void apply(const VectorXd& x, VectorXd& y) const override { linalg::symmetric_product(Q_, x, y); }

 private:
  MatrixXd Q_;
};

class MumpsImplicitOperator final : public MumpsOperator {
 public:
  using MumpsOperator::MumpsOperator;
  dual::DualOperatorKind kind() const override { return dual::DualOperatorKind::Implicit; }
  void apply(const VectorXd& x, VectorXd& y) const override {
    y = B_ * factor_.solve(VectorXd(B_.transpose() * x));
    ++n_kinv_;
  }
};

}  // namespace

std::unique_ptr<dual::DualOperator> make_mumps_operator(dual::DualOperatorKind kind,
                                                        const MumpsFactor& factor,
                                                        const SparseMatrix& B, const VectorXd& f,
                                                        const VectorXd* offset) {
  switch (kind) {
    case dual::DualOperatorKind::Schur:
      return std::make_unique<MumpsSchurOperator>(factor, B, f, offset);
    case dual::DualOperatorKind::Implicit:
      return std::make_unique<MumpsImplicitOperator>(factor, B, f, offset);
    default:
      throw Error(fmt::format("make_mumps_operator: no MUMPS operator \"{}\"", enum_name(kind)));
  }
}

}  // namespace fricon::parallel
