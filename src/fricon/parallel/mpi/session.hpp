#pragma once
// parallel/mpi: the MPI job of a distributed run (docs/parallel.md): starting MPI and PETSc once
// per process, and the two rules that keep ranks from hanging (docs/parallel.md, "When a rank
// fails"):
//   - a step that can fail on some ranks, and makes no collective call, is run by collectively(),
//     which ends every rank with the same error (Agreed) when any rank fails;
//   - a step that makes collective calls is run by or_abort(): a rank that fails between them
//     cannot tell the others, which wait for it inside a collective call, so it prints its error
//     and ends the job (MPI_Abort, exit code 3). Errors that every rank raises at the same point
//     (Agreed: the result of an agreement, or MUMPS's global status) pass through.

#include <mpi.h>

#include <functional>
#include <string>
#include <string_view>

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
  enum Kind : int { None = 0, Input, Numerical, Interrupted, Other, Output };
  int kind = None;
  std::string message;
};

/// The packet of the exception being handled (call inside a catch block).
ErrorPacket capture_current_exception();
/// Throws the packet's exception (InputError, NumericalError, Interrupted, OutputError or Error) as
/// AgreedError: call it where every rank raises the same packet (after an agreement).
[[noreturn]] void raise(const ErrorPacket& e);
/// The packet of rank `root` on every rank of `comm`. Collective.
void broadcast(ErrorPacket& e, int root, MPI_Comm comm);

/// Returns when `code` is MPI_SUCCESS; else throws Error("<during>: <call> failed (MPI error
/// <code>)"), `call` the MPI function that returned it and `during` what the rank was doing
/// (may be empty).
void check_mpi(int code, const char* call, std::string_view during = {});

/// Runs `step` on every rank of `comm`; returns on all ranks when it succeeded on all, else
/// every rank throws the error of the lowest failing rank (its type and message, with
/// "rank r: " before it when r is not 0) as AgreedError. Collective: every rank must call it.
/// A collective call in `step` (collectively() included) must be in or_abort(), or be matched
/// on every path, failures included (scatter_model): a rank that failed before it would skip it
/// and leave the others waiting there.
void collectively(const std::function<void()>& step, MPI_Comm comm = world());

/// The exit code of a job ended by abort_job(): the program's code for an internal error
/// (apps/fricon/main.cpp, "Exit codes").
inline constexpr int kAbortExitCode = 3;

/// Marks an exception that every rank of the communicator raises at the same point: the error
/// of an agreement (collectively(), CommandChannel::fail()) or a status that every rank reads
/// (MUMPS's INFOG(1)). The ranks leave the step together, so it passes through or_abort().
class Agreed {
 public:
  virtual ~Agreed() = default;
};

/// The exception E (InputError, NumericalError, ...) raised by every rank at the same point.
template <class E>
class AgreedError final : public E, public Agreed {
 public:
  using E::E;
};

/// Ends the job at once: prints "fricon: internal error: rank R: <message>" (R: this rank of
/// MPI_COMM_WORLD) to this rank's standard error as it was when initialize() ran (the ranks
/// other than 0 send theirs to /dev/null afterwards), then MPI_Abort(MPI_COMM_WORLD,
/// kAbortExitCode): mpirun ends every rank and exits with that code. For a failure of this rank
/// alone while the others wait for it in a collective call.
[[noreturn]] void abort_job(const ErrorPacket& e);

/// In a catch block of a step that makes collective calls: returns when the exception being
/// handled is Agreed, or when `comm` has one rank (no other rank waits); else abort_job() with it.
void abort_unless_agreed(MPI_Comm comm = world());

/// Runs `step`, which makes collective calls over `comm`: an Agreed exception (any exception on
/// a job of one rank) passes; any other ends the job (abort_unless_agreed()). Call it on every
/// rank that takes part in the step's collective calls.
void or_abort(const std::function<void()>& step, MPI_Comm comm = world());

/// Peak resident memory of this process [MiB] (getrusage).
double peak_memory_mib();

}  // namespace fricon::parallel
