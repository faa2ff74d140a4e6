// Tests of the Gmsh reader and writer: round trips of the brick through every MSH flavour, .geo
// files meshed on the fly (volumes, areas, outward normals, regions), rigid surfaces (physical
// surfaces off the tetrahedra, read, scaled and written back) and the refused meshes.
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
#include <thread>
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

using Key3 = std::array<Index, 3>;
using Key4 = std::array<Index, 4>;

std::set<Key4> tet_set(const TetMesh& m) {
  std::set<Key4> s;
  for (Index t = 0; t < m.n_tets(); ++t) {
    Key4 k{m.tets(0, t), m.tets(1, t), m.tets(2, t), m.tets(3, t)};
    std::sort(k.begin(), k.end());
    s.insert(k);
  }
  return s;
}

Key3 face_key(const TetMesh& m, Index f) {
  Key3 k{m.faces(0, f), m.faces(1, f), m.faces(2, f)};
  std::sort(k.begin(), k.end());
  return k;
}

// The faces of each tag, by tag name.
std::map<std::string, std::set<Key3>> faces_by_tag(const TetMesh& m) {
  std::map<std::string, std::set<Key3>> s;
  for (Index f = 0; f < m.n_faces(); ++f)
    s[m.tag_names[m.face_tag[f]]].insert(face_key(m, f));
  return s;
}

// The faces of each entity.
std::map<int, std::set<Key3>> faces_by_entity(const TetMesh& m) {
  std::map<int, std::set<Key3>> s;
  for (Index f = 0; f < m.n_faces(); ++f)
    s[m.face_entity[f]].insert(face_key(m, f));
  return s;
}

Real total_volume(const TetMesh& m) {
  Real v = 0;
  for (Index t = 0; t < m.n_tets(); ++t)
    v += tet_volume(m, t);
  return v;
}

Real tag_area(const TetMesh& m, const std::string& tag) {
  Real a = 0;
  for (Index f : m.faces_with_tag(tag))
    a += face_area(m, f);
  return a;
}

Vec3 tag_area_normal(const TetMesh& m, const std::string& tag) {
  Vec3 s = Vec3::Zero();
  for (Index f : m.faces_with_tag(tag))
    s += face_area(m, f) * face_normal(m, f);
  return s;
}

// Each test writes its files in a fresh folder of its own.
class GmshFile : public test::TempDirTest {
 protected:
  fs::path test_dir() const { return dir_.path(); }
  fs::path write_file(const std::string& name, const std::string& content) const {
    return dir_.write(name, content);
  }
  void expect_round_trip(int version, bool binary, const std::string& name) const;
};

// @sect: round trips.

void GmshFile::expect_round_trip(int version, bool binary, const std::string& name) const {
  const TetMesh brick = make_brick(BrickSpec{Vec3(3.0, 1.0, 1.0), {6, 2, 3}});
  const fs::path file = test_dir() / name;
  write_gmsh(file, brick, version, binary);
  const TetMesh back = read_gmsh(file);
  ASSERT_EQ(back.n_nodes(), brick.n_nodes());
  EXPECT_LE((back.nodes - brick.nodes).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(tet_set(back), tet_set(brick));
  EXPECT_EQ(back.tag_names, brick.tag_names);
  EXPECT_EQ(faces_by_tag(back), faces_by_tag(brick));
  EXPECT_EQ(faces_by_entity(back), faces_by_entity(brick));
  EXPECT_EQ(back.n_regions(), 1);
  EXPECT_EQ(back.find_region("body"), 0);
  for (const auto& [tag, n] :
       std::map<std::string, Vec3>{{"x0", -Vec3::UnitX()}, {"z1", Vec3::UnitZ()}})
    for (Index f : back.faces_with_tag(tag))
      EXPECT_NEAR((face_normal(back, f) - n).norm(), 0.0, 1e-14) << tag;
  for (const auto& entry : fs::directory_iterator(test_dir()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left behind: " << entry.path();
}

TEST_F(GmshFile, BrickRoundTripMsh41Ascii) {
  expect_round_trip(kMsh41, false, "brick41.msh");
}

TEST_F(GmshFile, BrickRoundTripMsh41Binary) {
  expect_round_trip(kMsh41, true, "brick41b.msh");
}

TEST_F(GmshFile, BrickRoundTripMsh22Ascii) {
  expect_round_trip(kMsh22, false, "brick22.msh");
}

TEST_F(GmshFile, RegionsRoundTrip) {
  TetMesh m = make_brick(BrickSpec{Vec3(2.0, 1.0, 1.0), {2, 1, 1}});
  m.region_names = {"left", "right"};
  m.tet_region.resize(static_cast<size_t>(m.n_tets()));
  for (Index t = 0; t < m.n_tets(); ++t)
    m.tet_region[t] = m.nodes(0, m.tets(0, t)) + m.nodes(0, m.tets(1, t)) +
                                  m.nodes(0, m.tets(2, t)) + m.nodes(0, m.tets(3, t)) <
                              4.0
                          ? 0
                          : 1;
  const fs::path file = test_dir() / "regions.msh";
  write_gmsh(file, m);
  const TetMesh back = read_gmsh(file);
  EXPECT_EQ(back.region_names, m.region_names);
  std::map<Key4, std::string> region_of;
  for (Index t = 0; t < m.n_tets(); ++t) {
    Key4 k{m.tets(0, t), m.tets(1, t), m.tets(2, t), m.tets(3, t)};
    std::sort(k.begin(), k.end());
    region_of[k] = m.region_names[m.tet_region[t]];
  }
  for (Index t = 0; t < back.n_tets(); ++t) {
    Key4 k{back.tets(0, t), back.tets(1, t), back.tets(2, t), back.tets(3, t)};
    std::sort(k.begin(), k.end());
    EXPECT_EQ(back.region_names[back.region(t)], region_of[k]);
  }
}

TEST_F(GmshFile, TriangleInTwoTagsRoundTrips) {
  // The bottom's triangles also in a tag "contact", on the same entities; and faces of no entity.
  TetMesh m = make_brick(BrickSpec{Vec3(2.0, 1.0, 1.0), {4, 2, 2}});
  test::add_second_tag(m, "z0", "contact");
  for (Index f : m.faces_with_tag("x0"))
    m.face_entity[f] = -1;
  for (int version : {kMsh41, kMsh22}) {
    const fs::path file = test_dir() / ("two_tags" + std::to_string(version) + ".msh");
    write_gmsh(file, m, version);
    const TetMesh back = read_gmsh(file);
    EXPECT_EQ(back.n_faces(), m.n_faces()) << version;
    EXPECT_EQ(faces_by_tag(back), faces_by_tag(m)) << version;
    // The same grouping into entities (the -1 faces get a new entity of their own).
    std::set<std::set<Key3>> groups, groups_back;
    for (const auto& [e, faces] : faces_by_entity(m))
      groups.insert(faces);
    for (const auto& [e, faces] : faces_by_entity(back))
      groups_back.insert(faces);
    EXPECT_EQ(groups_back, groups) << version;
  }
}

TEST_F(GmshFile, WriteRefusesBadVersionAndName) {
  const TetMesh m = make_brick(BrickSpec{Vec3(1, 1, 1), {1, 1, 1}});
  test::expect_input_error([&] { write_gmsh(test_dir() / "v3.msh", m, 30); }, {"v3.msh", "30"});
  test::expect_input_error([&] { write_gmsh(test_dir() / "mesh.vtk", m); }, {"mesh.vtk", ".msh"});
}

// @sect: .geo files meshed on the fly.

const char* const kBoxGeo = R"(SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 2,1,1};
Mesh.MeshSizeMax = 0.4;
Physical Volume("solid") = {1};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Surface("all") = {1, 2, 3, 4, 5, 6};
)";

TEST_F(GmshFile, GeoBoxIsMeshedWithOutwardFaces) {
  const TetMesh m = read_gmsh(write_file("box.geo", kBoxGeo));
  EXPECT_NEAR(total_volume(m), 2.0, 1e-12);
  EXPECT_EQ(m.region_names, std::vector<std::string>{"solid"});
  EXPECT_NEAR(tag_area(m, "bottom"), 2.0, 1e-12);
  EXPECT_NEAR(tag_area(m, "top"), 2.0, 1e-12);
  EXPECT_NEAR(tag_area(m, "all"), 10.0, 1e-12);
  EXPECT_NEAR(tag_area_normal(m, "all").norm(), 0.0, 1e-12);
  for (Index f : m.faces_with_tag("bottom"))
    EXPECT_NEAR((face_normal(m, f) + Vec3::UnitZ()).norm(), 0.0, 1e-12);
  // The bottom triangles are in two groups: listed once in each, on the same entity.
  EXPECT_EQ(static_cast<Index>(m.faces_with_tag("all").size()),
            m.n_faces() - static_cast<Index>(m.faces_with_tag("bottom").size() +
                                             m.faces_with_tag("top").size()));
  std::set<int> bottom_entities;
  for (Index f : m.faces_with_tag("bottom"))
    bottom_entities.insert(m.face_entity[f]);
  EXPECT_EQ(bottom_entities, std::set<int>{5});
  std::set<int> all_entities;
  for (Index f : m.faces_with_tag("all"))
    all_entities.insert(m.face_entity[f]);
  EXPECT_EQ(all_entities.size(), 6u);
}

TEST_F(GmshFile, SizeFactorRefines) {
  const fs::path geo = write_file("box_factor.geo", kBoxGeo);
  EXPECT_GT(read_gmsh(geo, 0.5).n_tets(), read_gmsh(geo, 1.0).n_tets());
}

// Gmsh 4.8 kept the rest of a .geo file it failed to parse and read it as the start of the next
// one: the box then failed with "syntax error (;)" (issue 23; gmsh_api::flush_geo_parser).
TEST_F(GmshFile, AGeoFileThatFailedToParseDoesNotSpoilTheNext) {
  for (const char* bad : {"this is not Gmsh;\n", "this is not Gmsh's language;\n"}) {
    test::expect_input_error([&] { read_gmsh(write_file("bad.geo", bad)); }, {"bad.geo"});
    EXPECT_NEAR(total_volume(read_gmsh(write_file("box_after_bad.geo", kBoxGeo))), 2.0, 1e-12)
        << "after " << bad;
  }
}

// Gmsh's state is the process's: threads that read .geo files at once took turns in it before
// issue 23 only by chance (they crashed, or read each other's models). Each now gets the mesh
// it would get alone, and one thread's bad file is its own error.
TEST_F(GmshFile, ThreadsReadingGeoFilesAtOnceGetTheMeshOfOne) {
  const fs::path box = write_file("box_threads.geo", kBoxGeo);
  const fs::path bad = write_file("bad_threads.geo", "this is not Gmsh;\n");
  const TetMesh alone = read_gmsh(box);
  constexpr int kRounds = 4;
  constexpr int kThreads = 3;  // two read the box, the last the bad file
  for (int round = 0; round < kRounds; ++round) {
    std::vector<TetMesh> meshes(kThreads);
    std::vector<std::string> errors(kThreads);
    std::vector<std::thread> threads;
    for (int k = 0; k < kThreads; ++k)
      threads.emplace_back([&, k] {
        try {
          meshes[k] = read_gmsh(k + 1 < kThreads ? box : bad);
        } catch (const std::exception& e) {
          errors[k] = e.what();
        }
      });
    for (auto& t : threads)
      t.join();
    for (int k = 0; k + 1 < kThreads; ++k) {
      EXPECT_EQ(errors[k], "") << "round " << round;
      EXPECT_EQ(meshes[k].n_tets(), alone.n_tets()) << "round " << round;
      EXPECT_NEAR(total_volume(meshes[k]), 2.0, 1e-12) << "round " << round;
    }
    EXPECT_NE(errors.back().find("bad_threads.geo"), std::string::npos) << errors.back();
  }
}

TEST_F(GmshFile, SizeFactorOnlyForGeo) {
  const fs::path file = test_dir() / "factor.msh";
  write_gmsh(file, make_brick(BrickSpec{Vec3(1, 1, 1), {1, 1, 1}}));
  test::expect_input_error([&] { read_gmsh(file, 0.5); }, {"factor.msh", ".geo"});
}

TEST_F(GmshFile, SphereVolumeConverges) {
  const fs::path geo = write_file("sphere.geo", R"(SetFactory("OpenCASCADE");
Sphere(1) = {0,0,0,1};
Mesh.MeshSizeMax = 0.5;
)");
  const Real exact = 4.0 / 3.0 * M_PI;
  const Real coarse = std::abs(total_volume(read_gmsh(geo, 1.0)) - exact);
  const Real fine = std::abs(total_volume(read_gmsh(geo, 0.5)) - exact);
  EXPECT_LT(fine, coarse);
  EXPECT_LT(fine / exact, 0.05);
}

TEST_F(GmshFile, TwoPhysicalVolumesAreTwoRegions) {
  const TetMesh m = read_gmsh(write_file("two.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 1,1,1};
Box(2) = {1,0,0, 1,1,1};
Coherence;
Mesh.MeshSizeMax = 0.5;
Physical Volume("left") = {1};
Physical Volume(7) = {2};
)"));
  ASSERT_EQ(m.n_regions(), 2);
  EXPECT_EQ(m.region_names, (std::vector<std::string>{"left", "3:7"}));
  std::vector<Real> volume(2, 0.0);
  for (Index t = 0; t < m.n_tets(); ++t)
    volume[m.region(t)] += tet_volume(m, t);
  EXPECT_NEAR(volume[0], 1.0, 1e-12);
  EXPECT_NEAR(volume[1], 1.0, 1e-12);
}

// Physical curves and points are node sets (issue 33): all the nodes of a curve, its end points
// included, and the node of a point; nodes_with_tag gives them, faces_with_tag none, and a
// message about a surface says what they are.
TEST_F(GmshFile, PhysicalCurvesAndPointsAreNodeSets) {
  const TetMesh m = read_gmsh(write_file("plate.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.2};
e = 1e-6;
Physical Surface("z0") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Curve("edge") = Curve In BoundingBox{-e, -e, -e, 1 + e, e, e};
Physical Point("corner") = Point In BoundingBox{-e, -e, -e, e, e, e};
Physical Point(42) = Point In BoundingBox{1 - e, 1 - e, 0.2 - e, 1 + e, 1 + e, 0.2 + e};
MeshSize{PointsOf{Volume{1};}} = 0.25;
)"));
  ASSERT_EQ(m.node_sets.size(), 3u);
  const NodeSet* edge = m.find_node_set("edge");
  ASSERT_NE(edge, nullptr);
  EXPECT_EQ(edge->dim, 1);
  // Every node on the line y = z = 0, and every such node of the mesh, the ends included.
  std::vector<Index> on_line;
  for (Index a = 0; a < m.n_nodes(); ++a)
    if (std::abs(m.nodes(1, a)) < 1e-12 && std::abs(m.nodes(2, a)) < 1e-12) on_line.push_back(a);
  EXPECT_EQ(edge->nodes, on_line);
  EXPECT_GE(on_line.size(), 5u);  // 1 m at mesh size 0.25 m
  EXPECT_EQ(m.nodes_with_tag("edge"), on_line);
  EXPECT_TRUE(m.faces_with_tag("edge").empty());
  const NodeSet* corner = m.find_node_set("corner");
  ASSERT_NE(corner, nullptr);
  EXPECT_EQ(corner->dim, 0);
  ASSERT_EQ(corner->nodes.size(), 1u);
  EXPECT_LE(m.nodes.col(corner->nodes[0]).norm(), 1e-12);
  ASSERT_NE(m.find_node_set("0:42"), nullptr);  // an unnamed point
  EXPECT_EQ(m.tag_list(), "z0, edge (curve), corner (point), 0:42 (point)");
  EXPECT_NE(m.no_surface("edge").find("boundary 'edge' is a curve"), std::string::npos);
  EXPECT_NE(m.no_surface("corner").find("boundary 'corner' is a point"), std::string::npos);
  EXPECT_NE(m.no_surface("nothing").find("does not exist"), std::string::npos);
}

TEST_F(GmshFile, RefusesACurveNamedAsASurface) {
  test::expect_input_error(
      [&] {
        (void)read_gmsh(write_file("clash.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Surface("side") = {1};
Physical Curve("side") = {1};
Mesh.MeshSizeMax = 0.5;
)"));
      },
      {"clash.geo", "physical group 'side' of dimension 1", "the name of a physical surface"});
}

// @sect: refused meshes.

const char* const kHexMsh = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
8
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
$EndNodes
$Elements
1
3 5 2 0 1 1 2 3 4 5 6 7 8
$EndElements
)";

TEST_F(GmshFile, RefusesHexahedra) {
  test::expect_input_error([&] { read_gmsh(write_file("hex.msh", kHexMsh)); },
                           {"hex.msh", "Hexahedron", "Recombine"});
}

// One tetrahedron (Gmsh element 7) on nodes 1-4, then `extra` nodes and elements.
std::string one_tet_msh(const std::string& tet_nodes, const std::string& extra_nodes = "",
                        int n_extra_nodes = 0, const std::string& extra_elements = "",
                        int n_extra_elements = 0) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 3 \"contact\"\n"
         "$EndPhysicalNames\n$Nodes\n" +
         std::to_string(4 + n_extra_nodes) + "\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n" +
         extra_nodes + "$EndNodes\n$Elements\n" + std::to_string(1 + n_extra_elements) +
         "\n7 4 2 0 1 " + tet_nodes + "\n" + extra_elements + "$EndElements\n";
}

TEST_F(GmshFile, AcceptsTheHandWrittenTetrahedron) {
  const TetMesh m = read_gmsh(write_file("tet.msh", one_tet_msh("1 2 3 4")));
  EXPECT_EQ(m.n_tets(), 1);
  EXPECT_NEAR(total_volume(m), 1.0 / 6.0, 1e-15);
}

TEST_F(GmshFile, RefusesInvertedTetrahedron) {
  test::expect_input_error([&] { read_gmsh(write_file("inverted.msh", one_tet_msh("1 3 2 4"))); },
                           {"inverted.msh", "inverted", "Gmsh element 7"});
}

TEST_F(GmshFile, RefusesNodeOfNoTetrahedron) {
  // Gmsh node 15 carries only a point element (Gmsh type 15): it belongs to no tetrahedron.
  const std::string msh = one_tet_msh("1 2 3 4", "15 5 5 5\n", 1, "9 15 2 0 3 15\n", 1);
  test::expect_input_error([&] { read_gmsh(write_file("unused.msh", msh)); },
                           {"unused.msh", "Gmsh node 15"});
}

TEST_F(GmshFile, RefusesTaggedTriangleThatIsNoTetFace) {
  // A second tetrahedron (2 3 4 5); the group "contact" has the triangle 1 2 5 (Gmsh element 20)
  // on neither and the face 1 3 2 of the first: neither a boundary nor a rigid surface.
  const std::string msh = one_tet_msh("1 2 3 4", "5 1 1 1\n", 1,
                                      "8 4 2 0 1 2 3 4 5\n20 2 2 3 5 1 2 5\n21 2 2 3 5 1 3 2\n", 3);
  test::expect_input_error(
      [&] { read_gmsh(write_file("loose.msh", msh)); },
      {"loose.msh", "Gmsh element 20", "contact", "1 of its 2", "rigid surface"});
}

// @sect: rigid surfaces.

// The corners of the unit cube, corner i + 2 j + 4 k at (i, j, k).
Vec3 cube_corner(int c) {
  return Vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
}

// An MSH 2.2 file: the unit cube cut into six tetrahedra around its diagonal (Gmsh elements 1-6,
// physical volume "block"), its bottom z = 0 (elements 7, 8, physical surface "bottom"), and the
// square [0, 1]^2 at z = 2 (elements 9, 10, physical surface "plate") on Gmsh nodes 5, 6, 11, 12
// between the cube's (1-4 and 7-10 for corners 0-7); then the element lines `extra`.
std::string block_and_plate_msh(const std::string& extra = "", int n_extra = 0) {
  const std::array<int, 8> tag_of_corner{1, 2, 3, 4, 7, 8, 9, 10};
  std::string nodes;
  for (int c = 0; c < 8; ++c) {
    const Vec3 x = cube_corner(c);
    nodes += fmt::format("{} {} {} {}\n", tag_of_corner[c], x(0), x(1), x(2));
  }
  nodes += "5 0 0 2\n6 1 0 2\n11 1 1 2\n12 0 1 2\n";
  std::string elements;
  int element = 1;
  std::array<int, 3> axes{0, 1, 2};
  do {  // corners 0, e_a, e_a + e_b, 7 for each order (a, b, c) of the axes
    std::array<int, 4> tet{0, 1 << axes[0], (1 << axes[0]) + (1 << axes[1]), 7};
    if (signed_volume(cube_corner(tet[0]), cube_corner(tet[1]), cube_corner(tet[2]),
                      cube_corner(tet[3])) < 0)
      std::swap(tet[2], tet[3]);
    elements += fmt::format("{} 4 2 1 1 {} {} {} {}\n", element++, tag_of_corner[tet[0]],
                            tag_of_corner[tet[1]], tag_of_corner[tet[2]], tag_of_corner[tet[3]]);
  } while (std::next_permutation(axes.begin(), axes.end()));
  elements += "7 2 2 2 2 1 2 4\n8 2 2 2 2 1 4 3\n";  // corners 0 1 3, 0 3 2
  elements += "9 2 2 3 3 5 6 11\n10 2 2 3 3 5 11 12\n";
  return fmt::format(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n3 1 \"block\"\n2 2 "
      "\"bottom\"\n2 3 \"plate\"\n$EndPhysicalNames\n$Nodes\n12\n{}$EndNodes\n$Elements\n{}\n{}{}"
      "$EndElements\n",
      nodes, 10 + n_extra, elements, extra);
}

void expect_block_and_plate(const TetMesh& m) {
  // The block as it is, with its nodes only.
  ASSERT_EQ(m.n_nodes(), 8);
  for (int c = 0; c < 8; ++c)
    EXPECT_EQ(m.nodes.col(c), cube_corner(c)) << c;
  EXPECT_FALSE(first_unused_node(m).has_value());
  EXPECT_EQ(m.n_tets(), 6);
  EXPECT_NEAR(total_volume(m), 1.0, 1e-15);
  EXPECT_EQ(m.tag_names, std::vector<std::string>{"bottom"});
  EXPECT_NEAR(tag_area(m, "bottom"), 1.0, 1e-15);
  EXPECT_NEAR((tag_area_normal(m, "bottom") + Vec3::UnitZ()).norm(), 0.0, 1e-15);
  // The plate: its own four points, in the order of their Gmsh tags, and its triangles as given.
  ASSERT_EQ(m.rigid_surfaces.size(), 1u);
  const RigidSurface* plate = m.find_rigid_surface("plate");
  ASSERT_NE(plate, nullptr);
  Eigen::Matrix<Real, 3, 4> points;
  points << 0, 1, 1, 0, 0, 0, 1, 1, 2, 2, 2, 2;
  EXPECT_EQ(plate->points, points);
  Eigen::Matrix<Index, 3, 2> triangles;
  triangles << 0, 0, 1, 2, 2, 3;
  EXPECT_EQ(plate->triangles, triangles);
}

TEST_F(GmshFile, ASurfaceOffTheTetrahedraIsARigidSurface) {
  TetMesh m = read_gmsh(write_file("plate.msh", block_and_plate_msh()));
  expect_block_and_plate(m);
  EXPECT_EQ(m.find_tag("plate"), -1);
  EXPECT_TRUE(m.faces_with_tag("plate").empty());
  EXPECT_EQ(m.find_rigid_surface("bottom"), nullptr);
  EXPECT_EQ(m.tag_list(), "bottom, plate (rigid surface)");
  const std::string why = m.no_surface("plate");
  for (const char* part : {"boundary 'plate' is a rigid surface", "not a boundary of an elastic",
                           "kind = \"surface\", boundary = \"plate\""})
    EXPECT_NE(why.find(part), std::string::npos) << why;
  // A change of unit scales the plate with the block.
  scale_lengths(m, 1e-3);
  EXPECT_NEAR((m.nodes.col(7) - Vec3(1e-3, 1e-3, 1e-3)).norm(), 0.0, 1e-18);
  EXPECT_NEAR((m.rigid_surfaces[0].points.col(2) - Vec3(1e-3, 1e-3, 2e-3)).norm(), 0.0, 1e-18);
  // A part of the mesh keeps the rigid surfaces.
  const TetMesh part = submesh(m, {0, 1});
  ASSERT_EQ(part.rigid_surfaces.size(), 1u);
  EXPECT_EQ(part.rigid_surfaces[0].points, m.rigid_surfaces[0].points);
}

TEST_F(GmshFile, RigidSurfacesRoundTrip) {
  const TetMesh m = read_gmsh(write_file("plate.msh", block_and_plate_msh()));
  for (int version : {kMsh41, kMsh22}) {
    const fs::path file = test_dir() / fmt::format("plate_back{}.msh", version);
    write_gmsh(file, m, version);
    SCOPED_TRACE(version);
    expect_block_and_plate(read_gmsh(file));
  }
}

TEST_F(GmshFile, ATriangleOnNodesOfTheTetrahedraMayBeARigidSurface) {
  // The triangle 1 2 5 is no face of the tetrahedra 1 2 3 4 and 2 3 4 5, though its nodes are
  // theirs: a rigid surface with copies of them, every node staying in the mesh.
  const std::string msh =
      one_tet_msh("1 2 3 4", "5 1 1 1\n", 1, "8 4 2 0 1 2 3 4 5\n20 2 2 3 5 1 2 5\n", 2);
  const TetMesh m = read_gmsh(write_file("loose.msh", msh));
  EXPECT_EQ(m.n_nodes(), 5);
  ASSERT_EQ(m.rigid_surfaces.size(), 1u);
  EXPECT_EQ(m.rigid_surfaces[0].name, "contact");
  Eigen::Matrix<Real, 3, 3> points;
  points << 0, 1, 1, 0, 0, 1, 0, 0, 1;
  EXPECT_EQ(m.rigid_surfaces[0].points, points);
  EXPECT_TRUE(m.tag_names.empty());
}

TEST_F(GmshFile, RefusesASurfacePartlyOnTheTetrahedra) {
  // A triangle of the block's bottom in the group "plate" too.
  test::expect_input_error(
      [&] { read_gmsh(write_file("mixed.msh", block_and_plate_msh("11 2 2 3 3 1 2 4\n", 1))); },
      {"mixed.msh", "physical group 'plate'", "Gmsh element", "is no face of any tetrahedron",
       "1 of its 3"});
}

const char* const kBlockAndPlateGeo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Rectangle(10) = {0, 0, 2, 1, 1};
Mesh.MeshSizeMax = 0.5;
Physical Volume("block") = {1};
Physical Surface("bottom") = {5};
Physical Surface("plate") = {10};
)";

TEST_F(GmshFile, GeoSurfaceMeshedAloneIsARigidSurface) {
  const TetMesh m = read_gmsh(write_file("plate.geo", kBlockAndPlateGeo));
  EXPECT_NEAR(total_volume(m), 1.0, 1e-12);
  EXPECT_EQ(m.tag_names, std::vector<std::string>{"bottom"});
  EXPECT_FALSE(first_unused_node(m).has_value());
  EXPECT_LE(m.nodes.row(2).maxCoeff(), 1.0);
  const RigidSurface* plate = m.find_rigid_surface("plate");
  ASSERT_NE(plate, nullptr);
  EXPECT_GE(plate->triangles.cols(), 8);
  Real area = 0.0;
  for (Index t = 0; t < plate->triangles.cols(); ++t) {
    const Vec3 a = plate->points.col(plate->triangles(0, t));
    area += 0.5 * (plate->points.col(plate->triangles(1, t)) - a)
                      .cross(plate->points.col(plate->triangles(2, t)) - a)
                      .norm();
  }
  EXPECT_NEAR(area, 1.0, 1e-12);
  EXPECT_NEAR((plate->points.row(2).array() - 2.0).abs().maxCoeff(), 0.0, 1e-12);
}

TEST_F(GmshFile, RefusesACurveOnARigidSurfaceOnly) {
  test::expect_input_error(
      [&] {
        (void)read_gmsh(write_file("rim.geo", std::string(kBlockAndPlateGeo) + R"(e = 1e-6;
Physical Curve("rim") = Curve In BoundingBox{-e, -e, 2 - e, 1 + e, e, 2 + e};
)"));
      },
      {"rim.geo", "physical curve 'rim'", "only to a rigid surface"});
}

TEST_F(GmshFile, RefusesMissingFile) {
  test::expect_input_error([&] { read_gmsh(test_dir() / "nowhere.msh"); },
                           {"nowhere.msh", "no such file"});
}

TEST_F(GmshFile, RefusesGarbage) {
  test::expect_input_error(
      [&] { read_gmsh(write_file("garbage.msh", "this is not a mesh\n1 2 3\n$Nodes\nx\n")); },
      {"garbage.msh"});
}

}  // namespace
