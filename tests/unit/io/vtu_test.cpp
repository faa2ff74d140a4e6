// io::cell_layout and io::write_vtu: linear and quadratic cells (docs/theory.md §2.12) are written
// with VTK's cell types and node orders. fricon's (Gmsh's) quadratic tetrahedron has the edges 32
// and 31 as its nodes 8 and 9, VTK's the edges 13 and 23: they swap.
#include "fricon/io/vtu.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"

namespace fricon::io {
namespace {

// VTK's cell types (vtkCellType.h) by the number of nodes of fricon's cells.
const std::vector<std::pair<Index, int>> kVtkTypes = {{3, 5}, {4, 10}, {6, 22}, {10, 24}};

TEST(CellLayout, EachCellHasItsVtkTypeAndAPermutationOfItsNodes) {
  for (const auto& [nodes, type] : kVtkTypes) {
    const CellLayout& layout = cell_layout(nodes);
    EXPECT_EQ(layout.vtk_type, type) << nodes << " nodes";
    std::vector<int> sorted = layout.order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> all(static_cast<std::size_t>(nodes));
    std::iota(all.begin(), all.end(), 0);
    EXPECT_EQ(sorted, all) << nodes << " nodes";
  }
  // Only the quadratic tetrahedron's order is not the identity: VTK's nodes 8 and 9 are fricon's
  // 9 and 8.
  EXPECT_EQ(cell_layout(10).order, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 9, 8}));
  EXPECT_EQ(cell_layout(6).order, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}

TEST(CellLayout, OtherCellsAreRefused) {
  for (const Index nodes : {0, 1, 2, 5, 8, 20})
    EXPECT_THROW(cell_layout(nodes), Error) << nodes << " nodes";
}

// The lines of the DataArray `name` of the file's text (between its opening tag and its end).
std::vector<std::string> data_array(const std::string& text, const std::string& name) {
  const std::size_t tag = text.find("Name=\"" + name + "\"");
  EXPECT_NE(tag, std::string::npos) << name;
  if (tag == std::string::npos) return {};
  std::istringstream in(text.substr(text.find('\n', tag) + 1));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line) && line.find("</DataArray>") == std::string::npos;)
    lines.push_back(line.substr(line.find_first_not_of(' ')));
  return lines;
}

class WriteVtu : public test::TempDirTest {
 protected:
  // `grid` written to a file of dir_, read back as text (or bytes).
  std::string written(const VtuGrid& grid, VtuEncoding encoding = VtuEncoding::Ascii) const {
    const std::filesystem::path path = dir_.path() / "grid.vtu";
    write_vtu(path, grid, encoding);
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
};

// One cell of `nodes` points whose fricon order is 0, 1, ..., nodes - 1 (the points themselves
// do not matter to the connectivity).
VtuGrid one_cell(Index nodes) {
  VtuGrid grid;
  grid.points = Eigen::Matrix<Real, 3, Eigen::Dynamic>::Random(3, nodes);
  grid.cells.resize(nodes, 1);
  for (Index a = 0; a < nodes; ++a)
    grid.cells(a, 0) = a;
  return grid;
}

TEST_F(WriteVtu, AQuadraticTetrahedronIsVtksTenNodeTetrahedron) {
  const std::string text = written(one_cell(10));
  EXPECT_EQ(data_array(text, "connectivity"), std::vector<std::string>{"0 1 2 3 4 5 6 7 9 8"});
  EXPECT_EQ(data_array(text, "offsets"), std::vector<std::string>{"10"});
  EXPECT_EQ(data_array(text, "types"), std::vector<std::string>{"24"});
}

TEST_F(WriteVtu, AQuadraticTriangleIsVtksSixNodeTriangle) {
  const std::string text = written(one_cell(6));
  EXPECT_EQ(data_array(text, "connectivity"), std::vector<std::string>{"0 1 2 3 4 5"});
  EXPECT_EQ(data_array(text, "offsets"), std::vector<std::string>{"6"});
  EXPECT_EQ(data_array(text, "types"), std::vector<std::string>{"22"});
}

TEST_F(WriteVtu, LinearCellsAreAsTheyWere) {
  VtuGrid grid = one_cell(4);
  grid.cells.conservativeResize(4, 2);
  grid.cells.col(1) << 3, 2, 1, 0;
  const std::string text = written(grid);
  EXPECT_EQ(data_array(text, "connectivity"), (std::vector<std::string>{"0 1 2 3", "3 2 1 0"}));
  EXPECT_EQ(data_array(text, "offsets"), (std::vector<std::string>{"4", "8"}));
  EXPECT_EQ(data_array(text, "types"), (std::vector<std::string>{"10", "10"}));
}

// The binary encoding, read back by a reader of VTK's appended raw layout written here from the
// format's description (each array: its offset after the '_' that opens <AppendedData>, a
// UInt64 byte count, then the values, little endian), against the grid itself, bit for bit.
template <typename T>
std::vector<T> appended_array(const std::string& text, const std::string& name) {
  const std::size_t tag = text.find("Name=\"" + name + "\"");
  EXPECT_NE(tag, std::string::npos) << name;
  if (tag == std::string::npos) return {};
  const std::size_t end_of_tag = text.find('>', tag);
  const std::string element = text.substr(tag, end_of_tag - tag);
  EXPECT_NE(element.find("format=\"appended\""), std::string::npos) << element;
  const std::size_t at = element.find("offset=\"");
  const std::size_t offset = std::stoul(element.substr(at + 8));
  const std::size_t data = text.find("<AppendedData encoding=\"raw\">");
  EXPECT_NE(data, std::string::npos);
  const std::size_t start = text.find('_', data) + 1 + offset;
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, text.data() + start, sizeof bytes);
  EXPECT_EQ(bytes % sizeof(T), 0u) << name;
  std::vector<T> values(bytes / sizeof(T));
  std::memcpy(values.data(), text.data() + start + sizeof bytes, bytes);
  return values;
}

TEST_F(WriteVtu, TheBinaryEncodingHoldsEveryValueExactly) {
  VtuGrid grid = one_cell(10);
  grid.cells.conservativeResize(10, 2);
  grid.cells.col(1) = grid.cells.col(0).reverse();
  grid.points.row(0) *= 1.0 / 3.0;  // values that text would round without round-trip care
  grid.point_data.push_back({"displacement", MatrixXd::Random(3, 10)});
  grid.cell_data.push_back({"region", MatrixXd(MatrixXd::Constant(1, 2, 7.0)), VtuType::Int32});
  grid.field_data.push_back({"centre", Eigen::Vector3d(1.0, 2.0, 3.0)});
  const std::string text = written(grid, VtuEncoding::Binary);

  const auto points = appended_array<double>(text, "Points");
  ASSERT_EQ(points.size(), 30u);
  EXPECT_TRUE(std::equal(points.begin(), points.end(), grid.points.data()));
  const auto u = appended_array<double>(text, "displacement");
  ASSERT_EQ(u.size(), 30u);
  EXPECT_TRUE(std::equal(u.begin(), u.end(), grid.point_data[0].values.data()));
  EXPECT_EQ(appended_array<std::int32_t>(text, "region"), (std::vector<std::int32_t>{7, 7}));
  // VTK's node order (nodes 8 and 9 swapped), the offsets and the types, as in ASCII.
  EXPECT_EQ(
      appended_array<std::int64_t>(text, "connectivity"),
      (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7, 9, 8, 9, 8, 7, 6, 5, 4, 3, 2, 0, 1}));
  EXPECT_EQ(appended_array<std::int64_t>(text, "offsets"), (std::vector<std::int64_t>{10, 20}));
  EXPECT_EQ(appended_array<std::uint8_t>(text, "types"), (std::vector<std::uint8_t>{24, 24}));
  // The dataset's values stay text.
  EXPECT_EQ(data_array(text, "centre"), std::vector<std::string>{"1 2 3"});
}

TEST_F(WriteVtu, TheTwoEncodingsDescribeTheSameArrays) {
  VtuGrid grid = one_cell(4);
  grid.cell_data.push_back({"von_mises", MatrixXd::Constant(1, 1, 2.5)});
  const std::string ascii = written(grid, VtuEncoding::Ascii);
  const std::string binary = written(grid, VtuEncoding::Binary);
  EXPECT_EQ(ascii.find("AppendedData"), std::string::npos);
  EXPECT_EQ(binary.find("format=\"ascii\""), std::string::npos);
  for (const std::string name : {"Points", "connectivity", "offsets", "types", "von_mises"}) {
    EXPECT_NE(ascii.find("Name=\"" + name + "\""), std::string::npos) << name;
    EXPECT_NE(binary.find("Name=\"" + name + "\""), std::string::npos) << name;
  }
  EXPECT_EQ(appended_array<double>(binary, "von_mises"), std::vector<double>{2.5});
  EXPECT_EQ(data_array(ascii, "von_mises"), std::vector<std::string>{"2.5"});
}

}  // namespace
}  // namespace fricon::io
