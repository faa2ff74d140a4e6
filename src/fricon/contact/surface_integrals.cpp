#include "fricon/contact/surface_integrals.hpp"

#include <cmath>

#include "fricon/fe/element.hpp"

namespace fricon::contact {

FaceIntegrals face_integrals(const mesh::TetMesh& mesh, const ContactSurface& surface, Index k) {
  const fe::Element& element = fe::elements_of(mesh).face;
  const fe::Tabulation& points = element.mass_points();
  const fe::ElementNodes x = fe::face_points(mesh, surface.faces[static_cast<size_t>(k)]);
  const Index n = element.n_nodes();
  FaceIntegrals out{VectorXd::Zero(n), MatrixXd::Zero(n, n)};
  for (Index q = 0; q < points.size(); ++q) {
    const fe::ShapeValues& N = points.values[static_cast<size_t>(q)];
    const Real dS =
        points.weight(q) * fe::map_face(x, points.derivatives[static_cast<size_t>(q)]).area_element;
    out.shape += dS * N;
    out.mass += dS * N * N.transpose();
  }
  // The corners of a straight 6-node triangle integrate to zero: exactly, not to rounding, so
  // that B has no entries for them (curved triangles keep their small integrals).
  constexpr Real kRounding = 1e-14;
  const Real area = out.shape.sum();
  for (Index a = 0; a < n; ++a)
    if (std::abs(out.shape(a)) <= kRounding * area) out.shape(a) = 0.0;
  return out;
}

std::vector<std::array<Index, 3>> linear_pieces(const mesh::TetMesh& mesh,
                                                const ContactSurface& surface, Index k) {
  const Eigen::MatrixXi local = fe::elements_of(mesh).face.linear_pieces();
  std::vector<std::array<Index, 3>> pieces(static_cast<size_t>(local.cols()));
  for (Index j = 0; j < local.cols(); ++j)
    for (int v = 0; v < 3; ++v)
      pieces[static_cast<size_t>(j)][static_cast<size_t>(v)] = surface.face_nodes(local(v, j), k);
  return pieces;
}

}  // namespace fricon::contact
