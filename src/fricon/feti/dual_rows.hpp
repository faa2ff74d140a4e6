#pragma once
// feti: the multipliers of Total FETI shared out over the processes (docs/theory.md §8.8). Each
// process holds the rows of B it owns, in increasing order, and the QP's vectors are its part:
//   - the contact rows are process 0's (a patch's bound and disc stay together; they are few
//     against the gluing rows);
//   - the equality rows fall into groups that share a torn dof (a node's chain of gluing rows
//     and its Dirichlet row, per component), and a group is owned by the process of the lowest
//     subdomain its rows touch or, every other group, of the highest (so that neighbouring
//     processes share their interface about evenly); B_E B_E^T, block diagonal over the groups,
//     is then local (the preconditioners solve with it).
// A product with F needs, besides a process's own rows, the rows of its subdomains that another
// owns (ghosts): fetched from their owners before the local solves, and their sums returned to
// them after (Ranks::exchange), instead of a sum over all the multipliers. Every process computes
// the same ownership from the replicated rows, so that each knows what its neighbours need.

#include <utility>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/feti/subdomains.hpp"
#include "fricon/feti/torn_rows.hpp"
#include "fricon/qp/dual_space.hpp"

namespace fricon::feti {

class DualRows {
 public:
  /// The rows of `rows` over the subdomains `subdomains` (attach_rows done), shared over
  /// `ranks` (which must outlive this), whose blocks of subdomains (Ranks::block) they serve.
  DualRows(const std::vector<Subdomain>& subdomains, const TornRows& rows, const Ranks& ranks);

  /// The rows this process owns, ascending (its contact rows first).
  const std::vector<Index>& owned() const { return owned_[static_cast<size_t>(rank_)]; }
  Index n_local() const { return static_cast<Index>(owned().size()); }
  /// This process's contact rows: all of them on process 0, none elsewhere.
  Index n_local_contact() const { return n_local_contact_; }

  /// This process's entries of a vector over all the rows.
  VectorXd restrict(const VectorXd& whole) const;
  /// The vector over all rows whose parts every process holds (`local`), on every process.
  /// Collective.
  VectorXd assemble(const VectorXd& local) const;
  /// The columns of G (over all the rows) of this process's rows, in its order.
  SparseMatrix restrict_columns(const SparseMatrix& G) const;

  /// The extended vector of this process: its own entries `local`, then its ghosts' (fetched
  /// from their owners). Collective.
  void fetch_ghosts(const VectorXd& local, VectorXd& extended) const;
  /// `extended`'s own entries into `local`, plus the ghost entries that the other processes
  /// computed for this one's rows (each its extended ghosts, sent back to their owners).
  /// Collective.
  void return_ghosts(const VectorXd& extended, VectorXd& local) const;
  /// Own rows and ghosts: the size of an extended vector.
  Index n_extended() const { return n_local() + n_ghosts_; }
  /// The rows of this process's subdomains that other processes hold.
  Index n_ghosts() const { return n_ghosts_; }
  /// The extended index of each row of this process's subdomain i (its Subdomain::rows).
  const std::vector<Index>& extended_rows(Index i) const {
    return extended_rows_[static_cast<size_t>(i - first_subdomain_)];
  }

 private:
  // The steps of the constructor (theory.md §8.8), in order.
  void share_rows(const std::vector<int>& owner, Index n_contact);
  std::vector<Index> number_ghosts(const std::vector<Subdomain>& subdomains,
                                   const std::vector<int>& owner);
  void plan_sends(const std::vector<Subdomain>& subdomains, const std::vector<int>& owner,
                  const std::vector<Index>& extended);
  void map_subdomain_rows(const std::vector<Subdomain>& subdomains,
                          const std::vector<Index>& extended);

  const Ranks* ranks_;
  int rank_ = 0;
  Index n_local_contact_ = 0;
  std::vector<std::vector<Index>> owned_;  ///< per process, its rows ascending
  /// Per process q: the local indices of this process's rows that q's subdomains read, in
  /// ascending row order (what is sent to q, and what comes back from it).
  std::vector<std::vector<Index>> send_;
  /// Per process q: how many of this process's ghosts q owns (consecutive in the extended vector,
  /// from recv_offset_[q]).
  std::vector<Index> recv_count_, recv_offset_;
  Index n_ghosts_ = 0;
  Index first_subdomain_ = 0;
  std::vector<std::vector<Index>> extended_rows_;  ///< per subdomain of this process
};

/// The QP's reductions over the processes of `ranks` (qp/dual_space.hpp): sums through
/// Ranks::sum (rank 0's bits on every process), maxima through Ranks::gather.
class RanksSpace final : public qp::DualSpace {
 public:
  explicit RanksSpace(const Ranks& ranks) : ranks_(&ranks) {}
  using DualSpace::sum;
  void sum(Eigen::Ref<Eigen::VectorXd> v) const override;
  double max(double value) const override;
  Eigen::VectorXd concat(const Eigen::VectorXd& local) const override {
    return ranks_->concat(local);
  }
  bool distributed() const override { return ranks_->size() > 1; }

 private:
  const Ranks* ranks_;
};

}  // namespace fricon::feti
