#pragma once
// mesh: the structured brick of the paper (theory.md §7.2): a box cut into nx x ny x nz cubes,
// each split into five tetrahedra whose orientation alternates with the parity of the cube so that
// neighbouring cubes share their face diagonals (the mesh is conforming).

#include <array>

#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::mesh {

struct BrickSpec {
  Vec3 size{3.0, 1.0, 1.0};  ///< edge lengths [m] of the box [0,size_x]x[0,size_y]x[0,size_z]
  std::array<Index, 3> cells{12, 4, 4};  ///< cubes (cells) per direction, each >= 1
};

/// Node index of grid point (i, j, k), 0 <= i <= nx, 0 <= j <= ny, 0 <= k <= nz (i fastest).
inline Index brick_node(const BrickSpec& spec, Index i, Index j, Index k) {
  return i + (spec.cells[0] + 1) * (j + (spec.cells[1] + 1) * k);
}

/// The brick mesh: (nx+1)(ny+1)(nz+1) nodes, 5 nx ny nz positively oriented tetrahedra, and the
/// boundary triangles tagged "x0", "x1", "y0", "y1", "z0", "z1" by the side of the box they lie
/// on (x0 is the face x = 0, x1 the face x = size_x, ...). Each side is cut into blocks of 2 x 2
/// grid cells (the last block 1 cell wide where a cell count is odd), each block one face entity,
/// numbered 1, 2, ... over the whole mesh (side by side: x0, x1, y0, y1, z0, z1; on a side normal
/// to axis d, the blocks along axis d+1 fastest, then d+2, modulo 3). In each cube, the central
/// tetrahedron joins the four vertices with even (i+j+k); each vertex with odd (i+j+k) forms a
/// corner tetrahedron with its three neighbours in the cube. Throws InputError for non-positive
/// sizes.
TetMesh make_brick(const BrickSpec& spec);

}  // namespace fricon::mesh
