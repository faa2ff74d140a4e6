#include "fricon/qp/kkt.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::qp {

double KktResiduals::max() const {
  return std::max({feasibility, stationarity, complementarity});
}

KktScales default_kkt_scales(const Eigen::VectorXd& x, const Eigen::VectorXd& b,
                             const SeparableConstraints& c) {
  KktScales s;
  s.x = std::max(x.size() > 0 ? x.lpNorm<Eigen::Infinity>() : 0.0, c.max_radius());
  s.g = b.norm();
  if (!(s.x > 0.0)) s.x = 1.0;
  if (!(s.g > 0.0)) s.g = 1.0;
  return s;
}

KktResiduals kkt_residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                           const SeparableConstraints& c, double scale_x, double scale_g) {
  const Index n = c.size();
  if (x.size() != n || g.size() != n) {
    throw InputError(fmt::format("kkt_residuals: {} unknowns but x has {} and g has {} entries", n,
                                 x.size(), g.size()));
  }
  if (!(std::isfinite(scale_x) && scale_x > 0.0 && std::isfinite(scale_g) && scale_g > 0.0)) {
    throw InputError(fmt::format("kkt_residuals: scales must be finite and > 0, got x {} g {}",
                                 scale_x, scale_g));
  }
  double feas = 0.0, stat = 0.0, comp = 0.0;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Index o = c.blocks[k].offset;
    if (c.blocks[k].kind == BlockKind::Free) {
      // Always feasible; the normal cone of R is {0}, so g_i itself is the violation, and there
      // is no multiplier to complement.
      stat = std::max(stat, std::abs(g(o)));
      continue;
    }
    if (c.blocks[k].kind == BlockKind::Bound) {
      feas = std::max(feas, -x(o));
      stat = std::max(stat, -g(o));
      comp = std::max(comp, std::abs(x(o) * g(o)));
      continue;
    }
    const double rho = c.radius(static_cast<Index>(k));
    const double nx = std::hypot(x(o), x(o + 1));
    const double ng = std::hypot(g(o), g(o + 1));
    feas = std::max(feas, nx - rho);
    if (rho == 0.0) continue;  // pinned: every g is a normal-cone element
    if (nx == 0.0) {
      stat = std::max(stat, ng);
      continue;
    }
    const double e1 = x(o) / nx, e2 = x(o + 1) / nx;
    const double s = std::max(0.0, -(g(o) * e1 + g(o + 1) * e2));
    // g + s eta is g minus its projection onto the ray {-s eta}.
    stat = std::max(stat, std::hypot(g(o) + s * e1, g(o + 1) + s * e2));
    comp = std::max(comp, s * std::abs(rho - nx));
  }
  return {feas / scale_x, stat / scale_g, comp / (scale_x * scale_g)};
}

KktResiduals kkt_residuals(const Operator& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                           const SeparableConstraints& c) {
  Eigen::VectorXd g(x.size());
  A(x, g);
  g -= b;
  const KktScales s = default_kkt_scales(x, b, c);
  return kkt_residuals(x, g, c, s.x, s.g);
}

}  // namespace fricon::qp
