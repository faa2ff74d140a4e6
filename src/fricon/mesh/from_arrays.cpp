#include "fricon/mesh/from_arrays.hpp"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::mesh {

namespace {

constexpr Index kDimension = 3;

void require_rows(const std::string& source, std::string_view what, std::size_t size,
                  Index per_row) {
  if (size % static_cast<std::size_t>(per_row) != 0)
    throw InputError(fmt::format("{}: {}: expected {} columns per row, got {} values in all",
                                 source, what, per_row, size));
}

using Edge = std::pair<Index, Index>;
Edge edge_of(Index a, Index b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

// The nodes and the corners of the tetrahedra; `edge_nodes` gets the edge nodes of quadratic
// tetrahedra (one column per tetrahedron, no rows for linear ones), which join the mesh once the
// corners are checked.
void copy_nodes_and_tets(const MeshArrays& a, const std::string& source, TetMesh& mesh,
                         Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic>& edge_nodes) {
  if (a.nodes_per_tet != kLinearTetNodes && a.nodes_per_tet != kQuadraticTetNodes)
    throw InputError(fmt::format(
        "{}: tets: expected {} nodes per tetrahedron (linear) or {} (quadratic: the corners, then "
        "the edges 01, 12, 20, 30, 32, 31), got {}",
        source, kLinearTetNodes, kQuadraticTetNodes, a.nodes_per_tet));
  require_rows(source, "points", a.points.size(), kDimension);
  require_rows(source, "tets", a.tets.size(), a.nodes_per_tet);
  const Index n = static_cast<Index>(a.points.size()) / kDimension;
  const Index m = static_cast<Index>(a.tets.size()) / a.nodes_per_tet;
  mesh.nodes = Eigen::Map<const Eigen::Matrix<Real, 3, Eigen::Dynamic>>(a.points.data(), 3, n);
  // m rows of nodes_per_tet, row-major: a column per tetrahedron.
  const Eigen::Map<const Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic>> all(
      a.tets.data(), a.nodes_per_tet, m);
  mesh.tets = all.topRows(kLinearTetNodes);
  edge_nodes = all.bottomRows(a.nodes_per_tet - kLinearTetNodes);
}

void require_all_nodes_used(const std::string& source, const TetMesh& mesh) {
  if (const auto n = first_unused_node(mesh))
    throw InputError(
        fmt::format("{}: points[{}] belongs to no tetrahedron (remove it)", source, *n));
}

// A 6-node triangle as given: its column of mesh.faces, where it was given (boundary[tag], row)
// and its nodes, whose edge nodes are checked against the tetrahedra's (require_given_edge_nodes).
struct GivenTriangle {
  Index face = 0;
  const std::string* tag = nullptr;
  Index row = 0;
  std::array<Index, kQuadraticTriangleNodes> nodes{};
};

// The triangles' corners, tags and entities; returns the 6-node triangles as given.
std::vector<GivenTriangle> add_boundary(const MeshArrays& a, const std::string& source,
                                        TetMesh& mesh) {
  std::vector<Index> corners;
  std::vector<GivenTriangle> given;
  for (const auto& [name, triangles] : a.boundary) {
    const std::string what = fmt::format("boundary['{}']", name);
    const Index width = triangles.width;
    if (width != kLinearTriangleNodes && width != kQuadraticTriangleNodes)
      throw InputError(fmt::format(
          "{}: {}: expected {} nodes per triangle (its corners) or {} (the corners, then the "
          "edges 01, 12, 20), got {}",
          source, what, kLinearTriangleNodes, kQuadraticTriangleNodes, width));
    if (width == kQuadraticTriangleNodes && a.nodes_per_tet != kQuadraticTetNodes)
      throw InputError(fmt::format(
          "{}: {}: 6-node triangles on linear ({}-node) tetrahedra; give their {} corners, or "
          "quadratic ({}-node) tetrahedra",
          source, what, kLinearTetNodes, kLinearTriangleNodes, kQuadraticTetNodes));
    require_rows(source, what, triangles.nodes.size(), width);
    // A tag without triangles would be accepted here and "does not exist" where it is used.
    if (triangles.nodes.empty())
      throw InputError(fmt::format(
          "{}: {}: expected at least one triangle, got none (leave the tag out)", source, what));
    const int tag = static_cast<int>(mesh.tag_names.size());
    mesh.tag_names.push_back(name);
    const Index rows = static_cast<Index>(triangles.nodes.size()) / width;
    for (Index r = 0; r < rows; ++r) {
      const auto row = triangles.nodes.begin() + r * width;
      if (width == kQuadraticTriangleNodes) {
        GivenTriangle g{static_cast<Index>(corners.size()) / kLinearTriangleNodes, &name, r, {}};
        std::copy(row, row + width, g.nodes.begin());
        given.push_back(g);
      }
      corners.insert(corners.end(), row, row + kLinearTriangleNodes);
    }
    mesh.face_tag.insert(mesh.face_tag.end(), static_cast<std::size_t>(rows), tag);
  }
  const Index k = static_cast<Index>(corners.size()) / kLinearTriangleNodes;
  mesh.faces = Eigen::Map<const Eigen::Matrix<Index, 3, Eigen::Dynamic>>(corners.data(), 3, k);
  mesh.face_entity.assign(static_cast<std::size_t>(k), -1);
  return given;
}

void add_regions(const MeshArrays& a, const std::string& source, TetMesh& mesh) {
  if (a.regions.empty()) return;
  mesh.tet_region.assign(static_cast<std::size_t>(mesh.n_tets()), -1);
  for (const auto& [name, tets] : a.regions) {
    if (tets.empty())
      throw InputError(fmt::format(
          "{}: regions['{}']: expected at least one tetrahedron, got none (leave the region out)",
          source, name));
    const int region = static_cast<int>(mesh.region_names.size());
    mesh.region_names.push_back(name);
    for (const Index t : tets) {
      if (t < 0 || t >= mesh.n_tets())
        throw InputError(fmt::format("{}: regions['{}'] holds tetrahedron {}, but the mesh has {}",
                                     source, name, t, mesh.n_tets()));
      int& r = mesh.tet_region[static_cast<std::size_t>(t)];
      if (r >= 0)
        throw InputError(fmt::format("{}: tetrahedron {} is in two regions, '{}' and '{}'", source,
                                     t, mesh.region_names[static_cast<std::size_t>(r)], name));
      r = region;
    }
  }
  for (Index t = 0; t < mesh.n_tets(); ++t)
    if (mesh.tet_region[static_cast<std::size_t>(t)] < 0)
      throw InputError(
          fmt::format("{}: tetrahedron {} is in no region (regions must cover the "
                      "mesh)",
                      source, t));
}

// The edge nodes of quadratic tetrahedra (theory.md §2.12) are nodes of the mesh, and they
// conform: each edge has one edge node, each edge node lies on one edge and is no corner. Then
// the tetrahedra give every boundary triangle its edge nodes (fill_face_extra). Messages name
// the entries of `tets` (row t, column 4 + e for edge e).
void require_conforming_edge_nodes(
    const std::string& source, const TetMesh& mesh,
    const Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic>& extra) {
  struct EdgeNode {
    Edge edge;
    Index node = 0;
    Index tet = 0;
    Index column = 0;  ///< in the row of `tets`
  };
  const auto entry = [](const EdgeNode& x) { return fmt::format("tets[{}, {}]", x.tet, x.column); };
  std::vector<EdgeNode> all;
  all.reserve(static_cast<std::size_t>(kTetEdges * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int e = 0; e < kTetEdges; ++e) {
      const EdgeNode x{edge_of(mesh.tets(kTetEdge[e][0], t), mesh.tets(kTetEdge[e][1], t)),
                       extra(e, t), t, kLinearTetNodes + e};
      if (x.node < 0 || x.node >= mesh.n_nodes())
        throw InputError(fmt::format("{}: {} is node {}, but the mesh has {} nodes", source,
                                     entry(x), x.node, mesh.n_nodes()));
      all.push_back(x);
    }
  std::sort(all.begin(), all.end(), [](const EdgeNode& x, const EdgeNode& y) {
    return std::tie(x.edge, x.node) < std::tie(y.edge, y.node);
  });
  for (std::size_t k = 1; k < all.size(); ++k)
    if (all[k].edge == all[k - 1].edge && all[k].node != all[k - 1].node)
      throw InputError(fmt::format(
          "{}: {} and {} give the edge between nodes {} and {} two edge nodes, {} and {}: the "
          "quadratic tetrahedra do not conform",
          source, entry(all[k - 1]), entry(all[k]), all[k].edge.first, all[k].edge.second,
          all[k - 1].node, all[k].node));
  std::sort(all.begin(), all.end(), [](const EdgeNode& x, const EdgeNode& y) {
    return std::tie(x.node, x.edge) < std::tie(y.node, y.edge);
  });
  for (std::size_t k = 1; k < all.size(); ++k)
    if (all[k].node == all[k - 1].node && all[k].edge != all[k - 1].edge)
      throw InputError(
          fmt::format("{}: node {} is the edge node of two edges, {}-{} ({}) and {}-{} ({})",
                      source, all[k].node, all[k - 1].edge.first, all[k - 1].edge.second,
                      entry(all[k - 1]), all[k].edge.first, all[k].edge.second, entry(all[k])));
  std::vector<bool> corner(static_cast<std::size_t>(mesh.n_nodes()), false);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int a = 0; a < kLinearTetNodes; ++a)
      corner[static_cast<std::size_t>(mesh.tets(a, t))] = true;
  for (const EdgeNode& x : all)
    if (corner[static_cast<std::size_t>(x.node)])
      throw InputError(fmt::format(
          "{}: {} is node {}, the edge node of the edge {}-{} and a corner of a tetrahedron",
          source, entry(x), x.node, x.edge.first, x.edge.second));
}

// Each edge node of a 6-node triangle is the one the tetrahedra give its edge (face_extra, filled
// when the triangles were oriented; orienting may have permuted the corners).
void require_given_edge_nodes(const std::string& source, const TetMesh& mesh,
                              const std::vector<GivenTriangle>& given) {
  for (const GivenTriangle& g : given)
    for (int e = 0; e < kTriangleEdges; ++e) {
      const Edge edge = edge_of(g.nodes[kTriangleEdge[e][0]], g.nodes[kTriangleEdge[e][1]]);
      const Index node = g.nodes[static_cast<std::size_t>(kLinearTriangleNodes + e)];
      for (int k = 0; k < kTriangleEdges; ++k) {
        if (edge_of(mesh.faces(kTriangleEdge[k][0], g.face),
                    mesh.faces(kTriangleEdge[k][1], g.face)) != edge)
          continue;
        if (mesh.face_extra(k, g.face) != node)
          throw InputError(fmt::format(
              "{}: boundary['{}'][{}, {}] is node {}, but the tetrahedra give the edge between "
              "nodes {} and {} the edge node {} (a 6-node triangle lists its corners, then the "
              "edge nodes of its edges 01, 12, 20)",
              source, *g.tag, g.row, kLinearTriangleNodes + e, node, edge.first, edge.second,
              mesh.face_extra(k, g.face)));
      }
    }
}

}  // namespace

TetMesh mesh_from_arrays(const MeshArrays& arrays, const std::string& source) {
  TetMesh mesh;
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> edge_nodes;
  copy_nodes_and_tets(arrays, source, mesh, edge_nodes);
  const std::vector<GivenTriangle> given = add_boundary(arrays, source, mesh);
  add_regions(arrays, source, mesh);
  // The corners first, as a linear mesh: indices, finite coordinates, inverted or degenerate
  // tetrahedra. A quadratic mesh's edge nodes join once they are sound (theory.md §2.12).
  check_mesh(mesh, source);
  if (edge_nodes.rows() > 0) {
    require_conforming_edge_nodes(source, mesh, edge_nodes);
    mesh.tet_extra = std::move(edge_nodes);
  }
  require_all_nodes_used(source, mesh);
  if (face_sharing(mesh).n_overshared > 0)
    throw InputError(fmt::format(
        "{}: the mesh is not conforming: a triangle is a face of three or more tetrahedra",
        source));
  // Orients the triangles and gives those of a quadratic mesh their edge nodes (fill_face_extra).
  if (const Index f = orient_faces_outward(mesh); f >= 0)
    throw InputError(fmt::format(
        "{}: boundary triangle {} ('{}': nodes {} {} {}) is no face of "
        "any tetrahedron",
        source, f,
        mesh.tag_names[static_cast<std::size_t>(mesh.face_tag[static_cast<std::size_t>(f)])],
        mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)));
  if (mesh.order() > 1) {
    check_mesh(mesh, source);  // the whole quadratic mesh
    require_given_edge_nodes(source, mesh, given);
  }
  return mesh;
}

}  // namespace fricon::mesh
