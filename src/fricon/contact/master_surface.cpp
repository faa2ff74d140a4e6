#include "fricon/contact/master_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/element.hpp"

namespace fricon::contact {

namespace {

// The default search distance: this share of the slave tag's diameter.
constexpr Real kDefaultSearchShare = 0.1;
// A node this far inside the master (relative to the slave's diameter) is on it: rounding of the
// geometry. Deeper, the bodies overlap at the start.
constexpr Real kOverlapRoundoff = 1e-9;

/// One slave node's search result.
struct NodeHit {
  bool found = false;          ///< a facing master triangle within the search distance
  bool facing = true;          ///< false: the first hit faces away (same orientation as the slave)
  Real gap = 0.0;              ///< [m], along `normal`
  Vec3 normal = Vec3::Zero();  ///< the contact normal of the node (theory.md §2.8)
  Index face = -1;             ///< the master triangle (mesh face index)
  std::array<Real, 3> weights{};  ///< its vertices' shape functions at the hit
};

Real diameter(const mesh::TetMesh& mesh, const std::vector<Index>& nodes) {
  Vec3 lo = mesh.nodes.col(nodes.front()), hi = lo;
  for (Index a : nodes) {
    lo = lo.cwiseMin(mesh.nodes.col(a));
    hi = hi.cwiseMax(mesh.nodes.col(a));
  }
  return (hi - lo).norm();
}

std::vector<Index> faces_of_tag(const mesh::TetMesh& mesh, const std::string& tag,
                                const std::string& where) {
  std::vector<Index> faces = mesh.faces_with_tag(tag);
  if (faces.empty()) throw InputError(fmt::format("{}: {}", where, mesh.no_surface(tag)));
  return faces;
}

/// Self-contact is not supported: the slave and the master must be on different bodies.
void require_two_bodies(const mesh::TetMesh& mesh, const std::vector<Index>& slave_faces,
                        const std::vector<Index>& master_faces, const std::string& slave,
                        const MasterSpec& master, const std::string& where) {
  if (master.node_body.empty()) return;
  std::vector<bool> slave_body(mesh.n_nodes(), false);
  for (Index f : slave_faces)
    for (int v = 0; v < 3; ++v)
      slave_body[static_cast<size_t>(master.node_body[static_cast<size_t>(mesh.faces(v, f))])] =
          true;
  for (Index f : master_faces)
    for (int v = 0; v < 3; ++v) {
      const Index b = master.node_body[static_cast<size_t>(mesh.faces(v, f))];
      if (slave_body[static_cast<size_t>(b)])
        throw InputError(fmt::format(
            "{}: the master surface '{}' and the contact surface '{}' "
            "({}) are on the same body ({}): self-contact is not supported; the master must be a "
            "surface of another body (another volume of the mesh that shares no node with it)",
            master.where_boundary, master.boundary, slave, where, b));
    }
}

/// The hit of the ray x + t n on the master, if it meets a triangle facing n.
std::optional<RayHit> facing_hit(const mesh::TetMesh& mesh, const SurfaceLocator& locator,
                                 const Vec3& x, const Vec3& n, Real distance, bool& facing) {
  const std::optional<RayHit> hit = locator.ray_hit(x, n, distance);
  if (!hit) return std::nullopt;
  facing = mesh::face_normal(mesh, hit->face).dot(n) < -kFacingCosine;
  return facing ? hit : std::nullopt;
}

/// Step 1: every slave node's ray to the master: along its outward normal n_s, which finds the
/// master triangle opposite and its normal n_m, then along the averaged normal
/// n = (n_s - n_m) / |n_s - n_m| (theory.md §2.8), which is the node's contact normal.
std::vector<NodeHit> search_master(const mesh::TetMesh& mesh, const ContactSurface& whole,
                                   const SurfaceLocator& locator, Real distance) {
  std::vector<NodeHit> hits(static_cast<size_t>(whole.n_nodes()));
  for (Index k = 0; k < whole.n_nodes(); ++k) {
    NodeHit& h = hits[static_cast<size_t>(k)];
    const Vec3 x = mesh.nodes.col(whole.nodes[static_cast<size_t>(k)]);
    const Vec3 n_slave = whole.node_frames.n.col(k);
    std::optional<RayHit> hit = facing_hit(mesh, locator, x, n_slave, distance, h.facing);
    if (!hit) continue;
    h.normal = n_slave;
    const Vec3 averaged = (n_slave - mesh::face_normal(mesh, hit->face)).normalized();
    bool facing = true;
    if (const auto again = facing_hit(mesh, locator, x, averaged, distance, facing)) {
      hit = again;
      h.normal = averaged;
    }
    h.found = true;
    h.gap = hit->distance;
    h.face = hit->face;
    h.weights = hit->barycentric;
  }
  return hits;
}

/// Step 2: the slave triangles whose three vertices found the master.
std::vector<Index> faces_in_reach(const ContactSurface& whole, const std::vector<NodeHit>& hits) {
  std::vector<Index> kept;
  for (size_t k = 0; k < whole.faces.size(); ++k) {
    bool all = true;
    for (Index v = 0; v < whole.face_nodes.rows(); ++v)
      all = all && hits[static_cast<size_t>(whole.face_nodes(v, static_cast<Index>(k)))].found;
    if (all) kept.push_back(whole.faces[k]);
  }
  return kept;
}

[[noreturn]] void refuse_out_of_reach(const ContactSurface& whole, const std::vector<NodeHit>& hits,
                                      const std::string& slave, const MasterSpec& master,
                                      Real distance, const std::string& where) {
  const auto away =
      std::count_if(hits.begin(), hits.end(), [](const NodeHit& h) { return !h.facing; });
  if (away > 0)
    throw InputError(fmt::format(
        "{}: the surfaces '{}' and '{}' do not face each other: the master "
        "triangles that {} of the {} nodes of '{}' meet along their outward normal face the same "
        "way (their outward normals must be opposite); check the two tags",
        where, slave, master.boundary, away, whole.n_nodes(), slave));
  throw InputError(fmt::format(
      "{}: no triangle of '{}' has the master surface '{}' within the search "
      "distance {:.4g} m along its normal (contact.search_distance): the pair has no overlap; "
      "check the tags, the geometry's unit ([mesh] unit) and the search distance",
      where, slave, master.boundary, distance));
}

/// The kept nodes' gaps, refusing a node that starts inside the master.
VectorXd gaps_of(const mesh::TetMesh& mesh, const ContactSurface& s,
                 const std::vector<NodeHit>& hits, const std::vector<Index>& whole_position,
                 Real slave_diameter, const std::string& slave, const std::string& where) {
  VectorXd gap(s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Index a = s.nodes[static_cast<size_t>(k)];
    const NodeHit& h = hits[static_cast<size_t>(whole_position[static_cast<size_t>(a)])];
    if (h.gap < -kOverlapRoundoff * slave_diameter)
      throw InputError(fmt::format(
          "{}: node {} of '{}' at ({:.6g}, {:.6g}, {:.6g}) starts inside the "
          "master surface (gap {:.4g} m < 0): the bodies must not overlap at the start",
          where, a, slave, mesh.nodes(0, a), mesh.nodes(1, a), mesh.nodes(2, a), h.gap));
    gap(k) = h.gap > 0.0 ? h.gap : 0.0;  // no "-0" from a gap rounded below zero
  }
  return gap;
}

Real mean_edge(const mesh::TetMesh& mesh, const std::vector<Index>& faces) {
  Real sum = 0.0;
  for (Index f : faces)
    for (int v = 0; v < 3; ++v)
      sum += (mesh.nodes.col(mesh.faces(v, f)) - mesh.nodes.col(mesh.faces((v + 1) % 3, f))).norm();
  return sum / (3.0 * static_cast<Real>(faces.size()));
}

}  // namespace

SlaveSurface make_slave_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                const std::string& slave, const std::string& where,
                                const MasterSpec& master,
                                const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  // @sect: both surfaces, on two bodies.
  const std::vector<Index> slave_faces = faces_of_tag(mesh, slave, where);
  const std::vector<Index> master_faces =
      faces_of_tag(mesh, master.boundary, master.where_boundary);
  require_two_bodies(mesh, slave_faces, master_faces, slave, master, where);
  const ContactSurface whole = surface_of_faces(mesh, dofs, slave, slave_faces, where);
  SlaveSurface out;
  out.n_tag_faces = static_cast<Index>(slave_faces.size());
  const Real slave_diameter = diameter(mesh, whole.nodes);
  out.search_distance =
      master.search_distance > 0.0 ? master.search_distance : kDefaultSearchShare * slave_diameter;
  out.master_element_size = mean_edge(mesh, master_faces);

  // @sect: step 1, each node's ray to the master; step 2, the triangles in reach.
  out.master = std::make_shared<const SurfaceLocator>(mesh, master_faces);
  const std::vector<NodeHit> hits = search_master(mesh, whole, *out.master, out.search_distance);
  const std::vector<Index> kept = faces_in_reach(whole, hits);
  if (kept.empty()) refuse_out_of_reach(whole, hits, slave, master, out.search_distance, where);
  out.surface = surface_of_faces(mesh, dofs, slave, kept, where);
  ContactSurface& s = out.surface;
  // Against a body each node's frame is that of its contact normal (its ray's direction).
  std::vector<Index> whole_position(static_cast<size_t>(mesh.n_nodes()), -1);
  for (Index k = 0; k < whole.n_nodes(); ++k)
    whole_position[static_cast<size_t>(whole.nodes[static_cast<size_t>(k)])] = k;
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Index w = whole_position[static_cast<size_t>(s.nodes[static_cast<size_t>(k)])];
    const Vec3 n = hits[static_cast<size_t>(w)].normal;
    const auto [t1, t2] = Frames::tangents(n);
    s.node_frames.n.col(k) = n;
    s.node_frames.t1.col(k) = t1;
    s.node_frames.t2.col(k) = t2;
  }

  // @sect: the gaps and the master's interpolation at each node's projection.
  out.gap = gaps_of(mesh, s, hits, whole_position, slave_diameter, slave, where);
  // The master's face element at the hit's barycentric point on the flat triangle through its
  // corners (theory.md §2.12).
  const fe::Element& face_element = fe::elements_of(mesh).face;
  std::vector<Eigen::Triplet<Real, SparseIndex>> weights;
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const NodeHit& h = hits[static_cast<size_t>(
        whole_position[static_cast<size_t>(s.nodes[static_cast<size_t>(k)])])];
    const fe::ShapeValues N = face_element.values(Vec3(h.weights[0], h.weights[1], h.weights[2]));
    for (int v = 0; v < face_element.n_nodes(); ++v)
      if (N(v) != 0.0) weights.emplace_back(k, mesh.face_node(h.face, v), N(v));
  }
  s.master.resize(s.n_nodes(), mesh.n_nodes());
  s.master.setFromTriplets(weights.begin(), weights.end());
  if (prescribed.size() > 0 && !prescribed.isZero(0.0))
    s.master_prescribed = (s.master * prescribed.transpose()).transpose();
  return out;
}

SparseMatrix mortar_matrix(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const Patches& patches, const Frames& frames,
                           const SurfaceLocator& master, Real search_distance, Real& coverage) {
  const fe::Element& face_element = fe::elements_of(mesh).face;
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  Real covered = 0.0;
  for (Index p = 0; p < patches.size(); ++p)
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index f = surface.faces[static_cast<size_t>(k)];
      const Triangle3 slave{mesh.nodes.col(mesh.faces(0, f)), mesh.nodes.col(mesh.faces(1, f)),
                            mesh.nodes.col(mesh.faces(2, f))};
      // The overlaps are measured on the flat triangle through the slave's corners; the slave's
      // rows on its own (curved) triangle (theory.md §2.12). Scaled by the ratio of the two
      // areas, the master's integrals over a covered triangle add up to the slave's: the forces
      // on the two bodies cancel. 1 up to rounding on straight triangles.
      const Real curved_per_flat =
          face_integrals(mesh, surface, k).shape.sum() / mesh::face_area(mesh, f);
      for (const MortarOverlap& o :
           mortar_overlaps(slave, frames.n.col(p), master, search_distance)) {
        // Only the master triangles that face the slave (a thin master's far side does not).
        if (mesh::face_normal(mesh, o.master_face).dot(frames.n.col(p)) >= -kFacingCosine) continue;
        covered += curved_per_flat * o.area;
        // int over the overlap of each master node's shape function (the face element at the
        // master barycentric point of each quadrature point; theory.md §2.12).
        for (const MortarOverlap::Point& q : o.points) {
          const fe::ShapeValues N =
              face_element.values(Vec3(q.master[0], q.master[1], q.master[2]));
          for (int j = 0; j < face_element.n_nodes(); ++j)
            entries.emplace_back(p, mesh.face_node(o.master_face, j),
                                 curved_per_flat * q.weight * N(j));
        }
      }
    }
  coverage = covered / surface.area;
  SparseMatrix M(patches.size(), mesh.n_nodes());
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

}  // namespace fricon::contact
