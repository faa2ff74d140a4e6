#pragma once
// contact: the matrix B that couples displacements and multipliers (theory.md §2.4), and the
// stability check of the multiplier space, condition (5.1) of [HL09] (theory.md §2.5).

#include <string>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// The frame of each patch, in which its multipliers act: the surface's (n, t1, t2) against a
/// plane; against a body the frame of the area-weighted mean of its nodes' contact normals
/// (ContactSurface::node_frames; Frames::tangents).
Frames patch_frames(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches);

/// B over the free dofs: n_dual = 3 n_patches rows ordered (n, t1, t2) per patch, in the patch's
/// frame (frames, one per patch), (B v)_{n,p} = int_{R_p} v.n_p dS and likewise for t1, t2
/// [m^2], exact for the P1 traces; fixed dofs have no column. With `mortar` (against a body:
/// n_patches x mesh nodes, mortar(p, a) = int_{R_p} of master node a's shape function at the
/// projection, theory.md §2.8), the master's displacement is subtracted:
/// (B v)_{n,p} = int_{R_p} (v - v_master).n_p dS.
SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches, const Frames& frames,
                        const SparseMatrix* mortar = nullptr);
/// B against a plane: assemble_b with patch_frames(mesh, surface, patches), without master.
SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches);

/// How the stability of B was checked.
struct StabilityReport {
  Real ratio = 0.0;        ///< sigma_min / sigma_max of B
  bool estimated = false;  ///< true: power and inverse iteration; false: dense eigensolve
  /// Rows of B without entries (a direction that Dirichlet conditions fix on a whole patch):
  /// their multipliers act on nothing, stay zero, and are left out of the check.
  Index n_inactive = 0;
};

/// Condition (5.1): B^T has full column rank on the contact dofs (rows without entries left
/// out, see StabilityReport::n_inactive). Up to `dense_limit` rows the
/// eigenvalues of B B^T are computed exactly (dense, O(n_dual^3)); beyond, B B^T (sparse:
/// neighbouring patches only) is factored by a sparse Cholesky and its extreme eigenvalues
/// estimated by power and inverse iteration (to about a per cent). Throws NumericalError naming
/// `where` and the ratio when it is below `min_ratio`.
StabilityReport check_stability(const SparseMatrix& B, const std::string& where,
                                Real min_ratio = 1e-8, Index dense_limit = 500);

}  // namespace fricon::contact
