#pragma once
// contact: the slip bounds of the patches, rho_p = (1/|R_p|) int_{R_p} F(phi_h) g_h dS [Pa]
// (theory.md §2.6), integrated exactly when F is piecewise linear, else by adaptive
// Gauss-Kronrod quadrature on the level-line reduction to F's quadrature_rtol(). phi_h and g_h
// are the piecewise-linear interpolants on the triangles' linear pieces (surface_integrals.hpp:
// the triangles themselves at order 1, their four corner-and-midpoint triangles at order 2,
// theory.md §2.12).

#include <string>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// How patch_radii integrates for a piecewise-linear law (recorded in reports).
inline constexpr const char* kRadiusIntegration =
    "exact for piecewise-linear F: triangles cut at the level lines phi_h = kink, edge-midpoint "
    "rule on each piece";

/// How patch_radii integrates for the law F, for reports: kRadiusIntegration when F is piecewise
/// linear, else the quadrature and its tolerance.
std::string radius_integration(const FrictionLaw& F);

/// Radii for nodal slips phi [m] and nodal slip bounds g [Pa] (both per surface node). Exact
/// when F is piecewise linear: every triangle is cut at the level lines phi_h = kink and each
/// piece integrated with a rule of degree >= 2. Otherwise each triangle's integral is reduced to
/// a 1D integral over the range of phi_h (theory.md §2.6, eq. (2.6.2)), split at F's kinks and
/// integrated by adaptive Gauss-Kronrod (7-15) until the estimated error of every patch is at
/// most F.quadrature_rtol() times its integral of |F g_h|; F is evaluated in one batch
/// (FrictionLaw::evaluate) per round of bisection. Throws NumericalError when that tolerance is
/// not reached in 60 rounds, and whatever F.evaluate throws (InputError for a bad value of F).
VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g);

}  // namespace fricon::contact
