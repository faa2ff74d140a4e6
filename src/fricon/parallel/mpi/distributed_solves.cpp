#include "fricon/parallel/mpi/distributed_solves.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

namespace {

// The sum over the ranks of comm, on rank 0.
void sum_on_rank_0(VectorXd& x, int rank, MPI_Comm comm) {
  const int n = static_cast<int>(x.size());
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, x.data(), n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(x.data(), nullptr, n, MPI_DOUBLE, MPI_SUM, 0, comm);
}

// The contact dofs of a run without contact.
const std::vector<Index>& no_dofs() {
  static const std::vector<Index> none;
  return none;
}

}  // namespace

LoadPart LoadPart::of(const VectorXd& part_load, const std::vector<Index>& global_dof) {
  FRICON_CHECK(
      part_load.size() == static_cast<Index>(global_dof.size()),
      "a load part of " << part_load.size() << " rows for " << global_dof.size() << " dofs");
  LoadPart part;
  std::vector<Index> local;
  for (Index i = 0; i < part_load.size(); ++i)
    if (part_load(i) != 0.0) {
      local.push_back(i);
      part.rows.push_back(global_dof[static_cast<std::size_t>(i)]);
    }
  part.values = part_load(local);
  return part;
}

ContactCoupling ContactCoupling::of(const SparseMatrix& B, const std::vector<Index>& dofs) {
  ContactCoupling c;
  c.dofs = dofs;
  std::vector<Eigen::Triplet<Real>> entries;
  for (std::size_t k = 0; k < dofs.size(); ++k)
    for (SparseMatrix::InnerIterator it(B, dofs[k]); it; ++it)
      entries.emplace_back(it.row(), static_cast<Index>(k), it.value());
  c.B.resize(B.rows(), static_cast<Index>(dofs.size()));
  c.B.setFromTriplets(entries.begin(), entries.end());
  c.index();
  return c;
}

void ContactCoupling::index() {
  by_dof_.clear();
  for (std::size_t k = 0; k < dofs.size(); ++k)
    by_dof_.emplace_back(dofs[k], static_cast<Index>(k));
  std::sort(by_dof_.begin(), by_dof_.end());
}

Index ContactCoupling::position(Index dof) const {
  const auto it =
      std::lower_bound(by_dof_.begin(), by_dof_.end(), std::pair<Index, Index>{dof, -1});
  return it != by_dof_.end() && it->first == dof ? it->second : -1;
}

void ContactCoupling::broadcast(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // The sizes, then the contact dofs and B's compressed columns.
  long sizes[3] = {static_cast<long>(B.rows()), static_cast<long>(dofs.size()),
                   static_cast<long>(B.nonZeros())};
  MPI_Bcast(sizes, 3, MPI_LONG, 0, comm);
  std::vector<long> dof(dofs.begin(), dofs.end()), start(static_cast<std::size_t>(sizes[1] + 1)),
      row(static_cast<std::size_t>(sizes[2]));
  std::vector<double> value(static_cast<std::size_t>(sizes[2]));
  if (rank == 0) {
    B.makeCompressed();
    std::copy(B.outerIndexPtr(), B.outerIndexPtr() + sizes[1] + 1, start.begin());
    std::copy(B.innerIndexPtr(), B.innerIndexPtr() + sizes[2], row.begin());
    std::copy(B.valuePtr(), B.valuePtr() + sizes[2], value.begin());
  } else {
    dof.resize(static_cast<std::size_t>(sizes[1]));
  }
  MPI_Bcast(dof.data(), static_cast<int>(sizes[1]), MPI_LONG, 0, comm);
  MPI_Bcast(start.data(), static_cast<int>(sizes[1] + 1), MPI_LONG, 0, comm);
  MPI_Bcast(row.data(), static_cast<int>(sizes[2]), MPI_LONG, 0, comm);
  MPI_Bcast(value.data(), static_cast<int>(sizes[2]), MPI_DOUBLE, 0, comm);
  if (rank != 0) {
    dofs.assign(dof.begin(), dof.end());
    std::vector<Eigen::Triplet<Real>> entries;
    for (long c = 0; c < sizes[1]; ++c)
      for (long k = start[static_cast<std::size_t>(c)]; k < start[static_cast<std::size_t>(c + 1)];
           ++k)
        entries.emplace_back(row[static_cast<std::size_t>(k)], c,
                             value[static_cast<std::size_t>(k)]);
    B.resize(sizes[0], sizes[1]);
    B.setFromTriplets(entries.begin(), entries.end());
  }
  index();
}

DistributedSolves::DistributedSolves(const MumpsFactor& factor, const CommandChannel& channel,
                                     const ContactCoupling* contact, LoadPart load)
    : factor_(factor),
      channel_(channel),
      contact_(contact),
      contact_dofs_(contact ? contact->dofs : no_dofs()) {
  MPI_Comm_rank(world(), &rank_);
  if (rank_ != 0 || contact_dofs_.empty()) {
    load_rows_ = std::move(load.rows);
    load_values_ = std::move(load.values);
    return;
  }
  // Rank 0 gives each row once: its load rows and the contact dofs, merged.
  std::vector<Index> rows = load.rows;
  rows.insert(rows.end(), contact_dofs_.begin(), contact_dofs_.end());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  const auto position = [&rows](Index dof) {
    return static_cast<Index>(std::lower_bound(rows.begin(), rows.end(), dof) - rows.begin());
  };
  load_values_ = VectorXd::Zero(static_cast<Index>(rows.size()));
  for (std::size_t k = 0; k < load.rows.size(); ++k)
    load_values_(position(load.rows[k])) = load.values(static_cast<Index>(k));
  for (Index dof : contact_dofs_)
    contact_in_load_rows_.push_back(position(dof));
  load_rows_ = std::move(rows);
}

MatrixXd DistributedSolves::solve(const VectorXd& lambda, bool with_load) const {
  // Rank 0: (B^T lambda)_j on the contact dofs j (B's columns are the free dofs).
  VectorXd bt_lambda = VectorXd::Zero(static_cast<Index>(contact_dofs_.size()));
  if (rank_ == 0 && contact_ != nullptr && lambda.size() > 0)
    bt_lambda = contact_->B.transpose() * lambda;
  if (with_load) {
    MatrixXd rhs = load_values_;
    for (std::size_t c = 0; c < contact_in_load_rows_.size(); ++c)
      rhs(contact_in_load_rows_[c], 0) -= bt_lambda(static_cast<Index>(c));
    return factor_.solve_distributed(load_rows_, std::move(rhs), 1);
  }
  if (rank_ != 0) return factor_.solve_distributed({}, MatrixXd(0, 1), 1);
  return factor_.solve_distributed(contact_dofs_, -bt_lambda, 1);
}

VectorXd DistributedSolves::apply_step(const VectorXd& x) const {
  // B K^-1 B^T x = -B (K^-1 (-B^T x)): each rank sums the columns of B at its solution rows.
  const MatrixXd mine = solve(x, false);
  VectorXd y = VectorXd::Zero(contact_->B.rows());
  const std::vector<Index>& rows = factor_.solution_rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (const Index c = contact_->position(rows[k]); c >= 0)
      for (SparseMatrix::InnerIterator it(contact_->B, c); it; ++it)
        y(it.row()) -= it.value() * mine(static_cast<Index>(k), 0);
  sum_on_rank_0(y, rank_, world());
  return y;
}

VectorXd DistributedSolves::contact_step(const VectorXd& lambda) const {
  const MatrixXd mine = solve(lambda, true);
  // Each contact dof's value comes from the one rank that holds it.
  VectorXd w_c = VectorXd::Zero(static_cast<Index>(contact_dofs_.size()));
  const std::vector<Index>& rows = factor_.solution_rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (const Index c = contact_->position(rows[k]); c >= 0)
      w_c(c) = mine(static_cast<Index>(k), 0);
  sum_on_rank_0(w_c, rank_, world());
  return w_c;
}

VectorXd DistributedSolves::displacement_step(const VectorXd& lambda) const {
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

VectorXd DistributedSolves::step(Command command, const VectorXd& x) const {
  // The other ranks are inside MUMPS's solve or the reduction that follows it: a failure of this
  // rank alone ends the job; MUMPS's own failure is seen by every rank (Agreed) and passes.
  VectorXd result;
  or_abort([&] {
    test_fault("solve");
    switch (command) {
      case kApply:
        result = apply_step(x);
        break;
      case kContact:
        result = contact_step(x);
        break;
      case kDisplacement:
        result = displacement_step(x);
        break;
      default:
        throw Error(
            fmt::format("DistributedSolves: unknown command {}", static_cast<int>(command)));
    }
  });
  return result;
}

VectorXd DistributedSolves::apply(const VectorXd& x) const {
  test_fault("outer");
  channel_.send(kApply);
  return step(kApply, x);
}

void DistributedSolves::contact_displacement(const VectorXd& lambda, VectorXd& w) const {
  test_fault("outer");
  channel_.send(kContact);
  const VectorXd w_c = step(kContact, lambda);
  w.conservativeResize(factor_.n_free());
  for (std::size_t c = 0; c < contact_dofs_.size(); ++c)
    w(contact_dofs_[c]) = w_c(static_cast<Index>(c));
}

VectorXd DistributedSolves::displacement(const VectorXd& lambda) const {
  test_fault("outer");
  channel_.send(kDisplacement);
  return step(kDisplacement, lambda);
}

int DistributedSolves::follow() const {
  return channel_.follow([this](int command, int) {
    try {
      step(static_cast<Command>(command), VectorXd());
    } catch (const Agreed&) {
      // MUMPS's failure, seen by every rank at the same step: rank 0 reports it with fail().
    }
  });
}

}  // namespace fricon::parallel
