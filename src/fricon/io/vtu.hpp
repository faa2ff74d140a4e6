#pragma once
// io: VTK XML unstructured grids (.vtu) that ParaView and meshio open, for the body (tetrahedra)
// and for surfaces (triangles), linear or quadratic (theory.md §2.12: 10-node tetrahedra and
// 6-node triangles, which ParaView draws curved). The arrays are written in binary (VTK's
// appended raw data) or in ASCII with round-trip precision (io/vtu_encoding.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/io/vtu_encoding.hpp"

namespace fricon::io {

/// How the values of a field are written: as doubles, or as integers (indices, labels).
enum class VtuType { Float64, Int32 };

/// A named field with `components` values per point or cell (column-major: one column per entity).
struct VtuField {
  std::string name;
  MatrixXd values;  ///< components x n_entities (integral values when type is Int32)
  VtuType type = VtuType::Float64;
};

/// How a cell of fricon's is written as a VTK cell: its VTK cell type, and for each VTK node in
/// turn the position of that node in fricon's cell. fricon's cells list the corners, then the
/// edge nodes in Gmsh's order (mesh::kTetEdge, mesh::kTriangleEdge: TetMesh::tet_node and
/// face_node); VTK's 10-node tetrahedron has the edges 13 and 23 as its nodes 8 and 9, where Gmsh
/// has the edges 32 and 31, so its order swaps fricon's nodes 8 and 9 (theory.md §2.12). Every
/// writer of cells takes the layout from here (write_vtu does).
struct CellLayout {
  int vtk_type = 0;        ///< VTK_TETRA, VTK_QUADRATIC_TETRA, VTK_TRIANGLE, ...
  std::vector<int> order;  ///< VTK node k is node order[k] of fricon's cell
};

/// The layout of a cell of `nodes_per_cell` nodes: 4 a linear tetrahedron (VTK_TETRA), 10 a
/// quadratic one (VTK_QUADRATIC_TETRA), 3 a linear triangle (VTK_TRIANGLE), 6 a quadratic one
/// (VTK_QUADRATIC_TRIANGLE). Throws fricon::Error for another number.
const CellLayout& cell_layout(Index nodes_per_cell);

struct VtuGrid {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> points;
  /// Cell connectivity, one column per cell, in fricon's node order (corners, then edge nodes:
  /// TetMesh::tet_node, face_node): 4 or 10 rows for tetrahedra, 3 or 6 for triangles
  /// (cell_layout gives their VTK type and order).
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> cells;
  std::vector<VtuField> point_data;
  std::vector<VtuField> cell_data;
  /// Values of the whole dataset (VTK FieldData), each one tuple of `values.rows()` components
  /// (e.g. an obstacle's centre): ParaView's Information panel and meshio's field_data show them.
  std::vector<VtuField> field_data;
};

/// Writes `grid` to `path` atomically, its arrays in `encoding` (the dataset's FieldData always
/// as text). Throws fricon::Error on I/O failure or inconsistent sizes.
void write_vtu(const std::filesystem::path& path, const VtuGrid& grid, VtuEncoding encoding);

/// One dataset of a ParaView collection: its time, its part (the body 0, the contact surface 1)
/// and its file (relative to the .pvd's folder).
struct PvdEntry {
  Real time = 0.0;
  int part = 0;
  std::string file;
};

/// Writes a ParaView collection (.pvd) of `entries`, atomically.
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

}  // namespace fricon::io
