#include "fricon/io/vtu.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "fricon/core/error.hpp"
#include "fricon/io/atomic_file.hpp"

namespace fricon::io {

namespace {

// VTK's cell types (vtkCellType.h).
constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;
constexpr int kVtkQuadraticTriangle = 22;
constexpr int kVtkQuadraticTetra = 24;

// The cells fricon writes, each known by its number of nodes (theory.md §2.12). VTK numbers the
// corners and the triangle's edges 01, 12, 20 as Gmsh does, and the tetrahedron's edges 01, 12,
// 20, 30, 31, 32, where Gmsh (fricon) has 01, 12, 20, 30, 32, 31: VTK's nodes 8 and 9 are
// fricon's 9 and 8.
const std::array<CellLayout, 4>& cell_layouts() {
  static const std::array<CellLayout, 4> layouts{{
      {kVtkTriangle, {0, 1, 2}},
      {kVtkTetra, {0, 1, 2, 3}},
      {kVtkQuadraticTriangle, {0, 1, 2, 3, 4, 5}},
      {kVtkQuadraticTetra, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}},
  }};
  return layouts;
}

void write_data_array(std::ostream& out, const VtuField& field, Index n_entities) {
  FRICON_CHECK(field.values.cols() == n_entities, "field " << field.name << " has "
                                                           << field.values.cols()
                                                           << " entries, expected " << n_entities);
  const bool integer = field.type == VtuType::Int32;
  fmt::print(out,
             "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
             "format=\"ascii\">\n",
             integer ? "Int32" : "Float64", field.name, field.values.rows());
  for (Index j = 0; j < field.values.cols(); ++j) {
    out << "         ";
    for (Index i = 0; i < field.values.rows(); ++i) {
      if (integer)
        fmt::print(out, " {}", static_cast<int>(std::lround(field.values(i, j))));
      else
        fmt::print(out, " {}", field.values(i, j));
    }
    out << '\n';
  }
  out << "        </DataArray>\n";
}

}  // namespace

const CellLayout& cell_layout(Index nodes_per_cell) {
  const auto& layouts = cell_layouts();
  const auto it = std::find_if(layouts.begin(), layouts.end(), [&](const CellLayout& layout) {
    return static_cast<Index>(layout.order.size()) == nodes_per_cell;
  });
  FRICON_CHECK(it != layouts.end(), "cells with " << nodes_per_cell
                                                  << " nodes (fricon writes triangles of 3 or 6 "
                                                     "and tetrahedra of 4 or 10)");
  return *it;
}

void write_vtu(const std::filesystem::path& path, const VtuGrid& grid) {
  const Index n_points = grid.points.cols();
  const Index n_cells = grid.cells.cols();
  const Index nv = grid.cells.rows();
  const CellLayout& layout = cell_layout(nv);
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
    if (!grid.field_data.empty()) {
      out << "    <FieldData>\n";
      for (const auto& f : grid.field_data) {
        FRICON_CHECK(f.values.cols() == 1,
                     "field data " << f.name << " of " << f.values.cols() << " tuples");
        fmt::print(out,
                   "      <DataArray type=\"Float64\" Name=\"{}\" NumberOfTuples=\"1\" "
                   "NumberOfComponents=\"{}\" format=\"ascii\">\n       ",
                   f.name, f.values.rows());
        for (Index i = 0; i < f.values.rows(); ++i)
          fmt::print(out, " {}", f.values(i, 0));
        out << "\n      </DataArray>\n";
      }
      out << "    </FieldData>\n";
    }
    fmt::print(out, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n_points, n_cells);
    out << "      <Points>\n";
    write_data_array(out, VtuField{"Points", grid.points}, n_points);
    out << "      </Points>\n      <Cells>\n"
           "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (Index c = 0; c < n_cells; ++c) {
      out << "         ";
      for (const int v : layout.order)
        fmt::print(out, " {}", grid.cells(v, c));
      out << '\n';
    }
    out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    for (Index c = 0; c < n_cells; ++c)
      fmt::print(out, "{}\n", nv * (c + 1));
    out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (Index c = 0; c < n_cells; ++c)
      fmt::print(out, "{}\n", layout.vtk_type);
    out << "        </DataArray>\n      </Cells>\n      <PointData>\n";
    for (const auto& f : grid.point_data)
      write_data_array(out, f, n_points);
    out << "      </PointData>\n      <CellData>\n";
    for (const auto& f : grid.cell_data)
      write_data_array(out, f, n_cells);
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries) {
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  "
           "<Collection>\n";
    for (const PvdEntry& e : entries)
      fmt::print(out, "    <DataSet timestep=\"{}\" part=\"{}\" file=\"{}\"/>\n", e.time, e.part,
                 e.file);
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace fricon::io
