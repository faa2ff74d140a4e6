#pragma once
// outer: Anderson mixing (type II) for a fixed point x = Psi(x) (theory.md §5.3). From the last
// iterates x_i and their images g_i = Psi(x_i), the next iterate is g_k - sum_i gamma_i
// (g_(i+1) - g_i), with gamma minimising the norm of the mixed residual f_k - sum_i gamma_i
// (f_(i+1) - f_i), f = g - x. With depth 0, or before a second pair exists, it is the plain
// iteration x := g.

#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::outer {

class AndersonMixing {
 public:
  /// `depth` previous differences are kept (>= 0); entries of the result are clipped below at
  /// `lower_bound` (the states iterated here, slips and pressures, are non-negative).
  explicit AndersonMixing(int depth, Real lower_bound = 0.0);

  /// The next iterate from the current one x and its image g = Psi(x) (same size every call;
  /// a size change restarts the history).
  VectorXd next(const VectorXd& x, const VectorXd& g);

 private:
  size_t depth_;
  Real lower_bound_;
  std::vector<VectorXd> dF_, dG_;  // differences of residuals and of images, oldest first
  VectorXd f_last_, g_last_;
};

}  // namespace fricon::outer
