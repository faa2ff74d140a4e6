#pragma once
// parallel/mpi: the MPI job of a distributed run (docs/parallel.md): starting MPI and PETSc once
// per process, and the one rule that keeps ranks from hanging: a step that can fail on some
// ranks is run by collectively(), which ends every rank with the same error when any rank fails.

#include <mpi.h>

#include <functional>
#include <string>

namespace fricon::parallel {

/// True when this process was started by mpirun/mpiexec (OpenMPI, MPICH or PMIx variables).
bool launched_by_mpi();

/// Starts MPI and PETSc for this process unless already done (PetscInitialize; a process not
/// started by mpirun becomes a job of one rank). They are finalized at exit.
void initialize(int* argc = nullptr, char*** argv = nullptr);
bool initialized();

MPI_Comm world();
int world_rank();
int world_size();

/// An error as it crosses ranks: its kind (the fricon exception type) and message.
struct ErrorPacket {
  enum Kind : int { None = 0, Input, Numerical, Interrupted, Other };
  int kind = None;
  std::string message;
};

/// The packet of the exception being handled (call inside a catch block).
ErrorPacket capture_current_exception();
/// Throws the packet's exception (InputError, NumericalError, Interrupted or Error).
[[noreturn]] void raise(const ErrorPacket& e);
/// The packet of rank `root` on every rank of `comm`. Collective.
void broadcast(ErrorPacket& e, int root, MPI_Comm comm);

/// Runs `step` on every rank of `comm`; returns on all ranks when it succeeded on all, else
/// every rank throws the error of the lowest failing rank (its type and message, with
/// "rank r: " before it when r is not 0). Collective: every rank must call it.
void collectively(const std::function<void()>& step, MPI_Comm comm = world());

/// Peak resident memory of this process [MiB] (getrusage).
double peak_memory_mib();

}  // namespace fricon::parallel
