#include "fricon/mesh/bodies.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::mesh {

namespace {

// Union-find over the nodes, with path halving and union by size.
class NodeSets {
 public:
  explicit NodeSets(Index n) : parent_(static_cast<size_t>(n)), size_(static_cast<size_t>(n), 1) {
    std::iota(parent_.begin(), parent_.end(), Index{0});
  }
  Index root(Index a) {
    while (parent_[static_cast<size_t>(a)] != a) {
      Index& p = parent_[static_cast<size_t>(a)];
      p = parent_[static_cast<size_t>(p)];
      a = p;
    }
    return a;
  }
  void join(Index a, Index b) {
    a = root(a);
    b = root(b);
    if (a == b) return;
    if (size_[static_cast<size_t>(a)] < size_[static_cast<size_t>(b)]) std::swap(a, b);
    parent_[static_cast<size_t>(b)] = a;
    size_[static_cast<size_t>(a)] += size_[static_cast<size_t>(b)];
  }

 private:
  std::vector<Index> parent_;
  std::vector<Index> size_;
};

}  // namespace

Bodies find_bodies(const TetMesh& mesh) {
  const Index n_nodes = mesh.n_nodes(), n_tets = mesh.n_tets();
  NodeSets sets(n_nodes);
  for (Index t = 0; t < n_tets; ++t)
    for (int v = 1; v < 4; ++v)
      sets.join(mesh.tets(0, t), mesh.tets(v, t));
  Bodies bodies;
  bodies.tet_body.assign(static_cast<size_t>(n_tets), -1);
  bodies.node_body.assign(static_cast<size_t>(n_nodes), -1);
  // Number the roots in the order of the first tetrahedron that reaches them.
  std::vector<Index> body_of_root(static_cast<size_t>(n_nodes), -1);
  for (Index t = 0; t < n_tets; ++t) {
    Index& b = body_of_root[static_cast<size_t>(sets.root(mesh.tets(0, t)))];
    if (b < 0) {
      b = bodies.n_bodies();
      bodies.tets.emplace_back();
      bodies.regions.emplace_back();
    }
    bodies.tet_body[static_cast<size_t>(t)] = b;
    bodies.tets[static_cast<size_t>(b)].push_back(t);
    bodies.regions[static_cast<size_t>(b)].push_back(mesh.region(t));
    for (int v = 0; v < mesh.nodes_per_tet(); ++v)  // the extra nodes too
      bodies.node_body[static_cast<size_t>(mesh.tet_node(t, v))] = b;
  }
  bodies.nodes.resize(bodies.tets.size());
  for (Index a = 0; a < n_nodes; ++a) {
    const Index b = bodies.node_body[static_cast<size_t>(a)];
    if (b >= 0) bodies.nodes[static_cast<size_t>(b)].push_back(a);
  }
  for (auto& regions : bodies.regions) {
    std::sort(regions.begin(), regions.end());
    regions.erase(std::unique(regions.begin(), regions.end()), regions.end());
  }
  return bodies;
}

BoundingBox bounding_box(const TetMesh& mesh, const std::vector<Index>& nodes) {
  FRICON_CHECK(!nodes.empty(), "bounding_box of no node");
  BoundingBox box{mesh.nodes.col(nodes.front()), mesh.nodes.col(nodes.front())};
  for (Index a : nodes) {
    box.lo = box.lo.cwiseMin(mesh.nodes.col(a));
    box.hi = box.hi.cwiseMax(mesh.nodes.col(a));
  }
  return box;
}

std::string describe_body(const TetMesh& mesh, const Bodies& bodies, Index b) {
  FRICON_CHECK(b >= 0 && b < bodies.n_bodies(),
               "describe_body: body " << b << " of " << bodies.n_bodies());
  const auto& regions = bodies.regions[static_cast<size_t>(b)];
  std::string names;
  for (size_t i = 0; i < regions.size(); ++i)
    names += fmt::format(
        "{}\"{}\"", i == 0 ? "" : ", ",
        mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<size_t>(regions[i])]);
  const auto& nodes = bodies.nodes[static_cast<size_t>(b)];
  const BoundingBox box = bounding_box(mesh, nodes);
  return fmt::format(
      "body {} (region{} {}, {} nodes in [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x "
      "[{:.6g}, {:.6g}] m)",
      b, regions.size() == 1 ? "" : "s", names, nodes.size(), box.lo(0), box.hi(0), box.lo(1),
      box.hi(1), box.lo(2), box.hi(2));
}

TetMesh disjoint_union(const std::vector<TetMesh>& parts,
                       const std::vector<std::string>& prefixes) {
  FRICON_CHECK(parts.size() == prefixes.size(),
               "disjoint_union: " << parts.size() << " parts, " << prefixes.size() << " prefixes");
  Index n_nodes = 0, n_tets = 0, n_faces = 0;
  for (const TetMesh& part : parts) {
    n_nodes += part.n_nodes();
    n_tets += part.n_tets();
    n_faces += part.n_faces();
  }
  TetMesh whole;
  whole.nodes.resize(3, n_nodes);
  whole.tets.resize(4, n_tets);
  whole.faces.resize(3, n_faces);
  // The parts are of one order (checked): their extra nodes are carried like the corners.
  const Index tet_extra = parts.empty() ? 0 : parts.front().tet_extra.rows();
  const Index face_extra = parts.empty() ? 0 : parts.front().face_extra.rows();
  for (const TetMesh& part : parts)
    FRICON_CHECK(part.tet_extra.rows() == tet_extra && part.face_extra.rows() == face_extra,
                 "disjoint_union: parts of different element orders");
  whole.tet_extra.resize(tet_extra, n_tets);
  whole.face_extra.resize(face_extra, n_faces);
  // Index of `name` in `names`, appended if absent.
  const auto index_of = [](std::vector<std::string>& names, const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return static_cast<int>(it - names.begin());
    names.push_back(name);
    return static_cast<int>(names.size()) - 1;
  };
  Index node0 = 0, tet0 = 0, face0 = 0;
  int entity0 = 0;  // above every entity of the parts before
  for (size_t i = 0; i < parts.size(); ++i) {
    const TetMesh& part = parts[i];
    whole.nodes.middleCols(node0, part.n_nodes()) = part.nodes;
    whole.tets.middleCols(tet0, part.n_tets()) = part.tets.array() + node0;
    if (tet_extra > 0)  // a linear part's tet_extra may have no columns at all
      whole.tet_extra.middleCols(tet0, part.n_tets()) = part.tet_extra.array() + node0;
    for (Index t = 0; t < part.n_tets(); ++t) {
      const std::string region = part.region_names.empty()
                                     ? "body"
                                     : part.region_names[static_cast<size_t>(part.region(t))];
      whole.tet_region.push_back(index_of(whole.region_names, prefixes[i] + region));
    }
    whole.faces.middleCols(face0, part.n_faces()) = part.faces.array() + node0;
    if (face_extra > 0)
      whole.face_extra.middleCols(face0, part.n_faces()) = part.face_extra.array() + node0;
    for (const RigidSurface& surface : part.rigid_surfaces) {
      whole.rigid_surfaces.push_back(surface);
      whole.rigid_surfaces.back().name = prefixes[i] + surface.name;
    }
    int max_entity = 0;
    for (Index f = 0; f < part.n_faces(); ++f) {
      whole.face_tag.push_back(
          index_of(whole.tag_names,
                   prefixes[i] +
                       part.tag_names[static_cast<size_t>(part.face_tag[static_cast<size_t>(f)])]));
      const int entity = part.face_entity.empty() ? -1 : part.face_entity[static_cast<size_t>(f)];
      whole.face_entity.push_back(entity < 0 ? -1 : entity + entity0);
      max_entity = std::max(max_entity, entity);
    }
    node0 += part.n_nodes();
    tet0 += part.n_tets();
    face0 += part.n_faces();
    entity0 += max_entity + 1;
  }
  return whole;
}

}  // namespace fricon::mesh
