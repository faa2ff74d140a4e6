#include "fricon/mesh/tet_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::mesh {

int TetMesh::find_tag(const std::string& name) const {
  auto it = std::find(tag_names.begin(), tag_names.end(), name);
  return it == tag_names.end() ? -1 : static_cast<int>(it - tag_names.begin());
}

int TetMesh::find_region(const std::string& name) const {
  if (region_names.empty()) return name == "body" ? 0 : -1;
  auto it = std::find(region_names.begin(), region_names.end(), name);
  return it == region_names.end() ? -1 : static_cast<int>(it - region_names.begin());
}

std::vector<Index> TetMesh::faces_with_tag(const std::string& name) const {
  std::vector<Index> result;
  const int tag = find_tag(name);
  if (tag < 0) return result;
  for (Index f = 0; f < n_faces(); ++f)
    if (face_tag[f] == tag) result.push_back(f);
  return result;
}

const char* node_set_kind(int dim) {
  return dim == kPointDimension ? "point" : "curve";
}

const NodeSet* TetMesh::find_node_set(const std::string& name) const {
  const auto it = std::find_if(node_sets.begin(), node_sets.end(),
                               [&](const NodeSet& s) { return s.name == name; });
  return it == node_sets.end() ? nullptr : &*it;
}

const RigidSurface* TetMesh::find_rigid_surface(const std::string& name) const {
  const auto it = std::find_if(rigid_surfaces.begin(), rigid_surfaces.end(),
                               [&](const RigidSurface& s) { return s.name == name; });
  return it == rigid_surfaces.end() ? nullptr : &*it;
}

std::vector<Index> TetMesh::nodes_with_tag(const std::string& name) const {
  std::vector<Index> result;
  if (find_tag(name) < 0) {
    const NodeSet* set = find_node_set(name);
    return set ? set->nodes : result;
  }
  for (Index f : faces_with_tag(name))
    for (int v = 0; v < nodes_per_face(); ++v)
      result.push_back(face_node(f, v));
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

std::string TetMesh::tag_list() const {
  std::string s;
  for (const auto& name : tag_names)
    s += (s.empty() ? "" : ", ") + name;
  for (const NodeSet& set : node_sets)
    s += fmt::format("{}{} ({})", s.empty() ? "" : ", ", set.name, node_set_kind(set.dim));
  for (const RigidSurface& surface : rigid_surfaces)
    s += fmt::format("{}{} (rigid surface)", s.empty() ? "" : ", ", surface.name);
  return s;
}

std::string TetMesh::no_surface(const std::string& name) const {
  if (const NodeSet* set = find_node_set(name); set && find_tag(name) < 0)
    return fmt::format(
        "boundary '{}' is a {} (a Gmsh physical group of dimension {}), not a surface: only a "
        "[[dirichlet]] boundary may be a curve or a point; this key needs triangles, a physical "
        "group of dimension 2 (tags: {})",
        name, node_set_kind(set->dim), set->dim, tag_list());
  if (find_rigid_surface(name) != nullptr && find_tag(name) < 0)
    return fmt::format(
        "boundary '{}' is a rigid surface (a physical surface of the mesh file none of whose "
        "triangles is a face of a tetrahedron), not a boundary of an elastic body: it can only be "
        "a rigid obstacle, `obstacle = {{ kind = \"surface\", boundary = \"{}\" }}` (tags: {})",
        name, name, tag_list());
  return fmt::format("boundary '{}' does not exist on the mesh (tags: {})", name, tag_list());
}

std::optional<Index> first_unused_node(const TetMesh& mesh) {
  std::vector<bool> used(static_cast<std::size_t>(mesh.n_nodes()), false);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int v = 0; v < mesh.nodes_per_tet(); ++v)
      used[static_cast<std::size_t>(mesh.tet_node(t, v))] = true;
  for (std::size_t n = 0; n < used.size(); ++n)
    if (!used[n]) return static_cast<Index>(n);
  return std::nullopt;
}

void scale_lengths(TetMesh& mesh, Real factor) {
  FRICON_CHECK(factor > 0.0 && std::isfinite(factor), "scale_lengths: factor " << factor);
  mesh.nodes *= factor;
  for (RigidSurface& surface : mesh.rigid_surfaces)
    surface.points *= factor;
}

Real signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Mat3 m;
  m << b - a, c - a, d - a;
  return m.determinant() / 6.0;
}

Real tet_volume(const TetMesh& mesh, Index t) {
  return signed_volume(mesh.nodes.col(mesh.tets(0, t)), mesh.nodes.col(mesh.tets(1, t)),
                       mesh.nodes.col(mesh.tets(2, t)), mesh.nodes.col(mesh.tets(3, t)));
}

namespace {
Vec3 face_cross(const TetMesh& mesh, Index f) {
  const Vec3 a = mesh.nodes.col(mesh.faces(0, f));
  const Vec3 b = mesh.nodes.col(mesh.faces(1, f));
  const Vec3 c = mesh.nodes.col(mesh.faces(2, f));
  return (b - a).cross(c - a);
}
}  // namespace

Real face_area(const TetMesh& mesh, Index f) {
  return 0.5 * face_cross(mesh, f).norm();
}

Vec3 face_normal(const TetMesh& mesh, Index f) {
  return face_cross(mesh, f).normalized();
}

namespace {
// Each rigid surface has a name of its own, triangles, finite points and valid point indices.
void check_rigid_surfaces(const TetMesh& mesh, const std::string& source) {
  for (const RigidSurface& surface : mesh.rigid_surfaces) {
    const std::string what = fmt::format("{}: rigid surface '{}'", source, surface.name);
    if (mesh.find_tag(surface.name) >= 0 || mesh.find_node_set(surface.name) != nullptr ||
        mesh.find_rigid_surface(surface.name) != &surface)
      throw InputError(fmt::format(
          "{} has the name of a boundary tag, a node set or another rigid surface too; give it a "
          "name of its own",
          what));
    if (surface.triangles.cols() == 0) throw InputError(fmt::format("{} has no triangle", what));
    if (!surface.points.allFinite())
      throw InputError(fmt::format("{} has a non-finite coordinate", what));
    for (Index f = 0; f < surface.triangles.cols(); ++f)
      for (int v = 0; v < 3; ++v)
        if (surface.triangles(v, f) < 0 || surface.triangles(v, f) >= surface.points.cols())
          throw InputError(fmt::format("{}: triangle {} refers to point {}, but it has {} points",
                                       what, f, surface.triangles(v, f), surface.points.cols()));
  }
}

// The extra nodes: none (linear) or a quadratic tetrahedron's and triangle's edge nodes, one
// column per element, each a valid node index.
void check_extra_nodes(const TetMesh& mesh, const std::string& source) {
  const bool linear = mesh.tet_extra.rows() == 0 && mesh.face_extra.rows() == 0;
  const bool quadratic =
      mesh.tet_extra.rows() == kTetEdges && mesh.tet_extra.cols() == mesh.n_tets() &&
      mesh.face_extra.rows() == kTriangleEdges && mesh.face_extra.cols() == mesh.n_faces();
  if (!linear && !quadratic)
    throw InputError(fmt::format(
        "{}: the elements have {} nodes per tetrahedron and {} per boundary triangle; fricon "
        "takes 4 and 3 (linear) or 10 and 6 (quadratic)",
        source, 4 + mesh.tet_extra.rows(), 3 + mesh.face_extra.rows()));
  const Index n = mesh.n_nodes();
  for (Index t = 0; t < mesh.tet_extra.cols(); ++t)
    for (Index r = 0; r < mesh.tet_extra.rows(); ++r)
      if (mesh.tet_extra(r, t) < 0 || mesh.tet_extra(r, t) >= n)
        throw InputError(
            fmt::format("{}: tetrahedron {} refers to node {}, but the mesh has {} nodes", source,
                        t, mesh.tet_extra(r, t), n));
  for (Index f = 0; f < mesh.face_extra.cols(); ++f)
    for (Index r = 0; r < mesh.face_extra.rows(); ++r)
      if (mesh.face_extra(r, f) < 0 || mesh.face_extra(r, f) >= n)
        throw InputError(
            fmt::format("{}: boundary face {} refers to node {}, but the mesh has {} nodes", source,
                        f, mesh.face_extra(r, f), n));
}

// tet_region is empty or gives each tetrahedron a valid index into region_names.
void check_regions(const TetMesh& mesh, const std::string& source) {
  if (mesh.tet_region.empty()) return;
  if (mesh.tet_region.size() != static_cast<size_t>(mesh.n_tets()))
    throw InputError(fmt::format("{}: {} tetrahedra but {} tetrahedron regions", source,
                                 mesh.n_tets(), mesh.tet_region.size()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    if (mesh.tet_region[t] < 0 || mesh.tet_region[t] >= static_cast<int>(mesh.region_names.size()))
      throw InputError(fmt::format("{}: tetrahedron {} has region {} of {}", source, t,
                                   mesh.tet_region[t], mesh.region_names.size()));
}
}  // namespace

void check_mesh(const TetMesh& mesh, const std::string& source, Real relative_tolerance) {
  if (mesh.n_nodes() == 0 || mesh.n_tets() == 0)
    throw InputError(fmt::format("{}: the mesh is empty ({} nodes, {} tetrahedra)", source,
                                 mesh.n_nodes(), mesh.n_tets()));
  for (Index i = 0; i < mesh.n_nodes(); ++i)
    if (!mesh.nodes.col(i).allFinite())
      throw InputError(fmt::format("{}: node {} has a non-finite coordinate", source, i));
  const Index n = mesh.n_nodes();
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    for (int v = 0; v < 4; ++v)
      if (mesh.tets(v, t) < 0 || mesh.tets(v, t) >= n)
        throw InputError(
            fmt::format("{}: tetrahedron {} refers to node {}, but the mesh has {} nodes", source,
                        t, mesh.tets(v, t), n));
    Real longest = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        longest = std::max(
            longest, (mesh.nodes.col(mesh.tets(a, t)) - mesh.nodes.col(mesh.tets(b, t))).norm());
    const Real volume = tet_volume(mesh, t);
    if (volume <= relative_tolerance * longest * longest * longest)
      throw InputError(
          fmt::format("{}: tetrahedron {} (nodes {} {} {} {}) is {} (volume {:.3e} m^3)", source, t,
                      mesh.tets(0, t), mesh.tets(1, t), mesh.tets(2, t), mesh.tets(3, t),
                      volume < 0 ? "inverted" : "degenerate", volume));
  }
  if (mesh.face_tag.size() != static_cast<size_t>(mesh.n_faces()))
    throw InputError(fmt::format("{}: {} boundary faces but {} face tags", source, mesh.n_faces(),
                                 mesh.face_tag.size()));
  if (!mesh.face_entity.empty() && mesh.face_entity.size() != static_cast<size_t>(mesh.n_faces()))
    throw InputError(fmt::format("{}: {} boundary faces but {} face entities", source,
                                 mesh.n_faces(), mesh.face_entity.size()));
  check_regions(mesh, source);
  check_rigid_surfaces(mesh, source);
  check_extra_nodes(mesh, source);
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    for (int v = 0; v < 3; ++v)
      if (mesh.faces(v, f) < 0 || mesh.faces(v, f) >= n)
        throw InputError(
            fmt::format("{}: boundary face {} refers to node {}, but the mesh has {} nodes", source,
                        f, mesh.faces(v, f), n));
    if (mesh.face_tag[f] < 0 || mesh.face_tag[f] >= static_cast<int>(mesh.tag_names.size()))
      throw InputError(fmt::format("{}: boundary face {} has tag {} of {}", source, f,
                                   mesh.face_tag[f], mesh.tag_names.size()));
    if (!(face_area(mesh, f) > 0.0))
      throw InputError(fmt::format("{}: boundary face {} has zero area", source, f));
  }
  for (const NodeSet& set : mesh.node_sets) {
    if (set.dim != kPointDimension && set.dim != kCurveDimension)
      throw InputError(fmt::format("{}: node set '{}' has dimension {}, expected 0 or 1", source,
                                   set.name, set.dim));
    for (std::size_t k = 0; k < set.nodes.size(); ++k)
      if (set.nodes[k] < 0 || set.nodes[k] >= n || (k > 0 && set.nodes[k] <= set.nodes[k - 1]))
        throw InputError(
            fmt::format("{}: {} '{}' refers to node {}, not a sorted, unique index of the {} nodes",
                        source, node_set_kind(set.dim), set.name, set.nodes[k], n));
  }
}

namespace {
using FaceKey = std::array<Index, 3>;
FaceKey sorted_face(Index a, Index b, Index c) {
  FaceKey k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}
// Local faces of a tetrahedron (v0,v1,v2,v3), each listed with the opposite vertex last.
constexpr int kTetFace[4][4] = {{1, 2, 3, 0}, {0, 3, 2, 1}, {0, 1, 3, 2}, {0, 2, 1, 3}};
}  // namespace

namespace {
// Every face of every tetrahedron by its vertex set, sorted so that copies of the same face are
// adjacent, with the tetrahedron and local face it comes from (20 bytes a face, 80 a tetrahedron:
// the largest transient of building a mesh, so 32-bit numbers; meshes past 2^32 nodes or
// tetrahedra, far beyond one process's memory, are refused).
using CompactKey = std::array<std::uint32_t, 3>;
CompactKey compact(const FaceKey& k) {
  return {static_cast<std::uint32_t>(k[0]), static_cast<std::uint32_t>(k[1]),
          static_cast<std::uint32_t>(k[2])};
}
struct TetFace {
  CompactKey key;      // its vertices, ascending
  std::uint32_t tet;   // the tetrahedron
  std::uint8_t local;  // its row of kTetFace
  // Its vertices oriented outward (for a positively oriented tetrahedron).
  std::array<Index, 3> oriented(const TetMesh& mesh) const {
    const int* lf = kTetFace[local];
    const auto t = static_cast<Index>(tet);
    return {mesh.tets(lf[0], t), mesh.tets(lf[1], t), mesh.tets(lf[2], t)};
  }
};
constexpr Index kCompactLimit = Index{1} << 32;
std::vector<TetFace> sorted_tet_faces(const TetMesh& mesh) {
  if (mesh.n_nodes() >= kCompactLimit || mesh.n_tets() >= kCompactLimit)
    throw Error(
        fmt::format("a mesh of {} nodes and {} tetrahedra: more than 2^32 of either is "
                    "beyond what one process can hold",
                    mesh.n_nodes(), mesh.n_tets()));
  std::vector<TetFace> faces;
  faces.reserve(static_cast<size_t>(4 * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (std::uint8_t l = 0; l < 4; ++l) {
      const int* lf = kTetFace[l];
      faces.push_back(
          {compact(sorted_face(mesh.tets(lf[0], t), mesh.tets(lf[1], t), mesh.tets(lf[2], t))),
           static_cast<std::uint32_t>(t), l});
    }
  std::sort(faces.begin(), faces.end(),
            [](const TetFace& a, const TetFace& b) { return a.key < b.key; });
  return faces;
}
// Calls visit(first, count) for each group of equal faces.
template <class Visit>
void for_each_face_group(const std::vector<TetFace>& faces, Visit visit) {
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key)
      ++j;
    visit(i, j - i);
    i = j;
  }
}
}  // namespace

FaceSharing face_sharing(const TetMesh& mesh) {
  FaceSharing s;
  for_each_face_group(sorted_tet_faces(mesh), [&](size_t, size_t count) {
    if (count == 1)
      ++s.n_boundary;
    else if (count == 2)
      ++s.n_interior;
    else
      ++s.n_overshared;
  });
  return s;
}

std::vector<bool> faces_of(const TetMesh& mesh, const std::vector<Index>& tets) {
  using Triple = std::array<Index, 3>;
  const auto sorted = [](Index a, Index b, Index c) {
    Triple t{a, b, c};
    std::sort(t.begin(), t.end());
    return t;
  };
  std::multimap<Triple, Index> boundary;  // a triangle in several tags is several columns
  for (Index f = 0; f < mesh.n_faces(); ++f)
    boundary.emplace(sorted(mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)), f);
  std::vector<bool> mine(static_cast<size_t>(mesh.n_faces()), false);
  // Face k of a tetrahedron leaves out its vertex k.
  for (Index t : tets)
    for (int k = 0; k < 4; ++k) {
      const auto [first, last] = boundary.equal_range(
          sorted(mesh.tets((k + 1) % 4, t), mesh.tets((k + 2) % 4, t), mesh.tets((k + 3) % 4, t)));
      for (auto it = first; it != last; ++it)
        mine[static_cast<size_t>(it->second)] = true;
    }
  return mine;
}

std::vector<Index> tets_of_faces(const TetMesh& mesh, const std::vector<Index>& faces) {
  // The triangles' vertex sets, sorted, with their positions; only tetrahedra with three
  // vertices on them are looked up.
  std::vector<std::pair<FaceKey, size_t>> wanted;
  std::vector<bool> on_faces(static_cast<size_t>(mesh.n_nodes()), false);
  for (size_t k = 0; k < faces.size(); ++k) {
    const Index f = faces[k];
    wanted.emplace_back(sorted_face(mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)), k);
    for (int v = 0; v < 3; ++v)
      on_faces[static_cast<size_t>(mesh.faces(v, f))] = true;
  }
  std::sort(wanted.begin(), wanted.end());
  std::vector<Index> tet(faces.size(), -1);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    int marked = 0;
    for (int a = 0; a < 4; ++a)
      marked += on_faces[static_cast<size_t>(mesh.tets(a, t))] ? 1 : 0;
    if (marked < 3) continue;
    for (const auto& lf : kTetFace) {
      const FaceKey key =
          sorted_face(mesh.tets(lf[0], t), mesh.tets(lf[1], t), mesh.tets(lf[2], t));
      auto it = std::lower_bound(wanted.begin(), wanted.end(), std::make_pair(key, size_t{0}));
      for (; it != wanted.end() && it->first == key; ++it)
        tet[it->second] = t;
    }
  }
  return tet;
}

TetMesh submesh(const TetMesh& mesh, const std::vector<Index>& tets, std::vector<Index>* nodes) {
  // The nodes of the tetrahedra, ascending, and each one's index in the part.
  std::vector<Index> local(static_cast<size_t>(mesh.n_nodes()), -1);
  for (Index t : tets)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a)
      local[static_cast<size_t>(mesh.tet_node(t, a))] = 0;
  std::vector<Index> global;
  for (Index v = 0; v < mesh.n_nodes(); ++v)
    if (local[static_cast<size_t>(v)] == 0) {
      local[static_cast<size_t>(v)] = static_cast<Index>(global.size());
      global.push_back(v);
    }
  const auto local_of = [&local](Index v) { return local[static_cast<size_t>(v)]; };

  TetMesh part;
  part.nodes = mesh.nodes(Eigen::all, global);
  part.tets.resize(4, static_cast<Index>(tets.size()));
  for (size_t k = 0; k < tets.size(); ++k)
    for (int a = 0; a < 4; ++a)
      part.tets(a, static_cast<Index>(k)) = local_of(mesh.tets(a, tets[k]));
  part.tet_extra.resize(mesh.tet_extra.rows(), static_cast<Index>(tets.size()));
  for (size_t k = 0; k < tets.size(); ++k)
    for (Index r = 0; r < mesh.tet_extra.rows(); ++r)
      part.tet_extra(r, static_cast<Index>(k)) = local_of(mesh.tet_extra(r, tets[k]));
  if (!mesh.tet_region.empty())
    for (Index t : tets)
      part.tet_region.push_back(mesh.region(t));
  part.region_names = mesh.region_names;

  const std::vector<bool> mine = faces_of(mesh, tets);
  std::vector<Index> faces;
  for (Index f = 0; f < mesh.n_faces(); ++f)
    if (mine[static_cast<size_t>(f)]) faces.push_back(f);
  part.faces.resize(3, static_cast<Index>(faces.size()));
  part.face_extra.resize(mesh.face_extra.rows(), static_cast<Index>(faces.size()));
  for (size_t k = 0; k < faces.size(); ++k) {
    const Index f = faces[k];
    for (int a = 0; a < 3; ++a)
      part.faces(a, static_cast<Index>(k)) = local_of(mesh.faces(a, f));
    for (Index r = 0; r < mesh.face_extra.rows(); ++r)
      part.face_extra(r, static_cast<Index>(k)) = local_of(mesh.face_extra(r, f));
    part.face_tag.push_back(mesh.face_tag[static_cast<size_t>(f)]);
    if (!mesh.face_entity.empty())
      part.face_entity.push_back(mesh.face_entity[static_cast<size_t>(f)]);
  }
  part.tag_names = mesh.tag_names;
  for (const NodeSet& set : mesh.node_sets) {
    NodeSet in_part{set.name, set.dim, {}};
    for (Index v : set.nodes)
      if (local[static_cast<size_t>(v)] >= 0) in_part.nodes.push_back(local_of(v));
    part.node_sets.push_back(std::move(in_part));  // ascending: `local` keeps the order
  }
  part.rigid_surfaces = mesh.rigid_surfaces;  // points of their own: nothing to renumber
  if (nodes != nullptr) *nodes = std::move(global);
  return part;
}

Eigen::Matrix<Index, 3, Eigen::Dynamic> boundary_faces_of(const TetMesh& mesh) {
  // For a positively oriented tetrahedron, the local faces of kTetFace are listed so that their
  // right-hand normal points away from the opposite vertex, i.e. outward.
  const std::vector<TetFace> faces = sorted_tet_faces(mesh);
  std::vector<size_t> boundary;
  for_each_face_group(faces, [&](size_t first, size_t count) {
    if (count == 1) boundary.push_back(first);
  });
  Eigen::Matrix<Index, 3, Eigen::Dynamic> result(3, static_cast<Index>(boundary.size()));
  for (size_t f = 0; f < boundary.size(); ++f) {
    const std::array<Index, 3> o = faces[boundary[f]].oriented(mesh);
    for (int v = 0; v < 3; ++v)
      result(v, static_cast<Index>(f)) = o[static_cast<size_t>(v)];
  }
  return result;
}

Index orient_faces_outward(TetMesh& mesh) {
  const std::vector<TetFace> faces = sorted_tet_faces(mesh);
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    const CompactKey key =
        compact(sorted_face(mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)));
    const auto it =
        std::lower_bound(faces.begin(), faces.end(), key,
                         [](const TetFace& a, const CompactKey& k) { return a.key < k; });
    if (it == faces.end() || it->key != key) return f;
    const std::array<Index, 3> o = it->oriented(mesh);
    for (int v = 0; v < 3; ++v)
      mesh.faces(v, f) = o[static_cast<size_t>(v)];
  }
  // The edge nodes follow the corners' new order (every edge is a tetrahedron's).
  fill_face_extra(mesh, "the mesh");
  return -1;
}

namespace {
using EdgeKey = std::pair<Index, Index>;
EdgeKey edge_key(Index a, Index b) {
  return a < b ? EdgeKey{a, b} : EdgeKey{b, a};
}
// The edge node of every edge of the tetrahedra of a quadratic mesh, sorted by edge.
std::vector<std::pair<EdgeKey, Index>> edge_nodes(const TetMesh& mesh, const std::string& source) {
  std::vector<std::pair<EdgeKey, Index>> edges;
  edges.reserve(static_cast<size_t>(kTetEdges * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int e = 0; e < kTetEdges; ++e)
      edges.emplace_back(edge_key(mesh.tets(kTetEdge[e][0], t), mesh.tets(kTetEdge[e][1], t)),
                         mesh.tet_extra(e, t));
  std::sort(edges.begin(), edges.end());
  for (size_t k = 1; k < edges.size(); ++k)
    if (edges[k].first == edges[k - 1].first && edges[k].second != edges[k - 1].second)
      throw InputError(fmt::format(
          "{}: the edge between nodes {} and {} has two midpoint nodes, {} and {}: the quadratic "
          "tetrahedra around it do not conform",
          source, edges[k].first.first, edges[k].first.second, edges[k - 1].second,
          edges[k].second));
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}
}  // namespace

void fill_face_extra(TetMesh& mesh, const std::string& source) {
  if (mesh.order() == 1) return;
  const auto edges = edge_nodes(mesh, source);
  mesh.face_extra.resize(kTriangleEdges, mesh.n_faces());
  for (Index f = 0; f < mesh.n_faces(); ++f)
    for (int e = 0; e < kTriangleEdges; ++e) {
      const EdgeKey key =
          edge_key(mesh.faces(kTriangleEdge[e][0], f), mesh.faces(kTriangleEdge[e][1], f));
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(key, Index{-1}));
      if (it == edges.end() || it->first != key)
        throw InputError(
            fmt::format("{}: boundary face {} has the edge {}-{}, which is no tetrahedron's",
                        source, f, key.first, key.second));
      mesh.face_extra(e, f) = it->second;
    }
}

void add_edge_midpoints(TetMesh& mesh) {
  FRICON_CHECK(mesh.order() == 1, "add_edge_midpoints: the mesh is already quadratic");
  std::vector<std::pair<EdgeKey, Index>> edges;
  edges.reserve(static_cast<size_t>(kTetEdges * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int e = 0; e < kTetEdges; ++e)
      edges.emplace_back(edge_key(mesh.tets(kTetEdge[e][0], t), mesh.tets(kTetEdge[e][1], t)), -1);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const Index first = mesh.n_nodes();
  mesh.nodes.conservativeResize(3, first + static_cast<Index>(edges.size()));
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto [a, b] = edges[k].first;
    edges[k].second = first + static_cast<Index>(k);
    mesh.nodes.col(edges[k].second) = 0.5 * (mesh.nodes.col(a) + mesh.nodes.col(b));
  }
  const auto node_of = [&edges](Index a, Index b) {
    const EdgeKey key = edge_key(a, b);
    return std::lower_bound(edges.begin(), edges.end(), std::make_pair(key, Index{-1}))->second;
  };
  mesh.tet_extra.resize(kTetEdges, mesh.n_tets());
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int e = 0; e < kTetEdges; ++e)
      mesh.tet_extra(e, t) = node_of(mesh.tets(kTetEdge[e][0], t), mesh.tets(kTetEdge[e][1], t));
  fill_face_extra(mesh, "the mesh");
  // A curve's edges are the tetrahedra's edges between two of its nodes.
  for (NodeSet& set : mesh.node_sets) {
    if (set.dim != kCurveDimension) continue;
    std::vector<Index> nodes = set.nodes;
    for (const auto& [key, node] : edges)
      if (std::binary_search(set.nodes.begin(), set.nodes.end(), key.first) &&
          std::binary_search(set.nodes.begin(), set.nodes.end(), key.second))
        nodes.push_back(node);
    std::sort(nodes.begin(), nodes.end());
    set.nodes = std::move(nodes);
  }
}

}  // namespace fricon::mesh
