#include "fricon/driver/model_part.hpp"

#include "fricon/core/error.hpp"

namespace fricon::driver {

fe::DofMap part_dofs(const std::vector<bool>& fixed, const std::vector<Index>& global_dof) {
  fe::DofMap dofs(fixed);
  FRICON_CHECK(dofs.n_free() == static_cast<Index>(global_dof.size()),
               "a part of the model has " << dofs.n_free() << " free dofs and " << global_dof.size()
                                          << " global numbers");
  return dofs;
}

ModelPart model_part(const Model& whole, const std::vector<Index>& elements) {
  ModelPart part;
  std::vector<Index> nodes;  // of the part, in the whole mesh
  part.model.mesh = mesh::submesh(whole.mesh, elements, &nodes);
  part.model.materials = whole.materials;
  std::vector<bool> fixed(3 * nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a)
    for (int c = 0; c < 3; ++c) {
      const Index dof = whole.dofs.dof(nodes[a], c);
      fixed[3 * a + static_cast<size_t>(c)] = dof < 0;
      if (dof >= 0) part.global_dof.push_back(dof);
    }
  part.model.dofs = part_dofs(fixed, part.global_dof);
  if (whole.prescribed.cols() > 0) part.model.prescribed = whole.prescribed(Eigen::all, nodes);
  return part;
}

}  // namespace fricon::driver
