#pragma once
// feti: the constraints of Total FETI as rows of one B over the torn dofs (docs/theory.md §8.2),
//
//   B = [ B_C ]  contact rows (bounds and discs): the contact discretization's rows, each
//       [ B_G ]  gluing rows (equalities): the copies of a node agree
//       [ B_D ]  Dirichlet rows (equalities): a fixed component takes its prescribed value
//
// with c = (c_C, 0, c_D) so that B u <= c (contact) and B u = c (the rest). The contact rows act on
// the owner's copy of each node (the copies are glued, so any would do). Gluing rows are
// non-redundant: a chain through the copies of a node in subdomain order, one row per link and
// component. Each equality row is scaled by the lumped stiffness of its dofs (theory.md §8.5), so
// that its diagonal entry of F = B K^+ B^T is of order 1, like the scaled contact rows'.

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/feti/subdomains.hpp"

namespace fricon::feti {

struct TornRows {
  SparseMatrix B;  ///< n_rows x n_torn
  VectorXd c;      ///< n_rows [m^3 for contact rows; scaled m for the others]
  Index n_contact = 0, n_gluing = 0, n_dirichlet = 0;
  Index n_rows() const { return n_contact + n_gluing + n_dirichlet; }
  Index n_equality() const { return n_gluing + n_dirichlet; }
};

/// The torn dof of the owner's copy of each component of each node (3 n_nodes entries, node
/// major), for the subdomains `subdomains` (make_subdomains) and `owners` (node_owners).
std::vector<Index> owner_dofs(const std::vector<Subdomain>& subdomains,
                              const std::vector<Index>& owners, Index n_nodes);

/// The owner's torn dof of each free dof of `dofs` (the whole model's): where a contact column
/// or a displacement over the free dofs lives among the torn dofs. `owner_dof`: owner_dofs.
std::vector<Index> torn_of_free(const std::vector<Index>& owner_dof, const fe::DofMap& dofs);

/// B and c above: the contact rows B_contact (over the free dofs of `dofs`, the whole model's)
/// with their offset c_contact, then the gluing rows of the subdomains' copies of the mesh's
/// `n_nodes` nodes, then a Dirichlet row for every component `dofs` fixes, at the value
/// `prescribed` (3 x n_nodes [m]). `owner_dof`: owner_dofs.
TornRows tear_rows(const std::vector<Subdomain>& subdomains, const std::vector<Index>& owner_dof,
                   const fe::DofMap& dofs, const fe::NodalField& prescribed,
                   const SparseMatrix& B_contact, const VectorXd& c_contact, RowScaling scaling);

/// `rows` with its contact block replaced by B_contact (over the model's free dofs, moved to the
/// owners' copies by `torn_of_free`) and its offset c_contact [m^3]; the equality rows and their
/// c are kept, after the new contact rows. The contact search's candidates (theory.md §8.7).
void replace_contact_rows(TornRows& rows, const std::vector<Index>& torn_of_free,
                          const SparseMatrix& B_contact, const VectorXd& c_contact);

/// Stores in each subdomain the rows of B that act on it (Subdomain::B and rows).
void attach_rows(const SparseMatrix& B, std::vector<Subdomain>& subdomains);

}  // namespace fricon::feti
