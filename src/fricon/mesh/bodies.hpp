#pragma once
// mesh: the connected bodies of a mesh (theory.md §2.1).
//
// Two tetrahedra belong to the same body when a chain of tetrahedra, each sharing at least one
// node with the next, joins them: the bodies are the connected components of the graph whose
// vertices are the nodes and whose edges are the edges of the tetrahedra. A Gmsh file with two
// volumes that share no node (two separate parts) is a mesh of two bodies; the brick is one.
//
// The bodies partition the nodes and the tetrahedra, so the stiffness matrix K of the whole mesh
// is block diagonal over them (after a permutation) and each body's rigid motions are in its
// kernel unless the body's own Dirichlet conditions remove them (fe/rigid_motions.hpp). This is
// the data that work on several bodies builds on: contact between two elastic bodies pairs the
// surfaces of two bodies, and a body that no Dirichlet condition holds (a floating body, which
// fricon refuses today) would be handled through its own block of K and its rigid motions, as in
// TFETI.
//
// Bodies joined by a single node or a single edge count as one body here, although such a joint
// is a hinge that leaves a rotation free: the per-body check does not see it, and the Cholesky
// factorization reports the singular K instead.

#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::mesh {

/// The connected bodies of a mesh, numbered 0, 1, ... in the order of their first tetrahedron
/// (body 0 holds tetrahedron 0).
struct Bodies {
  /// Body of each node (n_nodes entries), or -1 for a node of no tetrahedron (the mesh readers
  /// refuse such nodes, so a checked mesh has none).
  std::vector<Index> node_body;
  /// Body of each tetrahedron (n_tets entries).
  std::vector<Index> tet_body;
  /// Per body, its nodes in ascending order.
  std::vector<std::vector<Index>> nodes;
  /// Per body, its tetrahedra in ascending order.
  std::vector<std::vector<Index>> tets;
  /// Per body, the regions of its tetrahedra (indices into TetMesh::region_names; 0 for a mesh of
  /// one region), ascending. A region may span several bodies (one physical volume of Gmsh made
  /// of two separate parts).
  std::vector<std::vector<int>> regions;

  Index n_bodies() const { return static_cast<Index>(tets.size()); }
};

/// The connected bodies of `mesh` (node indices in range, as check_mesh ensures). Linear in the
/// mesh size (union-find over the nodes of each tetrahedron). A mesh without tetrahedra has no
/// body.
Bodies find_bodies(const TetMesh& mesh);

/// The axis-aligned box [lo, hi] [m] of some nodes of a mesh.
struct BoundingBox {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
};

/// The bounding box of the nodes `nodes` (non-empty, indices into mesh.nodes).
BoundingBox bounding_box(const TetMesh& mesh, const std::vector<Index>& nodes);

/// Body b of `bodies` (0 <= b < n_bodies) in words for messages, for the user to find it:
/// its regions, node count and bounding box, e.g.
/// `body 1 (region "loose", 27 nodes in [2, 3] x [0, 1] x [0, 1] m)`.
std::string describe_body(const TetMesh& mesh, const Bodies& bodies, Index b);

/// One mesh of the meshes `parts` side by side, sharing no node (so each connected body of a part
/// is a body of the result): their nodes, tetrahedra and boundary triangles in the order of the
/// parts, indices shifted. Each boundary tag and region of parts[i] is renamed
/// `prefixes[i] + name` (an unnamed region is "body"); equal names after renaming are one tag or
/// region. Each rigid surface of parts[i] is copied, renamed `prefixes[i] + name`. Face entities
/// are shifted so that those of different parts differ (-1 stays -1). Expects as many prefixes as
/// parts. Builds meshes of several bodies from the brick generator, e.g. disjoint_union({a, b},
/// {"", "b_"}) with b's tags "b_x0", ... and regions "body", "b_body".
TetMesh disjoint_union(const std::vector<TetMesh>& parts, const std::vector<std::string>& prefixes);

}  // namespace fricon::mesh
