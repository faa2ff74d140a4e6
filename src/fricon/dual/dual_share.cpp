#include "fricon/dual/dual_share.hpp"

#include <utility>
#include <vector>

#include "fricon/core/error.hpp"
#include "fricon/dual/dual_operator.hpp"

namespace fricon::dual {

namespace {

// The blocks of `c` on this process's part: the contact blocks where it holds the contact
// multipliers, then a Free block per equality multiplier it holds.
qp::SeparableConstraints part_of(const qp::SeparableConstraints& c, const DualShare& share) {
  qp::SeparableConstraints part;
  std::vector<Real> radius;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const qp::Block& block = c.blocks[k];
    if (block.kind == qp::BlockKind::Free || block.offset >= share.n_contact()) continue;
    part.blocks.push_back(block);
    radius.push_back(c.radius(static_cast<Index>(k)));
  }
  part.radius = Eigen::Map<const VectorXd>(radius.data(), static_cast<Index>(radius.size()));
  part.append_free(share.size() - share.n_contact());
  return part;
}

// D on this process's part (one factor per block of `part`).
qp::BlockScaling part_of(const qp::BlockScaling& D, const qp::SeparableConstraints& part,
                         const DualShare& share) {
  const VectorXd d = share.restrict(D.d());
  VectorXd factor(static_cast<Index>(part.blocks.size()));
  for (std::size_t k = 0; k < part.blocks.size(); ++k)
    factor(static_cast<Index>(k)) = d(part.blocks[k].offset);
  return qp::BlockScaling::per_block(part, factor);
}

// M over this process's part: D^2 on the contact multipliers (the identity of the scaled QP
// there), M_E on the equality ones; none without M_E.
qp::Operator part_preconditioner(const DualShare& share, const VectorXd& d) {
  qp::Operator equality = share.equality_preconditioner();
  if (!equality) return {};
  const Index n_contact = share.n_contact(), n_equality = share.size() - n_contact;
  return [equality = std::move(equality), d2 = VectorXd(d.head(n_contact).array().square()),
          n_contact, n_equality](const VectorXd& x, VectorXd& y) {
    VectorXd y_E(n_equality);
    equality(x.tail(n_equality), y_E);
    y.head(n_contact) = d2.cwiseProduct(x.head(n_contact));
    y.tail(n_equality) = y_E;
  };
}

}  // namespace

Index WholeShare::size() const {
  return Q_.size();
}

Index WholeShare::n_contact() const {
  return Q_.n_contact();
}

void WholeShare::apply(const VectorXd& x, VectorXd& y) const {
  Q_.apply(x, y);
}

qp::SmalseReport solve_shared_smalse(const DualOperator& Q, const qp::SeparableConstraints& c,
                                     const qp::BlockScaling& D, const qp::EqualityConstraint& eq,
                                     const qp::SmalseOptions& opt, qp::MpgpOptions inner,
                                     VectorXd& lambda, VectorXd& mu) {
  const DualShare& share = Q.share();
  FRICON_CHECK(
      share.n_contact() == 0 || share.n_contact() == Q.n_contact(),
      "a share of " << share.n_contact() << " of " << Q.n_contact() << " contact multipliers");
  const qp::SeparableConstraints c_part = part_of(c, share);
  const qp::BlockScaling D_part = part_of(D, c_part, share);
  inner.space = &share.space();
  if (Q.n_equality() > 0) inner.preconditioner = part_preconditioner(share, D_part.d());
  const qp::Operator A = [&share](const VectorXd& x, VectorXd& y) { share.apply(x, y); };
  VectorXd x = share.restrict(lambda);
  const qp::SmalseReport rep =
      qp::solve_smalse_scaled(A, share.restrict(Q.h()), c_part, D_part,
                              {share.restrict_columns(eq.G), eq.e}, opt, inner, x, mu);
  lambda = share.assemble(x);
  return rep;
}

}  // namespace fricon::dual
