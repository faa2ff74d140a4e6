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

// The stiffness, rigid motions and factor of one subdomain (theory.md §8.1): K_s over every dof
// of its nodes, regularized as a floating body (fe/floating.hpp) so that its solves are K_s^+.
void factor_subdomain(const mesh::TetMesh& mesh, fe::Materials materials,
                      const std::vector<Index>& tets, Index index, Subdomain& s) {
  const Stopwatch watch;
  const mesh::TetMesh part = mesh::submesh(mesh, tets, &s.nodes);
  const fe::DofMap dofs(part.n_nodes());
  const SparseMatrix K = fe::assemble_stiffness(part, materials, dofs);
  s.stiffness_diagonal = K.diagonal();
  const fe::FloatingBodies floating = fe::find_floating_bodies(part, mesh::find_bodies(part), dofs);
  FRICON_CHECK(floating.bodies.size() == 1 && floating.n_motions() == kSubdomainMotions,
               "subdomain " << index << " is not one body with six rigid motions");
  s.R = MatrixXd(floating.R);
  try {
    s.factor.factorize(fe::regularized_stiffness(K, floating));
  } catch (const NumericalError& e) {
    throw NumericalError(
        fmt::format("the stiffness of subdomain {} ({} tetrahedra) regularized by its rigid "
                    "motions is not positive definite: {}",
                    index, tets.size(), e.what()));
  }
  s.n_tets = static_cast<Index>(tets.size());
  s.factor_seconds = watch.seconds();
}

}  // namespace

std::vector<Index> node_owners(const mesh::TetMesh& mesh, const Partition& partition) {
  std::vector<Index> owner(static_cast<size_t>(mesh.n_nodes()), partition.n_subdomains);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const Index s = partition.subdomain_of_tet[static_cast<size_t>(t)];
    for (Index a = 0; a < mesh.nodes_per_tet(); ++a) {
      Index& o = owner[static_cast<size_t>(mesh.tet_node(t, a))];
      o = std::min(o, s);
    }
  }
  return owner;
}

std::vector<Subdomain> make_subdomains(const mesh::TetMesh& mesh, fe::Materials materials,
                                       const Partition& partition, const std::vector<Index>& owners,
                                       const fe::NodalField& applied, int threads) {
  std::vector<Subdomain> subdomains(static_cast<size_t>(partition.n_subdomains));
  parallel_for(partition.n_subdomains, threads, [&](Index i, int) {
    factor_subdomain(mesh, materials, partition.tets[static_cast<size_t>(i)], i,
                     subdomains[static_cast<size_t>(i)]);
  });
  Index first = 0;
  for (Index i = 0; i < partition.n_subdomains; ++i) {
    Subdomain& s = subdomains[static_cast<size_t>(i)];
    s.first_dof = first;
    first += s.n_dofs();
    s.f = VectorXd::Zero(s.n_dofs());
    for (std::size_t a = 0; a < s.nodes.size(); ++a)
      if (owners[static_cast<size_t>(s.nodes[a])] == i)
        s.f.segment<3>(3 * static_cast<Index>(a)) = applied.col(s.nodes[a]);
  }
  return subdomains;
}

}  // namespace fricon::feti
