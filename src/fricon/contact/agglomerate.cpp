// contact: fricon's multiplier partition of any triangulated contact surface (theory.md §2.3):
// stars of an independent set of surface vertices, grown over the remaining triangles.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include "fricon/contact/patches.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

constexpr Index kUnassigned = -1;
// Seeds at least this fraction of the target patch diameter apart: the grown cells are then
// about the target across (on a grid of seeds of spacing s a cell's diameter is s sqrt(2)).
constexpr Real kSeedSeparationPerDiameter = 0.7071067811865476;  // 1/sqrt(2)

// The triangulation of the surface by surface-node and surface-face positions.
struct SurfaceTopology {
  std::vector<std::vector<Index>> vertex_faces;       // per vertex: the faces around it (its star)
  std::vector<std::vector<Index>> vertex_neighbours;  // per vertex: the vertices joined by an edge
  std::vector<std::vector<Index>> face_neighbours;    // per face: the faces sharing an edge with it
  std::vector<bool> on_boundary;                      // per vertex: on an edge of a single face
};

SurfaceTopology surface_topology(const ContactSurface& surface) {
  const auto n_vertices = static_cast<size_t>(surface.n_nodes());
  const auto n_faces = static_cast<Index>(surface.faces.size());
  SurfaceTopology t;
  t.vertex_faces.resize(n_vertices);
  t.vertex_neighbours.resize(n_vertices);
  t.face_neighbours.resize(static_cast<size_t>(n_faces));
  t.on_boundary.assign(n_vertices, false);
  std::vector<std::tuple<Index, Index, Index>> edges;  // (lower vertex, higher vertex, face)
  for (Index k = 0; k < n_faces; ++k)
    for (int v = 0; v < 3; ++v) {
      const Index a = surface.face_nodes(v, k), b = surface.face_nodes((v + 1) % 3, k);
      t.vertex_faces[static_cast<size_t>(a)].push_back(k);
      edges.emplace_back(std::min(a, b), std::max(a, b), k);
    }
  std::sort(edges.begin(), edges.end());
  for (size_t first = 0; first < edges.size();) {
    size_t last = first;
    while (last < edges.size() && std::get<0>(edges[last]) == std::get<0>(edges[first]) &&
           std::get<1>(edges[last]) == std::get<1>(edges[first]))
      ++last;
    const auto [a, b, face] = edges[first];
    t.vertex_neighbours[static_cast<size_t>(a)].push_back(b);
    t.vertex_neighbours[static_cast<size_t>(b)].push_back(a);
    if (last - first == 1)
      t.on_boundary[static_cast<size_t>(a)] = t.on_boundary[static_cast<size_t>(b)] = true;
    for (size_t i = first; i < last; ++i)
      for (size_t j = first; j < last; ++j)
        if (i != j)
          t.face_neighbours[static_cast<size_t>(std::get<2>(edges[i]))].push_back(
              std::get<2>(edges[j]));
    first = last;
  }
  return t;
}

// The vertices in the order seeds are tried: fewest components fixed by Dirichlet conditions
// first (a seed's columns of B are its patch's alone: a free seed makes its patch stable), then
// interior vertices before boundary ones, then by (t2, t1), so that on a structured grid the
// greedy choice sweeps row by row from a corner.
std::vector<Index> seed_order(const mesh::TetMesh& mesh, const ContactSurface& surface,
                              const SurfaceTopology& topology) {
  using Key = std::tuple<Index, bool, Real, Real, Index>;
  std::vector<Key> keys;
  for (Index v = 0; v < surface.n_nodes(); ++v) {
    const auto k = static_cast<size_t>(v);
    const auto x = mesh.nodes.col(surface.nodes[k]);
    const auto n_fixed = k < surface.fixed.size()
                             ? std::count(surface.fixed[k].begin(), surface.fixed[k].end(), true)
                             : 0;
    keys.emplace_back(static_cast<Index>(n_fixed), topology.on_boundary[k], surface.t2.dot(x),
                      surface.t1.dot(x), v);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Index> order;
  for (const auto& key : keys)
    order.push_back(std::get<4>(key));
  return order;
}

// Seeds already chosen, bucketed in cubes of edge `separation` for the distance test.
class SeedGrid {
 public:
  explicit SeedGrid(Real separation) : separation_(separation) {}
  bool far_from_all(const Vec3& x) const {
    if (separation_ <= 0.0) return true;
    const auto c = cell(x);
    for (Index i = -1; i <= 1; ++i)
      for (Index j = -1; j <= 1; ++j)
        for (Index k = -1; k <= 1; ++k) {
          const auto it = cells_.find({c[0] + i, c[1] + j, c[2] + k});
          if (it == cells_.end()) continue;
          for (const Vec3& y : it->second)
            if ((x - y).norm() < separation_) return false;
        }
    return true;
  }
  void add(const Vec3& x) { cells_[cell(x)].push_back(x); }

 private:
  std::array<Index, 3> cell(const Vec3& x) const {
    return {static_cast<Index>(std::floor(x(0) / separation_)),
            static_cast<Index>(std::floor(x(1) / separation_)),
            static_cast<Index>(std::floor(x(2) / separation_))};
  }
  Real separation_;
  std::map<std::array<Index, 3>, std::vector<Vec3>> cells_;
};

// Step 1: a greedy independent set of vertices, in seed_order, at least `separation` [m] apart.
std::vector<Index> choose_seeds(const mesh::TetMesh& mesh, const ContactSurface& surface,
                                const SurfaceTopology& topology, Real separation) {
  std::vector<bool> blocked(static_cast<size_t>(surface.n_nodes()), false);
  SeedGrid grid(separation);
  std::vector<Index> seeds;
  for (Index v : seed_order(mesh, surface, topology)) {
    const Vec3 x = mesh.nodes.col(surface.nodes[static_cast<size_t>(v)]);
    // Only corners have a star (an edge node of a 6-node triangle is no vertex of the surface).
    if (topology.vertex_faces[static_cast<size_t>(v)].empty()) continue;
    if (blocked[static_cast<size_t>(v)] || !grid.far_from_all(x)) continue;
    seeds.push_back(v);
    grid.add(x);
    for (Index w : topology.vertex_neighbours[static_cast<size_t>(v)])
      blocked[static_cast<size_t>(w)] = true;
  }
  return seeds;
}

// The partition under construction: the patch of each face, and each patch's reference point
// (the centroid of its seed star) that growing faces measure their distance to.
struct Growth {
  std::vector<Index> patch_of;            // per face, or kUnassigned
  std::vector<Vec3> reference;            // per patch [m]
  std::vector<std::vector<Index>> faces;  // per patch
  void assign(Index face, Index patch) {
    patch_of[static_cast<size_t>(face)] = patch;
    faces[static_cast<size_t>(patch)].push_back(face);
  }
  Index new_patch(const Vec3& x) {
    reference.push_back(x);
    faces.emplace_back();
    return static_cast<Index>(reference.size()) - 1;
  }
};

// Step 2: each seed's star is a patch.
Growth seed_stars(const mesh::TetMesh& mesh, const ContactSurface& surface,
                  const SurfaceTopology& topology, const std::vector<Index>& seeds) {
  Growth g;
  g.patch_of.assign(surface.faces.size(), kUnassigned);
  for (Index v : seeds) {
    Real area = 0.0;
    Vec3 moment = Vec3::Zero();
    for (Index k : topology.vertex_faces[static_cast<size_t>(v)]) {
      const Index f = surface.faces[static_cast<size_t>(k)];
      area += mesh::face_area(mesh, f);
      moment += mesh::face_area(mesh, f) * face_centroid(mesh, f);
    }
    const Index p = g.new_patch(moment / area);
    for (Index k : topology.vertex_faces[static_cast<size_t>(v)])
      g.assign(k, p);
  }
  return g;
}

// Step 3a: grow the patches across edges, nearest first: a face joins, of the patches next to
// it, the one whose reference point is nearest to its centroid (a Dijkstra-like sweep).
void grow_across_edges(const mesh::TetMesh& mesh, const ContactSurface& surface,
                       const SurfaceTopology& topology, Growth& g) {
  using Candidate = std::tuple<Real, Index, Index>;  // (distance [m], face, patch)
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue;
  auto offer_neighbours = [&](Index k) {
    const Index p = g.patch_of[static_cast<size_t>(k)];
    for (Index j : topology.face_neighbours[static_cast<size_t>(k)])
      if (g.patch_of[static_cast<size_t>(j)] == kUnassigned) {
        const Vec3 c = face_centroid(mesh, surface.faces[static_cast<size_t>(j)]);
        queue.emplace((c - g.reference[static_cast<size_t>(p)]).norm(), j, p);
      }
  };
  for (Index k = 0; k < static_cast<Index>(surface.faces.size()); ++k)
    if (g.patch_of[static_cast<size_t>(k)] != kUnassigned) offer_neighbours(k);
  while (!queue.empty()) {
    const auto [distance, k, p] = queue.top();
    queue.pop();
    if (g.patch_of[static_cast<size_t>(k)] != kUnassigned) continue;
    g.assign(k, p);
    offer_neighbours(k);
  }
}

// Step 3b, for a face no edge growth reaches (a piece of surface joined to the rest at vertices
// only, without a seed): it joins the nearest patch it shares a vertex with, else starts one.
void attach_unreached(const mesh::TetMesh& mesh, const ContactSurface& surface,
                      const SurfaceTopology& topology, Index k, Growth& g) {
  const Vec3 c = face_centroid(mesh, surface.faces[static_cast<size_t>(k)]);
  Index best = kUnassigned;
  Real best_distance = 0.0;
  for (int v = 0; v < 3; ++v)
    for (Index j : topology.vertex_faces[static_cast<size_t>(surface.face_nodes(v, k))]) {
      const Index p = g.patch_of[static_cast<size_t>(j)];
      if (p == kUnassigned) continue;
      const Real distance = (c - g.reference[static_cast<size_t>(p)]).norm();
      if (best == kUnassigned || distance < best_distance) {
        best = p;
        best_distance = distance;
      }
    }
  g.assign(k, best != kUnassigned ? best : g.new_patch(c));
}

}  // namespace

Patches agglomerate_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                            Real patch_size, const std::string& where) {
  FRICON_CHECK(patch_size >= 0.0 && std::isfinite(patch_size),
               where << ": agglomerate patch size " << patch_size << " m is not >= 0");
  const SurfaceTopology topology = surface_topology(surface);
  const std::vector<Index> seeds =
      choose_seeds(mesh, surface, topology, kSeedSeparationPerDiameter * patch_size);
  Growth g = seed_stars(mesh, surface, topology, seeds);
  for (;;) {
    grow_across_edges(mesh, surface, topology, g);
    const auto unreached = std::find(g.patch_of.begin(), g.patch_of.end(), kUnassigned);
    if (unreached == g.patch_of.end()) break;
    attach_unreached(mesh, surface, topology, static_cast<Index>(unreached - g.patch_of.begin()),
                     g);
  }
  for (auto& list : g.faces)
    std::sort(list.begin(), list.end());
  return finish_patches(mesh, surface, std::move(g.faces));
}

}  // namespace fricon::contact
