#include "fricon/parallel/mpi/mumps_operator.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::parallel {

namespace {

// What both operators share: u0, h and the displacement by distributed solves.
class MumpsOperator : public dual::DualOperator {
 public:
  MumpsOperator(const DistributedSolves& solves, const SparseMatrix& B, const VectorXd* offset)
      : solves_(solves), B_(B) {
    set_free_solution(solves_.displacement(VectorXd::Zero(B.rows())), B_, offset);
    ++n_kinv_;
  }
  VectorXd displacement(const VectorXd& lambda) const override {
    ++n_kinv_;
    return solves_.displacement(lambda);
  }
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override {
    ++n_kinv_;
    solves_.contact_displacement(lambda, w);
  }

 protected:
  const DistributedSolves& solves_;
  const SparseMatrix& B_;
};

class MumpsSchurOperator final : public MumpsOperator {
 public:
  MumpsSchurOperator(const DistributedSolves& solves, const MatrixXd& schur, const SparseMatrix& B,
                     const VectorXd* offset)
      : MumpsOperator(solves, B, offset), Q_(-schur) {
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
    y = solves_.apply(x);
    ++n_kinv_;
  }
};

}  // namespace

std::unique_ptr<dual::DualOperator> make_mumps_operator(dual::DualOperatorKind kind,
                                                        const DistributedSolves& solves,
                                                        const MatrixXd* schur,
                                                        const SparseMatrix& B,
                                                        const VectorXd* offset) {
  switch (kind) {
    case dual::DualOperatorKind::Schur:
      FRICON_CHECK(schur != nullptr, "make_mumps_operator: schur needs the Schur complement");
      return std::make_unique<MumpsSchurOperator>(solves, *schur, B, offset);
    case dual::DualOperatorKind::Implicit:
      return std::make_unique<MumpsImplicitOperator>(solves, B, offset);
    default:
      throw Error(fmt::format("make_mumps_operator: no MUMPS operator \"{}\"", enum_name(kind)));
  }
}

}  // namespace fricon::parallel
