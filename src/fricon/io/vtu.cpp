#include "fricon/io/vtu.hpp"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "fricon/core/error.hpp"
#include "fricon/io/atomic_file.hpp"

namespace fricon::io {

namespace {

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

void write_vtu(const std::filesystem::path& path, const VtuGrid& grid) {
  const Index n_points = grid.points.cols();
  const Index n_cells = grid.cells.cols();
  const Index nv = grid.cells.rows();
  FRICON_CHECK(nv == 3 || nv == 4, "cells with " << nv << " vertices");
  const int vtk_type = nv == 4 ? 10 : 5;  // VTK_TETRA, VTK_TRIANGLE
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
      for (Index v = 0; v < nv; ++v)
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
      fmt::print(out, "{}\n", vtk_type);
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
