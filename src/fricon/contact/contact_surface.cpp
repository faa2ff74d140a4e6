#include "fricon/contact/contact_surface.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::contact {

Index ContactSurface::n_contact_nodes() const {
  return static_cast<Index>(std::count(contact_node.begin(), contact_node.end(), true));
}

namespace {
// A component with a share of the normal below this (relative) does not move the node along it.
constexpr Real kNormalShareTolerance = 1e-12;
}  // namespace

ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where) {
  ContactSurface s;
  s.tag = tag;
  s.faces = mesh.faces_with_tag(tag);
  if (s.faces.empty())
    throw InputError(
        fmt::format("{}: contact.boundary: boundary '{}' does not exist on the mesh (tags: {})",
                    where, tag, mesh.tag_list()));
  s.nodes = mesh.nodes_with_tag(tag);
  std::map<Index, Index> position;
  for (size_t k = 0; k < s.nodes.size(); ++k)
    position[s.nodes[k]] = static_cast<Index>(k);
  s.face_nodes.resize(3, static_cast<Index>(s.faces.size()));
  Vec3 normal_sum = Vec3::Zero();
  for (size_t k = 0; k < s.faces.size(); ++k) {
    for (int v = 0; v < 3; ++v)
      s.face_nodes(v, static_cast<Index>(k)) = position[mesh.faces(v, s.faces[k])];
    const Real a = mesh::face_area(mesh, s.faces[k]);
    s.area += a;
    normal_sum += a * mesh::face_normal(mesh, s.faces[k]);
  }
  s.n = normal_sum.normalized();
  for (Index f : s.faces)
    if ((mesh::face_normal(mesh, f) - s.n).norm() > 1e-9)
      throw InputError(fmt::format(
          "{}: contact.boundary: the surface '{}' is not planar (face {} has normal ({:.3g}, "
          "{:.3g}, "
          "{:.3g}), the mean normal is ({:.3g}, {:.3g}, {:.3g})); contact with a rigid half-space "
          "needs a flat surface",
          where, tag, f, mesh::face_normal(mesh, f)(0), mesh::face_normal(mesh, f)(1),
          mesh::face_normal(mesh, f)(2), s.n(0), s.n(1), s.n(2)));
  const Vec3 e = std::abs(s.n(0)) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  s.t1 = (e - e.dot(s.n) * s.n).normalized();
  s.t2 = s.t1.cross(s.n);
  s.fixed.resize(s.nodes.size());
  s.contact_node.resize(s.nodes.size());
  for (size_t k = 0; k < s.nodes.size(); ++k) {
    bool normal_free = false;
    for (int c = 0; c < 3; ++c) {
      s.fixed[k][static_cast<size_t>(c)] = dofs.is_fixed(s.nodes[k], c);
      if (!s.fixed[k][static_cast<size_t>(c)] && std::abs(s.n(c)) > kNormalShareTolerance)
        normal_free = true;
    }
    s.contact_node[k] = normal_free;
  }
  if (s.n_contact_nodes() == 0)
    throw InputError(
        fmt::format("{}: contact.boundary: every node of '{}' is clamped in the normal direction "
                    "by Dirichlet conditions, so none can touch the foundation",
                    where, tag));
  return s;
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
    Vec3 u = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index dof = dofs.dof(s.nodes[static_cast<size_t>(k)], c);
      if (dof >= 0) u(c) = w(dof);
    }
    d.wn(k) = u.dot(s.n);
    d.wt1(k) = u.dot(s.t1);
    d.wt2(k) = u.dot(s.t2);
  }
  return d;
}

Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v) {
  Real sum = 0.0;
  for (size_t k = 0; k < surface.faces.size(); ++k) {
    const Real area = mesh::face_area(mesh, surface.faces[k]);
    Real s = 0.0, sq = 0.0;
    for (int a = 0; a < 3; ++a) {
      const Real va = v(surface.face_nodes(a, static_cast<Index>(k)));
      s += va;
      sq += va * va;
    }
    sum += area / 12.0 * (sq + s * s);  // v^T M v with M = |T|/12 (1 + delta_ab)
  }
  return std::sqrt(sum);
}

}  // namespace fricon::contact
