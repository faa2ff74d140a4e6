#pragma once
// parallel/mpi: rank 0 leads, the other ranks follow (docs/parallel.md). After the factorization
// rank 0 runs the outer loop alone; each collective step it takes (a distributed solve) starts
// with a command that the other ranks, waiting in follow(), receive and join. Rank 0 ends the
// run with finish() (its status) or fail() (its error), so no rank is left waiting; a rank that
// fails while passing a command or an error on ends the job (or_abort(), docs/parallel.md).

#include <mpi.h>

#include <functional>

#include "fricon/parallel/mpi/session.hpp"

namespace fricon::parallel {

class CommandChannel {
 public:
  explicit CommandChannel(MPI_Comm comm) : comm_(comm) {}

  /// Rank 0: announces `command` (>= 0) with an argument to the ranks in follow().
  void send(int command, int argument = 0) const;
  /// Ranks other than 0: runs handle(command, argument) for each command rank 0 sends, until it
  /// calls finish() (returns its status) or fail() (throws its error here too). The wait does
  /// not spin (it polls every 200 us), leaving the cores to rank 0's QP and BLAS threads.
  int follow(const std::function<void(int command, int argument)>& handle) const;
  /// Rank 0: ends the other ranks' follow() with `status`.
  void finish(int status) const;
  /// Rank 0: ends the other ranks' follow() by throwing `error` there (as AgreedError).
  void fail(const ErrorPacket& error) const;

 private:
  MPI_Comm comm_;
};

}  // namespace fricon::parallel
