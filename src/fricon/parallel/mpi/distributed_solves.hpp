#pragma once
// parallel/mpi: the solves with K that a distributed run's dual operator needs (docs/theory.md
// §3.3), as collective steps on distributed right-hand sides and solutions (MUMPS ICNTL(20) = 10,
// ICNTL(21) = 1). Each rank gives the part of f its own tetrahedra contribute (MUMPS sums the
// rows that several ranks give), rank 0 adds -B^T lambda on the contact dofs, and each rank keeps
// its rows of the solution; only what rank 0 asks for reaches it:
//   apply                 Q x = B K^-1 B^T x                n_dual numbers (a sum over ranks)
//   contact_displacement  w on the contact dofs            one number per contact dof
//   displacement          w everywhere                      gathered (for the results)
// Rank 0 calls these; each first sends its command to the other ranks, which run the same step
// from follow(). Once the command is sent, a failure of one rank alone ends the job (the others
// wait for it inside the step: or_abort()); MUMPS's failure, which every rank sees, is thrown on
// rank 0 (Agreed) and leaves the others following.

#include <utility>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/parallel/mpi/command_channel.hpp"
#include "fricon/parallel/mpi/mumps_factor.hpp"

namespace fricon::parallel {

/// A rank's part of the load vector: the rows its tetrahedra touch and their values [N].
struct LoadPart {
  std::vector<Index> rows;  ///< free dofs of the whole model, ascending
  VectorXd values;
  /// The non-zero rows of `part_load` (driver::load_vector of a part, over its own free dofs), in
  /// the whole model's numbering `global_dof` (ascending, driver::ModelPart).
  static LoadPart of(const VectorXd& part_load, const std::vector<Index>& global_dof);
};

/// What every rank needs of the contact discretization: B on the contact dofs only
/// (O(contact surface), where B itself has a column per free dof).
struct ContactCoupling {
  std::vector<Index> dofs;  ///< the free dofs B touches (contact::ContactDiscretization::dofs)
  SparseMatrix B;           ///< n_dual x dofs.size(): column c is B's column dofs[c] [m^2]
  /// From the whole B (n_dual x n_free) and its contact dofs.
  static ContactCoupling of(const SparseMatrix& B, const std::vector<Index>& dofs);
  /// The position of free dof `dof` in `dofs`, or -1 when it is not a contact dof.
  Index position(Index dof) const;
  /// Rank 0's coupling on every rank of `comm`. Collective.
  void broadcast(MPI_Comm comm);

 private:
  void index();
  std::vector<std::pair<Index, Index>> by_dof_;  // (dof, position), ascending
};

class DistributedSolves {
 public:
  /// Every rank, with the same contact coupling (null without contact) and its own part of f.
  /// The references must outlive this object.
  DistributedSolves(const MumpsFactor& factor, const CommandChannel& channel,
                    const ContactCoupling* contact, LoadPart load);

  /// Rank 0: Q x = B K^-1 B^T x [m^3/Pa times the unit of x]. Collective with follow().
  VectorXd apply(const VectorXd& x) const;
  /// Rank 0: w = K^-1 (f - B^T lambda) [m] on the contact dofs, written into w (sized n_free; the
  /// other entries are left as they were). Collective with follow().
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const;
  /// Rank 0: w = K^-1 (f - B^T lambda) [m] over all free dofs (lambda empty without contact).
  /// Collective with follow().
  VectorXd displacement(const VectorXd& lambda) const;

  /// Ranks other than 0: take part in rank 0's steps until it calls finish() (returns its
  /// status) or fail() (throws its error, Agreed) on the channel. A solve that MUMPS fails is
  /// reported by rank 0 (MUMPS's error is global: every rank sees it); any other failure of a
  /// step, on any rank, ends the job (or_abort(): the other ranks wait for it inside the step).
  int follow() const;

 private:
  enum Command : int { kApply = 0, kContact = 1, kDisplacement = 2 };

  // Runs a command's step on every rank (or_abort()): after rank 0 has sent it, a failure of one
  // rank alone cannot be agreed on. x is rank 0's (the other ranks pass an empty vector).
  VectorXd step(Command command, const VectorXd& x) const;
  // The steps, on every rank (lambda and x are rank 0's; the other ranks pass empty vectors).
  VectorXd apply_step(const VectorXd& x) const;
  VectorXd contact_step(const VectorXd& lambda) const;
  VectorXd displacement_step(const VectorXd& lambda) const;
  // This rank's rows of K^-1 r (rows solution_rows()) for r = f - B^T lambda (with_load) or
  // -B^T lambda: this rank's part of f, and on rank 0 the contact dofs' -B^T lambda.
  MatrixXd solve(const VectorXd& lambda, bool with_load) const;

  const MumpsFactor& factor_;
  const CommandChannel& channel_;
  const ContactCoupling* contact_;
  const std::vector<Index>& contact_dofs_;  // contact_->dofs, or none
  int rank_ = 0;
  // The rows this rank gives with the load: its part of f and, on rank 0, the contact dofs.
  std::vector<Index> load_rows_;
  VectorXd load_values_;
  std::vector<Index> contact_in_load_rows_;  // rank 0: where each contact dof is in load_rows_
};

}  // namespace fricon::parallel
