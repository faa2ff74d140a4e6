#include "fricon/fe/stiffness.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::fe {

StrainMatrix strain_matrix(const ShapeDerivatives& grad) {
  const Index n = grad.rows();
  StrainMatrix B = StrainMatrix::Zero(6, 3 * n);
  for (Index a = 0; a < n; ++a) {
    const Real bx = grad(a, 0), by = grad(a, 1), bz = grad(a, 2);
    const Index c = 3 * a;
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

ElementMatrix element_stiffness(const Element& element, const ElementNodes& x,
                                const Material& material) {
  const Tabulation& points = element.stiffness_points();
  const Index n_dofs = 3 * element.n_nodes();
  ElementMatrix K = ElementMatrix::Zero(n_dofs, n_dofs);
  for (Index q = 0; q < points.size(); ++q) {
    const CellMap map = map_cell(x, points.derivatives[static_cast<size_t>(q)]);
    if (!(map.det > 0.0))
      throw NumericalError(fmt::format("inverted or degenerate element (det J = {:.3e})", map.det));
    const StrainMatrix B = strain_matrix(map.grad);
    K.noalias() += (points.weight(q) * map.det) * (B.transpose() * material.D * B);
  }
  return K;
}

}  // namespace fricon::fe
