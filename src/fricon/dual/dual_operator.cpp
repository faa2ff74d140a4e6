#include "fricon/dual/dual_operator.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::dual {

FactorizationRequest factorization_request(DualOperatorKind kind,
                                           const std::vector<Index>& contact_dofs) {
  FactorizationRequest r;
  if (kind == DualOperatorKind::Schur) r.last = contact_dofs;
  return r;
}

// One process: the forward sweep (measured the fastest on the paper's brick,
// docs/benchmarks.md) while Q takes no more memory than the factor of K already does, or on small
// meshes; distributed: MUMPS's Schur complement, 288 MB of dense Q on rank 0 at most.
DualOperatorKind resolve(DualOperatorKind kind, FactorLocation where, Index n_dual, double nnz_L) {
  if (kind != DualOperatorKind::Auto) return kind;
  const double q_entries = static_cast<double>(n_dual) * static_cast<double>(n_dual);
  const double small = static_cast<double>(kDenseDualLimit) * static_cast<double>(kDenseDualLimit);
  if (where == FactorLocation::Distributed)
    return q_entries <= small ? DualOperatorKind::Schur : DualOperatorKind::Implicit;
  return q_entries <= std::max(nnz_L, small) ? DualOperatorKind::Forward
                                             : DualOperatorKind::Implicit;
}

void DualOperator::set_free_solution(VectorXd u0, const SparseMatrix& B, const VectorXd* offset) {
  u0_ = std::move(u0);
  h_ = B * u0_;
  if (offset != nullptr) h_ -= *offset;
}

void DualOperator::set_equality(const SparseMatrix* R, const SparseMatrix& B, const VectorXd& f) {
  if (R == nullptr || R->cols() == 0) return;
  FRICON_CHECK(R->rows() == B.cols() && R->rows() == f.size(),
               "set_equality: R of " << R->rows() << " rows for " << B.cols() << " free dofs");
  R_ = R;
  if (G_.rows() != R->cols()) G_ = SparseMatrix(R->transpose() * B.transpose());
  e_ = R->transpose() * f;
}

VectorXd DualOperator::rigid_displacement(const VectorXd& alpha) const {
  FRICON_CHECK(alpha.size() == n_motions(),
               "rigid_displacement: " << alpha.size() << " amplitudes for " << n_motions());
  if (R_ == nullptr) return VectorXd::Zero(u0_.size());
  return *R_ * alpha;
}

void DualOperator::set_load(const VectorXd&, const VectorXd&, const VectorXd*, const NodalLoad&) {
  throw Error("this dual operator cannot change its load (a loading path runs on one process)");
}

FactorDualOperator::FactorDualOperator(const DualInput& input) : in_(input), f_(input.f) {
  set_equality(in_.R, in_.B, in_.f);
  if (in_.free_solution != nullptr) {
    set_free_solution(*in_.free_solution, in_.B, in_.offset);
    return;
  }
  set_free_solution(in_.factor.solve(in_.f), in_.B, in_.offset);
  ++n_kinv_;
}

VectorXd FactorDualOperator::displacement(const VectorXd& lambda) const {
  ++n_kinv_;
  return in_.factor.solve(VectorXd(f_ - in_.B.transpose() * lambda));
}

void FactorDualOperator::set_load(const VectorXd& f, const VectorXd& offset, const VectorXd* u0,
                                  const NodalLoad&) {
  FRICON_CHECK(f.size() == f_.size() && offset.size() == in_.B.rows(),
               "set_load: a load of " << f.size() << " and an offset of " << offset.size());
  f_ = f;
  set_equality(in_.R, in_.B, f_);
  if (u0 != nullptr) {
    set_free_solution(*u0, in_.B, &offset);
  } else {
    set_free_solution(in_.factor.solve(f_), in_.B, &offset);
    ++n_kinv_;
  }
  load_changed();
}

MatrixXd DualOperator::to_dense() const {
  if (const MatrixXd* Q = dense()) return *Q;
  const Index n = size();
  MatrixXd Q(n, n);
  VectorXd e = VectorXd::Zero(n), y(n);
  for (Index j = 0; j < n; ++j) {
    e(j) = 1.0;
    apply(e, y);
    Q.col(j) = y;
    e(j) = 0.0;
  }
  return Q;
}

qp::Operator DualOperator::as_qp_operator() const {
  return [this](const VectorXd& x, VectorXd& y) { apply(x, y); };
}

const DualShare& DualOperator::share() const {
  if (!whole_share_) whole_share_ = std::make_unique<WholeShare>(*this);
  return *whole_share_;
}

std::unique_ptr<DualOperator> make_dual_operator(DualOperatorKind kind, const DualInput& input) {
  switch (resolve(kind, FactorLocation::OneProcess, input.B.rows(), input.factor.info().nnz_L)) {
    case DualOperatorKind::Implicit:
      return make_implicit_operator(input);
    case DualOperatorKind::Forward:
      return make_forward_operator(input);
    case DualOperatorKind::Schur:
      return make_schur_operator(input);
    case DualOperatorKind::Auto:
      break;
  }
  throw Error(fmt::format("make_dual_operator: invalid kind {}", static_cast<int>(kind)));
}

}  // namespace fricon::dual
