// mesh::find_bodies, the connected bodies of a mesh (tetrahedra joined through shared nodes), and
// mesh::disjoint_union, which puts meshes side by side: one brick is one body; two bricks that
// share no node are two, even where their faces coincide; bricks that share a single node are one.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::mesh;

namespace {

const BrickSpec kSmall{Vec3(3.0, 1.0, 1.0), {3, 2, 2}};
const BrickSpec kTiny{Vec3(1.0, 1.0, 1.0), {1, 1, 1}};

TetMesh shifted(TetMesh m, const Vec3& by) {
  m.nodes.colwise() += by;
  return m;
}

std::vector<Index> range(Index first, Index count) {
  std::vector<Index> r(static_cast<size_t>(count));
  std::iota(r.begin(), r.end(), first);
  return r;
}

TEST(Bodies, OneBrickIsOneBody) {
  const TetMesh m = make_brick(kSmall);
  const Bodies b = find_bodies(m);
  ASSERT_EQ(b.n_bodies(), 1);
  EXPECT_EQ(b.nodes[0], range(0, m.n_nodes()));
  EXPECT_EQ(b.tets[0], range(0, m.n_tets()));
  EXPECT_EQ(b.regions[0], std::vector<int>{0});
  EXPECT_EQ(b.node_body, std::vector<Index>(static_cast<size_t>(m.n_nodes()), 0));
  EXPECT_EQ(b.tet_body, std::vector<Index>(static_cast<size_t>(m.n_tets()), 0));
  const BoundingBox box = bounding_box(m, b.nodes[0]);
  EXPECT_EQ(box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(box.hi, Vec3(3, 1, 1));
  EXPECT_EQ(describe_body(m, b, 0), "body 0 (region \"body\", " + std::to_string(m.n_nodes()) +
                                        " nodes in [0, 3] x [0, 1] x [0, 1] m)");
}

TEST(Bodies, TwoDisjointBricksAreTwoBodiesWithTheirNodesTetrahedraAndRegions) {
  const TetMesh a = make_brick(kSmall);
  const TetMesh m = disjoint_union({a, shifted(make_brick(kTiny), Vec3(5, 0, 0))}, {"a_", "b_"});
  const Index na = a.n_nodes(), ta = a.n_tets();
  const Bodies b = find_bodies(m);
  ASSERT_EQ(b.n_bodies(), 2);
  EXPECT_EQ(b.nodes[0], range(0, na));
  EXPECT_EQ(b.nodes[1], range(na, m.n_nodes() - na));
  EXPECT_EQ(b.tets[0], range(0, ta));
  EXPECT_EQ(b.tets[1], range(ta, m.n_tets() - ta));
  for (Index v = 0; v < m.n_nodes(); ++v)
    EXPECT_EQ(b.node_body[static_cast<size_t>(v)], v < na ? 0 : 1) << "node " << v;
  for (Index t = 0; t < m.n_tets(); ++t)
    EXPECT_EQ(b.tet_body[static_cast<size_t>(t)], t < ta ? 0 : 1) << "tetrahedron " << t;
  ASSERT_EQ(m.region_names, (std::vector<std::string>{"a_body", "b_body"}));
  EXPECT_EQ(b.regions[0], std::vector<int>{0});
  EXPECT_EQ(b.regions[1], std::vector<int>{1});
  EXPECT_EQ(describe_body(m, b, 1),
            "body 1 (region \"b_body\", 8 nodes in [5, 6] x [0, 1] x [0, 1] m)");
  // The tags of each part, renamed, on its own faces.
  for (Index f : m.faces_with_tag("b_x0"))
    EXPECT_EQ(b.node_body[static_cast<size_t>(m.faces(0, f))], 1);
  EXPECT_EQ(m.faces_with_tag("a_x0").size(), a.faces_with_tag("x0").size());
}

// Bodies are numbered by their first tetrahedron, whatever their node numbers.
TEST(Bodies, AreNumberedInTheOrderOfTheirFirstTetrahedron) {
  TetMesh m =
      disjoint_union({make_brick(kTiny), shifted(make_brick(kTiny), Vec3(2, 0, 0))}, {"a_", "b_"});
  m.tets.col(0).swap(m.tets.col(m.n_tets() - 1));  // the first tetrahedron is now b's
  std::swap(m.tet_region.front(), m.tet_region.back());
  const Bodies b = find_bodies(m);
  ASSERT_EQ(b.n_bodies(), 2);
  EXPECT_EQ(b.tet_body[0], 0);
  EXPECT_EQ(b.node_body[static_cast<size_t>(m.n_nodes() - 1)], 0);  // a node of b
  EXPECT_EQ(b.node_body[0], 1);                                     // a node of a
  EXPECT_EQ(b.regions[0], std::vector<int>{1});
}

// Coinciding faces do not join bodies: only shared nodes do (two Gmsh volumes meshed apart).
TEST(Bodies, BricksTouchingAlongAFaceWithoutSharedNodesAreTwoBodies) {
  const TetMesh m =
      disjoint_union({make_brick(kTiny), shifted(make_brick(kTiny), Vec3(1, 0, 0))}, {"a_", "b_"});
  EXPECT_EQ(find_bodies(m).n_bodies(), 2);
}

// A single shared node joins two bricks into one body (a hinge; see bodies.hpp).
TEST(Bodies, BricksSharingOneNodeAreOneBody) {
  TetMesh m =
      disjoint_union({make_brick(kTiny), shifted(make_brick(kTiny), Vec3(1, 1, 1))}, {"a_", "b_"});
  const Index corner_a = brick_node(kTiny, 1, 1, 1), corner_b = 8 + brick_node(kTiny, 0, 0, 0);
  ASSERT_EQ(m.nodes.col(corner_a), m.nodes.col(corner_b));
  for (Index t = 0; t < m.n_tets(); ++t)
    for (int v = 0; v < 4; ++v)
      if (m.tets(v, t) == corner_b) m.tets(v, t) = corner_a;  // corner_b is left unused
  const Bodies b = find_bodies(m);
  ASSERT_EQ(b.n_bodies(), 1);
  EXPECT_EQ(b.node_body[static_cast<size_t>(corner_b)], -1);
  EXPECT_EQ(b.nodes[0].size(), static_cast<size_t>(m.n_nodes() - 1));
  EXPECT_EQ(b.regions[0], (std::vector<int>{0, 1}));
}

TEST(Bodies, DisjointUnionKeepsTheFaceEntitiesOfDifferentPartsApart) {
  const TetMesh a = make_brick(kSmall);
  const TetMesh m = disjoint_union({a, a}, {"", "b_"});
  std::vector<int> first(m.face_entity.begin(), m.face_entity.begin() + a.n_faces());
  std::vector<int> second(m.face_entity.begin() + a.n_faces(), m.face_entity.end());
  EXPECT_EQ(first, a.face_entity);
  const int max_first = *std::max_element(first.begin(), first.end());
  for (int e : second)
    EXPECT_GT(e, max_first);
  check_mesh(m, "disjoint_union");
}

}  // namespace
