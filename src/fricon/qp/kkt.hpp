#pragma once
// qp: optimality (KKT) residuals of a candidate solution of min 1/2 x^T A x - b^T x over Omega,
// for tests, solver reports and the driver's sanity checks. Independent of the solver: it needs
// only x, the gradient g = A x - b and the constraints.
//
// Per block (eta = x_i / ||x_i|| the outward normal of a disc, defined for x_i != 0):
//
//   Bound (x_i >= 0):
//     feasibility      max(0, -x_i)
//     stationarity     max(0, -g_i)             (an optimum needs g_i >= 0: a multiplier of a >=)
//     complementarity  |x_i g_i|
//   Disc (||x_i|| <= rho):
//     feasibility      max(0, ||x_i|| - rho)
//     stationarity     distance from g_i to the ray {-s eta : s >= 0} (an optimum needs
//                      g_i = -s eta with s >= 0); ||g_i|| if x_i = 0 and rho > 0 (the normal
//                      cone of an interior point is {0}); 0 if rho = 0 (the block is pinned)
//     complementarity  s |rho - ||x_i|||  with s = max(0, -g_i . eta)   (0 if x_i = 0 or rho = 0)
//   Free (x_i in R):
//     feasibility      0
//     stationarity     |g_i|                    (an optimum needs g_i = 0: no constraint)
//     complementarity  0
//
// Like the Bound test, the Disc stationarity test does not ask whether x_i is on the circle: a
// normal force at an interior point shows up in the complementarity residual instead, so a point
// a rounding error inside the circle is not penalised by the full normal force.
//
// Each returned value is the maximum over the blocks, divided by its scale: feasibility by
// scale_x, stationarity by scale_g, complementarity by scale_x * scale_g. Then 1e-10 means
// "exact to 1e-10 relative".

#include <Eigen/Core>

#include "fricon/qp/constraints.hpp"
#include "fricon/qp/operator.hpp"

namespace fricon::qp {

struct KktResiduals {
  double feasibility = 0.0;      ///< max block violation of Omega / scale_x
  double stationarity = 0.0;     ///< max block distance of g to the normal cone / scale_g
  double complementarity = 0.0;  ///< max block multiplier times gap / (scale_x scale_g)

  /// The largest of the three.
  double max() const;
};

/// Scales for kkt_residuals.
struct KktScales {
  double x = 1.0;  ///< unit of x
  double g = 1.0;  ///< unit of g
};

/// The default scales: x = max(||x||_inf, largest disc radius), g = ||b||_2 (the unit of the
/// solver's stopping test). A scale that comes out 0 (x = 0 with no positive radius, or b = 0)
/// is replaced by 1: then the problem is trivial and absolute residuals are meaningful.
KktScales default_kkt_scales(const Eigen::VectorXd& x, const Eigen::VectorXd& b,
                             const SeparableConstraints& c);

/// The residuals defined above, for x and g = A x - b. Throws fricon::InputError if the sizes do
/// not match c.size() or a scale is not finite and > 0.
KktResiduals kkt_residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                           const SeparableConstraints& c, double scale_x, double scale_g);

/// Convenience: g = A x - b (one product) and the default scales.
KktResiduals kkt_residuals(const Operator& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                           const SeparableConstraints& c);

}  // namespace fricon::qp
