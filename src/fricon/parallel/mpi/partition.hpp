#pragma once
// parallel/mpi: which rank assembles each tetrahedron of a distributed run (docs/parallel.md).
// Each rank computes the element matrices of its own tetrahedra only; MUMPS sums the entries the
// ranks give, so the partition changes the work of each rank, not the matrix.

#include <mpi.h>

#include <vector>

#include "fricon/mesh/tet_mesh.hpp"
#include "fricon/parallel/backend.hpp"

namespace fricon::parallel {

/// The owner rank (0 .. size-1) of every tetrahedron of `mesh`, on rank 0 (empty on the others).
/// Graph: PETSc's MatPartitioning (PT-Scotch) on the dual graph (tetrahedra sharing a face):
/// rank 0 builds the graph and gives each rank the rows of a block of tetrahedra, PT-Scotch
/// partitions it across the ranks, and rank 0 gathers the owners. Blocks: consecutive blocks in
/// mesh order. Collective over `comm`; `mesh` is read on rank 0 only (the others pass null).
/// A failure of rank 0 alone building the graph or the blocks is raised on every rank (Agreed);
/// one inside the collective calls of the graph partition ends the job (or_abort()).
std::vector<int> partition_elements(const mesh::TetMesh* mesh, PartitionKind kind, MPI_Comm comm);

/// The tetrahedra that `owner` gives to each rank 0 .. size-1, ascending, in one pass.
std::vector<std::vector<Index>> elements_by_rank(const std::vector<int>& owner, int size);

}  // namespace fricon::parallel
