#include "fricon/contact/master_penetration.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fricon/contact/mortar_geometry.hpp"

namespace fricon::contact {

namespace {

// The slave triangles of the pair (mesh face indices).
std::vector<Index> pair_faces(const ContactSurface& surface, Index pair) {
  std::vector<Index> faces;
  for (size_t f = 0; f < surface.faces.size(); ++f)
    if (surface.node_pair[static_cast<size_t>(surface.face_nodes(0, static_cast<Index>(f)))] ==
        pair)
      faces.push_back(surface.faces[f]);
  return faces;
}

// Per master node (mesh node index, in `nodes`): its area-weighted mean outward normal.
std::vector<Vec3> master_normals(const mesh::TetMesh& mesh, const std::vector<Index>& faces,
                                 std::vector<Index>& nodes) {
  nodes.clear();
  for (Index f : faces)
    for (int v = 0; v < 3; ++v)
      nodes.push_back(mesh.faces(v, f));
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::vector<Vec3> normal(nodes.size(), Vec3::Zero());
  for (Index f : faces) {
    const Vec3 weighted = mesh::face_area(mesh, f) * mesh::face_normal(mesh, f);
    for (int v = 0; v < 3; ++v) {
      const auto at = std::lower_bound(nodes.begin(), nodes.end(), mesh.faces(v, f));
      normal[static_cast<size_t>(at - nodes.begin())] += weighted;
    }
  }
  for (Vec3& n : normal)
    n.normalize();
  return normal;
}

}  // namespace

MasterPenetration master_penetration(const mesh::TetMesh& mesh, const ContactSurface& surface,
                                     Index pair, const std::string& master, Real search_distance,
                                     const Eigen::Matrix<Real, 3, Eigen::Dynamic>& u) {
  MasterPenetration out;
  const std::vector<Index> slave_faces = pair_faces(surface, pair);
  const std::vector<Index> master_faces = mesh.faces_with_tag(master);
  if (slave_faces.empty() || master_faces.empty()) return out;
  for (Index k = 0; k < surface.n_nodes(); ++k)
    if (surface.node_pair[static_cast<size_t>(k)] == pair)
      out.normal_displacement = std::max(
          out.normal_displacement,
          std::abs(u.col(surface.nodes[static_cast<size_t>(k)]).dot(surface.node_frames.n.col(k))));
  const SurfaceLocator slave(mesh, slave_faces);
  std::vector<Index> nodes;
  const std::vector<Vec3> normal = master_normals(mesh, master_faces, nodes);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Index a = nodes[i];
    const Vec3& m = normal[i];
    const auto hit = slave.ray_hit(mesh.nodes.col(a), m, search_distance);
    if (!hit || !(mesh::face_normal(mesh, hit->face).dot(m) < -kFacingCosine)) continue;
    Vec3 u_slave = Vec3::Zero();
    for (int v = 0; v < 3; ++v)
      u_slave += hit->barycentric[static_cast<size_t>(v)] * u.col(mesh.faces(v, hit->face));
    out.normal_displacement = std::max(out.normal_displacement, std::abs(u.col(a).dot(m)));
    const Real gap = hit->distance + (u_slave - u.col(a)).dot(m);
    if (-gap > out.depth) {
      out.depth = -gap;
      out.node = a;
    }
  }
  return out;
}

}  // namespace fricon::contact
