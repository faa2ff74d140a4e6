#include "fricon/parallel/mpi/feti_ranks.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/session.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

MpiRanks::MpiRanks(MPI_Comm comm, const std::atomic<bool>* stop_requested)
    : comm_(comm), stop_requested_(stop_requested) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void MpiRanks::join() const {
  if (joined_) return;
  joined_ = true;
  parallel::collectively([] {}, comm_);
}

void MpiRanks::fail_before_joining(const std::exception_ptr& error) const {
  joined_ = true;
  parallel::collectively([&] { std::rethrow_exception(error); }, comm_);
  std::rethrow_exception(error);  // (collectively() has thrown the agreed error)
}

void MpiRanks::collectively(const std::function<void()>& step) const {
  joined_ = true;
  parallel::collectively(
      [&] {
        test_fault("subdomains");
        step();
      },
      comm_);
}

void MpiRanks::sum(VectorXd& x) const {
  join();
  test_fault("products");
  const Index n = x.size();
  n_sums_ += 1.0;
  buffer_.resize(n + 2);
  buffer_.head(n) = x;
  buffer_(n) = stop_requested_ != nullptr && stop_requested_->load() ? 1.0 : 0.0;
  buffer_(n + 1) = n_sums_;
  const int count = static_cast<int>(n + 2);
  // Reduced on rank 0 and sent from there: every rank holds the same bits (an MPI_Allreduce
  // may add in a different order on different ranks).
  check_mpi(MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : buffer_.data(), buffer_.data(), count,
                       MPI_DOUBLE, MPI_SUM, 0, comm_),
            "MPI_Reduce");
  check_mpi(MPI_Bcast(buffer_.data(), count, MPI_DOUBLE, 0, comm_), "MPI_Bcast");
  if (buffer_(n + 1) != n_sums_ * size_)
    abort_job({ErrorPacket::Other,
               fmt::format("the ranks of the Total FETI run went different ways: at this rank's "
                           "sum {} the ranks' counts add up to {}",
                           n_sums_, buffer_(n + 1))});
  x = buffer_.head(n);
  if (buffer_(n) > 0.0) agreed_stop_.store(true);
}

std::vector<double> MpiRanks::gather(double value) const {
  join();
  std::vector<double> all(static_cast<std::size_t>(size_));
  check_mpi(MPI_Allgather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm_),
            "MPI_Allgather");
  return all;
}

}  // namespace fricon::parallel
