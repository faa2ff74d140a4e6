// feti::partition_mesh, the subdomains of the Total FETI backend: every tetrahedron in exactly
// one subdomain, every subdomain face-connected (checked here by a search of our own over the
// faces) and inside one body, about as many subdomains as asked, distributed over the bodies by
// their size; bad requests are InputErrors naming solver.subdomains. feti::subdomains_for_size
// turns nodes per subdomain into a count that partition_mesh accepts; feti::node_owners picks
// the copy of each node that carries its rows.
#include "fricon/feti/partition.hpp"
#include "fricon/feti/subdomains.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::feti;
using mesh::BrickSpec;
using mesh::TetMesh;

namespace {

const BrickSpec kBar{Vec3(3.0, 1.0, 1.0), {12, 4, 4}};  // 960 tetrahedra, 325 nodes
const BrickSpec kCube{Vec3(1.0, 1.0, 1.0), {2, 2, 2}};  // 40 tetrahedra
const BrickSpec kTiny{Vec3(1.0, 1.0, 1.0), {1, 1, 1}};  // 5 tetrahedra, 8 nodes
const std::string kWhere = "problem.toml:7:14";

TetMesh shifted(TetMesh m, const Vec3& by) {
  m.nodes.colwise() += by;
  return m;
}

// The bar and, 5 m beside it, a cube: two bodies of 960 and 40 tetrahedra.
TetMesh bar_and_cube() {
  return mesh::disjoint_union(
      {mesh::make_brick(kBar), shifted(mesh::make_brick(kCube), Vec3(5, 0, 0))}, {"", "cube_"});
}

// Two cubes sharing only the corner (1, 1, 1): one body (a node joins them) in two face-connected
// pieces, tetrahedra 0..39 and 40..79.
TetMesh hinged_cubes() {
  TetMesh m = mesh::disjoint_union(
      {mesh::make_brick(kCube), shifted(mesh::make_brick(kCube), Vec3(1, 1, 1))}, {"a_", "b_"});
  const Index corner_a = mesh::brick_node(kCube, 2, 2, 2);
  const Index corner_b = 27 + mesh::brick_node(kCube, 0, 0, 0);
  for (Index t = 0; t < m.n_tets(); ++t)
    for (int v = 0; v < 4; ++v)
      if (m.tets(v, t) == corner_b) m.tets(v, t) = corner_a;
  return m;
}

// The tetrahedra that share a face with each tetrahedron, from the sorted corners of each face.
std::vector<std::vector<Index>> face_neighbours(const TetMesh& m) {
  std::map<std::array<Index, 3>, std::vector<Index>> tets_of_face;
  for (Index t = 0; t < m.n_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> face{};
      int k = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) face[static_cast<size_t>(k++)] = m.tets(a, t);
      std::sort(face.begin(), face.end());
      tets_of_face[face].push_back(t);
    }
  std::vector<std::vector<Index>> neighbours(static_cast<size_t>(m.n_tets()));
  for (const auto& [face, tets] : tets_of_face)
    for (Index t : tets)
      for (Index u : tets)
        if (t != u) neighbours[static_cast<size_t>(t)].push_back(u);
  return neighbours;
}

// Whether the tetrahedra `tets` (non-empty) are face-connected: a breadth-first search from the
// first, through faces to tetrahedra of the set, reaches them all.
bool face_connected(const std::vector<std::vector<Index>>& neighbours,
                    const std::vector<Index>& tets) {
  std::vector<bool> in_set(neighbours.size(), false), reached(neighbours.size(), false);
  for (Index t : tets)
    in_set[static_cast<size_t>(t)] = true;
  std::vector<Index> queue{tets.front()};
  reached[static_cast<size_t>(tets.front())] = true;
  for (size_t head = 0; head < queue.size(); ++head)
    for (Index u : neighbours[static_cast<size_t>(queue[head])])
      if (in_set[static_cast<size_t>(u)] && !reached[static_cast<size_t>(u)]) {
        reached[static_cast<size_t>(u)] = true;
        queue.push_back(u);
      }
  return queue.size() == tets.size();
}

// The invariants of every partition of `m`: each tetrahedron in exactly one subdomain, listed in
// it ascending, as subdomain_of_tet says; no subdomain empty, face-connected, inside one body.
void expect_valid(const TetMesh& m, const mesh::Bodies& bodies, const Partition& p) {
  ASSERT_EQ(static_cast<Index>(p.subdomain_of_tet.size()), m.n_tets());
  ASSERT_EQ(static_cast<Index>(p.tets.size()), p.n_subdomains);
  std::vector<int> times_listed(static_cast<size_t>(m.n_tets()), 0);
  const auto neighbours = face_neighbours(m);
  for (Index s = 0; s < p.n_subdomains; ++s) {
    const auto& tets = p.tets[static_cast<size_t>(s)];
    ASSERT_FALSE(tets.empty()) << "subdomain " << s;
    EXPECT_TRUE(std::is_sorted(tets.begin(), tets.end())) << "subdomain " << s;
    const Index body = bodies.tet_body[static_cast<size_t>(tets.front())];
    for (Index t : tets) {
      ASSERT_TRUE(t >= 0 && t < m.n_tets()) << "subdomain " << s << ": tetrahedron " << t;
      ++times_listed[static_cast<size_t>(t)];
      EXPECT_EQ(p.subdomain_of_tet[static_cast<size_t>(t)], s) << "tetrahedron " << t;
      EXPECT_EQ(bodies.tet_body[static_cast<size_t>(t)], body) << "subdomain " << s;
    }
    EXPECT_TRUE(face_connected(neighbours, tets)) << "subdomain " << s;
  }
  for (Index t = 0; t < m.n_tets(); ++t)
    EXPECT_EQ(times_listed[static_cast<size_t>(t)], 1) << "tetrahedron " << t;
}

// The number of subdomains of `p` in each body.
std::vector<Index> subdomains_per_body(const mesh::Bodies& bodies, const Partition& p) {
  std::vector<Index> count(static_cast<size_t>(bodies.n_bodies()), 0);
  for (const auto& tets : p.tets)
    ++count[static_cast<size_t>(bodies.tet_body[static_cast<size_t>(tets.front())])];
  return count;
}

#define SKIP_WITHOUT_METIS() \
  if (!metis_available()) GTEST_SKIP() << "fricon built without METIS (libmetis-dev)"

TEST(Partition, BarIntoSubdomainsCoversEveryTetrahedronOnceWithFaceConnectedSubdomains) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = mesh::make_brick(kBar);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  for (Index requested : {2, 3, 8, 17, 40}) {
    SCOPED_TRACE("solver.subdomains = " + std::to_string(requested));
    const Partition p = partition_mesh(m, bodies, requested, kWhere);
    expect_valid(m, bodies, p);
    // About as many as asked: a part may be split or dropped, but not many.
    EXPECT_GE(p.n_subdomains, requested - requested / 4);
    EXPECT_LE(p.n_subdomains, requested + requested / 4);
    EXPECT_EQ(p.note.empty(), p.n_subdomains == requested && p.n_split == 0) << p.note;
    // Balanced: no subdomain more than twice the mean.
    for (const auto& tets : p.tets)
      EXPECT_LE(static_cast<Index>(tets.size()), 2 * m.n_tets() / p.n_subdomains);
  }
}

TEST(Partition, IsTheSameOnEveryCall) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = mesh::make_brick(kBar);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Partition a = partition_mesh(m, bodies, 6, kWhere);
  const Partition b = partition_mesh(m, bodies, 6, kWhere);
  EXPECT_EQ(a.subdomain_of_tet, b.subdomain_of_tet);
}

TEST(Partition, SubdomainsAreNumberedByTheirFirstTetrahedron) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = mesh::make_brick(kBar);
  const Partition p = partition_mesh(m, mesh::find_bodies(m), 5, kWhere);
  for (Index s = 1; s < p.n_subdomains; ++s)
    EXPECT_LT(p.tets[static_cast<size_t>(s - 1)].front(), p.tets[static_cast<size_t>(s)].front());
}

// The cube has 1/25 of the tetrahedra: of 3 subdomains it gets 1, of 10 still 1, of 50 2 (the
// bar 48, both of 20 tetrahedra per subdomain).
TEST(Partition, DisjointBodiesNeverShareASubdomainAndGetSubdomainsByTheirSize) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = bar_and_cube();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  ASSERT_EQ(bodies.n_bodies(), 2);
  const std::vector<std::array<Index, 2>> requested_and_cube = {{3, 1}, {10, 1}, {50, 2}};
  for (const auto& [requested, cube] : requested_and_cube) {
    SCOPED_TRACE("solver.subdomains = " + std::to_string(requested));
    const Partition p = partition_mesh(m, bodies, requested, kWhere);
    expect_valid(m, bodies, p);  // each subdomain inside one body
    const std::vector<Index> per_body = subdomains_per_body(bodies, p);
    EXPECT_EQ(per_body[1], cube);
    EXPECT_EQ(per_body[0], p.n_subdomains - cube);
    EXPECT_GE(per_body[0], requested - cube - (requested - cube) / 4);
  }
}

TEST(Partition, OneSubdomainPerBodyNeedsNoMetis) {
  const TetMesh m = bar_and_cube();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Partition p = partition_mesh(m, bodies, bodies.n_bodies(), kWhere);
  expect_valid(m, bodies, p);
  EXPECT_EQ(p.n_subdomains, 2);
  EXPECT_EQ(p.tets, bodies.tets);
  EXPECT_EQ(p.subdomain_of_tet, bodies.tet_body);
  EXPECT_EQ(p.n_split, 0);
  EXPECT_EQ(p.note, "");
}

TEST(Partition, FewerSubdomainsThanBodiesGivesOnePerBodyAndSaysSo) {
  const TetMesh m = bar_and_cube();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Partition p = partition_mesh(m, bodies, 1, kWhere);
  expect_valid(m, bodies, p);
  EXPECT_EQ(p.n_subdomains, 2);
  EXPECT_NE(p.note.find("solver.subdomains = 1 gave 2 subdomains"), std::string::npos) << p.note;
  EXPECT_NE(p.note.find("2 bodies"), std::string::npos) << p.note;
}

// A body joined through one node only is not face-connected: as one subdomain it is split into
// its two cubes.
TEST(Partition, BodyThatIsNotFaceConnectedIsSplitIntoItsPieces) {
  const TetMesh m = hinged_cubes();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  ASSERT_EQ(bodies.n_bodies(), 1);
  const Partition p = partition_mesh(m, bodies, 1, kWhere);
  expect_valid(m, bodies, p);
  ASSERT_EQ(p.n_subdomains, 2);
  EXPECT_EQ(p.tets[0].size(), 40u);
  EXPECT_EQ(p.tets[0].back(), 39);
  EXPECT_EQ(p.n_split, 1);
  EXPECT_NE(p.note.find("1 part was not face-connected and split into 2 face-connected pieces"),
            std::string::npos)
      << p.note;
}

// METIS is not asked for contiguous parts on such a body; every subdomain is still one piece.
TEST(Partition, BodyThatIsNotFaceConnectedCutByMetisGivesFaceConnectedSubdomains) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = hinged_cubes();
  const mesh::Bodies bodies = mesh::find_bodies(m);
  for (Index requested : {2, 3, 6}) {
    SCOPED_TRACE("solver.subdomains = " + std::to_string(requested));
    const Partition p = partition_mesh(m, bodies, requested, kWhere);
    expect_valid(m, bodies, p);
    EXPECT_GE(p.n_subdomains, 2);  // the two cubes at least
    for (const auto& tets : p.tets)
      EXPECT_EQ(tets.front() < 40, tets.back() < 40) << "a subdomain in both cubes";
  }
}

// As many subdomains as tetrahedra: METIS may leave parts empty (dropped) but never returns a
// part of two tetrahedra that share no face as one subdomain.
TEST(Partition, AsManySubdomainsAsTetrahedraIsAccepted) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = mesh::make_brick(kTiny);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Partition p = partition_mesh(m, bodies, m.n_tets(), kWhere);
  expect_valid(m, bodies, p);
  EXPECT_LE(p.n_subdomains, m.n_tets());
  EXPECT_EQ(p.note.empty(), p.n_subdomains == m.n_tets()) << p.note;
}

TEST(Partition, MoreSubdomainsThanTetrahedraIsAnInputErrorNamingTheKey) {
  const TetMesh m = mesh::make_brick(kTiny);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  test::expect_input_error([&] { partition_mesh(m, bodies, 6, kWhere); },
                           {kWhere, "solver.subdomains = 6", "5 tetrahedra"});
  const TetMesh two = mesh::disjoint_union({m, shifted(m, Vec3(2, 0, 0))}, {"", "b_"});
  test::expect_input_error([&] { partition_mesh(two, mesh::find_bodies(two), 11, kWhere); },
                           {kWhere, "solver.subdomains = 11", "10 tetrahedra"});
}

TEST(Partition, FewerThanOneSubdomainIsAnInputErrorNamingTheKey) {
  const TetMesh m = mesh::make_brick(kTiny);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  test::expect_input_error([&] { partition_mesh(m, bodies, 0, kWhere); },
                           {kWhere, "solver.subdomains = 0", "at least 1"});
  test::expect_input_error([&] { partition_mesh(m, bodies, -3, kWhere); },
                           {kWhere, "solver.subdomains = -3"});
}

TEST(Partition, WithoutMetisCuttingABodySaysWhatToInstall) {
  if (metis_available()) GTEST_SKIP() << "fricon built with METIS";
  const TetMesh m = mesh::make_brick(kBar);
  test::expect_input_error([&] { partition_mesh(m, mesh::find_bodies(m), 4, kWhere); },
                           {kWhere, "solver.subdomains", "\"tfeti\" needs METIS", "libmetis-dev"});
}

TEST(SubdomainsForSize, IsTheNodeCountOverTheSizeWithinOneAndTheTetrahedra) {
  const TetMesh bar = mesh::make_brick(kBar);  // 325 nodes, 960 tetrahedra
  ASSERT_EQ(bar.n_nodes(), 325);
  EXPECT_EQ(subdomains_for_size(bar, 325), 1);
  EXPECT_EQ(subdomains_for_size(bar, 100), 3);  // 3.25
  EXPECT_EQ(subdomains_for_size(bar, 50), 7);   // 6.5, rounded up
  EXPECT_EQ(subdomains_for_size(bar, 10), 33);  // 32.5
  EXPECT_EQ(subdomains_for_size(bar, 1000), 1);
  EXPECT_EQ(subdomains_for_size(bar, 1), 325);
  const TetMesh tiny = mesh::make_brick(kTiny);  // 8 nodes, 5 tetrahedra
  EXPECT_EQ(subdomains_for_size(tiny, 1), 5);
  EXPECT_EQ(subdomains_for_size(tiny, 3), 3);  // 2.67
}

TEST(SubdomainsForSize, GivesACountThatPartitionMeshAccepts) {
  SKIP_WITHOUT_METIS();
  const TetMesh m = mesh::make_brick(kBar);
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Index n = subdomains_for_size(m, 60);
  EXPECT_EQ(n, 5);  // 5.42
  const Partition p = partition_mesh(m, bodies, n, kWhere);
  expect_valid(m, bodies, p);
  EXPECT_EQ(p.n_subdomains, n);
}

}  // namespace

// The owner of a node (theory.md §8.1) against a count made here: the subdomain with the most
// tetrahedra at the node, the lowest index among equals. Three interleaved subdomains of the bar
// give nodes held by 1 to 6 tetrahedra of each, with ties; and a node's copy in subdomain 0 is
// often not its owner, which the former rule (the lowest index) would have made it.
TEST(Partition, ANodeIsOwnedByTheSubdomainWithTheMostTetrahedraAtIt) {
  const TetMesh m = mesh::make_brick(kBar);
  constexpr Index kInterleaved = 3;
  Partition p;
  p.n_subdomains = kInterleaved;
  p.tets.resize(kInterleaved);
  for (Index t = 0; t < m.n_tets(); ++t) {
    p.subdomain_of_tet.push_back(t % kInterleaved);
    p.tets[static_cast<size_t>(t % kInterleaved)].push_back(t);
  }
  std::vector<std::array<Index, kInterleaved>> count(static_cast<size_t>(m.n_nodes()));
  for (auto& c : count)
    c.fill(0);
  for (Index t = 0; t < m.n_tets(); ++t)
    for (Index a = 0; a < 4; ++a)
      ++count[static_cast<size_t>(m.tets(a, t))][t % kInterleaved];

  const std::vector<Index> owner = node_owners(m, p);
  ASSERT_EQ(static_cast<Index>(owner.size()), m.n_nodes());
  Index not_lowest = 0;
  for (Index node = 0; node < m.n_nodes(); ++node) {
    const auto& c = count[static_cast<size_t>(node)];
    const auto most = std::max_element(c.begin(), c.end());  // the first of the largest
    EXPECT_EQ(owner[static_cast<size_t>(node)], most - c.begin()) << "node " << node;
    const auto lowest = std::find_if(c.begin(), c.end(), [](Index k) { return k > 0; });
    if (most != lowest) ++not_lowest;
  }
  EXPECT_GT(not_lowest, 0);
}
