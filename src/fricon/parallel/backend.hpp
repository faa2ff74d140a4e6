#pragma once
// parallel: where the linear algebra of a run happens ([solver] backend, docs/parallel.md):
// CHOLMOD on one process, or MUMPS on the ranks of an MPI job through PETSc's MPI stack. The
// backend and the element partition of a distributed run are chosen by these enums; nothing here
// needs MPI, so every build knows the names (a build without PETSc says how to get it).

#include <array>
#include <string_view>
#include <utility>

#include "fricon/core/enum_names.hpp"

namespace fricon::parallel {

enum class Backend {
  /// One process: K factored by CHOLMOD, the dual operators of dual/ (the default).
  Cholmod,
  /// P MPI ranks (P >= 1): each rank assembles its own elements, MUMPS factors the augmented
  /// matrix [[K, B^T], [B, 0]] across the ranks and returns Q as its Schur complement on rank 0
  /// (docs/theory.md §3.3).
  Petsc,
  /// Total FETI (docs/theory.md §8): each body cut into subdomains, each factored on its own
  /// (threads on one process); the subdomains glued by equality multipliers that join the
  /// contact multipliers in one dual QP.
  Tfeti,
};

/// How the tetrahedra are split among the ranks of a distributed run ([solver] partition).
enum class PartitionKind {
  /// PETSc's graph partitioner (PT-Scotch) on the dual graph of the mesh (the default).
  Graph,
  /// Consecutive blocks of tetrahedra in mesh order; for comparison (the answer must not change).
  Blocks,
};

/// True when this build of fricon has the PETSc backend (Debian petsc-dev found at configure).
bool petsc_available();

}  // namespace fricon::parallel

FRICON_ENUM_NAMES(fricon::parallel::Backend, "solver.backend",
                  {parallel::Backend::Cholmod, "cholmod"}, {parallel::Backend::Petsc, "petsc"},
                  {parallel::Backend::Tfeti, "tfeti"});
FRICON_ENUM_NAMES(fricon::parallel::PartitionKind, "solver.partition",
                  {parallel::PartitionKind::Graph, "graph"},
                  {parallel::PartitionKind::Blocks, "blocks"});
