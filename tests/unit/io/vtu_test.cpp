// io::cell_layout and io::write_vtu: linear and quadratic cells (docs/theory.md §2.12) are written
// with VTK's cell types and node orders. fricon's (Gmsh's) quadratic tetrahedron has the edges 32
// and 31 as its nodes 8 and 9, VTK's the edges 13 and 23: they swap.
#include "fricon/io/vtu.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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
  // `grid` written to a file of dir_, read back as text.
  std::string written(const VtuGrid& grid) const {
    const std::filesystem::path path = dir_.path() / "grid.vtu";
    write_vtu(path, grid);
    std::ifstream in(path);
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

}  // namespace
}  // namespace fricon::io
