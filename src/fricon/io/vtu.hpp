#pragma once
// io: VTK XML unstructured grids (.vtu) that ParaView and meshio open, for the body (tetrahedra)
// and for surfaces (triangles). Values are written in ASCII with round-trip precision.

#include <filesystem>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::io {

/// How the values of a field are written: as doubles, or as integers (indices, labels).
enum class VtuType { Float64, Int32 };

/// A named field with `components` values per point or cell (column-major: one column per entity).
struct VtuField {
  std::string name;
  MatrixXd values;  ///< components x n_entities (integral values when type is Int32)
  VtuType type = VtuType::Float64;
};

struct VtuGrid {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> points;
  /// Cell connectivity, one column per cell: 4 rows for tetrahedra, 3 for triangles.
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> cells;
  std::vector<VtuField> point_data;
  std::vector<VtuField> cell_data;
  /// Values of the whole dataset (VTK FieldData), each one tuple of `values.rows()` components
  /// (e.g. an obstacle's centre): ParaView's Information panel and meshio's field_data show them.
  std::vector<VtuField> field_data;
};

/// Writes `grid` to `path` atomically. Throws fricon::Error on I/O failure or inconsistent sizes.
void write_vtu(const std::filesystem::path& path, const VtuGrid& grid);

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
