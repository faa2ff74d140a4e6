#pragma once
// feti: the subdomains of Total FETI (docs/theory.md §8.1): each a face-connected set of
// tetrahedra (feti/partition.hpp) with its own copy of every node it touches (the torn dofs),
// its stiffness K_s over all of them (no Dirichlet condition: every subdomain floats), its rigid
// motions R_s (K_s R_s = 0) and the factor of the regularized K_s, whose solves are a generalized
// inverse K_s^+ (fe/floating.hpp, the floating bodies' own). Built on a pool of threads.

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/feti/partition.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::feti {

/// Rigid motions of a subdomain: three translations and three rotations.
inline constexpr Index kSubdomainMotions = 6;

struct Subdomain {
  std::vector<Index> nodes;  ///< the mesh node of each local node, ascending
  /// Its first torn dof: component c of local node a is torn dof first_dof + 3 a + c.
  Index first_dof = 0;
  Index n_tets = 0;
  Index n_dofs() const { return 3 * static_cast<Index>(nodes.size()); }

  VectorXd stiffness_diagonal;  ///< the diagonal of K_s [N/m] (scales the gluing rows)
  MatrixXd R;                   ///< n_dofs x 6: its rigid motions [m per unit amplitude]
  /// Of the regularized K_s, its solves K_s^+ [m/N]: only in the subdomains of this process
  /// (Ranks::block); empty in the others.
  linalg::CholeskyFactor factor;
  VectorXd f;                   ///< its share of the applied load [N] (at the nodes it owns)
  double factor_seconds = 0.0;  ///< the assembly and factorization of K_s [s]

  /// The rows of the torn B that act on it (feti/torn_rows.hpp) over its local dofs, as
  /// `rows.size()` x n_dofs, and the dual row of each.
  SparseMatrix B;
  std::vector<Index> rows;
};

/// The subdomain that owns each node of `mesh`: of those whose tetrahedra touch it, the one with
/// the most tetrahedra at the node (the copy most firmly attached to its subdomain), the lowest
/// index among equals. The load of a node, its contact columns and its Dirichlet rows act on the
/// owner's copy, and its displacement is read there (theory.md §8.1).
std::vector<Index> node_owners(const mesh::TetMesh& mesh, const Partition& partition);

/// The subdomains of `partition` of `mesh`, numbered as it numbers them, torn dofs consecutive in
/// that order: for each, its nodes, K_s assembled with `materials` (one per region of the mesh)
/// and factored after regularization, R_s, and the applied forces `applied` (3 x n_nodes [N],
/// every component, fixed ones too) at the nodes it owns (`owners`, node_owners). Only the
/// subdomains of this process's block (ranks.block) are factored; every process holds the
/// others' nodes, R_s and (shared by `ranks`) stiffness diagonals. Runs on `threads` threads.
/// Collective over `ranks`. Throws NumericalError, on every process, when a regularized K_s is
/// not positive definite.
std::vector<Subdomain> make_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                       const Partition& partition, const std::vector<Index>& owners,
                                       const fe::NodalField& applied, int threads,
                                       const Ranks& ranks);

/// As make_subdomains for `partition`, a re-cut of `before` (recut_necked, theory.md §8.9) whose
/// subdomains `previous` were made by make_subdomains (or this) on the same mesh, materials and
/// ranks: a subdomain of the same tetrahedra as one of `before`, which this process factored and
/// whose index falls in its block again, takes that one's nodes, R_s, factor and diagonal instead
/// of being assembled and factored again. `previous` is emptied (the other factors freed) before
/// the new subdomains are factored. `n_kept`, if given, receives the number of subdomains this
/// process kept. Collective over `ranks`; throws as make_subdomains.
std::vector<Subdomain> remake_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                         const Partition& partition,
                                         const std::vector<Index>& owners,
                                         const fe::NodalField& applied, int threads,
                                         const Ranks& ranks, const Partition& before,
                                         std::vector<Subdomain>&& previous,
                                         Index* n_kept = nullptr);

/// K_s [N/m] of the subdomain made of the tetrahedra `tets` of `mesh` (a Partition's), both
/// triangles, over its local dofs as make_subdomains numbers them: assembled again, for what a
/// preconditioner keeps of it (feti/preconditioner.hpp), so that no whole K_s has to stay
/// beside the factors. Thread-safe.
SparseMatrix subdomain_stiffness(const mesh::TetMesh& mesh, fe::Materials materials,
                                 const std::vector<Index>& tets);

}  // namespace fricon::feti
