#include "fricon/fe/element.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/fe/elements/lagrange.hpp"

namespace fricon::fe {

Tabulation Element::tabulate(const QuadratureRule& rule, Real reference_measure) const {
  Tabulation t;
  t.rule = rule;
  t.reference_measure = reference_measure;
  for (Index q = 0; q < rule.weights.size(); ++q) {
    const VectorXd point = rule.points.col(q);
    t.values.push_back(values(point));
    t.derivatives.push_back(derivatives(point));
  }
  return t;
}

const ElementFamily& lagrange_elements(int order) {
  static const ElementFamily linear{tet_p1(), triangle_p1()};
  static const ElementFamily quadratic{tet_p2(), triangle_p2()};
  if (order == 1) return linear;
  if (order == 2) return quadratic;
  throw InputError(fmt::format("elements of order {}: fricon has orders 1 and 2", order));
}

ElementNodes tet_points(const mesh::TetMesh& mesh, Index t) {
  ElementNodes x(3, mesh.nodes_per_tet());
  for (int a = 0; a < mesh.nodes_per_tet(); ++a)
    x.col(a) = mesh.nodes.col(mesh.tet_node(t, a));
  return x;
}

ElementNodes face_points(const mesh::TetMesh& mesh, Index f) {
  ElementNodes x(3, mesh.nodes_per_face());
  for (int a = 0; a < mesh.nodes_per_face(); ++a)
    x.col(a) = mesh.nodes.col(mesh.face_node(f, a));
  return x;
}

CellMap map_cell(const ElementNodes& x, const ShapeDerivatives& dN) {
  const Mat3 J = x * dN;  // J_ij = d x_i / d xi_j
  CellMap m;
  m.det = J.determinant();
  if (m.det != 0.0) m.grad = dN * J.inverse();  // dN/dx = dN/dxi J^-1
  return m;
}

FaceMap map_face(const ElementNodes& x, const ShapeDerivatives& dN) {
  const Eigen::Matrix<Real, 3, 2> J = x * dN;
  const Vec3 cross = J.col(0).cross(J.col(1));
  FaceMap m;
  m.area_element = cross.norm();
  if (m.area_element > 0.0) m.normal = cross / m.area_element;
  return m;
}

void check_jacobians(const mesh::TetMesh& mesh, const std::string& source, Real min_ratio) {
  const Element& element = elements_of(mesh).cell;
  // The points to test: the stiffness points and the corners (where a curved edge folds first).
  std::vector<ShapeDerivatives> at_points = element.stiffness_points().derivatives;
  for (int a = 0; a < 4; ++a)
    at_points.push_back(element.derivatives(VectorXd::Unit(4, a)));
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const ElementNodes x = tet_points(mesh, t);
    const Real straight = 6.0 * mesh::tet_volume(mesh, t);
    Real worst = std::numeric_limits<Real>::infinity();
    for (const ShapeDerivatives& dN : at_points)
      worst = std::min(worst, map_cell(x, dN).det);
    if (straight > 0.0 && worst > min_ratio * straight) continue;
    throw InputError(fmt::format(
        "{}: tetrahedron {} (corner nodes {} {} {} {}) is {}: its Jacobian determinant reaches "
        "{:.3e}, against {:.3e} for the straight tetrahedron through its corners; fix the mesh "
        "(a smaller element where the boundary curves, or order 1)",
        source, t, mesh.tets(0, t), mesh.tets(1, t), mesh.tets(2, t), mesh.tets(3, t),
        straight <= 0.0 ? "inverted" : "so curved that it folds", worst, straight));
  }
}

}  // namespace fricon::fe
