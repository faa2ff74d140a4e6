#pragma once
// mesh: a TetMesh from plain arrays (a script's mesh: numpy, meshio, Gmsh's Python API), checked
// as thoroughly as a mesh file.

#include <map>
#include <string>
#include <vector>

#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::mesh {

/// A mesh as arrays: 0-based node indices, row-major (one row per entity).
struct MeshArrays {
  std::vector<Real> points;  ///< n x 3 node coordinates [m]
  std::vector<Index> tets;   ///< m x 4 node indices of linear tetrahedra, positively oriented
  /// Boundary tags: name -> k x 3 node indices of triangles that are faces of the tetrahedra
  /// (any orientation; they are oriented outward).
  std::map<std::string, std::vector<Index>> boundary;
  /// Regions: name -> indices of the tetrahedra it holds; empty: one region "body". When given,
  /// every tetrahedron is in exactly one region.
  std::map<std::string, std::vector<Index>> regions;
};

/// The mesh the arrays describe; `source` names them in messages (e.g. "fricon.Mesh"). Throws
/// InputError for: array sizes that are not multiples of 3 or 4, indices out of range, non-finite
/// coordinates, inverted or degenerate tetrahedra, unused nodes, triangles that are no face of a
/// tetrahedron, a face shared by three tetrahedra, tetrahedra in no or in two regions, a boundary
/// tag without triangles, a region without tetrahedra.
TetMesh mesh_from_arrays(const MeshArrays& arrays, const std::string& source);

}  // namespace fricon::mesh
