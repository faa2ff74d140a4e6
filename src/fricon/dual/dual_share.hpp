#pragma once
// dual: the dual QP as this process holds it (docs/theory.md §8.8). An operator whose multipliers
// are shared out over processes (Total FETI under MPI, feti/dual_rows.hpp) gives each process a
// part of them: the QP runs on the parts (qp::DualSpace takes its reductions over the processes),
// and the whole vectors are put together once per QP. One process holding everything is the
// default share of every operator, the identity. PERMON's chain of transforms is the model:
// dualize, scale, project, and here distribute, each with its own map back.

#include "fricon/core/types.hpp"
#include "fricon/qp/dual_space.hpp"
#include "fricon/qp/operator.hpp"
#include "fricon/qp/scaling.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::dual {

class DualOperator;

class DualShare {
 public:
  virtual ~DualShare() = default;

  /// The QP's reductions over the processes that share the multipliers.
  virtual const qp::DualSpace& space() const = 0;
  /// The multipliers this process holds.
  virtual Index size() const = 0;
  /// Of them, the contact multipliers: the first n_contact(), either all of the operator's or
  /// none.
  virtual Index n_contact() const = 0;
  /// This process's part of a vector over all the multipliers, in the order it holds them.
  virtual VectorXd restrict(const VectorXd& whole) const = 0;
  /// The columns of G (over all the multipliers) of this process's part.
  virtual SparseMatrix restrict_columns(const SparseMatrix& G) const = 0;
  /// The vector over all the multipliers from every process's part, on every process.
  /// Collective.
  virtual VectorXd assemble(const VectorXd& part) const = 0;
  /// Q x on this process's part (x and y both parts; y is overwritten). Collective.
  virtual void apply(const VectorXd& x, VectorXd& y) const = 0;
  /// M_E on this process's equality multipliers (its last size() - n_contact()), an
  /// approximation of the inverse of Q's equality block (theory.md §8.5); empty: none.
  /// Collective, as apply().
  virtual qp::Operator equality_preconditioner() const { return {}; }
};

/// Every multiplier of `Q` on this process (which must outlive it): the identity.
class WholeShare final : public DualShare {
 public:
  explicit WholeShare(const DualOperator& Q) : Q_(Q) {}
  const qp::DualSpace& space() const override { return qp::whole_space(); }
  Index size() const override;
  Index n_contact() const override;
  VectorXd restrict(const VectorXd& whole) const override { return whole; }
  SparseMatrix restrict_columns(const SparseMatrix& G) const override { return G; }
  VectorXd assemble(const VectorXd& part) const override { return part; }
  void apply(const VectorXd& x, VectorXd& y) const override;

 private:
  const DualOperator& Q_;
};

/// qp::solve_smalse_scaled of Q's QP on Q's share (Q.share()): the constraints `c` (the contact
/// layout of Q's contact multipliers, then one Free block per equality multiplier), the scaling
/// D and the equality {G, e} over all the multipliers are restricted to this process's part,
/// the inner options get its space and, with equality multipliers, the share's preconditioner
/// (the identity of the scaled contact multipliers beside M_E). lambda: in, the whole initial
/// guess; out, the whole last iterate (on every process). mu as solve_smalse's. Collective over
/// the processes of the share.
qp::SmalseReport solve_shared_smalse(const DualOperator& Q, const qp::SeparableConstraints& c,
                                     const qp::BlockScaling& D, const qp::EqualityConstraint& eq,
                                     const qp::SmalseOptions& opt, qp::MpgpOptions inner,
                                     VectorXd& lambda, VectorXd& mu);

}  // namespace fricon::dual
