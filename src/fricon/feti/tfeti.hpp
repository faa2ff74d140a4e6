#pragma once
// feti: Total FETI from a model's pieces, in data-flow order (docs/theory.md §8): the partition of
// each body into subdomains -> their factored stiffnesses and rigid motions (threads) -> the torn
// rows of B (contact, gluing, Dirichlet) -> the dual operator F, h, G, e. Also the report of it.

#include <memory>
#include <string>

#include "fricon/contact/discretization.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/feti/feti_operator.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/feti/torn_rows.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::feti {

/// The Total FETI operator of a model: its mesh, bodies, materials, dofs (the Dirichlet
/// conditions), prescribed displacements (3 x n_nodes [m]) and applied forces (3 x n_nodes [N]),
/// with the contact rows B [m^2] over the free dofs and their offset c [m^3] (both empty without
/// contact). The subdomains are shared by `ranks` (this_process(): all here), which must outlive
/// the operator; collective over them, and every process gets the whole report. Fills `report`
/// (all but the solve's counts). Throws InputError for a partition that cannot be made
/// (feti::partition_mesh), NumericalError for a subdomain that cannot be factored.
std::unique_ptr<FetiOperator> make_tfeti(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                                         fe::Materials materials, const fe::DofMap& dofs,
                                         const fe::NodalField& prescribed,
                                         const fe::NodalField& applied, const SparseMatrix& B,
                                         const VectorXd& offset, const FetiOptions& options,
                                         const Ranks& ranks, FetiReport& report);

/// Peak resident memory of this process so far [MiB].
double peak_memory_mib();

/// The peak memory of every process so far into `report` (its ranks and their largest).
/// Collective over `ranks`.
void record_peak_memory(const Ranks& ranks, FetiReport& report);

/// Every process's share of F's multipliers, and its ghosts (RankShare::n_multipliers,
/// n_ghosts), into `report`. Collective over F's ranks.
void record_shares(const FetiOperator& F, FetiReport& report);

}  // namespace fricon::feti
