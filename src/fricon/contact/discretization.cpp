#include "fricon/contact/discretization.hpp"

#include "fricon/contact/radii.hpp"

namespace fricon::contact {

ContactDiscretization discretize_contact(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                         const ContactSpec& spec) {
  ContactDiscretization d;
  d.surface = make_contact_surface(mesh, dofs, spec.boundary, spec.where_boundary);
  d.patches = make_patches(spec.patches, mesh, d.surface, spec.where_patches);
  d.B = assemble_b(mesh, dofs, d.surface, d.patches);
  d.stability = check_stability(d.B, spec.where_patches);
  d.slip_bound = VectorXd::Constant(d.surface.n_nodes(), spec.slip_bound);
  d.gap = VectorXd::Zero(d.surface.n_nodes());
  d.dofs = dofs.free_dofs(d.surface.nodes);
  d.radius_integration = kRadiusIntegration;
  return d;
}

}  // namespace fricon::contact
