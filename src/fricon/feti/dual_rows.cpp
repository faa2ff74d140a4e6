#include "fricon/feti/dual_rows.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "fricon/core/error.hpp"

namespace fricon::feti {

namespace {

constexpr Index kNone = std::numeric_limits<Index>::max();

// The process of each of the n subdomains: the one whose block (Ranks::block_of) holds it.
std::vector<int> subdomain_processes(Index n, const Ranks& ranks) {
  std::vector<int> process(static_cast<size_t>(n), 0);
  for (int q = 0; q < ranks.size(); ++q) {
    const auto [first, last] = ranks.block_of(q, n);
    for (Index i = first; i < last; ++i)
      process[static_cast<size_t>(i)] = q;
  }
  return process;
}

// Groups of rows by union: a row's group is named by its root.
class Groups {
 public:
  explicit Groups(Index n) : parent_(static_cast<size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), Index{0});
  }
  Index root(Index i) {
    while (parent_[static_cast<size_t>(i)] != i) {
      Index& p = parent_[static_cast<size_t>(i)];
      p = parent_[static_cast<size_t>(p)];  // halve the path
      i = p;
    }
    return i;
  }
  void join(Index a, Index b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }

 private:
  std::vector<Index> parent_;
};

// The owner of every row (theory.md §8.8): process 0 for a contact row; for an equality row the
// process of the lowest or, for every other group, the highest subdomain that a row of its group
// (the equality rows sharing a torn dof, transitively) touches: two neighbouring processes share
// the groups between them about evenly.
std::vector<int> row_owners(const std::vector<Subdomain>& subdomains, const TornRows& rows,
                            const Ranks& ranks) {
  const Index n_rows = rows.n_rows(), n_contact = rows.n_contact;
  std::vector<Index> lowest(static_cast<size_t>(n_rows), kNone), highest(lowest.size(), -1);
  for (std::size_t i = 0; i < subdomains.size(); ++i)
    for (Index r : subdomains[i].rows) {
      lowest[static_cast<size_t>(r)] =
          std::min(lowest[static_cast<size_t>(r)], static_cast<Index>(i));
      highest[static_cast<size_t>(r)] =
          std::max(highest[static_cast<size_t>(r)], static_cast<Index>(i));
    }
  Groups groups(n_rows);
  for (Index j = 0; j < rows.B.outerSize(); ++j) {
    Index first = -1;
    for (SparseMatrix::InnerIterator it(rows.B, j); it; ++it) {
      if (it.row() < n_contact) continue;
      if (first < 0)
        first = it.row();
      else
        groups.join(first, it.row());
    }
  }
  std::vector<Index> group_lowest(static_cast<size_t>(n_rows), kNone),
      group_highest(group_lowest.size(), -1);
  for (Index r = n_contact; r < n_rows; ++r) {
    const auto g = static_cast<size_t>(groups.root(r));
    group_lowest[g] = std::min(group_lowest[g], lowest[static_cast<size_t>(r)]);
    group_highest[g] = std::max(group_highest[g], highest[static_cast<size_t>(r)]);
  }
  const std::vector<int> process =
      subdomain_processes(static_cast<Index>(subdomains.size()), ranks);
  // The groups in the order of their first rows, the even ones to their lowest subdomain's
  // process, the odd ones to their highest's.
  std::vector<Index> chosen(static_cast<size_t>(n_rows), kNone);
  Index n_groups = 0;
  for (Index r = n_contact; r < n_rows; ++r)
    if (groups.root(r) == r)
      chosen[static_cast<size_t>(r)] = n_groups++ % 2 == 0 ? group_lowest[static_cast<size_t>(r)]
                                                           : group_highest[static_cast<size_t>(r)];
  std::vector<int> owner(static_cast<size_t>(n_rows), 0);
  for (Index r = n_contact; r < n_rows; ++r) {
    const Index s = chosen[static_cast<size_t>(groups.root(r))];
    owner[static_cast<size_t>(r)] = s == kNone || s < 0 ? 0 : process[static_cast<size_t>(s)];
  }
  return owner;
}

// The rows that the subdomains [first, last) act on, ascending.
std::vector<Index> rows_read(const std::vector<Subdomain>& subdomains, Index first, Index last) {
  std::vector<Index> read;
  for (Index i = first; i < last; ++i) {
    const std::vector<Index>& r = subdomains[static_cast<size_t>(i)].rows;
    read.insert(read.end(), r.begin(), r.end());
  }
  std::sort(read.begin(), read.end());
  read.erase(std::unique(read.begin(), read.end()), read.end());
  return read;
}

}  // namespace

DualRows::DualRows(const std::vector<Subdomain>& subdomains, const TornRows& rows,
                   const Ranks& ranks)
    : ranks_(&ranks), rank_(ranks.rank()) {
  const std::vector<int> owner = row_owners(subdomains, rows, ranks);
  share_rows(owner, rows.n_contact);
  std::vector<Index> extended = number_ghosts(subdomains, owner);
  plan_sends(subdomains, owner, extended);
  map_subdomain_rows(subdomains, extended);
}

// Every process's rows, ascending.
void DualRows::share_rows(const std::vector<int>& owner, Index n_contact) {
  owned_.assign(static_cast<size_t>(ranks_->size()), {});
  for (std::size_t r = 0; r < owner.size(); ++r)
    owned_[static_cast<size_t>(owner[r])].push_back(static_cast<Index>(r));
  n_local_contact_ = rank_ == 0 ? n_contact : 0;
}

// The extended index of every row this process's subdomains read (-1 for the others): its own
// rows first, then the ghosts, by owner and ascending.
std::vector<Index> DualRows::number_ghosts(const std::vector<Subdomain>& subdomains,
                                           const std::vector<int>& owner) {
  std::vector<Index> extended(owner.size(), -1);
  for (std::size_t k = 0; k < owned().size(); ++k)
    extended[static_cast<size_t>(owned()[k])] = static_cast<Index>(k);
  const auto [first, last] = ranks_->block(static_cast<Index>(subdomains.size()));
  const std::vector<Index> read = rows_read(subdomains, first, last);
  const auto P = static_cast<size_t>(ranks_->size());
  recv_count_.assign(P, 0);
  recv_offset_.assign(P, 0);
  Index next = n_local();
  for (std::size_t q = 0; q < P; ++q) {
    recv_offset_[q] = next;
    if (static_cast<int>(q) == rank_) continue;
    for (Index r : read)
      if (owner[static_cast<size_t>(r)] == static_cast<int>(q))
        extended[static_cast<size_t>(r)] = next++;
    recv_count_[q] = next - recv_offset_[q];
  }
  n_ghosts_ = next - n_local();
  return extended;
}

// What every other process's subdomains read of this one's rows: sent before a product, and
// their sums returned after, in ascending row order.
void DualRows::plan_sends(const std::vector<Subdomain>& subdomains, const std::vector<int>& owner,
                          const std::vector<Index>& extended) {
  send_.assign(static_cast<size_t>(ranks_->size()), {});
  for (int q = 0; q < ranks_->size(); ++q) {
    if (q == rank_) continue;
    const auto [first, last] = ranks_->block_of(q, static_cast<Index>(subdomains.size()));
    for (Index r : rows_read(subdomains, first, last))
      if (owner[static_cast<size_t>(r)] == rank_)
        send_[static_cast<size_t>(q)].push_back(extended[static_cast<size_t>(r)]);
  }
}

// The extended index of each row of each of this process's subdomains.
void DualRows::map_subdomain_rows(const std::vector<Subdomain>& subdomains,
                                  const std::vector<Index>& extended) {
  const auto [first, last] = ranks_->block(static_cast<Index>(subdomains.size()));
  first_subdomain_ = first;
  extended_rows_.assign(static_cast<size_t>(last - first), {});
  for (Index i = first; i < last; ++i)
    for (Index r : subdomains[static_cast<size_t>(i)].rows)
      extended_rows_[static_cast<size_t>(i - first)].push_back(extended[static_cast<size_t>(r)]);
}

VectorXd DualRows::restrict(const VectorXd& whole) const {
  VectorXd local(n_local());
  for (std::size_t k = 0; k < owned().size(); ++k)
    local(static_cast<Index>(k)) = whole(owned()[k]);
  return local;
}

SparseMatrix DualRows::restrict_columns(const SparseMatrix& G) const {
  if (owned_.size() == 1) return G;
  SparseMatrix part(G.rows(), n_local());
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  for (std::size_t k = 0; k < owned().size(); ++k)
    for (SparseMatrix::InnerIterator it(G, owned()[k]); it; ++it)
      entries.emplace_back(it.row(), static_cast<Index>(k), it.value());
  part.setFromTriplets(entries.begin(), entries.end());
  part.makeCompressed();
  return part;
}

VectorXd DualRows::assemble(const VectorXd& local) const {
  FRICON_CHECK(local.size() == n_local(),
               "assemble: " << local.size() << " entries for " << n_local());
  if (owned_.size() == 1) return local;
  const VectorXd all = ranks_->concat(local);
  Index total = 0;
  for (const std::vector<Index>& rows : owned_)
    total += static_cast<Index>(rows.size());
  VectorXd whole(total);
  Index k = 0;
  for (const std::vector<Index>& rows : owned_)
    for (Index r : rows)
      whole(r) = all(k++);
  return whole;
}

void DualRows::fetch_ghosts(const VectorXd& local, VectorXd& extended) const {
  extended.resize(n_extended());
  extended.head(n_local()) = local;
  if (owned_.size() == 1) return;
  std::vector<VectorXd> out(owned_.size()), in(owned_.size());
  for (std::size_t q = 0; q < owned_.size(); ++q) {
    out[q].resize(static_cast<Index>(send_[q].size()));
    for (std::size_t k = 0; k < send_[q].size(); ++k)
      out[q](static_cast<Index>(k)) = local(send_[q][k]);
    in[q].resize(recv_count_[q]);
  }
  ranks_->exchange(out, in);
  for (std::size_t q = 0; q < owned_.size(); ++q)
    extended.segment(recv_offset_[q], recv_count_[q]) = in[q];
}

void DualRows::return_ghosts(const VectorXd& extended, VectorXd& local) const {
  local = extended.head(n_local());
  if (owned_.size() == 1) return;
  std::vector<VectorXd> out(owned_.size()), in(owned_.size());
  for (std::size_t q = 0; q < owned_.size(); ++q) {
    out[q] = extended.segment(recv_offset_[q], recv_count_[q]);
    in[q].resize(static_cast<Index>(send_[q].size()));
  }
  ranks_->exchange(out, in);
  for (std::size_t q = 0; q < owned_.size(); ++q)
    for (std::size_t k = 0; k < send_[q].size(); ++k)
      local(send_[q][k]) += in[q](static_cast<Index>(k));
}

void RanksSpace::sum(Eigen::Ref<Eigen::VectorXd> v) const {
  ranks_->sum(v);  // every process takes part, alone too: the stop request rides on the sums
}

double RanksSpace::max(double value) const {
  if (ranks_->size() == 1) return value;
  const std::vector<double> all = ranks_->gather(value);
  return *std::max_element(all.begin(), all.end());
}

}  // namespace fricon::feti
