#pragma once
// contact: the factors of the scaled dual (theory.md §4.5): one positive number d_R per patch,
// so that the multipliers of patch R are solved as lambda_R / d_R. The patch's three rows of
// Q = B K^-1 B^T are about its area times the mean displacement that a unit pressure on it
// causes; on an elastic half-space of indentation modulus M a uniform pressure p on a disc of
// area A displaces it by 16 p r / (3 pi M) on average, r = sqrt(A / pi), so
//
//   Q_RR ~ 16 A^(3/2) / (3 pi^(3/2) M)   and   d_R = sqrt(3 pi^(3/2) M_R / 16) A_R^(-3/4)
//
// make the diagonal of the scaled Q about 1 [sqrt(Pa/m^3)]. Patches of equal area and material
// get equal factors: a uniform mesh's QP is only multiplied by a constant (the paper's counts do
// not move), while a graded mesh's patch areas, a hundred times apart, no longer spread the
// spectrum of Q. The factors need no product with Q, so every dual operator gets the same ones.

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// How the dual QP's unknowns are scaled ([solver] dual_scaling).
enum class DualScaling {
  None,   ///< lambda itself, as in [HL09]
  Patch,  ///< one factor per patch from its area and material (above); default
};

/// The indentation modulus M = E / (1 - nu^2) [Pa] of an isotropic material, computed from its
/// Voigt matrix; for an anisotropic one the same formula on the means of the normal diagonal
/// (lambda + 2 mu) and off-diagonal (lambda) entries, an isotropic stand-in.
Real indentation_modulus(const fe::Material& material);

/// d_R [sqrt(Pa/m^3)] per patch, with M_R the area-weighted mean of the indentation modulus of
/// the tetrahedra under the patch's triangles.
VectorXd patch_scale_factors(const mesh::TetMesh& mesh, const ContactSurface& surface,
                             const Patches& patches, fe::Materials materials);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::DualScaling, "solver.dual_scaling",
                  {contact::DualScaling::None, "none"}, {contact::DualScaling::Patch, "patch"});
