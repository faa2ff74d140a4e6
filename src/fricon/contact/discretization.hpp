#pragma once
// contact: the whole contact discretization of a problem as one value (theory.md §2.2-2.6),
// built once by discretize_contact and read by every later stage: the dual operator (B and the
// contact dofs), the outer loop (surface, patches, slip bounds for the radii), the output, the
// `check` command, the benchmarks and the dual dump.

#include <optional>
#include <string>
#include <vector>

#include "fricon/contact/b_matrix.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/master_surface.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// What discretize_contact needs to know of the problem, with the positions of the keys (for
/// messages: "file:line:col" or "--set KEY=VALUE").
struct ContactSpec {
  std::string boundary;  ///< tag of the contact surface
  PatchKind patches = PatchKind::Chessboard;
  /// Target diameter [m] of the patches of PatchKind::Agglomerate; 0: chosen from the mesh.
  Real patch_size = 0.0;
  Real slip_bound = 0.0;  ///< g [Pa], the same at every surface node
  /// The rigid obstacle (theory.md §2.11). Null: the plane of a flat contact surface, at zero
  /// gap (or a master, below).
  ObstaclePtr obstacle;
  /// The obstacle's displacement [m]: its translation from where it rests.
  Vec3 obstacle_displacement = Vec3::Zero();
  /// Where gap and normal of a rigid obstacle are evaluated (theory.md §2.11): the obstacle moved
  /// by `linearized_displacement` [m] and the body by `deformation` (3 x mesh nodes [m]; empty:
  /// the reference configuration).
  Vec3 linearized_displacement = Vec3::Zero();
  Eigen::Matrix<Real, 3, Eigen::Dynamic> deformation;
  /// Against a body (theory.md §2.8): the master surface; exclusive with `obstacle`.
  std::optional<MasterSpec> master;
  /// The pair's key path ("contact", "contact[1]"), for reports.
  std::string key = "contact";
  /// The prescribed displacement [m] of every mesh node (3 x n_nodes, zero where nothing is
  /// prescribed), or empty when nothing is.
  Eigen::Matrix<Real, 3, Eigen::Dynamic> prescribed;
  /// Where each key was given and its name as the file writes it, the start of messages
  /// ("file:19:1: contact[0].boundary"; in code-built problems just the key).
  std::string where_boundary = "contact.boundary";
  std::string where_patches = "contact.patches";
  std::string where_patch_size = "contact.patch_size";
  std::string where_obstacle = "contact.obstacle";
};

/// One contact pair of a discretization: what the reports say of it.
struct PairInfo {
  std::string key;       ///< "contact" or "contact[i]"
  std::string boundary;  ///< the contact surface's tag (the slave)
  std::string master;    ///< the master surface's tag; empty against a rigid obstacle
  /// The rigid obstacle (null against a body, and for a flat surface's own plane when no
  /// obstacle was given) and its displacement at the current load [m].
  ObstaclePtr obstacle;
  Vec3 obstacle_displacement = Vec3::Zero();
  Index n_tag_faces = 0;  ///< triangles of the slave tag (against a body: some may be out of reach)
  Real search_distance = 0.0;      ///< against a body: d [m]
  Real master_coverage = 1.0;      ///< against a body: share of the surface opposite the master
  Real master_element_size = 0.0;  ///< against a body: the master's mean edge [m]
  StabilityReport stability;       ///< condition (5.1) of the pair's own B
  /// The pair surface's own frame (ContactSurface::n, t1, t2): the plane's, or against a body
  /// that of the surface's mean outward normal (the view of its maps).
  Vec3 n = Vec3::Zero(), t1 = Vec3::Zero(), t2 = Vec3::Zero();
};

struct ContactDiscretization {
  ContactSurface surface;
  Patches patches;
  SparseMatrix B;       ///< n_dual x n_free [m^2], rows (n, t1, t2) per patch (b_matrix.hpp)
  VectorXd slip_bound;  ///< g per surface node [Pa]
  /// Gap per surface node [m]: its distance to the obstacle, linearized (contact::obstacle_gap;
  /// 0 without an obstacle: the body rests on its own plane).
  VectorXd gap;
  /// c per multiplier row [m^3], the constant part of the constraints (theory.md §2.4): normal
  /// row int_R (gap - u_p.n) dS, tangential rows -int_R u_p.t dS, with u_p the prescribed
  /// displacement of fixed components, plus int_R u_o . d dS of a rigid obstacle's displacement
  /// u_o in every row (theory.md §2.11); zero for the paper's problem. The dual's
  /// h = B K^-1 f - c.
  VectorXd offset;
  /// The parts of `offset`: offset = gap_offset - prescribed_offset vec(u_p) for the prescribed
  /// displacement u_p of every mesh node (3 x n_nodes, column-major), so that a loading path
  /// (theory.md §2.9) moves it with the step's values (constraint_offset). gap_offset [m^3] per
  /// multiplier row; prescribed_offset [m^2] is n_dual x 3 n_nodes. A part of a discretization
  /// (restrict_to_patches) leaves both empty.
  VectorXd gap_offset;
  SparseMatrix prescribed_offset;
  /// The free dofs of the surface nodes, node by node: the only columns B touches.
  std::vector<Index> dofs;
  /// Per patch: the frame (n, t1, t2) of its multipliers (b_matrix.hpp, patch_frames).
  Frames patch_frames;
  /// Per patch: int_R d dS for its directions d (rows n, t1, t2) [m^2] (PatchRowWeights::integral):
  /// the force on the body is -frame_integrals[p]^T lambda_p, and a translation d of a rigid
  /// obstacle adds frame_integrals[p] d to the patch's offset. Area times the frame with one
  /// frame per patch.
  std::vector<Mat3> frame_integrals;
  /// Per patch: its pair (an index into `pairs`); the surface's node_pair does the same for nodes.
  std::vector<Index> patch_pair;
  std::vector<PairInfo> pairs;  ///< the contact pairs, in the problem's order
  /// Condition (5.1), checked for each pair; here the smallest ratio of all.
  StabilityReport stability;
  /// How the partition was made stable: empty when the partition asked for passed condition
  /// (5.1) as built; for PatchKind::Agglomerate, the coarsenings that made it pass (the patch
  /// sizes tried and their ratios), for the log and the report.
  std::string partition_note;
  /// How the radii are integrated for a piecewise-linear law (radii.hpp); the report names the
  /// method for the law in use (contact::radius_integration).
  std::string radius_integration;

  Index n_patches() const { return patches.size(); }
  Index n_dual() const { return 3 * patches.size(); }
};

/// Surface, patches, B, slip bounds and gap of the contact boundary, with the stability of B
/// checked. An unstable PatchKind::Agglomerate partition is rebuilt coarser (patch size twice the
/// mean patch diameter, a few times; see ContactDiscretization::partition_note). Throws
/// InputError (a tag that does not exist, a surface that is not planar or admits no such
/// partition) and NumericalError (an unstable partition: a chessboard or mesh partition, or an
/// agglomerate one still unstable after the coarsenings), naming the key's position.
ContactDiscretization discretize_contact(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                         const ContactSpec& spec);

/// ContactDiscretization::offset for the prescribed displacement `prescribed` of every mesh node
/// (3 x n_nodes; empty: none) and the pairs' obstacle displacements [m^3].
VectorXd constraint_offset(const ContactDiscretization& disc,
                           const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed);

/// Moves the discretization to another prescribed displacement of the mesh nodes (3 x n_nodes;
/// empty: none) and, when given, other displacements of the pairs' rigid obstacles (one per pair,
/// zero for a pair against a body) [m], a step of a loading path: the surface's prescribed values
/// (slave and master or obstacle) and the offset. B, the gap and everything else stay.
void set_prescribed(ContactDiscretization& disc,
                    const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed,
                    const std::vector<Vec3>* obstacle_displacements = nullptr);

/// Per multiplier row: int_R (u - u_o) . d dS [m^3] of the whole displacement u (w over the free
/// dofs, the prescribed values `prescribed` elsewhere, 3 x n_nodes or empty) relative to the
/// obstacle's u_o (a rigid obstacle's displacement; a master's prescribed part through the mortar
/// integrals), in the rows' directions d.
VectorXd patch_integrals(const ContactDiscretization& disc, const VectorXd& w,
                         const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed);
/// The same with the obstacles at `obstacles` (one displacement per pair [m]) instead of where
/// disc has them.
VectorXd patch_integrals(const ContactDiscretization& disc, const VectorXd& w,
                         const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed,
                         const std::vector<Vec3>& obstacles);

/// How far the linearized gap of each rigid pair is from the true one at the displacement u of
/// every mesh node (3 x mesh nodes [m]; theory.md §2.11): per surface node of a rigid obstacle
/// whose `in_contact` is true, |dist(x + u - d) - (g - n . (u - d))| [m], with d the obstacle's
/// displacement and g the node's linearized gap; the largest such change, and the largest
/// |n . (u - d)| of those nodes (the scale it is judged against). Zero for planes (exact) and
/// without such nodes.
struct LinearizationError {
  Real change = 0.0;  ///< [m]
  Real scale = 0.0;   ///< [m]
};
LinearizationError linearization_error(const mesh::TetMesh& mesh, const ContactDiscretization& disc,
                                       const Eigen::Matrix<Real, 3, Eigen::Dynamic>& u,
                                       const std::vector<bool>& in_contact);

/// Several pairs as one discretization: surfaces, patches and rows of B in the order of `pairs`
/// (each discretize_contact of one pair), the pair of every node and patch recorded. One pair is
/// returned as it is.
ContactDiscretization merge_pairs(std::vector<ContactDiscretization> pairs);

}  // namespace fricon::contact
