#include "fricon/qp/mpgp_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fricon::qp::detail {

namespace {

/// The unit tangent (-eta_2, eta_1) of a disc at x_i = (x1, x2) with ||x_i|| = nx > 0, and the
/// component of v_i = (v1, v2) along it.
struct Tangent {
  double t1, t2;
  double of(double v1, double v2) const { return t1 * v1 + t2 * v2; }
};

Tangent tangent_at(double x1, double x2, double nx) {
  return {-x2 / nx, x1 / nx};
}

}  // namespace

Split Kernels::split(const Eigen::VectorXd& x, const Eigen::VectorXd& g, Eigen::VectorXd& phi,
                     Eigen::VectorXd& beta) {
  Split s;
  n_turned_ = 0;
  const double abar = alpha_bar_;
  for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
    const Index o = c_.blocks[k].offset;
    if (c_.blocks[k].kind == BlockKind::Free) {
      // Never active: the whole gradient is free, and (x - P(x - abar g)) / abar = g.
      const double gi = g(o);
      phi(o) = gi;
      beta(o) = 0.0;
      s.gp2 += gi * gi;
      s.phi2 += gi * gi;
      s.phit_phi += gi * gi;
      continue;
    }
    if (c_.blocks[k].kind == BlockKind::Bound) {
      const double xi = x(o);
      const double gi = g(o);
      if (xi <= tol_bound_) {
        const double bi = std::min(gi, 0.0);
        phi(o) = 0.0;
        beta(o) = bi;
        s.gp2 += bi * bi;
        s.beta2 += bi * bi;
      } else {
        phi(o) = gi;
        beta(o) = 0.0;
        s.gp2 += gi * gi;
        s.phi2 += gi * gi;
        // (x - max(x - abar g, 0)) / abar
        const double ti = gi > 0.0 ? std::min(gi, xi / abar) : gi;
        s.phit_phi += ti * gi;
      }
      continue;
    }
    const double rho = c_.radius(static_cast<Index>(k));
    const double x1 = x(o), x2 = x(o + 1);
    const double g1 = g(o), g2 = g(o + 1);
    const double nx = norm2(x1, x2);
    turned_[k] = 0;
    if (rho == 0.0) {  // pinned block
      phi(o) = phi(o + 1) = beta(o) = beta(o + 1) = 0.0;
    } else if (nx >= (1.0 - tol_disc_) * rho) {  // active: nx > 0 here
      const double e1 = x1 / nx, e2 = x2 / nx;   // outward normal
      const double mu = std::max(-(e1 * g1 + e2 * g2), 0.0);
      if (mu <= turn_limit_ * rho) {  // turned (§4.7): the tangent is free, the inward part chopped
        turned_[k] = 1;
        ++n_turned_;
        const Tangent t = tangent_at(x1, x2, nx);
        const double gt = t.of(g1, g2);
        const double gin = std::max(e1 * g1 + e2 * g2, 0.0);
        phi(o) = gt * t.t1;
        phi(o + 1) = gt * t.t2;
        beta(o) = gin * e1;
        beta(o + 1) = gin * e2;
        s.gp2 += gt * gt + gin * gin;
        s.phi2 += gt * gt;
        s.phit_phi += gt * gt;  // the move x - abar phi returns to the circle: as if free
        s.beta2 += gin * gin;
        continue;
      }
      const double gn = -mu;
      const double b1 = g1 - gn * e1, b2 = g2 - gn * e2;
      phi(o) = phi(o + 1) = 0.0;
      beta(o) = b1;
      beta(o + 1) = b2;
      const double bb = b1 * b1 + b2 * b2;
      s.gp2 += bb;
      s.beta2 += bb;
    } else {
      phi(o) = g1;
      phi(o + 1) = g2;
      beta(o) = beta(o + 1) = 0.0;
      const double gg = g1 * g1 + g2 * g2;
      s.gp2 += gg;
      s.phi2 += gg;
      // (x - P_disc(x - abar g)) / abar
      const double y1 = x1 - abar * g1, y2 = x2 - abar * g2;
      const double ny = norm2(y1, y2);
      if (ny <= rho) {
        s.phit_phi += gg;
      } else {
        const double t1 = (x1 - rho * y1 / ny) / abar;
        const double t2 = (x2 - rho * y2 / ny) / abar;
        s.phit_phi += t1 * g1 + t2 * g2;
      }
    }
  }
  return reduced(s);
}

Split Kernels::reduced(Split s) {
  Eigen::Matrix<double, 5, 1> sums;
  sums << s.gp2, s.phi2, s.beta2, s.phit_phi, static_cast<double>(n_turned_);
  space_.sum(Eigen::Ref<Eigen::VectorXd>(sums));
  any_turned_ = sums(4) > 0.0;
  return {.gp2 = sums(0), .phi2 = sums(1), .beta2 = sums(2), .phit_phi = sums(3)};
}

void Kernels::reduced_free_gradient(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                    Eigen::VectorXd& gr) const {
  const double abar = alpha_bar_;
  for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
    const Index o = c_.blocks[k].offset;
    if (c_.blocks[k].kind == BlockKind::Free) {  // P is the identity: (x - (x - abar g)) / abar
      gr(o) = g(o);
      continue;
    }
    if (c_.blocks[k].kind == BlockKind::Bound) {
      const double xi = x(o);
      const double gi = g(o);
      // The same tests and formula as split(): (x - max(x - abar g, 0)) / abar on a free bound.
      gr(o) = xi <= tol_bound_ ? 0.0 : (gi > 0.0 ? std::min(gi, xi / abar) : gi);
      continue;
    }
    const double rho = c_.radius(static_cast<Index>(k));
    const double x1 = x(o), x2 = x(o + 1);
    const double nx = norm2(x1, x2);
    if (rho == 0.0 || nx >= (1.0 - tol_disc_) * rho) {  // pinned or active
      gr(o) = gr(o + 1) = 0.0;
      continue;
    }
    const double g1 = g(o), g2 = g(o + 1);
    const double y1 = x1 - abar * g1, y2 = x2 - abar * g2;
    const double ny = norm2(y1, y2);
    if (ny <= rho) {
      gr(o) = g1;
      gr(o + 1) = g2;
    } else {  // (x - P_disc(x - abar g)) / abar
      gr(o) = (x1 - rho * y1 / ny) / abar;
      gr(o + 1) = (x2 - rho * y2 / ny) / abar;
    }
  }
}

double Kernels::rounding_scale(const Eigen::VectorXd& x, const Eigen::VectorXd& g) const {
  double sum = 0.0;
  for (const Block& blk : c_.blocks) {
    const Index o = blk.offset;
    if (blk.kind == BlockKind::Bound || blk.kind == BlockKind::Free) {
      sum += std::abs(g(o) * x(o));
    } else {
      sum += norm2(g(o), g(o + 1)) * norm2(x(o), x(o + 1));
    }
  }
  return space_.sum(sum);
}

double Kernels::max_feasible_step(const Eigen::VectorXd& x, const Eigen::VectorXd& p) const {
  double a = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
    const Index o = c_.blocks[k].offset;
    if (c_.blocks[k].kind == BlockKind::Free) continue;  // no constraint: no limit
    if (turned(k)) continue;                             // returns to its circle after the step
    if (c_.blocks[k].kind == BlockKind::Bound) {
      if (p(o) > 0.0) a = std::min(a, std::max(x(o), 0.0) / p(o));
      continue;
    }
    const double p1 = p(o), p2 = p(o + 1);
    const double pp = p1 * p1 + p2 * p2;
    if (pp == 0.0) continue;
    const double rho = c_.radius(static_cast<Index>(k));
    const double x1 = x(o), x2 = x(o + 1);
    const double nx = norm2(x1, x2);
    const double xp = x1 * p1 + x2 * p2;
    // Root t >= 0 of ||x - t p||^2 = rho^2: pp t^2 - 2 xp t - slack = 0, with slack =
    // rho^2 - ||x||^2 clipped at 0 (x may sit outside by rounding). The two algebraically equal
    // forms avoid cancellation for either sign of xp.
    const double slack = std::max((rho - nx) * (rho + nx), 0.0);
    const double sq = std::sqrt(xp * xp + pp * slack);
    const double t = xp >= 0.0 ? (xp + sq) / pp : (sq > xp ? slack / (sq - xp) : 0.0);
    a = std::min(a, t);
  }
  return space_.min(a);
}

void Kernels::restrict_to_face(const Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  restrict(x, v, true);
}

void Kernels::clear_active(const Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  restrict(x, v, false);
}

void Kernels::restrict(const Eigen::VectorXd& x, Eigen::VectorXd& v, bool keep_tangents) const {
  for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
    const Index o = c_.blocks[k].offset;
    if (c_.blocks[k].kind == BlockKind::Free) continue;  // never active
    if (c_.blocks[k].kind == BlockKind::Bound) {
      if (x(o) <= tol_bound_) v(o) = 0.0;
      continue;
    }
    if (keep_tangents && turned(k)) {  // only the tangential part
      const Tangent t = tangent_at(x(o), x(o + 1), norm2(x(o), x(o + 1)));
      const double vt = t.of(v(o), v(o + 1));
      v(o) = vt * t.t1;
      v(o + 1) = vt * t.t2;
      continue;
    }
    const double rho = c_.radius(static_cast<Index>(k));
    if (rho == 0.0 || norm2(x(o), x(o + 1)) >= (1.0 - tol_disc_) * rho) v(o) = v(o + 1) = 0.0;
  }
}

double Kernels::turn_curvature(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                               const Eigen::VectorXd& p, Eigen::VectorXd& Dp) const {
  Dp.setZero(x.size());
  double pDp = 0.0;
  if (n_turned_ == 0) return space_.sum(pDp);
  for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
    if (!turned(k)) continue;
    const Index o = c_.blocks[k].offset;
    const double nx = norm2(x(o), x(o + 1));
    const Tangent t = tangent_at(x(o), x(o + 1), nx);
    const double mu = std::max(t.t1 * g(o + 1) - t.t2 * g(o), 0.0);  // -eta^T g, eta = (t2, -t1)
    const double curvature = mu / c_.radius(static_cast<Index>(k));
    const double pt = t.of(p(o), p(o + 1));
    Dp(o) = curvature * pt * t.t1;
    Dp(o + 1) = curvature * pt * t.t2;
    pDp += curvature * pt * pt;
  }
  return space_.sum(pDp);
}

void SpectralLength::update(double ss, double sy, double yy) {
  if (!(ss > 0.0 && sy > 0.0 && yy > 0.0) || !std::isfinite(ss + sy + yy)) return;
  const double a1 = ss / sy;
  const double a2 = sy / yy;
  short_[count_ % kMemory] = a2;
  ++count_;
  double a = a1;
  if (a2 < kTau * a1) {
    a = a2;
    for (int k = 0; k < std::min(count_, kMemory); ++k)
      a = std::min(a, short_[static_cast<std::size_t>(k)]);
  }
  if (std::isfinite(a)) length_ = std::clamp(a, lo_, hi_);
}

}  // namespace fricon::qp::detail
