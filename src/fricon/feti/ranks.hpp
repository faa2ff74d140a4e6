#pragma once
// feti: the processes that share the subdomains of a Total FETI run (docs/theory.md §8.8). Each
// process factors, and solves with, its own block of consecutive subdomains, and holds its share
// of the multipliers in the QP (feti/dual_rows.hpp); the mesh, the partition, the rows of B and
// the coarse problem every process holds whole. A product with F exchanges the multipliers that
// neighbouring processes' subdomains share (exchange); the QP's inner products and norms are
// sums over the processes (sum), the same bits on each, so that every process takes the same
// decisions afterwards. One process alone is the default
// (this_process()); the ranks of an MPI job are parallel/mpi's (feti_ranks.hpp).

#include <functional>
#include <utility>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::feti {

class Ranks {
 public:
  virtual ~Ranks() = default;

  /// This process's number among size() (0 alone).
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }

  /// x <- the sum of x over the processes, bit for bit the same on every one. Collective: every
  /// process calls it with a vector of the same size.
  virtual void sum(Eigen::Ref<VectorXd> x) const { (void)x; }

  /// `value` of every process, in rank order, on every process. Collective.
  virtual std::vector<double> gather(double value) const { return {value}; }

  /// The `local` vectors of every process, one after another in rank order, on every process
  /// (their sizes may differ). Collective.
  virtual VectorXd concat(const VectorXd& local) const { return local; }

  /// Messages between the processes: out[q] goes to process q, and in[q] receives what process q
  /// sent to this one, for every q (size() entries each; this process's own entry included). The
  /// caller sizes in[q] to what q sends (a process knows what its neighbours need of it: theory.md
  /// §8.8). Collective.
  virtual void exchange(const std::vector<VectorXd>& out, std::vector<VectorXd>& in) const {
    in.at(0) = out.at(0);
  }

  /// Runs `step`, which must not meet the other processes, on every process; when it failed on
  /// any, every process throws the error of the lowest failing one (as its own). Collective.
  virtual void collectively(const std::function<void()>& step) const { step(); }

  /// The subdomains this process works on, of `n` numbered 0 .. n - 1: [first, second), a
  /// block of consecutive ones, the blocks of the processes differing by at most one subdomain.
  std::pair<Index, Index> block(Index n) const { return block_of(rank(), n); }
  /// The block of process `q` (0 <= q < size()).
  std::pair<Index, Index> block_of(int q, Index n) const;
  /// Whether subdomain `i` of `n` is in this process's block.
  bool owns(Index i, Index n) const;
};

/// One process alone: every subdomain its own, no communication.
const Ranks& this_process();

}  // namespace fricon::feti
