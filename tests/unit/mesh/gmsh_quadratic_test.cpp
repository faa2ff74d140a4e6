// Tests of the Gmsh reader and writer with quadratic (10-node) tetrahedra (theory.md §2.12): a
// hand-written 10-node tetrahedron read node for node, .geo files meshed at order 2 (edge nodes
// on the curved geometry, curves, rigid surfaces), a linear mesh raised to order 2, round trips,
// and the refused meshes (4-node and 10-node tetrahedra together, triangles of the wrong order,
// order 1 asked of a quadratic mesh, third order).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/gmsh_file.hpp"
#include "fricon/mesh/tet_mesh.hpp"

using namespace fricon;
using namespace fricon::mesh;
namespace fs = std::filesystem;

namespace {

// The orders of the elements (TetMesh::order).
constexpr int kLinear = 1;
constexpr int kQuadratic = 2;
// Nodes of a 10-node tetrahedron and of a 6-node triangle.
constexpr int kTet10Nodes = 4 + kTetEdges;
constexpr int kTriangle6Nodes = 3 + kTriangleEdges;

// The edge node of tetrahedron t between its corners a and b (nodes of the mesh), or -1.
Index tet_edge_node(const TetMesh& m, Index t, Index a, Index b) {
  for (int e = 0; e < kTetEdges; ++e) {
    const Index p = m.tets(kTetEdge[e][0], t), q = m.tets(kTetEdge[e][1], t);
    if ((p == a && q == b) || (p == b && q == a)) return m.tet_extra(e, t);
  }
  return -1;
}

// Every boundary face of a quadratic mesh has, on each of its edges, the edge node of the
// tetrahedron it bounds.
void expect_face_edges_of_tets(const TetMesh& m) {
  ASSERT_EQ(m.order(), kQuadratic);
  ASSERT_EQ(m.face_extra.rows(), kTriangleEdges);
  ASSERT_EQ(m.face_extra.cols(), m.n_faces());
  std::vector<Index> faces(static_cast<size_t>(m.n_faces()));
  for (Index f = 0; f < m.n_faces(); ++f)
    faces[static_cast<size_t>(f)] = f;
  const std::vector<Index> tet = tets_of_faces(m, faces);
  for (Index f = 0; f < m.n_faces(); ++f) {
    const Index t = tet[static_cast<size_t>(f)];
    ASSERT_GE(t, 0) << "face " << f;
    for (int e = 0; e < kTriangleEdges; ++e)
      EXPECT_EQ(m.face_extra(e, f), tet_edge_node(m, t, m.faces(kTriangleEdge[e][0], f),
                                                  m.faces(kTriangleEdge[e][1], f)))
          << "face " << f << ", edge " << e;
  }
}

// Every edge node of the tetrahedra lies at the midpoint of its corners (straight edges).
void expect_straight_edges(const TetMesh& m) {
  ASSERT_EQ(m.order(), kQuadratic);
  for (Index t = 0; t < m.n_tets(); ++t)
    for (int e = 0; e < kTetEdges; ++e) {
      const Vec3 mid =
          0.5 * (m.nodes.col(m.tets(kTetEdge[e][0], t)) + m.nodes.col(m.tets(kTetEdge[e][1], t)));
      EXPECT_LE((m.nodes.col(m.tet_extra(e, t)) - mid).norm(), 1e-15)
          << "tetrahedron " << t << ", edge " << e;
    }
}

using Key3 = std::array<Index, 3>;

// The boundary faces of each tag by their sorted corners, with their edge nodes (sorted).
std::map<std::string, std::map<Key3, Key3>> quadratic_faces_by_tag(const TetMesh& m) {
  std::map<std::string, std::map<Key3, Key3>> s;
  for (Index f = 0; f < m.n_faces(); ++f) {
    Key3 corners{m.faces(0, f), m.faces(1, f), m.faces(2, f)};
    Key3 edges{m.face_extra(0, f), m.face_extra(1, f), m.face_extra(2, f)};
    std::sort(corners.begin(), corners.end());
    std::sort(edges.begin(), edges.end());
    s[m.tag_names[static_cast<size_t>(m.face_tag[static_cast<size_t>(f)])]][corners] = edges;
  }
  return s;
}

// The unit tetrahedron's corners (0,0,0), (1,0,0), (0,1,0), (0,0,1) as Gmsh nodes 1-4, then the
// midpoints of its edges 01, 12, 20, 30, 32, 31 as nodes 5-10 (Gmsh's 10-node order), the
// midpoint of the edge 12 (node 6) moved off the edge in the plane z = 0.
const std::array<Vec3, kTet10Nodes> kTet10Points{
    Vec3(0, 0, 0),       Vec3(1, 0, 0),   Vec3(0, 1, 0),   Vec3(0, 0, 1),     Vec3(0.5, 0, 0),
    Vec3(0.55, 0.55, 0), Vec3(0, 0.5, 0), Vec3(0, 0, 0.5), Vec3(0, 0.5, 0.5), Vec3(0.5, 0, 0.5)};

// An MSH 2.2 file: the 10-node tetrahedron of kTet10Points on Gmsh nodes 1-10 (element 1, type 11)
// with the physical groups "sides" (2D, tag 2) and "edge" (1D, tag 1); then `n_extra_nodes` more
// nodes `extra_nodes` and the element lines `extra`.
std::string tet10_msh(const std::string& extra = "", int n_extra = 0,
                      const std::string& extra_nodes = "", int n_extra_nodes = 0) {
  std::string nodes;
  for (size_t k = 0; k < kTet10Points.size(); ++k)
    nodes += fmt::format("{} {} {} {}\n", k + 1, kTet10Points[k](0), kTet10Points[k](1),
                         kTet10Points[k](2));
  return fmt::format(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"edge\"\n2 2 \"sides\"\n"
      "$EndPhysicalNames\n$Nodes\n{}\n{}{}$EndNodes\n$Elements\n{}\n"
      "1 11 2 0 1 1 2 3 4 5 6 7 8 9 10\n{}$EndElements\n",
      kTet10Nodes + n_extra_nodes, nodes, extra_nodes, 1 + n_extra, extra);
}

// The bottom z = 0 (corners 1 3 2, its edge nodes 7 6 5) and the slanted face (corners 2 3 4,
// edge nodes 6 9 10) as 6-node triangles of "sides", and the edge 01 as a 3-node line of "edge".
const char* const kSidesAndEdge =
    "2 9 2 2 1 1 3 2 7 6 5\n3 9 2 2 1 2 3 4 6 9 10\n4 8 2 1 1 1 2 5\n";
constexpr int kSidesAndEdgeElements = 3;

class GmshQuadratic : public test::TempDirTest {
 protected:
  fs::path write_file(const std::string& name, const std::string& content) const {
    return dir_.write(name, content);
  }
};

// @sect: the 10-node tetrahedron by hand.

TEST_F(GmshQuadratic, TenNodeTetrahedronKeepsGmshNodeOrder) {
  const TetMesh m =
      read_gmsh(write_file("tet10.msh", tet10_msh(kSidesAndEdge, kSidesAndEdgeElements)));
  EXPECT_EQ(m.order(), kQuadratic);
  EXPECT_EQ(m.nodes_per_tet(), kTet10Nodes);
  EXPECT_EQ(m.nodes_per_face(), kTriangle6Nodes);
  ASSERT_EQ(m.n_nodes(), kTet10Nodes);
  ASSERT_EQ(m.n_tets(), 1);
  EXPECT_FALSE(first_unused_node(m).has_value());
  // Node k of the element (Gmsh node k + 1) is node k of the tetrahedron, where the file put it.
  for (int k = 0; k < kTet10Nodes; ++k) {
    EXPECT_EQ(m.tet_node(0, k), k) << k;
    EXPECT_EQ(m.nodes.col(m.tet_node(0, k)), kTet10Points[static_cast<size_t>(k)]) << k;
  }
  // The boundary faces, oriented outward, with the tetrahedron's edge nodes.
  ASSERT_EQ(m.n_faces(), 2);
  expect_face_edges_of_tets(m);
  const Vec3 slanted = Vec3(1, 1, 1).normalized();
  for (Index f = 0; f < m.n_faces(); ++f) {
    const Vec3 n = face_normal(m, f);
    EXPECT_TRUE((n + Vec3::UnitZ()).norm() < 1e-15 || (n - slanted).norm() < 1e-15) << n;
  }
  // The curve: the ends of its 3-node line and its midpoint.
  const NodeSet* edge = m.find_node_set("edge");
  ASSERT_NE(edge, nullptr);
  EXPECT_EQ(edge->nodes, (std::vector<Index>{0, 1, 4}));
}

TEST_F(GmshQuadratic, TenNodeTetrahedronAtOrderOneIsRefused) {
  const fs::path file = write_file("tet10_linear.msh", tet10_msh());
  test::expect_input_error([&] { read_gmsh(file, {}, kLinear); },
                           {"tet10_linear.msh", "10-node (quadratic)", "order 1",
                            "[mesh] order = 2", "Mesh.ElementOrder = 1"});
  EXPECT_EQ(read_gmsh(file, {}, kQuadratic).order(), kQuadratic);
}

TEST_F(GmshQuadratic, RefusesAnOrderOtherThanOneAndTwo) {
  const fs::path file = write_file("tet10_order3.msh", tet10_msh());
  test::expect_input_error([&] { read_gmsh(file, {}, 3); },
                           {"tet10_order3.msh", "element order 3"});
}

TEST_F(GmshQuadratic, RefusesFourNodeAndTenNodeTetrahedraTogether) {
  // A 4-node tetrahedron (Gmsh element 2) on nodes 2 4 3 and node 11 beside the 10-node one, in
  // a volume of its own (elementary entity 2)...
  const std::string node = "11 1 1 1\n";
  test::expect_input_error(
      [&] { read_gmsh(write_file("mixed.msh", tet10_msh("2 4 2 0 2 2 4 3 11\n", 1, node, 1))); },
      {"mixed.msh", "'Tetrahedron 4' (Gmsh type 4)", "'Tetrahedron 10' (Gmsh type 11)",
       "Mesh.ElementOrder = 2"});
  // ... or in the same one, where Gmsh lists the tetrahedra together under the first one's type.
  test::expect_input_error(
      [&] { read_gmsh(write_file("mixed1.msh", tet10_msh("2 4 2 0 1 2 4 3 11\n", 1, node, 1))); },
      {"mixed1.msh", "entity 1 of dimension 3", "1 elements of type 'Tetrahedron 10'",
       "among 2 of their kind", "another order", "Mesh.ElementOrder = 2"});
}

TEST_F(GmshQuadratic, RefusesThreeNodeTrianglesOnTenNodeTetrahedra) {
  // The bottom as a 3-node triangle (Gmsh element 2) of "sides".
  test::expect_input_error(
      [&] { read_gmsh(write_file("tri3.msh", tet10_msh("2 2 2 2 1 1 3 2\n", 1))); },
      {"tri3.msh", "Gmsh element 2", "'sides'", "'Triangle 3' (Gmsh type 2)",
       "'Tetrahedron 10' (Gmsh type 11)", "6-node"});
}

TEST_F(GmshQuadratic, RefusesATriangleWhoseEdgeNodesAreNotItsTetrahedrons) {
  // The bottom with its edge nodes 6 and 7 swapped.
  test::expect_input_error(
      [&] { read_gmsh(write_file("swapped.msh", tet10_msh("2 9 2 2 1 1 3 2 6 7 5\n", 1))); },
      {"swapped.msh", "Gmsh element 2", "'sides'", "does not conform"});
}

// @sect: .geo files meshed at order 2.

TEST_F(GmshQuadratic, SphereAtOrderTwoHasItsEdgeNodesOnTheSphere) {
  const fs::path geo = write_file("sphere.geo", R"(SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMax = 0.5;
Physical Volume("ball") = {1};
Physical Surface("skin") = {1};
)");
  const TetMesh m = read_gmsh(geo, {}, kQuadratic);
  ASSERT_EQ(m.order(), kQuadratic);
  ASSERT_GT(m.n_faces(), 0);
  EXPECT_FALSE(first_unused_node(m).has_value());
  expect_face_edges_of_tets(m);
  // Every node of every boundary face on the unit sphere, the edge nodes off the chords.
  Real largest_sag = 0.0;  // [m]
  for (Index f = 0; f < m.n_faces(); ++f) {
    for (int a = 0; a < m.nodes_per_face(); ++a)
      EXPECT_NEAR(m.nodes.col(m.face_node(f, a)).norm(), 1.0, 1e-6) << "face " << f << ", " << a;
    for (int e = 0; e < kTriangleEdges; ++e) {
      const Vec3 chord_mid = 0.5 * (m.nodes.col(m.faces(kTriangleEdge[e][0], f)) +
                                    m.nodes.col(m.faces(kTriangleEdge[e][1], f)));
      largest_sag = std::max(largest_sag, (m.nodes.col(m.face_extra(e, f)) - chord_mid).norm());
    }
  }
  // An edge of about 0.5 m on the unit sphere bulges by about 0.5^2 / 8 m.
  EXPECT_GT(largest_sag, 1e-2);
  // The same file at order 1 (and without an order: the file's, 1) is linear.
  EXPECT_EQ(read_gmsh(geo, {}, kLinear).order(), kLinear);
  EXPECT_EQ(read_gmsh(geo).order(), kLinear);
}

const char* const kBoxOrder2Geo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = 0.5;
Mesh.ElementOrder = 2;
Physical Volume("block") = {1};
Physical Surface("bottom") = {5};
)";

TEST_F(GmshQuadratic, GeoElementOrderTwoIsQuadraticUnlessAnOrderIsAskedFor) {
  const fs::path geo = write_file("box2.geo", kBoxOrder2Geo);
  const TetMesh m = read_gmsh(geo);
  EXPECT_EQ(m.order(), kQuadratic);
  expect_face_edges_of_tets(m);
  expect_straight_edges(m);  // a box has no curved surface
  EXPECT_EQ(read_gmsh(geo, {}, kLinear).order(), kLinear);
}

TEST_F(GmshQuadratic, RefusesThirdOrder) {
  const fs::path geo = write_file("order3.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 1,1,1};
Mesh.MeshSizeMax = 1;
Mesh.ElementOrder = 3;
)");
  test::expect_input_error(
      [&] { read_gmsh(geo); },
      {"order3.geo", "Tetrahedron 20", "Mesh.ElementOrder = 1", "Mesh.ElementOrder = 2"});
}

TEST_F(GmshQuadratic, CurvesAtOrderTwoHaveTheirMidpoints) {
  const TetMesh m = read_gmsh(write_file("plate.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.2};
e = 1e-6;
Physical Curve("edge") = Curve In BoundingBox{-e, -e, -e, 1 + e, e, e};
MeshSize{PointsOf{Volume{1};}} = 0.25;
)"),
                              {}, kQuadratic);
  const NodeSet* edge = m.find_node_set("edge");
  ASSERT_NE(edge, nullptr);
  // Every node on the line y = z = 0, the edge nodes included, and no other.
  std::vector<Index> on_line;
  for (Index a = 0; a < m.n_nodes(); ++a)
    if (std::abs(m.nodes(1, a)) < 1e-12 && std::abs(m.nodes(2, a)) < 1e-12) on_line.push_back(a);
  EXPECT_EQ(edge->nodes, on_line);
  // The ends and, per segment, an inner node and a midpoint: an odd count, at least 2 * 4 + 1.
  EXPECT_GE(on_line.size(), 9u);
  EXPECT_EQ(on_line.size() % 2, 1u);
}

TEST_F(GmshQuadratic, SixNodeRigidSurfaceKeepsItsCorners) {
  const TetMesh m = read_gmsh(write_file("plate.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Rectangle(10) = {0, 0, 2, 1, 1};
Mesh.MeshSizeMax = 0.5;
Physical Volume("block") = {1};
Physical Surface("bottom") = {5};
Physical Surface("plate") = {10};
)"),
                              {}, kQuadratic);
  EXPECT_EQ(m.order(), kQuadratic);
  EXPECT_FALSE(first_unused_node(m).has_value());  // the plate's edge nodes are left out
  EXPECT_LE(m.nodes.row(2).maxCoeff(), 1.0);
  expect_face_edges_of_tets(m);
  const RigidSurface* plate = m.find_rigid_surface("plate");
  ASSERT_NE(plate, nullptr);
  // Its points are the corners of its triangles, every one used.
  std::set<Index> used;
  Real area = 0.0;  // [m^2]
  for (Index t = 0; t < plate->triangles.cols(); ++t) {
    for (int v = 0; v < 3; ++v)
      used.insert(plate->triangles(v, t));
    const Vec3 a = plate->points.col(plate->triangles(0, t));
    area += 0.5 * (plate->points.col(plate->triangles(1, t)) - a)
                      .cross(plate->points.col(plate->triangles(2, t)) - a)
                      .norm();
  }
  EXPECT_EQ(static_cast<Index>(used.size()), plate->points.cols());
  EXPECT_NEAR(area, 1.0, 1e-12);
  EXPECT_NEAR((plate->points.row(2).array() - 2.0).abs().maxCoeff(), 0.0, 1e-12);
}

// @sect: a linear mesh raised to order 2, and round trips.

TEST_F(GmshQuadratic, LinearMshAtOrderTwoGetsStraightEdgeNodes) {
  const TetMesh brick = make_brick(BrickSpec{Vec3(2.0, 1.0, 1.0), {2, 1, 1}});
  const fs::path file = dir_.path() / "brick.msh";
  write_gmsh(file, brick);
  const TetMesh m = read_gmsh(file, {}, kQuadratic);
  ASSERT_EQ(m.order(), kQuadratic);
  EXPECT_GT(m.n_nodes(), brick.n_nodes());
  EXPECT_EQ(m.nodes.leftCols(brick.n_nodes()), brick.nodes);  // the file's nodes first
  EXPECT_FALSE(first_unused_node(m).has_value());
  expect_straight_edges(m);
  expect_face_edges_of_tets(m);
  EXPECT_EQ(read_gmsh(file, {}, kLinear).order(), kLinear);
}

TEST_F(GmshQuadratic, QuadraticMeshRoundTrips) {
  TetMesh m = make_brick(BrickSpec{Vec3(2.0, 1.0, 1.0), {2, 1, 1}});
  const Index n_corners = m.n_nodes();
  add_edge_midpoints(m);  // the edge nodes come after the corners
  // Curved edges: the edge nodes moved along x, by 0, 1 or 2 steps each.
  constexpr Real kStep = 0.01;  // [m]
  constexpr Index kSteps = 3;
  for (Index a = n_corners; a < m.n_nodes(); ++a)
    m.nodes(0, a) += kStep * static_cast<Real>(a % kSteps);
  for (int version : {kMsh41, kMsh22}) {
    SCOPED_TRACE(version);
    const fs::path file = dir_.path() / fmt::format("quadratic{}.msh", version);
    write_gmsh(file, m, version);
    const TetMesh back = read_gmsh(file);
    ASSERT_EQ(back.order(), kQuadratic);
    ASSERT_EQ(back.n_nodes(), m.n_nodes());
    EXPECT_EQ(back.nodes, m.nodes);
    EXPECT_EQ(back.tets, m.tets);
    EXPECT_EQ(back.tet_extra, m.tet_extra);
    EXPECT_EQ(quadratic_faces_by_tag(back), quadratic_faces_by_tag(m));
    expect_face_edges_of_tets(back);
  }
}

}  // namespace
