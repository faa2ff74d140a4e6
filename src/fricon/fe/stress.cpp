#include "fricon/fe/stress.hpp"

#include <cmath>

#include "fricon/fe/element.hpp"
#include "fricon/fe/stiffness.hpp"

namespace fricon::fe {

Real von_mises(const Eigen::Matrix<Real, 6, 1>& s) {
  return std::sqrt(0.5 * ((s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) +
                          (s(2) - s(0)) * (s(2) - s(0))) +
                   3.0 * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5)));
}

namespace {
// sigma at the barycentric point `bary` of tetrahedron t.
Eigen::Matrix<Real, 6, 1> stress_at(const Element& element, const ElementNodes& x,
                                    const ElementVector& ue, const Material& material,
                                    const VectorXd& bary) {
  const CellMap map = map_cell(x, element.derivatives(bary));
  return material.D * (strain_matrix(map.grad) * ue);
}
}  // namespace

StressField compute_stresses(const mesh::TetMesh& mesh, Materials materials, const NodalField& u) {
  const Element& element = elements_of(mesh).cell;
  const MatrixXd node_points = element.node_points();
  const VectorXd centroid = VectorXd::Constant(4, 0.25);
  StressField out;
  out.stress.resize(6, mesh.n_tets());
  out.von_mises.resize(mesh.n_tets());
  out.nodal_stress = VoigtField::Zero(6, mesh.n_nodes());
  VectorXd count = VectorXd::Zero(mesh.n_nodes());
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const ElementNodes x = tet_points(mesh, t);
    ElementVector ue(3 * element.n_nodes());
    for (int a = 0; a < element.n_nodes(); ++a)
      ue.segment<3>(3 * a) = u.col(mesh.tet_node(t, a));
    const Material& material = material_of(materials, mesh, t);
    out.stress.col(t) = stress_at(element, x, ue, material, centroid);
    out.von_mises(t) = von_mises(out.stress.col(t));
    for (int a = 0; a < element.n_nodes(); ++a) {
      const Index node = mesh.tet_node(t, a);
      out.nodal_stress.col(node) += stress_at(element, x, ue, material, node_points.col(a));
      count(node) += 1.0;
    }
  }
  out.nodal_von_mises.resize(mesh.n_nodes());
  for (Index i = 0; i < mesh.n_nodes(); ++i) {
    if (count(i) > 0.0) out.nodal_stress.col(i) /= count(i);
    out.nodal_von_mises(i) = von_mises(out.nodal_stress.col(i));
  }
  return out;
}

}  // namespace fricon::fe
