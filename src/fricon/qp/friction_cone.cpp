#include "fricon/qp/friction_cone.hpp"

#include <algorithm>
#include <cmath>

#include "fricon/core/error.hpp"

namespace fricon::qp {

Vec3 project_friction_cone(const Vec3& x, Real mu) {
  const Real n = x(0);
  const Real t = std::hypot(x(1), x(2));
  if (t <= mu * n) return x;                      // inside
  if (mu * t <= -n) return Vec3::Zero();          // inside the polar cone
  const Real s = (n + mu * t) / (1.0 + mu * mu);  // the normal part of the projection
  return Vec3(s, mu * s * x(1) / t, mu * s * x(2) / t);
}

Real coulomb_residual(const VectorXd& l, const VectorXd& g, const VectorXd& mu, Real alpha,
                      Real scale) {
  FRICON_CHECK(l.size() == 3 * mu.size() && g.size() == l.size(),
               "coulomb_residual: " << l.size() << " multipliers, " << g.size() << " gradients, "
                                    << mu.size() << " coefficients");
  Real sum = 0.0;
  for (Index p = 0; p < mu.size(); ++p) {
    const Vec3 lp = l.segment<3>(3 * p);
    Vec3 u = g.segment<3>(3 * p);
    u(0) += mu(p) * std::hypot(u(1), u(2));  // De Saxce's modified velocity
    sum += (lp - project_friction_cone(lp - alpha * u, mu(p))).squaredNorm();
  }
  const Real reference = std::max(l.norm(), scale);
  return std::sqrt(sum) / (reference > 0.0 ? reference : 1.0);
}

Real tresca_residual(const VectorXd& l, const VectorXd& g, const VectorXd& threshold, Real alpha) {
  FRICON_CHECK(l.size() == 3 * threshold.size() && g.size() == l.size(),
               "tresca_residual: " << l.size() << " multipliers, " << g.size() << " gradients, "
                                   << threshold.size() << " thresholds");
  Real sum = 0.0;
  for (Index p = 0; p < threshold.size(); ++p) {
    const Vec3 lp = l.segment<3>(3 * p);
    Vec3 y = lp - alpha * g.segment<3>(3 * p);
    y(0) = std::max(y(0), 0.0);
    const Real t = std::hypot(y(1), y(2));
    if (t > threshold(p)) y.tail<2>() *= threshold(p) / t;
    sum += (lp - y).squaredNorm();
  }
  const Real norm_l = l.norm();
  return std::sqrt(sum) / (norm_l > 0.0 ? norm_l : 1.0);
}

}  // namespace fricon::qp
