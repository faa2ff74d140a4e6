#pragma once
// contact: integrals over the contact surface's triangles by the face element's quadrature
// (fe/element.hpp; theory.md §2.12): the shape functions' integrals and mass matrix of each
// triangle (exact on straight triangles), and its linear pieces where a piecewise-linear view is
// needed (the slip bounds' exact integration, theory.md §2.6). Every contact integral reads these
// instead of a closed form of one element.

#include <array>
#include <vector>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// The integrals over surface triangle k of the shape functions of its nodes (face_nodes.col(k)
/// order): `shape`(a) = int_T phi_a dS and `mass`(a, b) = int_T phi_a phi_b dS [m^2]. For a
/// 3-node triangle |T|/3 and |T| (1 + delta_ab) / 12; for a straight 6-node one 0 at the corners
/// and |T|/3 at the edge nodes.
struct FaceIntegrals {
  VectorXd shape;
  MatrixXd mass;
};
FaceIntegrals face_integrals(const mesh::TetMesh& mesh, const ContactSurface& surface, Index k);

/// Surface triangle k cut into the linear triangles through its nodes (the element's
/// linear_pieces), each as three surface nodes (positions in surface.nodes), counter-clockwise
/// seen from outside.
std::vector<std::array<Index, 3>> linear_pieces(const mesh::TetMesh& mesh,
                                                const ContactSurface& surface, Index k);

}  // namespace fricon::contact
