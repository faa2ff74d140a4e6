#include "fricon/contact/discretization.hpp"

#include "fricon/contact/radii.hpp"

namespace fricon::contact {

namespace {

/// The surface nodes' columns of the prescribed field (empty stays empty).
Eigen::Matrix<Real, 3, Eigen::Dynamic> prescribed_on_surface(
    const ContactSurface& s, const Eigen::Matrix<Real, 3, Eigen::Dynamic>& prescribed) {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> p;
  if (prescribed.size() == 0 || prescribed.isZero(0.0)) return p;
  p.resize(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k)
    p.col(k) = prescribed.col(s.nodes[static_cast<size_t>(k)]);
  return p;
}

/// c of ContactDiscretization::offset: the P1 integrals over each patch (exact: |T|/3 times the
/// sum of the vertex values on each triangle).
VectorXd constraint_offset(const mesh::TetMesh& mesh, const ContactSurface& s,
                           const Patches& patches, const VectorXd& gap) {
  VectorXd c = VectorXd::Zero(3 * patches.size());
  for (Index p = 0; p < patches.size(); ++p)
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Real third = mesh::face_area(mesh, s.faces[static_cast<size_t>(k)]) / 3.0;
      for (int v = 0; v < 3; ++v) {
        const Index node = s.face_nodes(v, k);
        const Vec3 u = s.prescribed.size() > 0 ? Vec3(s.prescribed.col(node)) : Vec3::Zero();
        c(3 * p) += third * (gap(node) - u.dot(s.n));
        c(3 * p + 1) -= third * u.dot(s.t1);
        c(3 * p + 2) -= third * u.dot(s.t2);
      }
    }
  return c;
}

}  // namespace

ContactDiscretization discretize_contact(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                         const ContactSpec& spec) {
  ContactDiscretization d;
  d.surface = make_contact_surface(mesh, dofs, spec.boundary, spec.where_boundary, spec.obstacle);
  d.surface.prescribed = prescribed_on_surface(d.surface, spec.prescribed);
  d.patches = make_patches(spec.patches, mesh, d.surface, spec.where_patches);
  d.B = assemble_b(mesh, dofs, d.surface, d.patches);
  d.stability = check_stability(d.B, spec.where_patches);
  d.slip_bound = VectorXd::Constant(d.surface.n_nodes(), spec.slip_bound);
  d.gap = spec.obstacle ? initial_gap(mesh, d.surface, *spec.obstacle, spec.where_obstacle)
                        : VectorXd::Zero(d.surface.n_nodes());
  d.offset = constraint_offset(mesh, d.surface, d.patches, d.gap);
  d.dofs = dofs.free_dofs(d.surface.nodes);
  d.radius_integration = kRadiusIntegration;
  return d;
}

}  // namespace fricon::contact
