#include "fricon/feti/tfeti.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <sys/resource.h>

#include <fmt/format.h>

#include "fricon/core/timer.hpp"
#include "fricon/feti/partition.hpp"
#include "fricon/feti/preconditioner.hpp"
#include "fricon/feti/softness.hpp"
#include "fricon/feti/subdomains.hpp"

namespace fricon::feti {

namespace {
constexpr double kBytesPerMib = 1024.0 * 1024.0;
constexpr double kBytesPerEntry = 8.0;

// Sizes over all subdomains; factors and their times over those of every process (summed).
void describe_subdomains(const std::vector<Subdomain>& subdomains, const Ranks& ranks,
                         FetiReport& report) {
  const auto n = static_cast<Index>(subdomains.size());
  report.n_subdomains = n;
  report.min_nodes = subdomains.empty() ? 0 : static_cast<Index>(subdomains[0].nodes.size());
  double total = 0.0;
  for (const Subdomain& s : subdomains) {
    const auto n_nodes = static_cast<Index>(s.nodes.size());
    report.min_nodes = std::min(report.min_nodes, n_nodes);
    report.max_nodes = std::max(report.max_nodes, n_nodes);
    total += static_cast<double>(n_nodes);
  }
  report.mean_nodes = subdomains.empty() ? 0.0 : total / static_cast<double>(n);
  const auto [first, last] = ranks.block(n);
  double nnz = 0.0, cpu_s = 0.0, tets = 0.0;
  for (Index i = first; i < last; ++i) {
    const Subdomain& s = subdomains[static_cast<size_t>(i)];
    nnz += s.factor.info().nnz_L;
    cpu_s += s.factor_seconds;
    tets += static_cast<double>(s.n_tets);
  }
  const std::vector<double> rank_nnz = ranks.gather(nnz), rank_cpu_s = ranks.gather(cpu_s),
                            rank_tets = ranks.gather(tets);
  report.n_ranks = ranks.size();
  report.ranks.assign(static_cast<size_t>(ranks.size()), {});
  for (std::size_t r = 0; r < report.ranks.size(); ++r) {
    RankShare& share = report.ranks[r];
    const auto [its_first, its_last] = ranks.block_of(static_cast<int>(r), n);
    share.n_subdomains = its_last - its_first;
    share.n_tets = static_cast<Index>(rank_tets[r]);
    share.factor_mib = rank_nnz[r] * kBytesPerEntry / kBytesPerMib;
    share.factorization_cpu_s = rank_cpu_s[r];
    report.nnz_factors += rank_nnz[r];
    report.factorization_cpu_s += rank_cpu_s[r];
  }
  report.factor_mib = report.nnz_factors * kBytesPerEntry / kBytesPerMib;
}

// The partition's note, and what the re-cuts of necked subdomains did.
std::string partition_note(const Partition& partition, const FetiReport& report) {
  if (report.n_recut == 0) return partition.note;
  return fmt::format(
      "{}{}{} subdomain{} joined by a neck cut again with {} neighbours in {} "
      "round{} (theory.md §8.9){}; {} others kept their factors.",
      partition.note, partition.note.empty() ? "" : " ", report.n_recut,
      report.n_recut == 1 ? "" : "s", report.n_recut == 1 ? "its" : "their", report.recut_rounds,
      report.recut_rounds == 1 ? "" : "s", report.softness.necked.empty() ? "" : "; some still are",
      report.n_kept_factors);
}

}  // namespace

void record_peak_memory(const Ranks& ranks, FetiReport& report) {
  const std::vector<double> peaks = ranks.gather(peak_memory_mib());
  report.peak_memory_mib = *std::max_element(peaks.begin(), peaks.end());
  for (std::size_t r = 0; r < report.ranks.size() && r < peaks.size(); ++r)
    report.ranks[r].peak_memory_mib = peaks[r];
}

void record_shares(const FetiOperator& F, FetiReport& report) {
  const std::vector<double> held = F.ranks().gather(static_cast<double>(F.dual_rows().n_local()));
  const std::vector<double> ghosts =
      F.ranks().gather(static_cast<double>(F.dual_rows().n_ghosts()));
  for (std::size_t r = 0; r < report.ranks.size() && r < held.size(); ++r) {
    report.ranks[r].n_multipliers = std::llround(held[r]);
    report.ranks[r].n_ghosts = std::llround(ghosts[r]);
  }
}

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
                                         const Ranks& ranks, FetiReport& report) {
  const std::vector<double> model_mib = ranks.gather(peak_memory_mib());
  report.threads = options.threads;
  report.row_scaling = std::string(enum_name(options.scaling));
  report.preconditioner = std::string(enum_name(options.preconditioner));
  // @sect: the subdomains of each body (METIS on its dual graph).
  Stopwatch watch;
  const Index wanted = options.subdomains > 0 ? options.subdomains
                                              : subdomains_for_size(mesh, options.subdomain_size);
  Partition partition = partition_mesh(mesh, bodies, wanted, options.key_context);
  report.partition_s = watch.seconds();

  // @sect: each subdomain's K_s^+ and R_s, on the threads, and how soft it is beyond its rigid
  // motions; the subdomains joined by a neck cut again with their neighbours (theory.md §8.9).
  watch.restart();
  std::vector<Index> owners = node_owners(mesh, partition);
  std::vector<Subdomain> subdomains =
      make_subdomains(mesh, materials, partition, owners, applied, options.threads, ranks);
  Stopwatch softness_watch;
  Softness soft = subdomain_softness(subdomains, options.threads, ranks);
  report.softness_s = softness_watch.seconds();
  for (Index round = 1; round <= options.neck_cuts && !soft.necked.empty(); ++round) {
    report.n_recut += static_cast<Index>(soft.necked.size());
    report.recut_rounds = round;
    Partition cut = recut_necked(mesh, bodies, partition, soft.necked, round, options.key_context);
    owners = node_owners(mesh, cut);
    Index kept = 0;
    subdomains = remake_subdomains(mesh, materials, cut, owners, applied, options.threads, ranks,
                                   partition, std::move(subdomains), &kept);
    VectorXd kept_count = VectorXd::Constant(1, static_cast<Real>(kept));
    ranks.sum(kept_count);
    report.n_kept_factors = std::lround(kept_count(0));
    partition = std::move(cut);
    softness_watch.restart();
    soft = subdomain_softness(subdomains, options.threads, ranks);
    report.softness_s += softness_watch.seconds();
  }
  report.factorization_s = watch.seconds();
  report.softness = std::move(soft);
  report.n_split = partition.n_split;
  report.partition_note = partition_note(partition, report);
  report.subdomain_of_tet = partition.subdomain_of_tet;
  describe_subdomains(subdomains, ranks, report);
  for (std::size_t r = 0; r < report.ranks.size(); ++r)
    report.ranks[r].model_memory_mib = model_mib[r];

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
                                           options.threads, ranks);
  // @sect: the preconditioner, from each K_s assembled again (one per thread alive at a time).
  const StiffnessSource stiffness = [&](Index i) {
    return subdomain_stiffness(mesh, materials, partition.tets[static_cast<size_t>(i)]);
  };
  op->set_preconditioner(make_preconditioner(options.preconditioner, *op, stiffness));
  report.operator_s = watch.seconds();
  record_peak_memory(ranks, report);
  return op;
}

}  // namespace fricon::feti
