#pragma once
// contact: the slip bounds of the patches, rho_p = (1/|R_p|) int_{R_p} F(phi_h) g_h dS [Pa]
// (theory.md §2.6), integrated exactly when F is piecewise linear.

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// How patch_radii integrates (recorded in reports).
inline constexpr const char* kRadiusIntegration =
    "exact for piecewise-linear F: triangles cut at the level lines phi_h = kink, edge-midpoint "
    "rule on each piece";

/// Radii for nodal slips phi [m] and nodal slip bounds g [Pa] (both per surface node). Exact
/// when F is piecewise linear: every triangle is cut at the level lines phi_h = kink and each
/// piece integrated with a rule of degree >= 2.
VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g);

}  // namespace fricon::contact
