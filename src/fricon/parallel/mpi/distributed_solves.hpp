#pragma once
// parallel/mpi: the solves with K that a distributed run's dual operator needs (docs/theory.md
// §3.3), as collective steps on distributed right-hand sides and solutions (MUMPS ICNTL(20) = 10,
// ICNTL(21) = 1). Every rank forms its rows of the right-hand side f - B^T lambda from its copy
// of f and B, and keeps its rows of the solution; only what rank 0 asks for reaches it:
//   apply                 Q x = B K^-1 B^T x                n_dual numbers (a sum over ranks)
//   contact_displacement  w on the contact dofs            one number per contact dof
//   displacement          w everywhere                      gathered (for the results)
// Rank 0 calls these; each first sends its command to the other ranks, which run the same step
// from follow().

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/parallel/mpi/command_channel.hpp"
#include "fricon/parallel/mpi/mumps_factor.hpp"

namespace fricon::parallel {

class DistributedSolves {
 public:
  /// Every rank, with the same B (n_dual x n_free [m^2]; null without contact), load f over the
  /// free dofs [N] and contact dofs (the free dofs B touches, for contact_displacement). The
  /// references must outlive this object.
  DistributedSolves(const MumpsFactor& factor, const CommandChannel& channel, const SparseMatrix* B,
                    const VectorXd& f, const std::vector<Index>& contact_dofs);

  /// Rank 0: Q x = B K^-1 B^T x [m^3/Pa times the unit of x]. Collective with follow().
  VectorXd apply(const VectorXd& x) const;
  /// Rank 0: w = K^-1 (f - B^T lambda) [m] on the contact dofs, written into w (sized n_free; the
  /// other entries are left as they were). Collective with follow().
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const;
  /// Rank 0: w = K^-1 (f - B^T lambda) [m] over all free dofs (lambda empty without contact).
  /// Collective with follow().
  VectorXd displacement(const VectorXd& lambda) const;

  /// Ranks other than 0: take part in rank 0's steps until it calls finish() (returns its
  /// status) or fail() (throws its error) on the channel. A solve that fails is reported by rank
  /// 0 (MUMPS's error is global: every rank sees it).
  int follow() const;

 private:
  enum Command : int { kApply = 0, kContact = 1, kDisplacement = 2 };

  // The steps, on every rank.
  VectorXd apply_step(VectorXd x) const;
  VectorXd contact_step(VectorXd lambda) const;
  VectorXd displacement_step(VectorXd lambda) const;
  // This rank's rows of K^-1 r (rows solution_rows()), r = f - B^T lambda when with_load, else
  // -B^T lambda, lambda broadcast from rank 0.
  MatrixXd solve(VectorXd& lambda, bool with_load) const;
  // The rows this rank gives of the next right-hand side: a block of dofs at first, then the
  // rows of its solution (where MUMPS wants them).
  const std::vector<Index>& rhs_rows() const;

  const MumpsFactor& factor_;
  const CommandChannel& channel_;
  const SparseMatrix* B_;
  const VectorXd& f_;
  const std::vector<Index>& contact_dofs_;
  std::vector<Index> first_rows_;
  std::vector<Index> contact_position_;  // of each free dof in contact_dofs, or -1
  mutable bool solved_ = false;
  int rank_ = 0;
};

}  // namespace fricon::parallel
