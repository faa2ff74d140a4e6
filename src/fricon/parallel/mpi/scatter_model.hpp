#pragma once
// parallel/mpi: rank 0 gives each rank of a distributed run its part of the model
// (docs/parallel.md): the tetrahedra the partition assigns to it, their nodes, the boundary
// triangles that are faces of them, the dofs of those nodes with their numbers in the whole model,
// and their prescribed displacements (driver::model_part). No rank but 0 holds the whole mesh.

#include <mpi.h>

#include <vector>

#include "fricon/driver/model_part.hpp"
#include "fricon/driver/problem.hpp"

namespace fricon::parallel {

/// Every rank's part of the model: rank 0 builds each one from `whole` (its model; null on the
/// other ranks) and `owner` (the rank of each tetrahedron, partition_elements) and sends it, one
/// rank at a time; each rank returns its own. The other ranks make the part's materials from
/// their `problem`. Collective over `comm`. When rank 0 cannot build a part it tells the ranks
/// still waiting before it throws, so that no rank is left waiting (run it in collectively());
/// a rank that fails before its part has arrived ends the job (or_abort()).
driver::ModelPart scatter_model(const driver::Problem& problem, const driver::Model* whole,
                                const std::vector<int>& owner, MPI_Comm comm);

}  // namespace fricon::parallel
