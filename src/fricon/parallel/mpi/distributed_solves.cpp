#include "fricon/parallel/mpi/distributed_solves.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::parallel {

namespace {

// x of rank 0 (its size too) on every rank of comm.
void broadcast(VectorXd& x, MPI_Comm comm) {
  long size = static_cast<long>(x.size());
  MPI_Bcast(&size, 1, MPI_LONG, 0, comm);
  x.conservativeResize(static_cast<Index>(size));
  MPI_Bcast(x.data(), static_cast<int>(size), MPI_DOUBLE, 0, comm);
}

// The sum over the ranks of comm, on rank 0.
void sum_on_rank_0(VectorXd& x, int rank, MPI_Comm comm) {
  const int n = static_cast<int>(x.size());
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, x.data(), n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(x.data(), nullptr, n, MPI_DOUBLE, MPI_SUM, 0, comm);
}

}  // namespace

DistributedSolves::DistributedSolves(const MumpsFactor& factor, const CommandChannel& channel,
                                     const SparseMatrix* B, const VectorXd& f,
                                     const std::vector<Index>& contact_dofs)
    : factor_(factor), channel_(channel), B_(B), f_(f), contact_dofs_(contact_dofs) {
  int size = 1;
  MPI_Comm_rank(world(), &rank_);
  MPI_Comm_size(world(), &size);
  const Index n = factor_.n_free();
  for (Index i = n * rank_ / size; i < n * (rank_ + 1) / size; ++i)
    first_rows_.push_back(i);
  contact_position_.assign(static_cast<std::size_t>(n), -1);
  for (std::size_t c = 0; c < contact_dofs_.size(); ++c)
    contact_position_[static_cast<std::size_t>(contact_dofs_[c])] = static_cast<Index>(c);
}

const std::vector<Index>& DistributedSolves::rhs_rows() const {
  return solved_ ? factor_.solution_rows() : first_rows_;
}

MatrixXd DistributedSolves::solve(VectorXd& lambda, bool with_load) const {
  broadcast(lambda, world());
  const std::vector<Index>& rows = rhs_rows();
  VectorXd r = with_load ? f_ : VectorXd::Zero(f_.size());
  if (B_ != nullptr && lambda.size() > 0) r -= B_->transpose() * lambda;
  MatrixXd mine = factor_.solve_distributed(rows, r(rows), 1);
  solved_ = true;
  return mine;
}

VectorXd DistributedSolves::apply_step(VectorXd x) const {
  // B K^-1 B^T x = -B (K^-1 (-B^T x)): each rank sums the columns of B at its solution rows.
  const MatrixXd mine = solve(x, false);
  VectorXd y = VectorXd::Zero(B_->rows());
  const std::vector<Index>& rows = factor_.solution_rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (SparseMatrix::InnerIterator it(*B_, rows[k]); it; ++it)
      y(it.row()) -= it.value() * mine(static_cast<Index>(k), 0);
  sum_on_rank_0(y, rank_, world());
  return y;
}

VectorXd DistributedSolves::contact_step(VectorXd lambda) const {
  const MatrixXd mine = solve(lambda, true);
  // Each contact dof's value comes from the one rank that holds it.
  VectorXd w_c = VectorXd::Zero(static_cast<Index>(contact_dofs_.size()));
  const std::vector<Index>& rows = factor_.solution_rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (const Index c = contact_position_[static_cast<std::size_t>(rows[k])]; c >= 0)
      w_c(c) = mine(static_cast<Index>(k), 0);
  sum_on_rank_0(w_c, rank_, world());
  return w_c;
}

VectorXd DistributedSolves::displacement_step(VectorXd lambda) const {
  const MatrixXd mine = solve(lambda, true);
  const std::vector<Index>& rows = factor_.solution_rows();
  int size = 1;
  MPI_Comm_size(world(), &size);
  const int n_mine = static_cast<int>(rows.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  MPI_Gather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world());
  for (int r = 1; r < size; ++r)
    offsets[static_cast<std::size_t>(r)] =
        offsets[static_cast<std::size_t>(r - 1)] + counts[static_cast<std::size_t>(r - 1)];
  const Index n = factor_.n_free();
  std::vector<long> all_rows(rank_ == 0 ? static_cast<std::size_t>(n) : 0);
  VectorXd all_values(rank_ == 0 ? n : 0);
  const std::vector<long> my_rows(rows.begin(), rows.end());
  MPI_Gatherv(my_rows.data(), n_mine, MPI_LONG, all_rows.data(), counts.data(), offsets.data(),
              MPI_LONG, 0, world());
  MPI_Gatherv(mine.data(), n_mine, MPI_DOUBLE, all_values.data(), counts.data(), offsets.data(),
              MPI_DOUBLE, 0, world());
  VectorXd w(rank_ == 0 ? n : 0);
  for (std::size_t k = 0; k < all_rows.size(); ++k)
    w(static_cast<Index>(all_rows[k])) = all_values(static_cast<Index>(k));
  return w;
}

VectorXd DistributedSolves::apply(const VectorXd& x) const {
  channel_.send(kApply);
  return apply_step(x);
}

void DistributedSolves::contact_displacement(const VectorXd& lambda, VectorXd& w) const {
  channel_.send(kContact);
  const VectorXd w_c = contact_step(lambda);
  w.conservativeResize(factor_.n_free());
  for (std::size_t c = 0; c < contact_dofs_.size(); ++c)
    w(contact_dofs_[c]) = w_c(static_cast<Index>(c));
}

VectorXd DistributedSolves::displacement(const VectorXd& lambda) const {
  channel_.send(kDisplacement);
  return displacement_step(lambda);
}

int DistributedSolves::follow() const {
  return channel_.follow([this](int command, int) {
    try {
      switch (command) {
        case kApply:
          apply_step(VectorXd());
          break;
        case kContact:
          contact_step(VectorXd());
          break;
        case kDisplacement:
          displacement_step(VectorXd());
          break;
        default:
          throw Error(fmt::format("DistributedSolves::follow: unknown command {}", command));
      }
    } catch (const NumericalError&) {
      // A failed solve fails on every rank at the same step; rank 0 reports it with fail().
    }
  });
}

}  // namespace fricon::parallel
