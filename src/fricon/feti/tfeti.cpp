#include "fricon/feti/tfeti.hpp"

#include <algorithm>

#include <sys/resource.h>

#include "fricon/core/timer.hpp"
#include "fricon/feti/partition.hpp"
#include "fricon/feti/subdomains.hpp"

namespace fricon::feti {

namespace {
constexpr double kBytesPerMib = 1024.0 * 1024.0;
constexpr double kBytesPerEntry = 8.0;

void describe_subdomains(const std::vector<Subdomain>& subdomains, FetiReport& report) {
  report.n_subdomains = static_cast<Index>(subdomains.size());
  report.min_nodes = subdomains.empty() ? 0 : static_cast<Index>(subdomains[0].nodes.size());
  double total = 0.0;
  for (const Subdomain& s : subdomains) {
    const auto n = static_cast<Index>(s.nodes.size());
    report.min_nodes = std::min(report.min_nodes, n);
    report.max_nodes = std::max(report.max_nodes, n);
    total += static_cast<double>(n);
    report.nnz_factors += s.factor.info().nnz_L;
    report.factorization_cpu_s += s.factor_seconds;
  }
  report.mean_nodes = subdomains.empty() ? 0.0 : total / static_cast<double>(subdomains.size());
  report.factor_mib = report.nnz_factors * kBytesPerEntry / kBytesPerMib;
}

}  // namespace

double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::unique_ptr<FetiOperator> make_tfeti(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                                         fe::Materials materials, const fe::DofMap& dofs,
                                         const fe::NodalField& prescribed,
                                         const fe::NodalField& applied, const SparseMatrix& B,
                                         const VectorXd& offset, const FetiOptions& options,
                                         FetiReport& report) {
  report.threads = options.threads;
  report.row_scaling = options.scaling == RowScaling::Stiffness ? "stiffness" : "uniform";
  // @sect: the subdomains of each body (METIS on its dual graph).
  Stopwatch watch;
  const Index wanted = options.subdomains > 0 ? options.subdomains
                                              : subdomains_for_size(mesh, options.subdomain_size);
  const Partition partition = partition_mesh(mesh, bodies, wanted, options.key_context);
  report.n_split = partition.n_split;
  report.partition_note = partition.note;
  report.partition_s = watch.seconds();

  // @sect: each subdomain's K_s^+ and R_s, on the threads.
  watch.restart();
  const std::vector<Index> owners = node_owners(mesh, partition);
  std::vector<Subdomain> subdomains =
      make_subdomains(mesh, materials, partition, owners, applied, options.threads);
  report.factorization_s = watch.seconds();
  describe_subdomains(subdomains, report);

  // @sect: the rows of B over the torn dofs, each subdomain's share, and F, h, G, e.
  watch.restart();
  const std::vector<Index> owner_dof = owner_dofs(subdomains, owners, mesh.n_nodes());
  TornRows rows = tear_rows(subdomains, owner_dof, dofs, prescribed, B, offset, options.scaling);
  attach_rows(rows.B, subdomains);
  report.n_torn = rows.B.cols();
  report.n_contact = rows.n_contact;
  report.n_gluing = rows.n_gluing;
  report.n_dirichlet = rows.n_dirichlet;
  report.n_coarse = kSubdomainMotions * report.n_subdomains;
  auto op = std::make_unique<FetiOperator>(std::move(subdomains), std::move(rows), owner_dof, dofs,
                                           options.threads);
  report.operator_s = watch.seconds();
  report.peak_memory_mib = peak_memory_mib();
  return op;
}

}  // namespace fricon::feti
