#pragma once
// driver: a part of the model, made of some of its tetrahedra: what one rank of a distributed run
// holds and assembles (docs/parallel.md). A part is itself a Model (its own mesh, dofs and
// prescribed displacements, numbered within the part), with the number in the whole model of
// each of its free dofs; K and f of the whole are the sums of the parts' K and f (load_vector with
// Extent::Part), mapped.

#include <vector>

#include "fricon/driver/model.hpp"

namespace fricon::driver {

struct ModelPart {
  /// The mesh of the part's tetrahedra (mesh::submesh), their materials, the dofs of the part's
  /// nodes (fixed where the whole model fixes them, the free ones numbered node-major within the
  /// part) and the prescribed displacements of those nodes. K, f and the factor are empty.
  Model model;
  /// The free dof of the whole model of each free dof of the part: ascending (the part's nodes
  /// keep the order of the whole mesh, and dofs are numbered node-major in both).
  std::vector<Index> global_dof;
};

/// The part of `whole` made of the tetrahedra `elements` (ascending indices into whole.mesh).
ModelPart model_part(const Model& whole, const std::vector<Index>& elements);

/// The dofs of a part's mesh: `fixed[3 * node + c]` as in the whole model, with the check that
/// their count agrees with `global_dof`. Throws Error when it does not.
fe::DofMap part_dofs(const std::vector<bool>& fixed, const std::vector<Index>& global_dof);

}  // namespace fricon::driver
