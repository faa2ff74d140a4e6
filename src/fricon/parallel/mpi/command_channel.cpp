#include "fricon/parallel/mpi/command_channel.hpp"

#include <chrono>
#include <thread>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::parallel {

namespace {

// The commands that end a follow(); the callers' commands are >= 0.
constexpr int kFinish = -1, kFail = -2;

// Waits for rank 0's next command without spinning: a blocking MPI_Bcast busy-polls a core,
// which rank 0's QP and BLAS threads need while the other ranks only wait (rank 0 may work
// for minutes between two solves). Polling every kIdlePoll adds that much latency per command.
constexpr auto kIdlePoll = std::chrono::microseconds(200);

void receive(int (&message)[2], MPI_Comm comm) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(message, 2, MPI_INT, 0, comm, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(kIdlePoll);
  }
}

void announce(int command, int argument, MPI_Comm comm) {
  int message[2] = {command, argument};
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(message, 2, MPI_INT, 0, comm, &request);
  MPI_Wait(&request, MPI_STATUS_IGNORE);
}

}  // namespace

void CommandChannel::send(int command, int argument) const {
  FRICON_CHECK(command >= 0, "CommandChannel::send: command " << command);
  announce(command, argument, comm_);
}

int CommandChannel::follow(const std::function<void(int, int)>& handle) const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  FRICON_CHECK(rank != 0, "CommandChannel::follow is called by the ranks other than 0");
  for (;;) {
    int message[2] = {0, 0};
    receive(message, comm_);
    switch (message[0]) {
      case kFinish:
        return message[1];
      case kFail: {
        ErrorPacket error;
        or_abort([&] { broadcast(error, 0, comm_); }, comm_);
        raise(error);  // (Agreed: rank 0 throws it too)
      }
      default:
        handle(message[0], message[1]);
    }
  }
}

void CommandChannel::finish(int status) const {
  announce(kFinish, status, comm_);
}

void CommandChannel::fail(const ErrorPacket& error) const {
  or_abort(
      [&] {
        announce(kFail, 0, comm_);
        ErrorPacket copy = error;
        broadcast(copy, 0, comm_);
      },
      comm_);
}

}  // namespace fricon::parallel
