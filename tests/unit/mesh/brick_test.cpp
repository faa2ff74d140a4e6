// Tests of the brick generator against the paper's counts and exact geometry.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "fricon/core/error.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::mesh;

namespace {
BrickSpec paper_brick(Index n) {
  return BrickSpec{Vec3(3.0, 1.0, 1.0), {3 * n, n, n}};
}
}  // namespace

TEST(Brick, CountsMatchThePaper) {
  for (Index n : {4, 6, 8}) {
    const TetMesh m = make_brick(paper_brick(n));
    EXPECT_EQ(m.n_nodes(), (3 * n + 1) * (n + 1) * (n + 1));
    EXPECT_EQ(m.n_tets(), 15 * n * n * n);
    // Boundary: two triangles per boundary square.
    EXPECT_EQ(m.n_faces(), 2 * (2 * 3 * n * n + 2 * 3 * n * n + 2 * n * n));
  }
}

TEST(Brick, EveryTetrahedronIsPositivelyOriented) {
  const TetMesh m = make_brick(BrickSpec{Vec3(2.0, 1.5, 0.5), {5, 3, 4}});
  for (Index t = 0; t < m.n_tets(); ++t)
    EXPECT_GT(tet_volume(m, t), 0.0) << "tet " << t;
  EXPECT_NO_THROW(check_mesh(m, "brick"));
}

TEST(Brick, VolumeIsExact) {
  const BrickSpec spec{Vec3(2.0, 1.5, 0.5), {5, 3, 4}};
  const TetMesh m = make_brick(spec);
  Real volume = 0;
  for (Index t = 0; t < m.n_tets(); ++t)
    volume += tet_volume(m, t);
  EXPECT_NEAR(volume, 2.0 * 1.5 * 0.5, 1e-13);
}

TEST(Brick, IsConforming) {
  // Odd and even cell counts: each interior triangle is shared by exactly two tetrahedra.
  for (const BrickSpec& spec : {paper_brick(4), BrickSpec{Vec3(1, 1, 1), {3, 5, 2}}}) {
    const TetMesh m = make_brick(spec);
    const FaceSharing s = face_sharing(m);
    EXPECT_EQ(s.n_overshared, 0);
    EXPECT_EQ(s.n_boundary, m.n_faces());
    // Euler: 4 faces per tet = 2 per interior face + 1 per boundary face.
    EXPECT_EQ(4 * m.n_tets(), 2 * s.n_interior + s.n_boundary);
  }
}

TEST(Brick, BoundaryAreaPerTag) {
  const BrickSpec spec{Vec3(3.0, 1.0, 2.0), {6, 2, 4}};
  const TetMesh m = make_brick(spec);
  const std::map<std::string, Real> expected{{"x0", 2.0}, {"x1", 2.0}, {"y0", 6.0},
                                             {"y1", 6.0}, {"z0", 3.0}, {"z1", 3.0}};
  for (const auto& [tag, area] : expected) {
    Real sum = 0;
    for (Index f : m.faces_with_tag(tag))
      sum += face_area(m, f);
    EXPECT_NEAR(sum, area, 1e-13) << tag;
  }
}

TEST(Brick, BoundaryNormalsPointOutward) {
  const TetMesh m = make_brick(paper_brick(2));
  const std::map<std::string, Vec3> outward{{"x0", -Vec3::UnitX()}, {"x1", Vec3::UnitX()},
                                            {"y0", -Vec3::UnitY()}, {"y1", Vec3::UnitY()},
                                            {"z0", -Vec3::UnitZ()}, {"z1", Vec3::UnitZ()}};
  for (const auto& [tag, n] : outward)
    for (Index f : m.faces_with_tag(tag))
      EXPECT_NEAR((face_normal(m, f) - n).norm(), 0.0, 1e-14);
}

TEST(Brick, ContactFaceDiagonalsFollowParity) {
  // theory.md §7.2: on z = 0 the square [i,i+1]x[j,j+1] is cut along (i,j)-(i+1,j+1) if i+j is
  // even, else along (i+1,j)-(i,j+1). So nodes with even i+j touch 8 triangles inside the face.
  const BrickSpec spec = paper_brick(4);
  const TetMesh m = make_brick(spec);
  std::map<Index, int> triangles_at;
  for (Index f : m.faces_with_tag("z0"))
    for (int v = 0; v < 3; ++v)
      ++triangles_at[m.faces(v, f)];
  for (Index j = 1; j < spec.cells[1]; ++j)
    for (Index i = 1; i < spec.cells[0]; ++i)
      EXPECT_EQ(triangles_at[brick_node(spec, i, j, 0)], (i + j) % 2 == 0 ? 8 : 4)
          << "node (" << i << "," << j << ")";
}

TEST(Brick, EachSideIsAChessboardOfTwoByTwoBlocks) {
  // Even counts: each block of a side is 2 x 2 cells, i.e. 8 triangles of area 4 cell faces.
  const BrickSpec spec{Vec3(3.0, 1.0, 2.0), {6, 2, 4}};
  const TetMesh m = make_brick(spec);
  ASSERT_EQ(m.face_entity.size(), static_cast<size_t>(m.n_faces()));
  const std::array<Real, 3> h{3.0 / 6, 1.0 / 2, 2.0 / 4};
  std::map<int, Real> area_of;
  std::map<int, std::set<int>> entities_of_tag;
  for (Index f = 0; f < m.n_faces(); ++f) {
    area_of[m.face_entity[f]] += face_area(m, f);
    entities_of_tag[m.face_tag[f]].insert(m.face_entity[f]);
  }
  for (int side = 0; side < 6; ++side) {
    const int d = side / 2, p = (d + 1) % 3, q = (d + 2) % 3;
    EXPECT_EQ(static_cast<Index>(entities_of_tag[side].size()),
              (spec.cells[p] / 2) * (spec.cells[q] / 2))
        << m.tag_names[side];
    for (int e : entities_of_tag[side])
      EXPECT_NEAR(area_of[e], 4 * h[p] * h[q], 1e-13) << m.tag_names[side] << " entity " << e;
  }
  // Numbered 1, 2, ... with no entity on two sides.
  EXPECT_EQ(area_of.begin()->first, 1);
  EXPECT_EQ(area_of.rbegin()->first, static_cast<int>(area_of.size()));
}

TEST(Brick, OddCellCountsEndWithNarrowBlocks) {
  const BrickSpec spec{Vec3(1, 1, 1), {3, 5, 2}};
  const TetMesh m = make_brick(spec);
  std::map<int, std::set<int>> entities_of_tag;
  std::map<int, int> tag_of_entity;
  for (Index f = 0; f < m.n_faces(); ++f) {
    entities_of_tag[m.face_tag[f]].insert(m.face_entity[f]);
    const auto [it, inserted] = tag_of_entity.emplace(m.face_entity[f], m.face_tag[f]);
    EXPECT_EQ(it->second, m.face_tag[f]) << "entity " << m.face_entity[f] << " on two sides";
  }
  // Blocks per direction: 3 cells -> 2, 5 -> 3, 2 -> 1.
  const std::map<std::string, size_t> expected{{"x0", 3}, {"x1", 3}, {"y0", 2},
                                               {"y1", 2}, {"z0", 6}, {"z1", 6}};
  for (const auto& [tag, count] : expected)
    EXPECT_EQ(entities_of_tag[m.find_tag(tag)].size(), count) << tag;
}

TEST(Brick, RejectsBadSizes) {
  EXPECT_THROW(make_brick(BrickSpec{Vec3(-1, 1, 1), {1, 1, 1}}), InputError);
  EXPECT_THROW(make_brick(BrickSpec{Vec3(1, 1, 1), {0, 1, 1}}), InputError);
}

TEST(Mesh, CheckRejectsInvertedAndDegenerateTetrahedra) {
  TetMesh m = make_brick(BrickSpec{Vec3(1, 1, 1), {1, 1, 1}});
  TetMesh inverted = m;
  std::swap(inverted.tets(0, 2), inverted.tets(1, 2));
  try {
    check_mesh(inverted, "test.msh");
    FAIL() << "inverted tetrahedron accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.msh: tetrahedron 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
  }
  TetMesh flat = m;
  flat.nodes.row(2).setZero();  // all nodes in the plane z = 0
  EXPECT_THROW(check_mesh(flat, "flat"), InputError);
  TetMesh empty;
  EXPECT_THROW(check_mesh(empty, "empty"), InputError);
}
