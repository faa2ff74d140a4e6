#pragma once
// parallel/mpi: the ranks of an MPI job as the processes of a Total FETI run (feti/ranks.hpp,
// docs/theory.md §8.8, docs/parallel.md "Total FETI on ranks"). Every rank runs the same run and
// takes the same decisions; what crosses ranks are the sums of the QP's reductions (MPI_Reduce to
// rank 0, then MPI_Bcast, so that every rank has rank 0's bits), the messages between neighbouring
// ranks in a product with F (exchange: MPI_Isend/MPI_Irecv of the rows their subdomains share,
// theory.md §8.8), the gathering of the multipliers once per QP (concat) and a few figures for
// the report. Two more things ride on every sum:
//   - the stop request (a signal reaches the ranks at different moments): a rank whose request
//     is set adds 1, and after the sum every rank sees the same agreed_stop(), so all stop at the
//     same step;
//   - the number of sums so far, which every rank adds: a rank that took a different path (it
//     never should) ends the job at once rather than leaving the others to wait.
// Errors: the first collective step of a run is an agreement (parallel::collectively), so that
// an error every rank raises before it (reading, the model: the same input on every rank) ends
// every rank with that error; fail_before_joining() is the failing rank's side of it.

#include <mpi.h>

#include <atomic>
#include <exception>

#include "fricon/feti/ranks.hpp"

namespace fricon::parallel {

class MpiRanks final : public feti::Ranks {
 public:
  /// The ranks of `comm`; `stop_requested` (may be null) is this rank's own stop request.
  MpiRanks(MPI_Comm comm, const std::atomic<bool>* stop_requested);

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void sum(Eigen::Ref<VectorXd> x) const override;
  std::vector<double> gather(double value) const override;
  VectorXd concat(const VectorXd& local) const override;
  void exchange(const std::vector<VectorXd>& out, std::vector<VectorXd>& in) const override;
  void collectively(const std::function<void()>& step) const override;

  /// The stop request the ranks agreed on at their last sum: the same on every rank.
  const std::atomic<bool>* agreed_stop() const { return &agreed_stop_; }

  /// Whether the ranks have taken a collective step together.
  bool joined() const { return joined_; }
  /// The first collective step, an agreement that every step is ok, when none was taken yet.
  void join() const;
  /// In a catch block, before any collective step: every rank raises this rank's error (or that
  /// of a lower failing rank), as an agreed error. Collective.
  [[noreturn]] void fail_before_joining(const std::exception_ptr& error) const;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  const std::atomic<bool>* stop_requested_;
  mutable std::atomic<bool> agreed_stop_{false};
  mutable bool joined_ = false;
  mutable double n_sums_ = 0;
  mutable VectorXd buffer_;
};

}  // namespace fricon::parallel
