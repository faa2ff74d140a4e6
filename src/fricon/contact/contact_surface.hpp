#pragma once
// contact: the contact surface, the tagged boundary that may touch a rigid obstacle (theory.md
// §2.2, §2.11): its triangles and nodes, which displacement components Dirichlet conditions fix
// there, and per node the frame (n, t1, t2), n = -(the obstacle's outward normal at the node's
// nearest point), the direction in which the body would penetrate it. The surface may be curved
// or in pieces; without an obstacle it must be flat and the plane is its own, at zero gap (the
// paper's setting).
// The other pieces of the contact discretization build on it: patches.hpp (the multiplier
// partition), b_matrix.hpp (B and its stability), radii.hpp (slip bounds), and
// discretization.hpp, which assembles them into one value.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fricon/contact/obstacle.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// A rigid obstacle as a contact surface meets it (theory.md §2.11): the obstacle, and the
/// configuration at which its gap and normal are evaluated (linearized): the obstacle moved by
/// `displacement`, the body by `deformation`. The reference configuration has both zero.
struct RigidContact {
  const Obstacle* obstacle = nullptr;
  Vec3 displacement = Vec3::Zero();  ///< d_L, the obstacle's translation [m]
  /// u_L, the displacement of every mesh node (3 x mesh nodes) [m]; null: zero.
  const Eigen::Matrix<Real, 3, Eigen::Dynamic>* deformation = nullptr;
};

/// A node of the contact surface may start inside the obstacle by this share of the surface's
/// diameter (rounding, and the chords of a meshed surface) before it is refused.
inline constexpr Real kStartPenetrationTolerance = 1e-6;

/// Orthonormal frames (n, t1, t2), one per column: n the direction of penetration, t2 = t1 x n.
struct Frames {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> n, t1, t2;
  Index size() const { return n.cols(); }
  /// The frame of column k as a matrix with rows n, t1, t2: (F u) = (u.n, u.t1, u.t2).
  Mat3 rows(Index k) const;
  /// `count` copies of one frame.
  static Frames constant(const Vec3& n, const Vec3& t1, const Vec3& t2, Index count);
  /// The frame of unit normal n with t1 the projection of e1 on its plane (of e2 when n is
  /// near e1) and t2 = t1 x n: the rule of ContactSurface's (n, t1, t2).
  static std::pair<Vec3, Vec3> tangents(const Vec3& n);
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
  /// Per face: position in `nodes` of each of its nodes, corners first (mesh nodes_per_face x
  /// faces.size(): 3, or 6 on a quadratic mesh).
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> face_nodes;
  /// Unit normal of the contact: -(the obstacle's normal); without an obstacle the outward normal
  /// of the (flat) surface; against a body the mean outward normal (the frame in which the
  /// patches are laid out).
  Vec3 n = Vec3::Zero();
  Vec3 t1 = Vec3::Zero();  ///< first tangent (e1 projected on the plane, or e2 if n is near e1)
  Vec3 t2 = Vec3::Zero();  ///< second tangent, t1 x n (e2 on the brick's bottom, as in the paper)
  Real area = 0.0;         ///< [m^2]
  /// Per surface node: the prescribed displacement [m] of its fixed components (zero elsewhere;
  /// 3 x n_nodes, or empty when nothing is prescribed).
  Eigen::Matrix<Real, 3, Eigen::Dynamic> prescribed;
  /// Per surface node: its frame, in which its relative displacement is split into normal and
  /// tangential parts (the slip). Against a plane every node has (n, t1, t2); against a curved
  /// obstacle n is minus the obstacle's normal at the node's nearest point (theory.md §2.11);
  /// against a body n is the node's mean outward normal (theory.md §2.8).
  Frames node_frames;
  /// Whether the rows of B follow the nodes' normals inside a patch (a curved rigid obstacle,
  /// theory.md §2.11) instead of the patch's one frame (a plane, a body).
  bool frames_vary = false;
  /// Against a body: the master's displacement at each node's projection, as weights of the mesh
  /// nodes (n_nodes x mesh nodes, one entry per node of the master triangle the node's normal
  /// meets: its face element's shape functions there, theory.md §2.12); empty against a plane. The
  /// relative displacement of surface node k is u(nodes[k]) - sum_a master(k, a) u(a).
  Eigen::SparseMatrix<Real, Eigen::RowMajor, SparseIndex> master;
  /// Against a body: sum_a master(k, a) u_p(a) per surface node, the master's prescribed
  /// displacement at the projection [m]; against a rigid obstacle that moves, its displacement
  /// (3 x n_nodes, or empty when nothing is prescribed or moves).
  Eigen::Matrix<Real, 3, Eigen::Dynamic> master_prescribed;
  /// Per surface node: the contact pair it belongs to (0 with one pair).
  std::vector<Index> node_pair;

  Index n_nodes() const { return static_cast<Index>(nodes.size()); }
  /// Number of contact nodes (see contact_node).
  Index n_contact_nodes() const;
};

/// The contact surface of boundary `tag` against a rigid obstacle (`rigid`; null: the plane of
/// the surface itself), with each node's frame from the obstacle's normal at the node's position
/// in rigid's configuration and n the area-weighted mean of the normals at rest (so that the
/// patches, laid out in n's tangents, are the same at every linearization). Throws InputError
/// naming `where` (the position and name of the pair's boundary key) if the tag does not exist,
/// the surface is not a manifold (an edge in three or more of its triangles), it is not flat while
/// no obstacle is given, no triangle of it faces the obstacle (outward normal with a positive
/// component along its nodes' n), or no node of it can move along n.
ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where,
                                    const RigidContact* rigid = nullptr);

/// The gap [m] of every surface node to the obstacle, linearized at rigid's configuration
/// (theory.md §2.11): g = dist(x + u_L - d_L) + n . (u_L - d_L), so that the constraint on the
/// displacement u relative to the obstacle's d reads n . (u - d) <= g. In the reference
/// configuration it is the signed distance, and gaps within the start tolerance below zero count
/// as zero.
VectorXd obstacle_gap(const mesh::TetMesh& mesh, const ContactSurface& surface,
                      const RigidContact& rigid);

/// Refuses a body that starts inside the obstacle at rest: throws InputError naming `where`
/// (the position and name of the pair's obstacle key), the surface and the deepest node, when a
/// node lies deeper than kStartPenetrationTolerance times the surface's diameter.
void check_outside_obstacle(const mesh::TetMesh& mesh, const ContactSurface& surface,
                            const Obstacle& obstacle, const std::string& where);

/// The relative displacement on the surface in each node's frame, per surface node [m]: the
/// displacement itself against a plane, minus the master's at the node's projection against a
/// body.
struct SurfaceDisplacement {
  VectorXd wn, wt1, wt2;  ///< w.n, w.t1, w.t2 (fixed components count as zero)
  /// phi = ||w_t|| = sqrt(wt1^2 + wt2^2), the tangential slip.
  VectorXd slip() const;
};

/// The components of w (a vector over the free dofs, or over the contact dofs with the rest
/// unread) at the surface nodes in their frames, the prescribed displacements of the fixed
/// components included, relative to the master's against a body.
SurfaceDisplacement surface_displacement(const ContactSurface& surface, const fe::DofMap& dofs,
                                         const VectorXd& w);

/// Against a body: the master's displacement [m] at the projection of surface node k, from w
/// over the free dofs and the master's prescribed displacements.
Vec3 master_displacement(const ContactSurface& surface, const fe::DofMap& dofs, const VectorXd& w,
                         Index k);

/// The surface of the given boundary faces (mesh face indices) of tag `tag`: its nodes, its mean
/// outward normal as n (with t1, t2), each node's frame from its mean outward normal
/// (nodal_frames), and the fixed components. The step a surface against a body ends with.
/// Throws InputError naming `where` when the faces are not a manifold or no node can move.
ContactSurface surface_of_faces(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                const std::string& tag, const std::vector<Index>& faces,
                                const std::string& where);

/// Per surface node: the frame of its area-weighted mean outward normal (Frames::tangents).
Frames nodal_frames(const mesh::TetMesh& mesh, const ContactSurface& surface);

/// L2 norm over the surface of the function with nodal values v (per surface node),
/// interpolated by the face element (exact on straight triangles).
Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v);

}  // namespace fricon::contact
