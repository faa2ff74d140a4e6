#include "fricon/fe/p1_element.hpp"

#include <fmt/format.h>
#include <cmath>

#include "fricon/core/error.hpp"

namespace fricon::fe {

P1Gradients p1_gradients(const TetVertices& x) {
  Mat3 J;
  J << x.col(1) - x.col(0), x.col(2) - x.col(0), x.col(3) - x.col(0);
  const Real det = J.determinant();
  const Real scale = (x.col(1) - x.col(0)).squaredNorm() * (x.col(1) - x.col(0)).norm();
  if (!(std::abs(det) > 1e-14 * scale))
    throw NumericalError(fmt::format("degenerate tetrahedron (det J = {:.3e})", det));
  // Barycentric lambda_a (a = 1..3) are the rows of J^-1 applied to (y - x0).
  const Mat3 Jinv = J.inverse();
  P1Gradients g;
  g.grad.rightCols<3>() = Jinv.transpose();
  g.grad.col(0) = -g.grad.rightCols<3>().rowwise().sum();
  g.volume = det / 6.0;
  return g;
}

Strain6x12 strain_matrix(const Eigen::Matrix<Real, 3, 4>& grad) {
  Strain6x12 B = Strain6x12::Zero();
  for (int a = 0; a < 4; ++a) {
    const Real bx = grad(0, a), by = grad(1, a), bz = grad(2, a);
    const int c = 3 * a;
    B(0, c) = bx;
    B(1, c + 1) = by;
    B(2, c + 2) = bz;
    B(3, c + 1) = bz;
    B(3, c + 2) = by;
    B(4, c) = bz;
    B(4, c + 2) = bx;
    B(5, c) = by;
    B(5, c + 1) = bx;
  }
  return B;
}

ElementMatrix element_stiffness(const TetVertices& x, const Material& material) {
  const P1Gradients g = p1_gradients(x);
  const Strain6x12 B = strain_matrix(g.grad);
  return std::abs(g.volume) * B.transpose() * material.D * B;
}

}  // namespace fricon::fe
