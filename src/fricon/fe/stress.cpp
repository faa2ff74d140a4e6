#include "fricon/fe/stress.hpp"

#include <cmath>

#include "fricon/fe/p1_element.hpp"

namespace fricon::fe {

namespace {
Real von_mises(const Eigen::Matrix<Real, 6, 1>& s) {
  return std::sqrt(0.5 * ((s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) +
                          (s(2) - s(0)) * (s(2) - s(0))) +
                   3.0 * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5)));
}
}  // namespace

StressField compute_stresses(const mesh::TetMesh& mesh, Materials materials, const NodalField& u) {
  StressField out;
  out.stress.resize(6, mesh.n_tets());
  out.von_mises.resize(mesh.n_tets());
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const P1Gradients g = p1_gradients(tet_vertices(mesh, t));
    Eigen::Matrix<Real, 12, 1> ue;
    for (int a = 0; a < 4; ++a)
      ue.segment<3>(3 * a) = u.col(mesh.tets(a, t));
    const Eigen::Matrix<Real, 6, 1> s =
        material_of(materials, mesh, t).D * (strain_matrix(g.grad) * ue);
    out.stress.col(t) = s;
    out.von_mises(t) = von_mises(s);
  }
  return out;
}

}  // namespace fricon::fe
