#include "fricon/contact/dual_scaling.hpp"

#include <cmath>
#include <numbers>

#include "fricon/core/error.hpp"

namespace fricon::contact {

Real indentation_modulus(const fe::Material& material) {
  const fe::Voigt6& D = material.D;
  const Real normal = (D(0, 0) + D(1, 1) + D(2, 2)) / 3.0;        // lambda + 2 mu
  const Real off_diagonal = (D(0, 1) + D(0, 2) + D(1, 2)) / 3.0;  // lambda
  const Real mu = 0.5 * (normal - off_diagonal);
  // E / (1 - nu^2) = 2 mu / (1 - nu) = 4 mu (lambda + mu) / (lambda + 2 mu)
  return 4.0 * mu * (off_diagonal + mu) / normal;
}

VectorXd patch_scale_factors(const mesh::TetMesh& mesh, const ContactSurface& surface,
                             const Patches& patches, fe::Materials materials) {
  const std::vector<Index> tets = mesh::tets_of_faces(mesh, surface.faces);
  // sqrt(3 pi^(3/2) / 16): the half-space compliance of a uniformly loaded disc (header).
  const Real half_space = std::sqrt(3.0 * std::pow(std::numbers::pi, 1.5) / 16.0);
  VectorXd d(patches.size());
  for (Index p = 0; p < patches.size(); ++p) {
    Real modulus_area = 0.0;
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index t = tets[static_cast<size_t>(k)];
      FRICON_CHECK(t >= 0, "surface triangle " << k << " is a face of no tetrahedron");
      modulus_area += indentation_modulus(fe::material_of(materials, mesh, t)) *
                      mesh::face_area(mesh, surface.faces[static_cast<size_t>(k)]);
    }
    const Real area = patches.area(p);
    d(p) = half_space * std::sqrt(modulus_area / area) * std::pow(area, -0.75);
  }
  return d;
}

}  // namespace fricon::contact
