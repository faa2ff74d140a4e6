#include "fricon/feti/torn_rows.hpp"

#include <algorithm>
#include <cmath>

#include "fricon/core/error.hpp"

namespace fricon::feti {

namespace {

using Triplet = Eigen::Triplet<Real, SparseIndex>;

// The copies of every node, in subdomain order, as the torn dof of their x component
// (compressed rows: the copies of node a are copy_dof[start[a] .. start[a+1])).
struct Copies {
  std::vector<Index> start, copy_dof;
};

Copies node_copies(const std::vector<Subdomain>& subdomains, Index n_nodes) {
  Copies c;
  c.start.assign(static_cast<size_t>(n_nodes + 1), 0);
  for (const Subdomain& s : subdomains)
    for (Index a : s.nodes)
      ++c.start[static_cast<size_t>(a + 1)];
  for (Index a = 0; a < n_nodes; ++a)
    c.start[static_cast<size_t>(a + 1)] += c.start[static_cast<size_t>(a)];
  c.copy_dof.resize(static_cast<size_t>(c.start.back()));
  std::vector<Index> next(c.start.begin(), c.start.end() - 1);
  for (const Subdomain& s : subdomains)
    for (std::size_t k = 0; k < s.nodes.size(); ++k)
      c.copy_dof[static_cast<size_t>(next[static_cast<size_t>(s.nodes[k])]++)] =
          s.first_dof + 3 * static_cast<Index>(k);
  return c;
}

// The stiffness diagonal [N/m] at every torn dof.
VectorXd torn_diagonal(const std::vector<Subdomain>& subdomains, Index n_torn) {
  VectorXd d(n_torn);
  for (const Subdomain& s : subdomains)
    d.segment(s.first_dof, s.n_dofs()) = s.stiffness_diagonal;
  return d;
}

// The entries of B_contact (over the model's free dofs) at the owners' torn dofs, appended to
// `entries` at B_contact's own row numbers.
void append_contact_rows(const std::vector<Index>& torn_of_free, const SparseMatrix& B_contact,
                         std::vector<Triplet>& entries) {
  for (Index j = 0; j < B_contact.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B_contact, j); it; ++it)
      entries.emplace_back(it.row(), torn_of_free[static_cast<size_t>(j)], it.value());
}

}  // namespace

std::vector<Index> torn_of_free(const std::vector<Index>& owner_dof, const fe::DofMap& dofs) {
  std::vector<Index> torn(static_cast<size_t>(dofs.n_free()), -1);
  for (Index a = 0; a < dofs.n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      if (dofs.dof(a, c) >= 0)
        torn[static_cast<size_t>(dofs.dof(a, c))] = owner_dof[static_cast<size_t>(3 * a + c)];
  return torn;
}

std::vector<Index> owner_dofs(const std::vector<Subdomain>& subdomains,
                              const std::vector<Index>& owners, Index n_nodes) {
  std::vector<Index> dof(static_cast<size_t>(3 * n_nodes), -1);
  for (std::size_t i = 0; i < subdomains.size(); ++i) {
    const Subdomain& s = subdomains[i];
    for (std::size_t k = 0; k < s.nodes.size(); ++k) {
      const Index a = s.nodes[k];
      if (owners[static_cast<size_t>(a)] != static_cast<Index>(i)) continue;
      for (int c = 0; c < 3; ++c)
        dof[static_cast<size_t>(3 * a + c)] = s.first_dof + 3 * static_cast<Index>(k) + c;
    }
  }
  return dof;
}

TornRows tear_rows(const std::vector<Subdomain>& subdomains, const std::vector<Index>& owner_dof,
                   const fe::DofMap& dofs, const fe::NodalField& prescribed,
                   const SparseMatrix& B_contact, const VectorXd& c_contact, RowScaling scaling) {
  const Index n_nodes = dofs.n_nodes();
  const Index n_torn =
      subdomains.empty() ? 0 : subdomains.back().first_dof + subdomains.back().n_dofs();
  const VectorXd diagonal = torn_diagonal(subdomains, n_torn);
  const Real mean_diagonal = n_torn > 0 ? diagonal.mean() : 1.0;
  // The scale of a row on the torn dofs `a` and `b` (b < 0: a Dirichlet row on a alone): the
  // square root of the lumped stiffness 1 / (1/k_a + 1/k_b), so that the row's entry of F is of
  // order 1 (theory.md §8.5).
  const auto row_scale = [&](Index a, Index b) {
    const Real ka = scaling == RowScaling::Stiffness ? diagonal(a) : mean_diagonal;
    const Real kb = b < 0 ? 0.0 : (scaling == RowScaling::Stiffness ? diagonal(b) : mean_diagonal);
    return b < 0 ? std::sqrt(ka) : std::sqrt(ka * kb / (ka + kb));
  };

  TornRows rows;
  std::vector<Triplet> entries;
  // @sect: the contact rows, moved from the whole model's free dofs to the owners' copies.
  append_contact_rows(torn_of_free(owner_dof, dofs), B_contact, entries);
  rows.n_contact = B_contact.rows();
  std::vector<Real> c(c_contact.data(), c_contact.data() + c_contact.size());

  // @sect: the gluing rows: a chain through the copies of each node.
  const Copies copies = node_copies(subdomains, n_nodes);
  Index row = rows.n_contact;
  for (Index a = 0; a < n_nodes; ++a)
    for (Index k = copies.start[static_cast<size_t>(a)] + 1;
         k < copies.start[static_cast<size_t>(a + 1)]; ++k)
      for (int comp = 0; comp < 3; ++comp, ++row) {
        const Index left = copies.copy_dof[static_cast<size_t>(k - 1)] + comp;
        const Index right = copies.copy_dof[static_cast<size_t>(k)] + comp;
        const Real w = row_scale(left, right);
        entries.emplace_back(row, left, w);
        entries.emplace_back(row, right, -w);
        c.push_back(0.0);
      }
  rows.n_gluing = row - rows.n_contact;

  // @sect: the Dirichlet rows, on the owners' copies.
  for (Index a = 0; a < n_nodes; ++a)
    for (int comp = 0; comp < 3; ++comp) {
      if (!dofs.is_fixed(a, comp)) continue;
      const Index dof = owner_dof[static_cast<size_t>(3 * a + comp)];
      const Real w = row_scale(dof, -1);
      entries.emplace_back(row, dof, w);
      c.push_back(w * prescribed(comp, a));
      ++row;
    }
  rows.n_dirichlet = row - rows.n_contact - rows.n_gluing;
  rows.B.resize(row, n_torn);
  rows.B.setFromTriplets(entries.begin(), entries.end());
  rows.B.makeCompressed();
  rows.c = Eigen::Map<const VectorXd>(c.data(), static_cast<Index>(c.size()));
  return rows;
}

void replace_contact_rows(TornRows& rows, const std::vector<Index>& torn_of_free,
                          const SparseMatrix& B_contact, const VectorXd& c_contact) {
  FRICON_CHECK(
      B_contact.rows() == c_contact.size(),
      "replace_contact_rows: " << B_contact.rows() << " rows, " << c_contact.size() << " offsets");
  const Index n_contact = B_contact.rows(), n_equality = rows.n_equality();
  std::vector<Triplet> entries;
  entries.reserve(static_cast<size_t>(B_contact.nonZeros()));
  append_contact_rows(torn_of_free, B_contact, entries);
  const SparseMatrix equality = rows.B.middleRows(rows.n_contact, n_equality);
  for (Index j = 0; j < equality.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(equality, j); it; ++it)
      entries.emplace_back(n_contact + it.row(), j, it.value());
  VectorXd c(n_contact + n_equality);
  c << c_contact, rows.c.tail(n_equality);
  rows.B.resize(n_contact + n_equality, rows.B.cols());
  rows.B.setFromTriplets(entries.begin(), entries.end());
  rows.B.makeCompressed();
  rows.c = std::move(c);
  rows.n_contact = n_contact;
}

void attach_rows(const SparseMatrix& B, std::vector<Subdomain>& subdomains) {
  // The local number of each row of B in the subdomain at hand (-1: none), reset after each.
  std::vector<Index> local(static_cast<size_t>(B.rows()), -1);
  for (Subdomain& s : subdomains) {
    const SparseMatrix block = B.middleCols(s.first_dof, s.n_dofs());
    // The rows it touches, ascending, and their local numbers.
    s.rows.clear();
    for (Index j = 0; j < block.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(block, j); it; ++it)
        if (local[static_cast<size_t>(it.row())] < 0) {
          local[static_cast<size_t>(it.row())] = 0;
          s.rows.push_back(it.row());
        }
    std::sort(s.rows.begin(), s.rows.end());
    for (std::size_t k = 0; k < s.rows.size(); ++k)
      local[static_cast<size_t>(s.rows[k])] = static_cast<Index>(k);
    std::vector<Triplet> entries;
    entries.reserve(static_cast<size_t>(block.nonZeros()));
    for (Index j = 0; j < block.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(block, j); it; ++it)
        entries.emplace_back(local[static_cast<size_t>(it.row())], j, it.value());
    s.B.resize(static_cast<Index>(s.rows.size()), s.n_dofs());
    s.B.setFromTriplets(entries.begin(), entries.end());
    s.B.makeCompressed();
    for (Index row : s.rows)
      local[static_cast<size_t>(row)] = -1;
  }
}

}  // namespace fricon::feti
