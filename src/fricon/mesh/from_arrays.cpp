#include "fricon/mesh/from_arrays.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::mesh {

namespace {

constexpr Index kNodesPerTet = 4;
constexpr Index kNodesPerTriangle = 3;
constexpr Index kDimension = 3;

void require_rows(const std::string& source, std::string_view what, std::size_t size,
                  Index per_row) {
  if (size % static_cast<std::size_t>(per_row) != 0)
    throw InputError(fmt::format("{}: {}: expected {} columns per row, got {} values in all",
                                 source, what, per_row, size));
}

void copy_nodes_and_tets(const MeshArrays& a, const std::string& source, TetMesh& mesh) {
  require_rows(source, "points", a.points.size(), kDimension);
  require_rows(source, "tets", a.tets.size(), kNodesPerTet);
  const Index n = static_cast<Index>(a.points.size()) / kDimension;
  const Index m = static_cast<Index>(a.tets.size()) / kNodesPerTet;
  mesh.nodes = Eigen::Map<const Eigen::Matrix<Real, 3, Eigen::Dynamic>>(a.points.data(), 3, n);
  mesh.tets = Eigen::Map<const Eigen::Matrix<Index, 4, Eigen::Dynamic>>(a.tets.data(), 4, m);
}

void require_all_nodes_used(const std::string& source, const TetMesh& mesh) {
  if (const auto n = first_unused_node(mesh))
    throw InputError(
        fmt::format("{}: points[{}] belongs to no tetrahedron (remove it)", source, *n));
}

void add_boundary(const MeshArrays& a, const std::string& source, TetMesh& mesh) {
  std::vector<Index> corners;
  for (const auto& [name, triangles] : a.boundary) {
    require_rows(source, fmt::format("boundary['{}']", name), triangles.size(), kNodesPerTriangle);
    // A tag without triangles would be accepted here and "does not exist" where it is used.
    if (triangles.empty())
      throw InputError(fmt::format(
          "{}: boundary['{}']: expected at least one triangle, got none (leave the tag out)",
          source, name));
    const int tag = static_cast<int>(mesh.tag_names.size());
    mesh.tag_names.push_back(name);
    corners.insert(corners.end(), triangles.begin(), triangles.end());
    mesh.face_tag.insert(mesh.face_tag.end(), triangles.size() / kNodesPerTriangle, tag);
  }
  const Index k = static_cast<Index>(corners.size()) / kNodesPerTriangle;
  mesh.faces = Eigen::Map<const Eigen::Matrix<Index, 3, Eigen::Dynamic>>(corners.data(), 3, k);
  mesh.face_entity.assign(static_cast<std::size_t>(k), -1);
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

}  // namespace

TetMesh mesh_from_arrays(const MeshArrays& arrays, const std::string& source) {
  TetMesh mesh;
  copy_nodes_and_tets(arrays, source, mesh);
  add_boundary(arrays, source, mesh);
  add_regions(arrays, source, mesh);
  check_mesh(mesh, source);  // indices, finite coordinates, inverted or degenerate tetrahedra
  require_all_nodes_used(source, mesh);
  if (face_sharing(mesh).n_overshared > 0)
    throw InputError(fmt::format(
        "{}: the mesh is not conforming: a triangle is a face of three or more tetrahedra",
        source));
  if (const Index f = orient_faces_outward(mesh); f >= 0)
    throw InputError(fmt::format(
        "{}: boundary triangle {} ('{}': nodes {} {} {}) is no face of "
        "any tetrahedron",
        source, f,
        mesh.tag_names[static_cast<std::size_t>(mesh.face_tag[static_cast<std::size_t>(f)])],
        mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)));
  return mesh;
}

}  // namespace fricon::mesh
