// mesh::faces_of and mesh::submesh, the parts of a mesh that the ranks of a distributed run hold:
// over a split of the tetrahedra every boundary triangle lands in exactly one part, once per tag
// it carries, and each part is a mesh of its own with the geometry of the whole.
#include <gtest/gtest.h>

#include <vector>

#include "common/fixtures.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::mesh;

namespace {

// The brick with its top face also tagged "top" (each of those triangles listed twice), and
// two regions.
TetMesh brick_with_a_second_tag() {
  TetMesh m = make_brick(BrickSpec{Vec3(3.0, 1.0, 1.0), {6, 2, 2}});
  test::add_second_tag(m, "z1", "top");
  m.region_names = {"left", "right"};
  for (Index t = 0; t < m.n_tets(); ++t)
    m.tet_region.push_back(m.nodes(0, m.tets(0, t)) < 1.5 ? 0 : 1);
  return m;
}

std::vector<std::vector<Index>> interleaved(const TetMesh& m, int n_parts) {
  std::vector<std::vector<Index>> parts(static_cast<size_t>(n_parts));
  for (Index t = 0; t < m.n_tets(); ++t)
    parts[static_cast<size_t>(t % n_parts)].push_back(t);
  return parts;
}

TEST(FacesOf, EveryTriangleOfEveryTagIsInExactlyOnePart) {
  const TetMesh m = brick_with_a_second_tag();
  std::vector<int> count(static_cast<size_t>(m.n_faces()), 0);
  for (const auto& part : interleaved(m, 3)) {
    const std::vector<bool> mine = faces_of(m, part);
    for (Index f = 0; f < m.n_faces(); ++f)
      count[static_cast<size_t>(f)] += mine[static_cast<size_t>(f)] ? 1 : 0;
  }
  for (Index f = 0; f < m.n_faces(); ++f)
    EXPECT_EQ(count[static_cast<size_t>(f)], 1) << "boundary triangle " << f;
}

TEST(Submesh, PartsKeepTheGeometryTagsAndRegionsOfTheWhole) {
  const TetMesh m = brick_with_a_second_tag();
  Real volume = 0.0, top_area = 0.0, whole_top_area = 0.0;
  for (Index f : m.faces_with_tag("top"))
    whole_top_area += face_area(m, f);
  Index n_faces = 0;
  for (const auto& elements : interleaved(m, 3)) {
    std::vector<Index> nodes;
    const TetMesh part = submesh(m, elements, &nodes);
    ASSERT_EQ(part.n_tets(), static_cast<Index>(elements.size()));
    ASSERT_EQ(part.n_nodes(), static_cast<Index>(nodes.size()));
    EXPECT_LT(part.n_nodes(), m.n_nodes());
    EXPECT_EQ(part.tag_names, m.tag_names);
    EXPECT_EQ(part.region_names, m.region_names);
    ASSERT_EQ(part.face_entity.size(), static_cast<size_t>(part.n_faces()));
    for (size_t k = 0; k < elements.size(); ++k) {
      const Index t = elements[k];
      EXPECT_EQ(part.region(static_cast<Index>(k)), m.region(t));
      for (int a = 0; a < 4; ++a)
        EXPECT_EQ(nodes[static_cast<size_t>(part.tets(a, static_cast<Index>(k)))], m.tets(a, t));
      EXPECT_DOUBLE_EQ(tet_volume(part, static_cast<Index>(k)), tet_volume(m, t));
      volume += tet_volume(part, static_cast<Index>(k));
    }
    for (Index f : part.faces_with_tag("top"))
      top_area += face_area(part, f);
    n_faces += part.n_faces();
    EXPECT_NO_THROW(check_mesh(part, "a part of the brick"));
  }
  EXPECT_NEAR(volume, 3.0, 1e-12);
  EXPECT_NEAR(top_area, whole_top_area, 1e-12);
  EXPECT_EQ(n_faces, m.n_faces());
}

}  // namespace

namespace {

// A part holds the nodes of each node set (a curve, a point) that are its own, renumbered, and
// every node set by name, empty where it holds none of its nodes.
TEST(Submesh, PartsKeepTheirNodesOfEachNodeSet) {
  TetMesh m = make_brick(BrickSpec{Vec3(3.0, 1.0, 1.0), {6, 2, 2}});
  NodeSet edge{"edge", 1, {}};
  for (Index a = 0; a < m.n_nodes(); ++a)
    if (m.nodes(1, a) == 0.0 && m.nodes(2, a) == 0.0) edge.nodes.push_back(a);
  m.node_sets.push_back(edge);
  check_mesh(m, "test");
  std::vector<int> seen(static_cast<size_t>(m.n_nodes()), 0);
  for (const auto& elements : interleaved(m, 3)) {
    std::vector<Index> nodes;
    const TetMesh part = submesh(m, elements, &nodes);
    ASSERT_EQ(part.node_sets.size(), 1u);
    EXPECT_EQ(part.node_sets[0].name, "edge");
    EXPECT_NO_THROW(check_mesh(part, "part"));
    for (Index local : part.node_sets[0].nodes) {
      const Index global = nodes[static_cast<size_t>(local)];
      EXPECT_EQ(m.nodes(1, global), 0.0);
      EXPECT_EQ(m.nodes(2, global), 0.0);
      seen[static_cast<size_t>(global)] = 1;
    }
  }
  for (Index a : edge.nodes)
    EXPECT_EQ(seen[static_cast<size_t>(a)], 1) << "node " << a << " of the edge in no part";
}

}  // namespace
