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
/// plane; against a body or a curved obstacle the frame of the area-weighted mean of its nodes'
/// contact normals (ContactSurface::node_frames; Frames::tangents).
Frames patch_frames(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches);

/// The rows of one patch at the surface nodes of its triangles: W_a (rows n, t1, t2) with
/// (B v)_p = sum_a W_a v_a [m^2] over the nodes a of the patch (v_a the displacement of surface
/// node a); each row is int_R phi_a d dS for the row's direction d. With one frame per patch
/// (a plane, a body) d is the patch's and W_a = (int_R phi_a dS) F_p; against a curved obstacle
/// (ContactSurface::frames_vary, theory.md §2.11) d varies inside the patch: the interpolant (by
/// the face element) of the patch's frame turned onto each node's normal. Integrated by the face
/// element's quadrature (surface_integrals.hpp), exact on straight triangles.
struct PatchRowWeights {
  std::vector<Index> nodes;      ///< surface nodes of the patch
  std::vector<Mat3> W;           ///< per node [m^2]
  Mat3 integral = Mat3::Zero();  ///< sum of W: rows int_R d dS [m^2]
};

/// The row weights of every patch, in the patches' frames `frames`.
std::vector<PatchRowWeights> patch_row_weights(const mesh::TetMesh& mesh,
                                               const ContactSurface& surface,
                                               const Patches& patches, const Frames& frames);

/// B over the free dofs: n_dual = 3 n_patches rows ordered (n, t1, t2) per patch, in the patch's
/// frame (frames, one per patch), (B v)_{n,p} = int_{R_p} v.n dS and likewise for t1, t2
/// [m^2] (patch_row_weights), exact for the element's traces on straight triangles; fixed dofs have
/// no column. With `mortar` (against a body: n_patches x mesh nodes, mortar(p, a) = int_{R_p} of
/// master node a's shape function at the projection, theory.md §2.8), the master's displacement is
/// subtracted: (B v)_{n,p} = int_{R_p} (v - v_master).n_p dS.
SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches, const Frames& frames,
                        const SparseMatrix* mortar = nullptr);
/// B against a plane: assemble_b with patch_frames(mesh, surface, patches), without master.
SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches);

/// Condition (5.1) per patch: a patch with a contact node (free along its normal) must have a
/// normal row of B with entries. With 6-node triangles the corners' functions integrate to zero
/// over a straight triangle (theory.md §2.12): a patch whose edge nodes are all held while a
/// corner is free would constrain nothing. Throws NumericalError naming `where` and the patch.
void require_active_patches(const ContactSurface& surface, const Patches& patches,
                            const SparseMatrix& B, const std::string& where);

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
