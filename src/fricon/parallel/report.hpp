#pragma once
// parallel: what a distributed run ([solver] backend = "petsc", docs/parallel.md) adds to the
// report of a run. Data only: the run's report (driver::RunReport) holds it, and the writers
// (io/results.cpp) read it, without depending on MPI.

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/parallel/backend.hpp"

namespace fricon::parallel {

/// One rank of a distributed run (backend "petsc").
struct RankReport {
  Index n_tets = 0;  ///< tetrahedra this rank assembled
  /// Nodes of the mesh this rank holds: all on rank 0, the nodes of its tetrahedra elsewhere.
  Index n_nodes = 0;
  double peak_memory_mib = 0;     ///< peak resident memory of the process [MiB]
  double mumps_memory_mib = 0;    ///< memory MUMPS allocated for the factorization here [MiB]
  double mumps_estimate_mib = 0;  ///< what MUMPS's analysis estimated for it [MiB]
  /// Peak resident memory once the rank's input was built, before the assembly and
  /// factorization [MiB]: on rank 0 the whole model (mesh, loads, contact discretization), on
  /// the others their part of it (their tetrahedra and nodes, B on the contact dofs).
  double model_memory_mib = 0;
};

/// What a distributed run adds to the report.
struct ParallelReport {
  int rank = 0;     ///< of the process that holds this report
  int n_ranks = 1;  ///< MPI ranks of the run
  PartitionKind partition = PartitionKind::Graph;
  Index n_schur = 0;              ///< Schur variables of the MUMPS factorization (0: K alone)
  double analysis_s = 0.0;        ///< MUMPS's analysis (ordering, symbolic; on rank 0) [s]
  double factorization_s = 0.0;   ///< MUMPS's numerical factorization, across the ranks [s]
  std::vector<RankReport> ranks;  ///< per rank, on rank 0
};

}  // namespace fricon::parallel
