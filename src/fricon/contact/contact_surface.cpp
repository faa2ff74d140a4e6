#include "fricon/contact/contact_surface.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

Mat3 Frames::rows(Index k) const {
  Mat3 m;
  m.row(0) = n.col(k).transpose();
  m.row(1) = t1.col(k).transpose();
  m.row(2) = t2.col(k).transpose();
  return m;
}

Frames Frames::constant(const Vec3& n, const Vec3& t1, const Vec3& t2, Index count) {
  Frames f;
  f.n = n.replicate(1, count);
  f.t1 = t1.replicate(1, count);
  f.t2 = t2.replicate(1, count);
  return f;
}

std::pair<Vec3, Vec3> Frames::tangents(const Vec3& n) {
  // e1, unless n is within about 25 degrees of it: then e2 (a well-conditioned projection).
  constexpr Real kNearAxis = 0.9;
  const Vec3 e = std::abs(n(0)) < kNearAxis ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = (e - e.dot(n) * n).normalized();
  return {t1, t1.cross(n)};
}

Index ContactSurface::n_contact_nodes() const {
  return static_cast<Index>(std::count(contact_node.begin(), contact_node.end(), true));
}

namespace {
// A component with a share of the normal below this (relative) does not move the node along it.
constexpr Real kNormalShareTolerance = 1e-12;

// A face normal this close to the mean is flat (relative).
constexpr Real kFlatTolerance = 1e-9;
// A face whose outward normal has at most this component towards the obstacle does not face it.
constexpr Real kFacingTolerance = 1e-8;

/// The surface's triangles and nodes, and each triangle's vertices as positions in `nodes`.
ContactSurface surface_of_tag(const mesh::TetMesh& mesh, const std::string& tag,
                              const std::string& where) {
  ContactSurface s;
  s.tag = tag;
  s.faces = mesh.faces_with_tag(tag);
  if (s.faces.empty()) throw InputError(fmt::format("{}: {}", where, mesh.no_surface(tag)));
  s.nodes = mesh.nodes_with_tag(tag);
  std::map<Index, Index> position;
  for (size_t k = 0; k < s.nodes.size(); ++k)
    position[s.nodes[k]] = static_cast<Index>(k);
  s.face_nodes.resize(mesh.nodes_per_face(), static_cast<Index>(s.faces.size()));
  for (size_t k = 0; k < s.faces.size(); ++k) {
    for (int v = 0; v < mesh.nodes_per_face(); ++v)
      s.face_nodes(v, static_cast<Index>(k)) = position[mesh.face_node(s.faces[k], v)];
    s.area += face_integrals(mesh, s, static_cast<Index>(k)).shape.sum();  // curved at order 2
  }
  return s;
}

/// Every edge of the surface in at most two of its triangles.
void check_manifold(const mesh::TetMesh& mesh, const ContactSurface& s, const std::string& where) {
  std::map<std::pair<Index, Index>, int> count;
  for (Index f : s.faces)
    for (int v = 0; v < 3; ++v) {
      const Index a = mesh.faces(v, f), b = mesh.faces((v + 1) % 3, f);
      if (++count[{std::min(a, b), std::max(a, b)}] > 2)
        throw InputError(fmt::format(
            "{}: the surface '{}' is not a manifold: the edge between nodes {} "
            "({:.6g}, {:.6g}, {:.6g}) and {} ({:.6g}, {:.6g}, {:.6g}) is in three or more of its "
            "triangles (is a triangle listed twice, or do two bodies touch along an edge?)",
            where, s.tag, a, mesh.nodes(0, a), mesh.nodes(1, a), mesh.nodes(2, a), b,
            mesh.nodes(0, b), mesh.nodes(1, b), mesh.nodes(2, b)));
    }
}

/// Without an obstacle: the surface's own outward normal, which must be the same on every face.
Vec3 flat_surface_normal(const mesh::TetMesh& mesh, const ContactSurface& s,
                         const std::string& where) {
  Vec3 normal_sum = Vec3::Zero();
  for (Index f : s.faces)
    normal_sum += mesh::face_area(mesh, f) * mesh::face_normal(mesh, f);
  const Vec3 n = normal_sum.normalized();
  for (Index f : s.faces) {
    const Vec3 nf = mesh::face_normal(mesh, f);
    if ((nf - n).norm() > kFlatTolerance)
      throw InputError(fmt::format(
          "{}: the surface '{}' is not flat (face {} has normal ({:.3g}, "
          "{:.3g}, {:.3g}), the mean normal is ({:.3g}, {:.3g}, {:.3g})); a curved contact surface "
          "needs the plane it may touch: [contact] obstacle = {{ kind = \"plane\", point = [x, y, "
          "z], normal = [nx, ny, nz] }}",
          where, s.tag, f, nf(0), nf(1), nf(2), n(0), n(1), n(2)));
  }
  return n;
}

/// Which components Dirichlet conditions fix at each surface node, and which nodes can move
/// along n (the contact nodes).
void mark_fixed_components(const fe::DofMap& dofs, ContactSurface& s, const std::string& where) {
  s.fixed.resize(s.nodes.size());
  s.contact_node.resize(s.nodes.size());
  for (size_t k = 0; k < s.nodes.size(); ++k) {
    bool normal_free = false;
    const Vec3 n = s.node_frames.n.col(static_cast<Index>(k));
    for (int c = 0; c < 3; ++c) {
      s.fixed[k][static_cast<size_t>(c)] = dofs.is_fixed(s.nodes[k], c);
      if (!s.fixed[k][static_cast<size_t>(c)] && std::abs(n(c)) > kNormalShareTolerance)
        normal_free = true;
    }
    s.contact_node[k] = normal_free;
  }
  if (s.n_contact_nodes() == 0)
    throw InputError(
        fmt::format("{}: every node of '{}' is clamped in the normal direction "
                    "by Dirichlet conditions, so none can touch the foundation",
                    where, s.tag));
}

/// A unit vector's component for a message: rounding below 1e-12 shown as 0 (and no "-0").
Real shown(Real component) {
  constexpr Real kRounding = 1e-12;
  return std::abs(component) < kRounding ? 0.0 : component;
}

/// With an obstacle: some triangle of the surface must face it (its outward normal a positive
/// component along its nodes' mean n); a surface that faces away (a body's top against a plane
/// below it) could never touch and would solve silently without contact.
void require_facing_obstacle(const mesh::TetMesh& mesh, const ContactSurface& s,
                             const std::string& where) {
  for (size_t k = 0; k < s.faces.size(); ++k) {
    Vec3 n = Vec3::Zero();
    for (int v = 0; v < 3; ++v)
      n += s.node_frames.n.col(s.face_nodes(v, static_cast<Index>(k)));
    if (mesh::face_normal(mesh, s.faces[k]).dot(n.normalized()) > kFacingTolerance) return;
  }
  throw InputError(fmt::format(
      "{}: no triangle of the surface '{}' faces the obstacle (every outward "
      "normal n_f has n_f . n <= 0 for the direction n towards the obstacle, ({:.3g}, {:.3g}, "
      "{:.3g}) on the mean): the body could never touch it; check the tag, and where the "
      "obstacle is (a plane's normal points out of the obstacle towards the body)",
      where, s.tag, shown(s.n(0)), shown(s.n(1)), shown(s.n(2))));
}

/// The point of surface node k in rigid's configuration, relative to the obstacle at rest:
/// x + u_L - d_L.
Vec3 linearization_point(const mesh::TetMesh& mesh, const ContactSurface& s,
                         const RigidContact& rigid, Index k) {
  const Index a = s.nodes[static_cast<size_t>(k)];
  Vec3 y = mesh.nodes.col(a) - rigid.displacement;
  if (rigid.deformation != nullptr) y += rigid.deformation->col(a);
  return y;
}

/// Each node's frame from the obstacle's normal at its nearest point in rigid's configuration
/// (theory.md §2.11), and the surface's n: the plane's, or against a curved obstacle the
/// area-weighted mean of the nodes' normals at rest (the obstacle at rest, the body undeformed).
void obstacle_frames(const mesh::TetMesh& mesh, const RigidContact& rigid, ContactSurface& s) {
  const Obstacle& obstacle = *rigid.obstacle;
  if (obstacle.flat()) {
    s.n = -obstacle.closest(mesh.nodes.col(s.nodes.front())).normal;
    std::tie(s.t1, s.t2) = Frames::tangents(s.n);
    s.node_frames = Frames::constant(s.n, s.t1, s.t2, s.n_nodes());
    return;
  }
  s.frames_vary = true;
  s.node_frames.n.resize(3, s.n_nodes());
  s.node_frames.t1.resize(3, s.n_nodes());
  s.node_frames.t2.resize(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Vec3 n = -obstacle.closest(linearization_point(mesh, s, rigid, k)).normal;
    const auto [t1, t2] = Frames::tangents(n);
    s.node_frames.n.col(k) = n;
    s.node_frames.t1.col(k) = t1;
    s.node_frames.t2.col(k) = t2;
  }
  // The surface's own frame, in which the patches are laid out, from the obstacle at rest and the
  // body undeformed: the same partition at every linearization (theory.md §2.11).
  std::vector<Vec3> at_rest(static_cast<size_t>(s.n_nodes()));
  for (Index k = 0; k < s.n_nodes(); ++k)
    at_rest[static_cast<size_t>(k)] =
        -obstacle.closest(mesh.nodes.col(s.nodes[static_cast<size_t>(k)])).normal;
  Vec3 sum = Vec3::Zero();
  for (size_t f = 0; f < s.faces.size(); ++f)
    for (int v = 0; v < 3; ++v)
      sum += mesh::face_area(mesh, s.faces[f]) *
             at_rest[static_cast<size_t>(s.face_nodes(v, static_cast<Index>(f)))];
  s.n = sum.normalized();
  std::tie(s.t1, s.t2) = Frames::tangents(s.n);
}

/// The largest distance of a node of the surface from its first node [m] (at least half its
/// diameter).
Real surface_extent(const mesh::TetMesh& mesh, const ContactSurface& s) {
  Real extent = 0.0;
  for (Index a : s.nodes)
    extent = std::max(extent, (mesh.nodes.col(a) - mesh.nodes.col(s.nodes[0])).norm());
  return extent;
}

}  // namespace

ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where,
                                    const RigidContact* rigid) {
  ContactSurface s = surface_of_tag(mesh, tag, where);
  check_manifold(mesh, s, where);
  if (rigid != nullptr) {
    obstacle_frames(mesh, *rigid, s);
    require_facing_obstacle(mesh, s, where);
  } else {
    s.n = flat_surface_normal(mesh, s, where);
    std::tie(s.t1, s.t2) = Frames::tangents(s.n);
    s.node_frames = Frames::constant(s.n, s.t1, s.t2, s.n_nodes());
  }
  s.node_pair.assign(s.nodes.size(), 0);
  mark_fixed_components(dofs, s, where);
  return s;
}

ContactSurface surface_of_faces(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                const std::string& tag, const std::vector<Index>& faces,
                                const std::string& where) {
  ContactSurface s;
  s.tag = tag;
  s.faces = faces;
  std::map<Index, Index> position;
  for (Index f : faces)
    for (int v = 0; v < mesh.nodes_per_face(); ++v)
      position.emplace(mesh.face_node(f, v), 0);
  for (auto& [node, k] : position) {
    k = static_cast<Index>(s.nodes.size());
    s.nodes.push_back(node);
  }
  s.face_nodes.resize(mesh.nodes_per_face(), static_cast<Index>(faces.size()));
  Vec3 normal_sum = Vec3::Zero();
  for (size_t k = 0; k < faces.size(); ++k) {
    for (int v = 0; v < mesh.nodes_per_face(); ++v)
      s.face_nodes(v, static_cast<Index>(k)) = position[mesh.face_node(faces[k], v)];
    s.area += face_integrals(mesh, s, static_cast<Index>(k)).shape.sum();  // curved at order 2
    normal_sum += mesh::face_area(mesh, faces[k]) * mesh::face_normal(mesh, faces[k]);
  }
  check_manifold(mesh, s, where);
  s.n = normal_sum.normalized();
  std::tie(s.t1, s.t2) = Frames::tangents(s.n);
  s.node_frames = nodal_frames(mesh, s);
  s.node_pair.assign(s.nodes.size(), 0);
  mark_fixed_components(dofs, s, where);
  return s;
}

Frames nodal_frames(const mesh::TetMesh& mesh, const ContactSurface& s) {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> sum =
      Eigen::Matrix<Real, 3, Eigen::Dynamic>::Zero(3, s.n_nodes());
  for (size_t k = 0; k < s.faces.size(); ++k) {
    const Vec3 weighted = mesh::face_area(mesh, s.faces[k]) * mesh::face_normal(mesh, s.faces[k]);
    for (Index v = 0; v < s.face_nodes.rows(); ++v)
      sum.col(s.face_nodes(v, static_cast<Index>(k))) += weighted;
  }
  Frames f;
  f.n.resize(3, s.n_nodes());
  f.t1.resize(3, s.n_nodes());
  f.t2.resize(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Vec3 n = sum.col(k).normalized();
    const auto [t1, t2] = Frames::tangents(n);
    f.n.col(k) = n;
    f.t1.col(k) = t1;
    f.t2.col(k) = t2;
  }
  return f;
}

VectorXd obstacle_gap(const mesh::TetMesh& mesh, const ContactSurface& surface,
                      const RigidContact& rigid) {
  const bool reference = rigid.displacement.isZero(0.0) && rigid.deformation == nullptr;
  VectorXd gap(surface.n_nodes());
  for (Index k = 0; k < surface.n_nodes(); ++k) {
    const Vec3 y = linearization_point(mesh, surface, rigid, k);
    const Vec3 moved = y - mesh.nodes.col(surface.nodes[static_cast<size_t>(k)]);  // u_L - d_L
    gap(k) = rigid.obstacle->closest(y).distance + surface.node_frames.n.col(k).dot(moved);
    // At rest, a node within the start tolerance below the surface touches it
    // (check_outside_obstacle refuses deeper ones).
    if (reference) gap(k) = std::max(gap(k), 0.0);
  }
  return gap;
}

void check_outside_obstacle(const mesh::TetMesh& mesh, const ContactSurface& surface,
                            const Obstacle& obstacle, const std::string& where) {
  const Real tolerance = kStartPenetrationTolerance * surface_extent(mesh, surface);
  Index deepest = -1;
  Real depth = tolerance;
  for (Index a : surface.nodes) {
    const Real d = -obstacle.closest(mesh.nodes.col(a)).distance;
    if (d > depth) {
      depth = d;
      deepest = a;
    }
  }
  if (deepest < 0) return;
  throw InputError(fmt::format(
      "{}: the contact surface '{}' starts inside the {} obstacle: node {} at ({:.6g}, {:.6g}, "
      "{:.6g}) lies {:.6g} m deep in it (more than the tolerance {:.3g} m, {:g} of the surface's "
      "extent); the obstacle is taken at rest, before its displacement: check where it is (a "
      "plane's normal points out of the obstacle towards the body)",
      where, surface.tag, obstacle.kind(), deepest, mesh.nodes(0, deepest), mesh.nodes(1, deepest),
      mesh.nodes(2, deepest), depth, tolerance, kStartPenetrationTolerance));
}

VectorXd SurfaceDisplacement::slip() const {
  return (wt1.array().square() + wt2.array().square()).sqrt().matrix();
}

SurfaceDisplacement surface_displacement(const ContactSurface& s, const fe::DofMap& dofs,
                                         const VectorXd& w) {
  const Index n = s.n_nodes();
  SurfaceDisplacement d;
  d.wn.resize(n);
  d.wt1.resize(n);
  d.wt2.resize(n);
  for (Index k = 0; k < n; ++k) {
    Vec3 u = s.prescribed.size() > 0 ? Vec3(s.prescribed.col(k)) : Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index dof = dofs.dof(s.nodes[static_cast<size_t>(k)], c);
      if (dof >= 0) u(c) = w(dof);
    }
    if (s.master.size() > 0 || s.master_prescribed.size() > 0)
      u -= master_displacement(s, dofs, w, k);
    d.wn(k) = u.dot(s.node_frames.n.col(k));
    d.wt1(k) = u.dot(s.node_frames.t1.col(k));
    d.wt2(k) = u.dot(s.node_frames.t2.col(k));
  }
  return d;
}

Vec3 master_displacement(const ContactSurface& s, const fe::DofMap& dofs, const VectorXd& w,
                         Index k) {
  Vec3 u = s.master_prescribed.size() > 0 ? Vec3(s.master_prescribed.col(k)) : Vec3::Zero();
  if (k >= s.master.rows()) return u;  // against a rigid obstacle: its displacement alone
  for (decltype(s.master)::InnerIterator it(s.master, k); it; ++it)
    for (int c = 0; c < 3; ++c) {
      const Index dof = dofs.dof(it.col(), c);
      if (dof >= 0) u(c) += it.value() * w(dof);
    }
  return u;
}

Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v) {
  Real sum = 0.0;
  for (Index k = 0; k < static_cast<Index>(surface.faces.size()); ++k) {
    const VectorXd vk = v(surface.face_nodes.col(k));
    sum += vk.dot(face_integrals(mesh, surface, k).mass * vk);  // v^T M v
  }
  return std::sqrt(sum);
}

}  // namespace fricon::contact
