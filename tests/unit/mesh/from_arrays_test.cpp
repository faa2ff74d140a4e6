// mesh::mesh_from_arrays with quadratic tetrahedra (docs/theory.md §2.12): 10 nodes per
// tetrahedron in Gmsh's order and boundary triangles of 3 nodes (their edge nodes come from the
// tetrahedra) or 6 (checked against them); other widths, non-conforming edge nodes and 6-node
// triangles that disagree with the tetrahedra are refused, naming the array entry.
#include "fricon/mesh/from_arrays.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/tet_mesh.hpp"

using namespace fricon;
using namespace fricon::mesh;

namespace {

// Two positively oriented tetrahedra on the triangle 0 1 2, A = (0 1 2 3) above it and
// B = (0 2 1 4) below, their six outer triangles tagged "all"; linear (5 nodes).
TetMesh two_tets() {
  TetMesh m;
  m.nodes.resize(3, 5);
  m.nodes << 0, 1, 0, 0, 0,  //
      0, 0, 1, 0, 0,         //
      0, 0, 0, 1, -1;
  m.tets.resize(4, 2);
  m.tets << 0, 0,  //
      1, 2,        //
      2, 1,        //
      3, 4;
  m.faces = boundary_faces_of(m);
  m.face_tag.assign(static_cast<std::size_t>(m.n_faces()), 0);
  m.tag_names = {"all"};
  return m;
}

// The same, quadratic with straight edges: 5 corners and 9 edge nodes.
TetMesh two_quadratic_tets() {
  TetMesh m = two_tets();
  add_edge_midpoints(m);
  return m;
}

// Tetrahedron B's columns (of a row of 10) of its edges 10 and 40 (its edges 2 and 3, kTetEdge).
constexpr Index kEdge10OfB = kLinearTetNodes + 2;
constexpr Index kEdge40OfB = kLinearTetNodes + 3;

// The arrays of `m`: every node of each tetrahedron, and triangles of `width` nodes (3, or 6 of a
// quadratic mesh).
MeshArrays arrays_of(const TetMesh& m, Index width) {
  MeshArrays a;
  a.points.assign(m.nodes.data(), m.nodes.data() + m.nodes.size());
  a.nodes_per_tet = m.nodes_per_tet();
  for (Index t = 0; t < m.n_tets(); ++t)
    for (int k = 0; k < m.nodes_per_tet(); ++k)
      a.tets.push_back(m.tet_node(t, k));
  TriangleArray& all = a.boundary["all"];
  all.width = width;
  for (Index f = 0; f < m.n_faces(); ++f)
    for (int k = 0; k < width; ++k)
      all.nodes.push_back(m.face_node(f, static_cast<int>(k)));
  return a;
}

// Entry `column` of row `row` of the tetrahedra (rows of a.nodes_per_tet).
Index& tet_entry(MeshArrays& a, Index row, Index column) {
  return a.tets[static_cast<std::size_t>(row * a.nodes_per_tet + column)];
}

TEST(MeshFromArrays, LinearTetrahedraStayLinear) {
  const TetMesh m = mesh_from_arrays(arrays_of(two_tets(), kLinearTriangleNodes), "arrays");
  EXPECT_EQ(m.order(), 1);
  EXPECT_EQ(m.tet_extra.rows(), 0);
  EXPECT_EQ(m.face_extra.rows(), 0);
  EXPECT_EQ(m.n_faces(), 6);
}

TEST(MeshFromArrays, QuadraticTetrahedraKeepTheirEdgeNodesAndGiveTheTrianglesTheirs) {
  const TetMesh q = two_quadratic_tets();
  for (const Index width : {kLinearTriangleNodes, kQuadraticTriangleNodes}) {
    SCOPED_TRACE(width);
    const TetMesh m = mesh_from_arrays(arrays_of(q, width), "arrays");
    EXPECT_EQ(m.order(), 2);
    ASSERT_EQ(m.n_nodes(), q.n_nodes());
    ASSERT_EQ(m.tet_extra.rows(), kTetEdges);
    ASSERT_EQ(m.tet_extra.cols(), q.n_tets());
    EXPECT_TRUE(m.tets == q.tets);
    EXPECT_TRUE(m.tet_extra == q.tet_extra);
    ASSERT_EQ(m.face_extra.rows(), kTriangleEdges);
    ASSERT_EQ(m.face_extra.cols(), m.n_faces());
    // Each edge node of a triangle is the midpoint of that edge's corners (straight edges).
    for (Index f = 0; f < m.n_faces(); ++f)
      for (int e = 0; e < kTriangleEdges; ++e) {
        const Vec3 middle = 0.5 * (m.nodes.col(m.faces(kTriangleEdge[e][0], f)) +
                                   m.nodes.col(m.faces(kTriangleEdge[e][1], f)));
        EXPECT_EQ(m.nodes.col(m.face_extra(e, f)), middle) << "triangle " << f << " edge " << e;
      }
  }
}

TEST(MeshFromArrays, OtherWidthsAreRefused) {
  const TetMesh q = two_quadratic_tets();
  MeshArrays a = arrays_of(q, kQuadraticTriangleNodes);
  a.nodes_per_tet = 5;
  test::expect_input_error([&] { mesh_from_arrays(a, "arrays"); },
                           {"arrays: tets: expected 4 nodes per tetrahedron", "10", "got 5"});
  a = arrays_of(q, kQuadraticTriangleNodes);
  a.boundary["all"].width = 4;
  test::expect_input_error([&] { mesh_from_arrays(a, "arrays"); },
                           {"arrays: boundary['all']: expected 3 nodes per triangle", "got 4"});
  a = arrays_of(two_tets(), kLinearTriangleNodes);
  a.boundary["all"] = arrays_of(q, kQuadraticTriangleNodes).boundary["all"];
  test::expect_input_error([&] { mesh_from_arrays(a, "arrays"); },
                           {"boundary['all']: 6-node triangles on linear (4-node) tetrahedra"});
}

TEST(MeshFromArrays, NonConformingEdgeNodesAreRefused) {
  const TetMesh q = two_quadratic_tets();
  const auto error_of = [](const std::function<void(MeshArrays&)>& change,
                           const std::vector<std::string>& parts) {
    MeshArrays a = arrays_of(two_quadratic_tets(), kLinearTriangleNodes);
    change(a);
    test::expect_input_error([&] { mesh_from_arrays(a, "arrays"); }, parts);
  };
  // B gives the shared edge 0-1 a node of its own (a new point there).
  error_of(
      [&](MeshArrays& a) {
        const Vec3 middle = 0.5 * (q.nodes.col(0) + q.nodes.col(1));
        a.points.insert(a.points.end(), middle.data(), middle.data() + middle.size());
        tet_entry(a, 1, kEdge10OfB) = q.n_nodes();
      },
      {"tets[0, 4] and tets[1, 6] give the edge between nodes 0 and 1 two edge nodes"});
  // B's edge 4-0 takes A's node of the edge 3-0: one node on two edges.
  error_of([&](MeshArrays& a) { tet_entry(a, 1, kEdge40OfB) = q.tet_extra(3, 0); },
           {fmt::format("node {} is the edge node of two edges", q.tet_extra(3, 0))});
  // B's edge 4-0 takes the corner 3.
  error_of([&](MeshArrays& a) { tet_entry(a, 1, kEdge40OfB) = 3; },
           {"tets[1, 7] is node 3, the edge node of the edge 0-4 and a corner"});
  // An index out of range.
  error_of([&](MeshArrays& a) { tet_entry(a, 1, kEdge40OfB) = 99; },
           {fmt::format("tets[1, 7] is node 99, but the mesh has {} nodes", q.n_nodes())});
}

TEST(MeshFromArrays, ASixNodeTriangleMustHaveTheTetrahedrasEdgeNodes) {
  MeshArrays a = arrays_of(two_quadratic_tets(), kQuadraticTriangleNodes);
  std::vector<Index>& rows = a.boundary["all"].nodes;
  std::swap(rows[kLinearTriangleNodes], rows[kLinearTriangleNodes + 1]);  // row 0: edges 01, 12
  test::expect_input_error(
      [&] { mesh_from_arrays(a, "arrays"); },
      {"arrays: boundary['all'][0, 3] is node", "the tetrahedra give the edge"});
}

}  // namespace
