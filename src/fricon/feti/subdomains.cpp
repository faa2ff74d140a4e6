#include "fricon/feti/subdomains.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/parallel_for.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/floating.hpp"
#include "fricon/mesh/bodies.hpp"

namespace fricon::feti {

namespace {

// A subdomain's own mesh, its dofs (every component of every node) and rigid motions.
struct Piece {
  mesh::TetMesh mesh;
  fe::DofMap dofs;
  fe::FloatingBodies floating;
};

// The nodes and rigid motions of one subdomain (theory.md §8.1), from the tetrahedra `tets`
// of `mesh`.
Piece describe_subdomain(const mesh::TetMesh& mesh, const std::vector<Index>& tets, Index index,
                         Subdomain& s) {
  mesh::TetMesh part = mesh::submesh(mesh, tets, &s.nodes);
  const fe::DofMap dofs(part.n_nodes());
  fe::FloatingBodies floating = fe::find_floating_bodies(part, mesh::find_bodies(part), dofs);
  FRICON_CHECK(floating.bodies.size() == 1 && floating.n_motions() == kSubdomainMotions,
               "subdomain " << index << " is not one body with six rigid motions");
  s.R = MatrixXd(floating.R);
  s.n_tets = static_cast<Index>(tets.size());
  return {std::move(part), dofs, std::move(floating)};
}

// The stiffness and factor of one subdomain of this process (theory.md §8.1): K_s over every
// dof of its nodes, regularized as a floating body (fe/floating.hpp) so that its solves are
// K_s^+.
void factor_subdomain(const mesh::TetMesh& mesh, fe::Materials materials,
                      const std::vector<Index>& tets, Index index, Subdomain& s) {
  const Stopwatch watch;
  const Piece piece = describe_subdomain(mesh, tets, index, s);
  const SparseMatrix K = fe::assemble_stiffness(piece.mesh, materials, piece.dofs);
  s.stiffness_diagonal = K.diagonal();
  try {
    s.factor.factorize(fe::regularized_stiffness(K, piece.floating));
  } catch (const NumericalError& e) {
    throw NumericalError(
        fmt::format("the stiffness of subdomain {} ({} tetrahedra) regularized by its rigid "
                    "motions is not positive definite: {}",
                    index, tets.size(), e.what()));
  }
  s.factor_seconds = watch.seconds();
}

// Every subdomain's stiffness diagonal, from the processes that factored them.
void share_diagonals(std::vector<Subdomain>& subdomains, const Ranks& ranks) {
  Index n_torn = 0;
  for (const Subdomain& s : subdomains)
    n_torn += s.n_dofs();
  VectorXd d = VectorXd::Zero(n_torn);
  for (const Subdomain& s : subdomains)
    if (s.stiffness_diagonal.size() == s.n_dofs())
      d.segment(s.first_dof, s.n_dofs()) = s.stiffness_diagonal;
  ranks.sum(d);  // each torn dof has one subdomain, factored by one process: the sum is exact
  for (Subdomain& s : subdomains)
    s.stiffness_diagonal = d.segment(s.first_dof, s.n_dofs());
}

}  // namespace

std::vector<Index> node_owners(const mesh::TetMesh& mesh, const Partition& partition) {
  // Subdomain by subdomain, how many of its tetrahedra touch each node (`touching`, reset after
  // each subdomain); a node goes to the first subdomain whose count beats the best so far.
  std::vector<Index> owner(static_cast<size_t>(mesh.n_nodes()), partition.n_subdomains);
  std::vector<Index> best(static_cast<size_t>(mesh.n_nodes()), 0);
  std::vector<Index> touching(static_cast<size_t>(mesh.n_nodes()), 0);
  for (Index s = 0; s < partition.n_subdomains; ++s) {
    const std::vector<Index>& tets = partition.tets[static_cast<size_t>(s)];
    for (Index t : tets)
      for (Index a = 0; a < mesh.nodes_per_tet(); ++a)
        ++touching[static_cast<size_t>(mesh.tet_node(t, a))];
    for (Index t : tets)
      for (Index a = 0; a < mesh.nodes_per_tet(); ++a) {
        const auto node = static_cast<size_t>(mesh.tet_node(t, a));
        if (touching[node] > best[node]) {
          best[node] = touching[node];
          owner[node] = s;
        }
        touching[node] = 0;
      }
  }
  return owner;
}

namespace {

// The subdomains of `partition` from `subdomains` (one per subdomain, in its order): those marked
// in `made` are complete already (nodes, R_s, the factor of this process's, stiffness diagonal);
// the others are described and, in this process's block, factored. Then the torn dofs' numbering,
// the loads and the shared diagonals, for all.
std::vector<Subdomain> complete_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                           const Partition& partition,
                                           const std::vector<Index>& owners,
                                           const fe::NodalField& applied, int threads,
                                           const Ranks& ranks, std::vector<Subdomain> subdomains,
                                           const std::vector<char>& made) {
  const Index n = partition.n_subdomains;
  const auto [first, last] = ranks.block(n);
  ranks.collectively([&] {
    parallel_for(n, threads, [&](Index i, int) {
      if (made[static_cast<size_t>(i)]) return;
      const std::vector<Index>& tets = partition.tets[static_cast<size_t>(i)];
      Subdomain& s = subdomains[static_cast<size_t>(i)];
      if (first <= i && i < last)
        factor_subdomain(mesh, materials, tets, i, s);
      else
        (void)describe_subdomain(mesh, tets, i, s);
    });
  });
  Index first_dof = 0;
  for (Index i = 0; i < n; ++i) {
    Subdomain& s = subdomains[static_cast<size_t>(i)];
    s.first_dof = first_dof;
    first_dof += s.n_dofs();
    s.f = VectorXd::Zero(s.n_dofs());
    for (std::size_t a = 0; a < s.nodes.size(); ++a)
      if (owners[static_cast<size_t>(s.nodes[a])] == i)
        s.f.segment<3>(3 * static_cast<Index>(a)) = applied.col(s.nodes[a]);
  }
  share_diagonals(subdomains, ranks);
  return subdomains;
}

}  // namespace

std::vector<Subdomain> make_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                       const Partition& partition, const std::vector<Index>& owners,
                                       const fe::NodalField& applied, int threads,
                                       const Ranks& ranks) {
  const auto n = static_cast<size_t>(partition.n_subdomains);
  return complete_subdomains(mesh, materials, partition, owners, applied, threads, ranks,
                             std::vector<Subdomain>(n), std::vector<char>(n, 0));
}

std::vector<Subdomain> remake_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                         const Partition& partition,
                                         const std::vector<Index>& owners,
                                         const fe::NodalField& applied, int threads,
                                         const Ranks& ranks, const Partition& before,
                                         std::vector<Subdomain>&& previous, Index* n_kept) {
  // @sect: the earlier subdomains by their first tetrahedron (a tetrahedron is in one subdomain).
  std::vector<Index> earlier_by_tet(static_cast<size_t>(mesh.n_tets()), -1);
  for (Index j = 0; j < before.n_subdomains; ++j)
    earlier_by_tet[static_cast<size_t>(before.tets[static_cast<size_t>(j)].front())] = j;
  // @sect: a subdomain of the same tetrahedra, factored by this process before and in its block
  // now, is kept whole; its stiffness diagonal is this process's alone again, for the sum.
  const Index n = partition.n_subdomains;
  const auto [first, last] = ranks.block(n);
  std::vector<Subdomain> subdomains(static_cast<size_t>(n));
  std::vector<char> made(static_cast<size_t>(n), 0);
  Index kept = 0;
  for (Index i = first; i < last; ++i) {
    const std::vector<Index>& tets = partition.tets[static_cast<size_t>(i)];
    const Index j = earlier_by_tet[static_cast<size_t>(tets.front())];
    if (j < 0 || before.tets[static_cast<size_t>(j)] != tets) continue;
    Subdomain& old = previous[static_cast<size_t>(j)];
    if (old.factor.size() == 0) continue;  // another process's
    subdomains[static_cast<size_t>(i)] = std::move(old);
    Subdomain& s = subdomains[static_cast<size_t>(i)];
    s.B = SparseMatrix();
    s.rows.clear();
    made[static_cast<size_t>(i)] = 1;
    ++kept;
  }
  std::vector<Subdomain>().swap(previous);  // the re-cut ones' factors go before the new ones
  if (n_kept) *n_kept = kept;
  return complete_subdomains(mesh, materials, partition, owners, applied, threads, ranks,
                             std::move(subdomains), made);
}

SparseMatrix subdomain_stiffness(const mesh::TetMesh& mesh, fe::Materials materials,
                                 const std::vector<Index>& tets) {
  const mesh::TetMesh part = mesh::submesh(mesh, tets, nullptr);
  return fe::assemble_stiffness(part, materials, fe::DofMap(part.n_nodes()));
}

}  // namespace fricon::feti
