// The multiplier partitions on any contact surface: the mesh file's (one patch per elementary
// entity) and fricon's agglomerate (stars of separated vertices, grown), against the paper's
// chessboard on the brick, on odd and curved surfaces, and the coarsening of unstable ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/contact/b_matrix.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/discretization.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::contact;

namespace {

const std::string kWhere = "t.toml:7:1";

// The brick (size 3 x 1 x 1) with its surface z0, x0 clamped; no chessboard (odd cells too).
using Case = test::ClampedBrick;
Case brick(std::array<Index, 3> cells) {
  return test::clamped_brick(cells, test::Chessboard::No);
}

// The same surface fields as make_contact_surface, without its planarity check (curved faces).
ContactSurface curved_surface(const mesh::TetMesh& m, const fe::DofMap& dofs,
                              const std::string& tag) {
  ContactSurface s;
  s.tag = tag;
  s.faces = m.faces_with_tag(tag);
  s.nodes = m.nodes_with_tag(tag);
  std::map<Index, Index> position;
  for (size_t k = 0; k < s.nodes.size(); ++k)
    position[s.nodes[k]] = static_cast<Index>(k);
  s.face_nodes.resize(3, static_cast<Index>(s.faces.size()));
  Vec3 normal_sum = Vec3::Zero();
  for (size_t k = 0; k < s.faces.size(); ++k) {
    for (int v = 0; v < 3; ++v)
      s.face_nodes(v, static_cast<Index>(k)) = position[m.faces(v, s.faces[k])];
    s.area += mesh::face_area(m, s.faces[k]);
    normal_sum += mesh::face_area(m, s.faces[k]) * mesh::face_normal(m, s.faces[k]);
  }
  s.n = normal_sum.normalized();
  s.t1 = (Vec3::UnitX() - s.n(0) * s.n).normalized();
  s.t2 = s.t1.cross(s.n);
  for (Index a : s.nodes) {
    std::array<bool, 3> f{};
    for (int c = 0; c < 3; ++c)
      f[static_cast<size_t>(c)] = dofs.is_fixed(a, c);
    s.fixed.push_back(f);
    s.contact_node.push_back(!f[2]);
  }
  return s;
}

// The brick with `cells` bent along x: z -> z + 0.3 (x - 1.5)^2 [m] (a shear of unit Jacobian).
Case bent_brick(std::array<Index, 3> cells) {
  constexpr Real kBend = 0.3;  // [1/m]
  Case s;
  s.mesh = mesh::make_brick({Vec3(3, 1, 1), cells});
  for (Index a = 0; a < s.mesh.n_nodes(); ++a)
    s.mesh.nodes(2, a) += kBend * std::pow(s.mesh.nodes(0, a) - 1.5, 2);
  s.dofs = test::clamped_dofs(s.mesh);
  s.surface = curved_surface(s.mesh, s.dofs, "z0");
  return s;
}

// The partition as a set of sorted face lists (order-free comparison).
std::set<std::vector<Index>> as_sets(const Patches& p) {
  std::set<std::vector<Index>> sets;
  for (auto list : p.faces) {
    std::sort(list.begin(), list.end());
    sets.insert(list);
  }
  return sets;
}

// Every surface triangle is in exactly one patch.
bool covers_once(const ContactSurface& s, const Patches& p) {
  std::vector<int> count(s.faces.size(), 0);
  for (const auto& list : p.faces)
    for (Index k : list)
      ++count[static_cast<size_t>(k)];
  return std::all_of(count.begin(), count.end(), [](int c) { return c == 1; });
}

// Patch q's triangles are connected through shared edges.
bool edge_connected(const ContactSurface& s, const Patches& p, Index q) {
  const auto& list = p.faces[static_cast<size_t>(q)];
  auto share_edge = [&](Index a, Index b) {
    int shared = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        shared += s.face_nodes(i, a) == s.face_nodes(j, b);
    return shared == 2;
  };
  std::vector<bool> reached(list.size(), false);
  std::vector<size_t> stack{0};
  reached[0] = true;
  while (!stack.empty()) {
    const size_t i = stack.back();
    stack.pop_back();
    for (size_t j = 0; j < list.size(); ++j)
      if (!reached[j] && share_edge(list[i], list[j])) {
        reached[j] = true;
        stack.push_back(j);
      }
  }
  return std::all_of(reached.begin(), reached.end(), [](bool r) { return r; });
}

void expect_valid(const Case& s, const Patches& p) {
  EXPECT_TRUE(covers_once(s.surface, p));
  for (Index q = 0; q < p.size(); ++q)
    EXPECT_TRUE(edge_connected(s.surface, p, q)) << "patch " << q;
  EXPECT_NEAR(p.area.sum(), s.surface.area, 1e-12 * s.surface.area);
}

// The brick's z0 faces numbered by their 2 x 2 block (as a Gmsh drawing of the chessboard
// would), every other face without entity.
void set_block_entities(Case& s, std::array<Index, 3> cells) {
  const Real h1 = 3.0 / static_cast<Real>(cells[0]), h2 = 1.0 / static_cast<Real>(cells[1]);
  const Index n1 = cells[0] / 2;
  constexpr int kFirstEntity = 7;
  s.mesh.face_entity.assign(static_cast<size_t>(s.mesh.n_faces()), -1);
  for (Index f : s.surface.faces) {
    const Vec3 c = face_centroid(s.mesh, f);
    const auto a = static_cast<Index>(std::floor(c(0) / (2 * h1)));
    const auto b = static_cast<Index>(std::floor(c(1) / (2 * h2)));
    s.mesh.face_entity[static_cast<size_t>(f)] = kFirstEntity + static_cast<int>(a + n1 * b);
  }
}

Real mean_diameter(const Case& s, const Patches& p) {
  Real sum = 0.0;
  for (Index q = 0; q < p.size(); ++q)
    sum += patch_diameter(s.mesh, s.surface, p, q);
  return sum / static_cast<Real>(p.size());
}

ContactSpec spec_of(PatchKind kind) {
  ContactSpec spec;
  spec.boundary = "z0";
  spec.patches = kind;
  spec.where_patches = kWhere;
  return spec;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(Patches, AgglomerateIsTheChessboardOnTheBrick) {
  for (const std::array<Index, 3> cells :
       {std::array<Index, 3>{12, 4, 4}, std::array<Index, 3>{8, 8, 4},
        std::array<Index, 3>{16, 4, 2}}) {
    const Case s = brick(cells);
    const Patches chess = chessboard_patches(s.mesh, s.surface, "test");
    const Patches agg = agglomerate_patches(s.mesh, s.surface, 0.0, "test");
    EXPECT_EQ(agg.size(), cells[0] * cells[1] / 4);
    EXPECT_EQ(as_sets(agg), as_sets(chess)) << cells[0] << " x " << cells[1];
  }
}

TEST(Patches, MeshEntitiesOfTheChessboardBlocksAreTheChessboard) {
  const std::array<Index, 3> cells{12, 4, 4};
  Case s = brick(cells);
  set_block_entities(s, cells);
  const Patches chess = chessboard_patches(s.mesh, s.surface, "test");
  const Patches mesh = make_patches(PatchKind::Mesh, s.mesh, s.surface, 0.0, "test");
  EXPECT_EQ(mesh.size(), chess.size());
  EXPECT_EQ(as_sets(mesh), as_sets(chess));
  // In increasing entity order, which is the chessboard's order here.
  for (Index q = 0; q < mesh.size(); ++q)
    EXPECT_NEAR((mesh.centroid.col(q) - chess.centroid.col(q)).norm(), 0.0, 1e-12);
}

TEST(Patches, MeshWithoutEntitiesIsAnInputErrorAtTheKey) {
  Case s = brick({12, 4, 4});
  for (bool empty : {true, false}) {
    if (empty) {
      s.mesh.face_entity.clear();
    } else {
      set_block_entities(s, {12, 4, 4});
      s.mesh.face_entity[static_cast<size_t>(s.surface.faces[5])] = -1;
    }
    try {
      entity_patches(s.mesh, s.surface, kWhere);
      ADD_FAILURE() << "a surface without entities was partitioned";
    } catch (const InputError& e) {
      EXPECT_TRUE(contains(e.what(), kWhere)) << e.what();
      EXPECT_TRUE(contains(e.what(), "no elementary entities")) << e.what();
      EXPECT_TRUE(contains(e.what(), "agglomerate")) << e.what();
    }
  }
}

TEST(Patches, AgglomerateCoversAnOddBrickFaceStably) {
  const Case s = brick({5, 3, 2});
  EXPECT_THROW(chessboard_patches(s.mesh, s.surface, "test"), InputError);
  const Patches p = make_patches(PatchKind::Agglomerate, s.mesh, s.surface, 0.0, "test");
  expect_valid(s, p);
  const SparseMatrix B = assemble_b(s.mesh, s.dofs, s.surface, p);
  EXPECT_GE(check_stability(B, "test").ratio, 1e-8);
  // Through discretize_contact: stable as built, so no note.
  const ContactDiscretization d =
      discretize_contact(s.mesh, s.dofs, spec_of(PatchKind::Agglomerate));
  EXPECT_EQ(d.n_patches(), p.size());
  EXPECT_TRUE(d.partition_note.empty()) << d.partition_note;
}

TEST(Patches, AgglomerateOnACurvedSurface) {
  // The paper's mesh, bent: the finest partition (patch_size 0) is valid and stable.
  const Case coarse = bent_brick({12, 4, 4});
  ASSERT_GT(
      (mesh::face_normal(coarse.mesh, coarse.surface.faces.front()) - coarse.surface.n).norm(),
      0.1);
  const Patches finest = agglomerate_patches(coarse.mesh, coarse.surface, 0.0, "test");
  expect_valid(coarse, finest);
  EXPECT_GE(
      check_stability(assemble_b(coarse.mesh, coarse.dofs, coarse.surface, finest), "test").ratio,
      1e-8);
  // On a finer bent mesh (h = 1/16 m), patch_size sets the mean patch diameter.
  const Case fine = bent_brick({48, 16, 2});
  std::map<Real, Index> n_patches;
  for (Real patch_size : {0.25, 0.5}) {
    SCOPED_TRACE(patch_size);
    const Patches p = agglomerate_patches(fine.mesh, fine.surface, patch_size, "test");
    expect_valid(fine, p);
    const SparseMatrix B = assemble_b(fine.mesh, fine.dofs, fine.surface, p);
    EXPECT_GE(check_stability(B, "test").ratio, 1e-8);
    n_patches[patch_size] = p.size();
    const Real d = mean_diameter(fine, p);
    EXPECT_GT(d, 0.7 * patch_size);
    EXPECT_LT(d, 1.4 * patch_size);
  }
  EXPECT_LT(n_patches[0.5], n_patches[0.25]);
}

TEST(Patches, UnstableMeshPartitionIsANumericalErrorWithTheRatio) {
  // Every triangle its own entity: 3 x 96 multipliers for the 3 x 60 free traces.
  Case s = brick({12, 4, 4});
  s.mesh.face_entity.assign(static_cast<size_t>(s.mesh.n_faces()), -1);
  for (size_t k = 0; k < s.surface.faces.size(); ++k)
    s.mesh.face_entity[static_cast<size_t>(s.surface.faces[k])] = static_cast<int>(k);
  try {
    discretize_contact(s.mesh, s.dofs, spec_of(PatchKind::Mesh));
    ADD_FAILURE() << "an unstable mesh partition was accepted";
  } catch (const NumericalError& e) {
    EXPECT_TRUE(contains(e.what(), kWhere)) << e.what();
    EXPECT_TRUE(contains(e.what(), "sigma_min/sigma_max(B) =")) << e.what();
    EXPECT_TRUE(contains(e.what(), "\"agglomerate\"")) << e.what();
    EXPECT_TRUE(contains(e.what(), "96 patches")) << e.what();
  }
}

TEST(Patches, UnstableAgglomerateIsCoarsened) {
  // Normal motion free at the grid node (2, 2) only (its x fixed, like the others' z, so that
  // it is no better a seed than they): the finest agglomerate is the chessboard, the node is a
  // corner of four patches, and their four normal rows of B share its one column: rank
  // deficient. Coarser patches put it in one patch: stable.
  const mesh::BrickSpec spec{Vec3(3, 1, 1), {12, 4, 4}};
  Case s;
  s.mesh = mesh::make_brick(spec);
  const Index free_node = mesh::brick_node(spec, 2, 2, 0);
  std::vector<std::array<Index, 2>> fixed{{free_node, 0}};
  for (Index node : s.mesh.nodes_with_tag("z0"))
    if (node != free_node) fixed.push_back({node, 2});
  s.dofs = test::clamped_dofs(s.mesh, "x0", fixed);
  s.surface = make_contact_surface(s.mesh, s.dofs, "z0", "test");

  const Patches finest = agglomerate_patches(s.mesh, s.surface, 0.0, "test");
  EXPECT_THROW(check_stability(assemble_b(s.mesh, s.dofs, s.surface, finest), "test"),
               NumericalError);
  const ContactDiscretization d =
      discretize_contact(s.mesh, s.dofs, spec_of(PatchKind::Agglomerate));
  EXPECT_GE(d.stability.ratio, 1e-8);
  EXPECT_LT(d.n_patches(), finest.size());
  EXPECT_TRUE(contains(d.partition_note, "coarsened")) << d.partition_note;
  EXPECT_TRUE(covers_once(d.surface, d.patches));
  // A chessboard there is refused, as before.
  EXPECT_THROW(discretize_contact(s.mesh, s.dofs, spec_of(PatchKind::Chessboard)), NumericalError);
}
