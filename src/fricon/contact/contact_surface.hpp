#pragma once
// contact: the contact surface, the tagged planar boundary that rests on the rigid half-space
// (theory.md §2.2): its triangles and nodes, which displacement components Dirichlet conditions
// fix there, and the local orthonormal basis (n, t1, t2) with n the outward normal of the body.
// The other pieces of the contact discretization build on it: patches.hpp (the multiplier
// partition), b_matrix.hpp (B and its stability), radii.hpp (slip bounds), and
// discretization.hpp, which assembles them into one value.

#include <array>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// A rigid plane obstacle: the points x with (x - point) . normal = 0; `normal` is its unit
/// normal pointing out of the obstacle, towards the body.
struct Plane {
  Vec3 point = Vec3::Zero();          ///< [m]
  Vec3 normal = Vec3(0.0, 0.0, 1.0);  ///< unit
};

struct ContactSurface {
  std::string tag;
  std::vector<Index> faces;  ///< boundary triangles of the tag (mesh face indices)
  std::vector<Index> nodes;  ///< mesh nodes of those triangles, sorted; "surface nodes" below
  /// Per surface node: which of its components x, y, z Dirichlet conditions fix. A fixed
  /// component constrains that component only: B has no column for it.
  std::vector<std::array<bool, 3>> fixed;
  /// Per surface node: whether it is a contact node, i.e. its normal displacement is free (some
  /// free component has a non-zero share of n). A node whose normal motion is fixed cannot reach
  /// the obstacle; its free tangential components still carry friction.
  std::vector<bool> contact_node;
  /// Per surface node: position in `nodes` of each vertex of each face (3 x faces.size()).
  Eigen::Matrix<Index, 3, Eigen::Dynamic> face_nodes;
  Vec3 n = Vec3::Zero();   ///< outward unit normal of the body (the surface is planar)
  Vec3 t1 = Vec3::Zero();  ///< first tangent (e1 projected on the plane, or e2 if n is near e1)
  Vec3 t2 = Vec3::Zero();  ///< second tangent, t1 x n (e2 on the brick's bottom, as in the paper)
  Real area = 0.0;         ///< [m^2]

  Index n_nodes() const { return static_cast<Index>(nodes.size()); }
  /// Number of contact nodes (see contact_node).
  Index n_contact_nodes() const;
};

/// The contact surface of boundary `tag`. Throws InputError naming `where` (the position of the
/// contact.boundary key) if the tag does not exist, the surface is not planar (a rigid
/// half-space needs a flat contact face), or no node of it can move along the normal.
ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where);

/// The displacement w on the surface in the local basis, per surface node [m].
struct SurfaceDisplacement {
  VectorXd wn, wt1, wt2;  ///< w.n, w.t1, w.t2 (fixed components count as zero)
  /// phi = ||w_t|| = sqrt(wt1^2 + wt2^2), the tangential slip.
  VectorXd slip() const;
};

/// The components of w (a vector over the free dofs, or over the contact dofs with the rest
/// unread) at the surface nodes.
SurfaceDisplacement surface_displacement(const ContactSurface& surface, const fe::DofMap& dofs,
                                         const VectorXd& w);

/// Exact L2 norm over the surface of the P1 function with nodal values v (per surface node).
Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v);

}  // namespace fricon::contact
