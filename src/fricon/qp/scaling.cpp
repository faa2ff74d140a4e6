#include "fricon/qp/scaling.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::qp {

BlockScaling BlockScaling::identity(Index n) {
  return BlockScaling(Eigen::VectorXd::Ones(n));
}

BlockScaling BlockScaling::per_block(const SeparableConstraints& c, const Eigen::VectorXd& factor) {
  if (factor.size() != static_cast<Index>(c.blocks.size()))
    throw InputError(
        fmt::format("BlockScaling: {} factors for {} blocks", factor.size(), c.blocks.size()));
  Eigen::VectorXd d(c.size());
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const double f = factor(static_cast<Index>(k));
    if (!(std::isfinite(f) && f > 0.0))
      throw InputError(
          fmt::format("BlockScaling: the factor of block {} is {}; expected > 0", k, f));
    d.segment(c.blocks[k].offset, block_size(c.blocks[k].kind)).setConstant(f);
  }
  return BlockScaling(std::move(d));
}

Operator BlockScaling::scaled(const Operator& A) const {
  return [&A, this](const Eigen::VectorXd& y, Eigen::VectorXd& z) {
    A(y.cwiseProduct(d_), z);
    z.array() *= d_.array();
  };
}

Operator BlockScaling::scaled_inverse(const Operator& M) const {
  return [&M, this](const Eigen::VectorXd& y, Eigen::VectorXd& z) {
    M(y.cwiseQuotient(d_), z);
    z.array() /= d_.array();
  };
}

MpgpOptions BlockScaling::scaled(const MpgpOptions& opt) const {
  MpgpOptions o = opt;
  if (opt.preconditioner) o.preconditioner = scaled_inverse(opt.preconditioner);
  return o;
}

SeparableConstraints BlockScaling::scaled(const SeparableConstraints& c) const {
  FRICON_CHECK(c.size() == d_.size(), "constraints of " << c.size() << " for " << d_.size());
  SeparableConstraints s = c;
  for (std::size_t k = 0; k < c.blocks.size(); ++k)
    if (c.blocks[k].kind == BlockKind::Disc)
      s.radius(static_cast<Index>(k)) /= d_(c.blocks[k].offset);
  return s;
}

MpgpReport solve_mpgp_scaled(const Operator& A, const Eigen::VectorXd& b,
                             const SeparableConstraints& c, const BlockScaling& D,
                             const MpgpOptions& opt, Eigen::VectorXd& x) {
  FRICON_CHECK(x.size() == D.size() && b.size() == D.size(),
               "x has " << x.size() << " and b " << b.size() << " entries for " << D.size());
  const Operator A_scaled = D.scaled(A);
  const SeparableConstraints c_scaled = D.scaled(c);
  Eigen::VectorXd y = D.to_scaled(x);
  MpgpReport rep = solve_mpgp(A_scaled, D.dual_to_scaled(b), c_scaled, D.scaled(opt), y);
  x = D.from_scaled(y);
  return rep;
}

SmalseReport solve_smalse_scaled(const Operator& A, const Eigen::VectorXd& b,
                                 const SeparableConstraints& c, const BlockScaling& D,
                                 const EqualityConstraint& eq, const SmalseOptions& opt,
                                 const MpgpOptions& inner, Eigen::VectorXd& x,
                                 Eigen::VectorXd& mu) {
  FRICON_CHECK(x.size() == D.size() && b.size() == D.size(),
               "x has " << x.size() << " and b " << b.size() << " entries for " << D.size());
  const EqualityConstraint eq_scaled{SparseMatrix(eq.G * D.d().asDiagonal()), eq.e};
  Eigen::VectorXd y = D.to_scaled(x);
  SmalseReport rep = solve_smalse(D.scaled(A), D.dual_to_scaled(b), D.scaled(c), eq_scaled, opt,
                                  D.scaled(inner), y, mu);
  x = D.from_scaled(y);
  return rep;
}

KktResiduals scaled_kkt_residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                  const Eigen::VectorXd& b, const SeparableConstraints& c,
                                  const BlockScaling& D, StopReference reference,
                                  double data_scale) {
  const SeparableConstraints c_scaled = D.scaled(c);
  const Eigen::VectorXd y = D.to_scaled(x);
  const Eigen::VectorXd b_scaled = D.dual_to_scaled(b);
  const Eigen::VectorXd r =
      reference == StopReference::Whole ? b_scaled : resisted_part(b_scaled, c_scaled);
  double scale_x =
      std::max(y.size() > 0 ? y.lpNorm<Eigen::Infinity>() : 0.0, c_scaled.max_radius());
  double scale_g = data_scale > 0.0 ? data_scale : r.norm();
  if (!(scale_x > 0.0)) scale_x = 1.0;
  if (!(scale_g > 0.0)) scale_g = 1.0;
  return kkt_residuals(y, D.dual_to_scaled(g), c_scaled, scale_x, scale_g);
}

}  // namespace fricon::qp
