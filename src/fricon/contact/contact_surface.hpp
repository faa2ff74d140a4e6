#pragma once
// contact: the discretization of contact (method.md §2.4-2.6), the only module that knows both the
// mesh and the multipliers.
//   ContactSurface  the tagged planar boundary that rests on the rigid half-space, its nodes and a
//                   local orthonormal basis (n, t1, t2) with n the outward normal of the body
//   Patches         the coarse partition T_H of the surface: a list of patches, each a set of
//                   surface triangles, carrying one multiplier triple (lambda_n, lambda_t1,
//                   lambda_t2)
//   B               n_dual x n_primal: (B v)_{n,p} = int_{R_p} v.n, (B v)_{t1,p} = int_{R_p} v.t1,
//   ... radii           rho_p = (1/|R_p|) int_{R_p} F(phi_h) g dS, integrated exactly for
//                   piecewise-linear F (split at its kinks)

#include <string>
#include <vector>

#include "fricon/contact/friction_law.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

struct ContactSurface {
  std::string tag;
  std::vector<Index> faces;  ///< boundary triangles of the tag (mesh face indices)
  std::vector<Index> nodes;  ///< mesh nodes of those triangles, sorted; "surface nodes" below
  std::vector<bool> fixed;   ///< per surface node: some component is a Dirichlet dof
  /// Per surface node: position in `nodes` of each vertex of each face (3 x faces.size()).
  Eigen::Matrix<Index, 3, Eigen::Dynamic> face_nodes;
  Vec3 n = Vec3::Zero();   ///< outward unit normal of the body (the surface is planar)
  Vec3 t1 = Vec3::Zero();  ///< first tangent (e1 projected on the plane, or e2 if n is along e1)
  Vec3 t2 = Vec3::Zero();  ///< second tangent, t1 x n (e2 on the brick's bottom, as in the paper)
  Real area = 0.0;         ///< [m^2]

  Index n_nodes() const { return static_cast<Index>(nodes.size()); }
  /// Number of contact nodes: surface nodes that are not Dirichlet nodes.
  Index n_contact_nodes() const;
};

/// The contact surface of boundary `tag`. Throws InputError if the tag does not exist, or the
/// surface is not planar (a rigid half-space needs a flat contact face), naming `where`.
ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where);

/// The coarse partition T_H: patch p is the list of surface-face positions (into surface.faces).
struct Patches {
  std::vector<std::vector<Index>> faces;
  VectorXd area;                                    ///< |R_p| [m^2]
  Eigen::Matrix<Real, 3, Eigen::Dynamic> centroid;  ///< [m]
  Index size() const { return static_cast<Index>(faces.size()); }
};

/// The paper's chessboard: 2 x 2 squares of the structured grid of the surface (each the union of
/// the eight triangles around a node of odd grid indices). The surface must be a rectangle of
/// grid squares with an even count in each tangential direction; throws InputError otherwise.
Patches chessboard_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const std::string& where);

/// B over the free dofs (n_dual = 3 n_patches rows, ordered (n, t1, t2) per patch), with exact
/// integrals of the P1 traces against the patch indicators; columns of fixed dofs are dropped.
SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches);

/// Stability of the multiplier space (condition (5.1)): B^T has full column rank on the contact
/// dofs. Returns sigma_min / sigma_max of B; throws NumericalError naming `where` and the value
/// when it is below `min_ratio` (default 1e-8). Up to `dense_limit` rows the eigenvalues of
/// B B^T are computed exactly (dense, O(n_dual^3)); beyond, B B^T (sparse: neighbouring patches
/// only) is factored by a sparse Cholesky and its extreme eigenvalues estimated by power and
/// inverse iteration (to about a per cent), so that the check stays cheap for thousands of
/// patches.
Real check_stability(const SparseMatrix& B, const std::string& where, Real min_ratio = 1e-8,
                     Index dense_limit = 500);

/// Radii rho_p = (1/|R_p|) int_{R_p} F(phi_h) g_h dS [Pa] for nodal slips phi and nodal slip
/// bounds g (both per surface node). Exact when F is piecewise linear: every triangle is cut at
/// the level lines phi_h = kink and each piece integrated with a rule of degree >= 2.
VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g);

/// Exact L2 norm over the surface of the P1 function with nodal values v (per surface node).
Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v);

}  // namespace fricon::contact
