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

void MpiRanks::sum(Eigen::Ref<VectorXd> x) const {
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

VectorXd MpiRanks::concat(const VectorXd& local) const {
  join();
  const int mine = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size(), 0);
  check_mpi(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_), "MPI_Allgather");
  for (std::size_t q = 1; q < counts.size(); ++q)
    offsets[q] = offsets[q - 1] + counts[q - 1];
  VectorXd all(offsets.back() + counts.back());
  check_mpi(MPI_Allgatherv(local.data(), mine, MPI_DOUBLE, all.data(), counts.data(),
                           offsets.data(), MPI_DOUBLE, comm_),
            "MPI_Allgatherv");
  return all;
}

void MpiRanks::exchange(const std::vector<VectorXd>& out, std::vector<VectorXd>& in) const {
  join();
  test_fault("products");
  const auto n = static_cast<std::size_t>(size_);
  FRICON_CHECK(out.size() == n && in.size() == n, "exchange: " << out.size() << " and " << in.size()
                                                               << " messages for " << n
                                                               << " ranks");
  // Messages only between neighbours (non-empty ones), in both directions at once; between two
  // ranks they arrive in the order sent (MPI's non-overtaking rule), so one tag does.
  constexpr int kTag = 37;
  std::vector<MPI_Request> requests;
  for (std::size_t q = 0; q < n; ++q) {
    if (q == static_cast<std::size_t>(rank_) || in[q].size() == 0) continue;
    requests.emplace_back();
    check_mpi(MPI_Irecv(in[q].data(), static_cast<int>(in[q].size()), MPI_DOUBLE,
                        static_cast<int>(q), kTag, comm_, &requests.back()),
              "MPI_Irecv");
  }
  for (std::size_t q = 0; q < n; ++q) {
    if (q == static_cast<std::size_t>(rank_) || out[q].size() == 0) continue;
    requests.emplace_back();
    check_mpi(MPI_Isend(out[q].data(), static_cast<int>(out[q].size()), MPI_DOUBLE,
                        static_cast<int>(q), kTag, comm_, &requests.back()),
              "MPI_Isend");
  }
  check_mpi(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
            "MPI_Waitall");
}

}  // namespace fricon::parallel
