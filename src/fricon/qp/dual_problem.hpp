#pragma once
// qp: one dual contact problem as plain data (theory.md §3.1), for dumps and other solvers:
//
//   minimise 1/2 l^T Q l - l^T h  over  l_n >= 0,  ||(l_t1, l_t2)|| <= radius  per patch,
//
// unknowns ordered (n, t1, t2) per patch (SeparableConstraints::contact_layout).

#include <string>

#include "fricon/core/types.hpp"

namespace fricon::qp {

struct DualProblem {
  MatrixXd Q;           ///< 3m x 3m, symmetric positive definite [m^3/Pa]
  VectorXd h;           ///< 3m [m^3]
  VectorXd radius;      ///< m slip bounds [Pa]
  VectorXd patch_area;  ///< m patch areas [m^2]
  std::string source;   ///< the problem it came from
};

}  // namespace fricon::qp
