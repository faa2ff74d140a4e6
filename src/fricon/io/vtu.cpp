#include "fricon/io/vtu.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

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

// The scalar types of the arrays fricon writes, with their VTK names and sizes (kScalars).
enum class Scalar { Float64, Int64, Int32, UInt8 };

struct ScalarType {
  const char* vtk_name;
  std::size_t bytes;
};

constexpr std::array<ScalarType, 4> kScalars{
    {{"Float64", 8}, {"Int64", 8}, {"Int32", 4}, {"UInt8", 1}}};

const ScalarType& scalar_type(Scalar s) {
  return kScalars[static_cast<std::size_t>(s)];
}

// One DataArray: `count` values in file order, value(k) each (integral for the integer types),
// `per_line` of them on a line of the ASCII encoding; `components` is written as
// NumberOfComponents when positive (the cells' arrays have none: connectivity is flat).
struct DataArray {
  Scalar scalar = Scalar::Float64;
  std::string name;
  Index components = 0;
  Index count = 0;
  Index per_line = 1;
  std::function<double(Index)> value;
};

// A field's array. The values are read where they are, when they are written: `values` must
// outlive the ArrayWriter (binary: until finish()).
DataArray values_array(const std::string& name, VtuType type, const Real* values, Index components,
                       Index n_entities) {
  return {type == VtuType::Int32 ? Scalar::Int32 : Scalar::Float64,
          name,
          components,
          components * n_entities,
          components,
          [values](Index k) { return values[k]; }};
}

DataArray field_array(const VtuField& field, Index n_entities) {
  FRICON_CHECK(field.values.cols() == n_entities, "field " << field.name << " has "
                                                           << field.values.cols()
                                                           << " entries, expected " << n_entities);
  return values_array(field.name, field.type, field.values.data(), field.values.rows(), n_entities);
}

// Writes the arrays of a file in one encoding: their XML elements in place, and (binary) their
// bytes after the XML, in the order they were declared.
class ArrayWriter {
 public:
  ArrayWriter(std::ostream& out, VtuEncoding encoding) : out_(out), encoding_(encoding) {}

  void write(DataArray array) {
    fmt::print(out_, "        <DataArray type=\"{}\" Name=\"{}\"",
               scalar_type(array.scalar).vtk_name, array.name);
    if (array.components > 0) fmt::print(out_, " NumberOfComponents=\"{}\"", array.components);
    if (encoding_ == VtuEncoding::Binary) {
      fmt::print(out_, " format=\"appended\" offset=\"{}\"/>\n", offset_);
      offset_ += sizeof(std::uint64_t) +
                 scalar_type(array.scalar).bytes * static_cast<std::size_t>(array.count);
      appended_.push_back(std::move(array));
      return;
    }
    out_ << " format=\"ascii\">\n";
    write_text(array);
    out_ << "        </DataArray>\n";
  }

  // After the XML element that holds the arrays: the appended bytes (binary), each array's
  // 64-bit byte count (the file's header_type) before its values.
  void finish() {
    if (appended_.empty()) return;
    out_ << "  <AppendedData encoding=\"raw\">\n   _";
    for (const DataArray& a : appended_)
      write_bytes(a);
    out_ << "\n  </AppendedData>\n";
  }

 private:
  void write_text(const DataArray& a) {
    const bool integer = a.scalar != Scalar::Float64;
    for (Index k = 0; k < a.count; ++k) {
      if (k % a.per_line == 0) out_ << (k == 0 ? "         " : "\n         ");
      if (integer)
        fmt::print(out_, " {}", std::llround(a.value(k)));
      else
        fmt::print(out_, " {}", a.value(k));
    }
    out_ << '\n';
  }

  template <typename T>
  void write_values(const DataArray& a) {
    constexpr Index kChunk = 8192;  // values per write
    std::vector<T> chunk;
    chunk.reserve(kChunk);
    for (Index k = 0; k < a.count; ++k) {
      const double v = a.value(k);
      chunk.push_back(std::is_floating_point_v<T> ? static_cast<T>(v)
                                                  : static_cast<T>(std::llround(v)));
      if (static_cast<Index>(chunk.size()) == kChunk || k + 1 == a.count) {
        out_.write(reinterpret_cast<const char*>(chunk.data()),
                   static_cast<std::streamsize>(chunk.size() * sizeof(T)));
        chunk.clear();
      }
    }
  }

  void write_bytes(const DataArray& a) {
    const std::uint64_t n = scalar_type(a.scalar).bytes * static_cast<std::uint64_t>(a.count);
    out_.write(reinterpret_cast<const char*>(&n), sizeof n);
    switch (a.scalar) {
      case Scalar::Float64:
        return write_values<double>(a);
      case Scalar::Int64:
        return write_values<std::int64_t>(a);
      case Scalar::Int32:
        return write_values<std::int32_t>(a);
      case Scalar::UInt8:
        return write_values<std::uint8_t>(a);
    }
  }

  std::ostream& out_;
  VtuEncoding encoding_;
  std::size_t offset_ = 0;
  std::vector<DataArray> appended_;
};

// Values of the whole dataset, always as text (a few numbers).
void write_field_data(std::ostream& out, const std::vector<VtuField>& fields) {
  if (fields.empty()) return;
  out << "    <FieldData>\n";
  for (const auto& f : fields) {
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

void write_vtu(const std::filesystem::path& path, const VtuGrid& grid, VtuEncoding encoding) {
  static_assert(std::endian::native == std::endian::little,
                "the binary encoding writes the machine's bytes as little endian");
  const Index n_points = grid.points.cols();
  const Index n_cells = grid.cells.cols();
  const Index nv = grid.cells.rows();
  const CellLayout& layout = cell_layout(nv);
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
    write_field_data(out, grid.field_data);
    ArrayWriter arrays(out, encoding);
    fmt::print(out, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n_points, n_cells);
    out << "      <Points>\n";
    arrays.write(values_array("Points", VtuType::Float64, grid.points.data(), 3, n_points));
    out << "      </Points>\n      <Cells>\n";
    const auto* cells = &grid.cells;
    const auto* order = &layout.order;
    arrays.write({Scalar::Int64, "connectivity", 0, nv * n_cells, nv, [=](Index k) {
                    return static_cast<double>(
                        (*cells)((*order)[static_cast<size_t>(k % nv)], k / nv));
                  }});
    arrays.write({Scalar::Int64, "offsets", 0, n_cells, 1,
                  [=](Index c) { return static_cast<double>(nv * (c + 1)); }});
    const auto type = static_cast<double>(layout.vtk_type);
    arrays.write({Scalar::UInt8, "types", 0, n_cells, 1, [=](Index) { return type; }});
    out << "      </Cells>\n      <PointData>\n";
    for (const auto& f : grid.point_data)
      arrays.write(field_array(f, n_points));
    out << "      </PointData>\n      <CellData>\n";
    for (const auto& f : grid.cell_data)
      arrays.write(field_array(f, n_cells));
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n";
    arrays.finish();
    out << "</VTKFile>\n";
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
