#pragma once
// qp: the matrix-free operator through which the QP layer applies its Hessian.

#include <functional>

#include <Eigen/Core>

namespace fricon::qp {

/// y := A x for a symmetric positive definite A. y arrives with the size of x (its content is
/// to be overwritten); write into it without resizing so that no allocation happens per product.
/// For a dense matrix M: [&](const auto& x, auto& y) { y.noalias() = M * x; }.
using Operator = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

}  // namespace fricon::qp
