#include "fricon/parallel/mpi/session.hpp"

#include <fcntl.h>
#include <petscsys.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::parallel {

namespace {

// This process's standard error as it was when initialize() ran, for abort_job(): the program
// sends the other ranks' standard error to /dev/null afterwards (docs/parallel.md). -1: not
// kept (MPI started elsewhere), abort_job() writes to the standard error of the moment.
int g_error_fd = -1;

void finalize_at_exit() {
  PetscBool done = PETSC_FALSE;
  PetscFinalized(&done);
  if (!done) PetscFinalize();
}

}  // namespace

void check_mpi(int code, const char* call, std::string_view during) {
  if (code == MPI_SUCCESS) return;
  if (during.empty()) throw Error(fmt::format("{} failed (MPI error {})", call, code));
  throw Error(fmt::format("{}: {} failed (MPI error {})", during, call, code));
}

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

bool initialized() {
  PetscBool done = PETSC_FALSE;
  PetscInitialized(&done);
  return done == PETSC_TRUE;
}

void initialize(int* argc, char*** argv) {
  if (initialized()) return;
  // PETSc reads its options from the command line only when given it; fricon's own options are
  // not PETSc's, so it is started without them (PETSc options go in PETSC_OPTIONS).
  (void)argc, (void)argv;
  if (PetscInitializeNoArguments() != 0) throw Error("PetscInitialize failed");
  g_error_fd = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
  std::atexit(finalize_at_exit);
}

MPI_Comm world() {
  return PETSC_COMM_WORLD;
}

int world_rank() {
  int r = 0;
  MPI_Comm_rank(world(), &r);
  return r;
}

int world_size() {
  int s = 1;
  MPI_Comm_size(world(), &s);
  return s;
}

ErrorPacket capture_current_exception() {
  try {
    throw;
  } catch (const Interrupted& e) {
    return {ErrorPacket::Interrupted, e.what()};
  } catch (const InputError& e) {
    return {ErrorPacket::Input, e.what()};
  } catch (const NumericalError& e) {
    return {ErrorPacket::Numerical, e.what()};
  } catch (const OutputError& e) {
    return {ErrorPacket::Output, e.what()};
  } catch (const std::exception& e) {
    return {ErrorPacket::Other, e.what()};
  } catch (...) {
    return {ErrorPacket::Other, "unknown exception"};
  }
}

void raise(const ErrorPacket& e) {
  switch (e.kind) {
    case ErrorPacket::Input:
      throw AgreedError<InputError>(e.message);
    case ErrorPacket::Numerical:
      throw AgreedError<NumericalError>(e.message);
    case ErrorPacket::Interrupted:
      throw AgreedError<Interrupted>(e.message);
    case ErrorPacket::Output:
      throw AgreedError<OutputError>(e.message);
    default:
      throw AgreedError<Error>(e.message);
  }
}

void broadcast(ErrorPacket& e, int root, MPI_Comm comm) {
  int head[2] = {e.kind, static_cast<int>(e.message.size())};
  check_mpi(MPI_Bcast(head, 2, MPI_INT, root, comm), "MPI_Bcast");
  e.kind = head[0];
  e.message.resize(static_cast<std::size_t>(head[1]));
  check_mpi(MPI_Bcast(e.message.data(), head[1], MPI_CHAR, root, comm), "MPI_Bcast");
}

void collectively(const std::function<void()>& step, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  ErrorPacket error;
  try {
    step();
  } catch (...) {
    error = capture_current_exception();
  }
  int first_failed = error.kind == ErrorPacket::None ? size : rank;
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, &first_failed, 1, MPI_INT, MPI_MIN, comm), "MPI_Allreduce");
  if (first_failed == size) return;
  broadcast(error, first_failed, comm);
  if (first_failed != 0) error.message = fmt::format("rank {}: {}", first_failed, error.message);
  raise(error);
}

void abort_job(const ErrorPacket& e) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::string line = fmt::format(
      "fricon: internal error: rank {}: {} (in a step that every rank takes together: the job "
      "is ended with MPI_Abort, exit code {})\n",
      rank, e.message, kAbortExitCode);
  const int fd = g_error_fd >= 0 ? g_error_fd : STDERR_FILENO;
  for (std::size_t at = 0; at < line.size();) {
    const ssize_t n = write(fd, line.data() + at, line.size() - at);
    if (n <= 0) break;
    at += static_cast<std::size_t>(n);
  }
  MPI_Abort(MPI_COMM_WORLD, kAbortExitCode);
  std::_Exit(kAbortExitCode);  // (MPI_Abort does not return)
}

void abort_unless_agreed(MPI_Comm comm) {
  try {
    throw;
  } catch (const Agreed&) {
    return;
  } catch (...) {
  }
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1) return;
  abort_job(capture_current_exception());
}

void or_abort(const std::function<void()>& step, MPI_Comm comm) {
  try {
    step();
  } catch (...) {
    abort_unless_agreed(comm);
    throw;
  }
}

double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace fricon::parallel
