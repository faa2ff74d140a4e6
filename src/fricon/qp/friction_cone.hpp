#pragma once
// qp: the Coulomb friction cone of the contact layout (theory.md §5.6) and the natural-map
// residual of the Coulomb problem in its local (dual) form:
//
//   find l with g = Q l - h:  l_R in K_R = {||l_t|| <= mu_R l_n},  g_R + mu_R ||g_t,R|| e_n in
//   K_R*,  l_R . (g_R + mu_R ||g_t,R|| e_n) = 0  for every patch R (De Saxce's complementarity),
//
// unknowns ordered (n, t1, t2) per patch. This is FCLIB's local problem with W = Q, q = -h,
// r = l and u = g.

#include "fricon/core/types.hpp"

namespace fricon::qp {

/// The Euclidean projection of (x_n, x_t) onto the cone {||x_t|| <= mu x_n}, mu >= 0.
Vec3 project_friction_cone(const Vec3& x, Real mu);

/// The natural-map residual ||l - P_K(l - alpha (g + mu ||g_t|| e_n))|| / max(||l||, scale)
/// (2-norms over all patches; absolute when both are 0), for multipliers l [Pa], the gradient
/// g = Q l - h [m^3], one coefficient mu per patch, a scale alpha [Pa/m^3] (1/||Q||) and a floor
/// `scale` >= 0 [Pa] of the multipliers' norm (theory.md §5.6: along a loading path the largest
/// ||l|| of the earlier steps, so that a step unloaded to l = 0 is not measured against its own
/// vanishing multipliers). Zero exactly at a solution of the Coulomb problem, for any alpha > 0.
Real coulomb_residual(const VectorXd& l, const VectorXd& g, const VectorXd& mu, Real alpha,
                      Real scale = 0.0);

/// The natural-map residual of the Tresca problem, ||l - P_C(l - alpha g)|| / ||l|| with C the
/// product of {l_n >= 0} and the discs ||l_t|| <= threshold (absolute when l = 0).
Real tresca_residual(const VectorXd& l, const VectorXd& g, const VectorXd& threshold, Real alpha);

}  // namespace fricon::qp
