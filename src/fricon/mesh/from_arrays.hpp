#pragma once
// mesh: a TetMesh from plain arrays (a script's mesh: numpy, meshio, Gmsh's Python API), checked
// as thoroughly as a mesh file.

#include <map>
#include <string>
#include <vector>

#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::mesh {

/// The widths of the rows of the arrays: a linear tetrahedron's 4 corners, a quadratic one's 10
/// nodes (the corners, then the midpoints of its edges 01, 12, 20, 30, 32, 31: Gmsh's order,
/// kTetEdge; theory.md §2.12); a linear triangle's 3 corners, a quadratic one's 6 (the corners,
/// then its edges 01, 12, 20: kTriangleEdge).
inline constexpr Index kLinearTetNodes = 4;
inline constexpr Index kQuadraticTetNodes = kLinearTetNodes + kTetEdges;
inline constexpr Index kLinearTriangleNodes = 3;
inline constexpr Index kQuadraticTriangleNodes = kLinearTriangleNodes + kTriangleEdges;

/// Triangles as a flat array: `width` node indices per triangle, row-major.
struct TriangleArray {
  std::vector<Index> nodes;
  Index width = kLinearTriangleNodes;  ///< kLinearTriangleNodes or kQuadraticTriangleNodes
};

/// A mesh as arrays: 0-based node indices, row-major (one row per entity).
struct MeshArrays {
  std::vector<Real> points;  ///< n x 3 node coordinates [m]
  /// m x nodes_per_tet node indices of the tetrahedra, positively oriented (the corners): of
  /// linear tetrahedra (kLinearTetNodes) or of quadratic ones (kQuadraticTetNodes, Gmsh's order).
  std::vector<Index> tets;
  Index nodes_per_tet = kLinearTetNodes;
  /// Boundary tags: name -> triangles that are faces of the tetrahedra (any orientation; they
  /// are oriented outward). On linear tetrahedra 3 nodes each; on quadratic ones 3 (the corners:
  /// the edge nodes are the tetrahedra's) or 6 (the corners, then the edge nodes, which must be
  /// the tetrahedra's).
  std::map<std::string, TriangleArray> boundary;
  /// Regions: name -> indices of the tetrahedra it holds; empty: one region "body". When given,
  /// every tetrahedron is in exactly one region.
  std::map<std::string, std::vector<Index>> regions;
};

/// The mesh the arrays describe, linear or quadratic as the tetrahedra are; `source` names them in
/// messages (e.g. "fricon.Mesh"). Throws InputError for: a width of tetrahedra or triangles that
/// is none of the above (6-node triangles on linear tetrahedra too), array sizes that are not
/// multiples of the width, indices out of range, non-finite coordinates, inverted or degenerate
/// tetrahedra (by their corners), unused nodes, triangles that are no face of a tetrahedron, a
/// face shared by three tetrahedra, quadratic tetrahedra that do not conform (two edge nodes on
/// one edge, one node on two edges or on an edge and a corner), a 6-node triangle whose edge node
/// is not the tetrahedra's, tetrahedra in no or in two regions, a boundary tag without
/// triangles, a region without tetrahedra.
TetMesh mesh_from_arrays(const MeshArrays& arrays, const std::string& source);

}  // namespace fricon::mesh
