#pragma once
// mesh: the tetrahedral mesh every later stage reads (first stage of the data flow).
//
// A TetMesh holds node coordinates, positively oriented tetrahedra (each in a named region), and
// tagged boundary triangles: each carries a named boundary tag ("x0", "z1", or a physical group
// name of a mesh file) and the elementary entity it was meshed on (a Gmsh surface; on the
// generator's brick, the chessboard square of a bottom face). A triangle in several tags is listed
// once per tag. It knows nothing of finite elements or contact.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::mesh {

/// A named boundary without triangles: the nodes of a Gmsh physical group of dimension 1 (a
/// curve: its line elements' nodes) or 0 (a point). Only a [[dirichlet]] boundary may be one
/// (fixing an edge or a point to remove a rigid motion); a traction and a contact surface need
/// triangles, a tag of TetMesh::tag_names.
/// The dimensions of a node set: a Gmsh physical curve's, a physical point's.
inline constexpr int kCurveDimension = 1;
inline constexpr int kPointDimension = 0;

struct NodeSet {
  std::string name;
  int dim = kPointDimension;  ///< kCurveDimension or kPointDimension
  std::vector<Index> nodes;   ///< sorted, unique node indices
};

/// "curve" or "point", the kind of a node set of dimension `dim`, for messages.
const char* node_set_kind(int dim);

/// A surface of the mesh file that is no boundary of the tetrahedra: a physical surface group
/// none of whose triangles is a face of a tetrahedron (a surface-only group, or the surface of a
/// volume that is not in any physical group, hence not simulated: in an .msh file, which Gmsh
/// saves without such volumes; read_gmsh says what a .geo file gives). A rigid obstacle
/// (contact.obstacle kind "surface") may use it; the elastic model ignores it.
struct RigidSurface {
  std::string name;
  Eigen::Matrix<Real, 3, Eigen::Dynamic> points;      ///< its own vertices [m]
  Eigen::Matrix<Index, 3, Eigen::Dynamic> triangles;  ///< indices into points, as in the file
};

struct TetMesh {
  /// Node coordinates [m], one column per node.
  Eigen::Matrix<Real, 3, Eigen::Dynamic> nodes;
  /// Tetrahedra as four node indices per column, ordered so that the signed volume is positive.
  Eigen::Matrix<Index, 4, Eigen::Dynamic> tets;
  /// Boundary triangles as three node indices per column, ordered counter-clockwise seen from
  /// outside (the right-hand normal points out of the body).
  Eigen::Matrix<Index, 3, Eigen::Dynamic> faces;
  /// The higher-order nodes beside the corners (theory.md §2.12): per tetrahedron the nodes of
  /// its element after the four corners, one column per tetrahedron; no rows in a linear mesh.
  /// In a quadratic mesh (10-node tetrahedra) the midpoints of the edges 01, 12, 20, 30, 32, 31,
  /// Gmsh's order. The corners in `tets` are what bodies, face search and partitions read; the
  /// finite element reads all nodes (tet_node).
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> tet_extra;
  /// Likewise per boundary triangle after its three corners: in a quadratic mesh (6-node
  /// triangles) the midpoints of the edges 01, 12, 20 (Gmsh's order), consistent with
  /// tet_extra (fill_face_extra).
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> face_extra;
  /// Tag of each boundary triangle: an index into tag_names.
  std::vector<int> face_tag;
  /// Names of the boundary tags.
  std::vector<std::string> tag_names;
  /// Elementary entity of each boundary triangle (a Gmsh surface tag), or -1 where there is
  /// none; `[contact] patches = "mesh"` makes each entity of the contact tag one patch.
  std::vector<int> face_entity;
  /// Region of each tetrahedron, an index into region_names; empty means one region, "body".
  std::vector<int> tet_region;
  /// Names of the regions (Gmsh physical groups of dimension 3).
  std::vector<std::string> region_names;
  /// The boundaries of lower dimension (curves, points), by name; a name that is also a tag of
  /// tag_names means the tag's triangles (the reader keeps none such).
  std::vector<NodeSet> node_sets;
  /// The rigid surfaces of the mesh file, by name: their points are their own (copies), and a
  /// node that only they use is not in `nodes`. Their names are neither tags nor node sets.
  std::vector<RigidSurface> rigid_surfaces;

  Index n_nodes() const { return nodes.cols(); }
  Index n_tets() const { return tets.cols(); }
  Index n_faces() const { return faces.cols(); }
  /// The polynomial order of the elements: 1 (4-node tetrahedra) or 2 (10-node).
  int order() const { return tet_extra.rows() == 0 ? 1 : 2; }
  /// Nodes per tetrahedron (4 or 10) and per boundary triangle (3 or 6).
  int nodes_per_tet() const { return 4 + static_cast<int>(tet_extra.rows()); }
  int nodes_per_face() const { return 3 + static_cast<int>(face_extra.rows()); }
  /// Node a (0 <= a < nodes_per_tet(): corners first) of tetrahedron t.
  Index tet_node(Index t, int a) const { return a < 4 ? tets(a, t) : tet_extra(a - 4, t); }
  /// Node a (0 <= a < nodes_per_face(): corners first) of boundary triangle f.
  Index face_node(Index f, int a) const { return a < 3 ? faces(a, f) : face_extra(a - 3, f); }

  /// Index of the tag called `name` in tag_names, or -1 if the mesh has no such tag.
  int find_tag(const std::string& name) const;
  /// Boundary triangles carrying tag `name` (empty if the tag does not exist).
  std::vector<Index> faces_with_tag(const std::string& name) const;
  /// The node set called `name`, or nullptr.
  const NodeSet* find_node_set(const std::string& name) const;
  /// The rigid surface called `name`, or nullptr.
  const RigidSurface* find_rigid_surface(const std::string& name) const;
  /// Sorted, unique node indices of the triangles carrying tag `name`, else of the node set
  /// `name` (a curve or point); empty if there is neither.
  std::vector<Index> nodes_with_tag(const std::string& name) const;
  /// Comma-separated list of the tag names, then of the node sets with their kind ("edge
  /// (curve)"), then of the rigid surfaces ("ball (rigid surface)"), for error messages.
  std::string tag_list() const;
  /// Why boundary `name` has no triangles, for the message of a key that needs a surface:
  /// "boundary 'NAME' is a curve (a Gmsh physical group of dimension 1), not a surface: ..." for
  /// a node set, "boundary 'NAME' is a rigid surface (...), not a boundary of an elastic body:
  /// ..." for a rigid surface, else "boundary 'NAME' does not exist on the mesh (tags: ...)".
  std::string no_surface(const std::string& name) const;
  /// Region index of tetrahedron t (0 when the mesh has one region).
  int region(Index t) const { return tet_region.empty() ? 0 : tet_region[static_cast<size_t>(t)]; }
  /// Number of regions (1 when tet_region is empty).
  int n_regions() const { return region_names.empty() ? 1 : static_cast<int>(region_names.size()); }
  /// Index of the region called `name`, or -1.
  int find_region(const std::string& name) const;
};

/// The number of edge nodes of a quadratic tetrahedron and triangle, and the corners of each edge
/// in Gmsh's order: tetrahedron edge e joins corners kTetEdge[e] (node 4 + e), triangle edge e
/// joins kTriangleEdge[e] (node 3 + e).
inline constexpr int kTetEdges = 6;
inline constexpr int kTriangleEdges = 3;
inline constexpr int kTetEdge[kTetEdges][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
inline constexpr int kTriangleEdge[kTriangleEdges][2] = {{0, 1}, {1, 2}, {2, 0}};

/// Gives every boundary triangle of a quadratic mesh its edge nodes, from the tetrahedra's
/// (face_extra from tet_extra, in the order of the triangle's corners); does nothing in a linear
/// mesh. Throws InputError naming `source` when two tetrahedra give one edge different midpoint
/// nodes (a non-conforming quadratic mesh) or a triangle's edge is no tetrahedron's.
void fill_face_extra(TetMesh& mesh, const std::string& source);

/// Makes a linear mesh quadratic with straight edges: a new node at the midpoint of every edge
/// of the tetrahedra (appended after the existing nodes), tet_extra and face_extra. Node sets
/// of dimension 1 (curves) gain the midpoints of the edges between their nodes. Requires
/// order() == 1.
void add_edge_midpoints(TetMesh& mesh);

/// The first node of no tetrahedron, or nothing when every node belongs to one (a reader
/// refuses such nodes: they would be free dofs that nothing holds).
std::optional<Index> first_unused_node(const TetMesh& mesh);

/// Multiplies every length of the mesh by `factor` > 0 (a change of unit, [mesh] unit): the
/// nodes and the points of the rigid surfaces. A uniform scaling keeps every check of check_mesh.
void scale_lengths(TetMesh& mesh, Real factor);

/// Signed volume [m^3] of the tetrahedron (a, b, c, d): det[b-a, c-a, d-a] / 6.
Real signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Volume [m^3] of tetrahedron t of the mesh (signed: negative if inverted).
Real tet_volume(const TetMesh& mesh, Index t);

/// Area [m^2] of boundary triangle f of the mesh.
Real face_area(const TetMesh& mesh, Index f);

/// Unit outward normal of boundary triangle f (from its orientation).
Vec3 face_normal(const TetMesh& mesh, Index f);

/// Checks that the mesh is usable: non-empty, node indices in range, finite coordinates, every
/// tetrahedron with volume > relative_tolerance * (its longest edge)^3, boundary faces with
/// positive area and valid tags, face_entity empty or one per face, tet_region empty or one valid
/// region per tetrahedron, node sets of dimension 0 or 1 with valid, sorted, unique nodes, rigid
/// surfaces with triangles, finite points and valid indices, named neither as a tag nor as a node
/// set (their triangles' shape is the obstacle's to check, contact/obstacles/meshed_surface.hpp).
/// Throws InputError naming the first offending entity and `source` (a file name or "brick
/// generator").
void check_mesh(const TetMesh& mesh, const std::string& source, Real relative_tolerance = 1e-12);

/// Applies a map of node indices (node i becomes renumber(i)) to the corners and extra nodes of
/// the tetrahedra and boundary triangles (not to the node sets). For readers that compact nodes.
template <class Renumber>
void renumber_nodes(TetMesh& mesh, Renumber renumber) {
  mesh.tets = mesh.tets.unaryExpr(renumber).eval();
  mesh.faces = mesh.faces.unaryExpr(renumber).eval();
  mesh.tet_extra = mesh.tet_extra.unaryExpr(renumber).eval();
  mesh.face_extra = mesh.face_extra.unaryExpr(renumber).eval();
}

/// Counts of how the triangular faces of the tetrahedra are shared.
struct FaceSharing {
  Index n_interior = 0;    ///< faces shared by exactly two tetrahedra
  Index n_boundary = 0;    ///< faces of exactly one tetrahedron
  Index n_overshared = 0;  ///< faces of three or more tetrahedra (non-manifold: an error)
};

/// Counts faces by the number of tetrahedra that contain them (a conformity check).
FaceSharing face_sharing(const TetMesh& mesh);

/// Extracts the faces that belong to exactly one tetrahedron, oriented outward.
Eigen::Matrix<Index, 3, Eigen::Dynamic> boundary_faces_of(const TetMesh& mesh);

/// The boundary triangles (columns of mesh.faces) that are faces of the tetrahedra `tets`, marked
/// over all triangles: each boundary triangle is a face of exactly one tetrahedron, so over a
/// partition of the tetrahedra every triangle is marked once (each copy of a triangle that
/// carries several tags).
std::vector<bool> faces_of(const TetMesh& mesh, const std::vector<Index>& tets);

/// For each of the boundary triangles `faces` (columns of mesh.faces), the tetrahedron it is a
/// face of, or -1 if it is a face of none.
std::vector<Index> tets_of_faces(const TetMesh& mesh, const std::vector<Index>& faces);

/// The mesh of the tetrahedra `tets` (ascending indices into mesh.tets) alone: their nodes (in
/// ascending order of their index in `mesh`, given back in `nodes` when not null), the boundary
/// triangles that are faces of them (faces_of) with their tags and entities, their regions, the
/// nodes of each node set among theirs (every node set, perhaps empty), every tag and region
/// name of `mesh` (so that a part knows the names of the whole), and every rigid surface of
/// `mesh` as it is (they have points of their own).
TetMesh submesh(const TetMesh& mesh, const std::vector<Index>& tets,
                std::vector<Index>* nodes = nullptr);

/// Orders every boundary triangle of `mesh` counter-clockwise seen from outside the tetrahedron
/// it bounds (tetrahedra positively oriented). Returns the index of the first triangle that is no
/// face of any tetrahedron, or -1 when every one is (the caller names it in its message).
Index orient_faces_outward(TetMesh& mesh);

}  // namespace fricon::mesh
