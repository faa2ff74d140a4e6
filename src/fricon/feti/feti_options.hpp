#pragma once
// feti: what a user chooses of Total FETI ([solver] subdomains, subdomain_size, tfeti_scaling,
// tfeti_preconditioner; docs/theory.md §8) and what a run reports of it. Data only: the problem and
// the run's report hold them without depending on the solver.

#include <string>
#include <vector>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"

namespace fricon::feti {

/// How the equality rows (gluing and Dirichlet) of B are scaled (theory.md §8.5).
enum class RowScaling {
  Stiffness,  ///< by the lumped stiffness of the row's dofs (the default)
  Uniform,    ///< by one factor, the mean stiffness diagonal (for comparison)
};

/// What approximates the inverse of F's equality block in MPGP's CG steps (theory.md §8.5).
enum class FetiPreconditioner {
  None,       ///< the diagonal scaling of the rows alone
  Lumped,     ///< (B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1, preconditioning in face
  Dirichlet,  ///< the same with K_s's Schur complements on the equality rows' dofs
};

/// solver.tfeti_preconditioner's default: the Dirichlet preconditioner. On the brick it saves
/// products with F and about as much time as it costs (MPGP applies it for CG and expansion
/// steps only); on a thin slab of flat elements the row scaling alone needed over a hundred
/// times its products with F (docs/benchmarks.md), so it is the safe choice.
inline constexpr FetiPreconditioner kDefaultPreconditioner = FetiPreconditioner::Dirichlet;

/// The smallest subdomain_size a user may ask for [nodes].
inline constexpr int kMinSubdomainSize = 4;

/// True when this build of fricon has METIS (Debian's libmetis-dev found at configure), which
/// backend "tfeti" partitions with.
bool metis_available();

/// The default target size of a subdomain [nodes] (solver.subdomain_size), measured with
/// bench/tfeti_bench.py (docs/benchmarks.md).
inline constexpr Index kDefaultSubdomainSize = 1000;

/// solver.tfeti_neck_cuts's default: rounds of cutting again the subdomains joined by a neck
/// (theory.md §8.9), each of which factors every subdomain again.
inline constexpr Index kDefaultNeckCuts = 3;

struct FetiOptions {
  /// The number of subdomains over all bodies (> 0), or 0 to take it from subdomain_size.
  Index subdomains = 0;
  Index subdomain_size = kDefaultSubdomainSize;  ///< target nodes per subdomain (> 0)
  RowScaling scaling = RowScaling::Stiffness;
  FetiPreconditioner preconditioner = kDefaultPreconditioner;
  Index neck_cuts = kDefaultNeckCuts;  ///< rounds of cutting necked subdomains again (>= 0)
  int threads = 1;                     ///< threads of the subdomains' factorizations and solves
  std::string key_context;             ///< where solver.subdomains was given, for messages
};

/// One process's share of the subdomains (feti/ranks.hpp).
struct RankShare {
  Index n_subdomains = 0;            ///< the subdomains it factors
  Index n_tets = 0;                  ///< their tetrahedra
  double factor_mib = 0.0;           ///< their factors, 8 bytes per non-zero [MiB]
  double factorization_cpu_s = 0.0;  ///< their assembly and factorization, summed [s]
  double peak_memory_mib = 0.0;      ///< its peak resident memory [MiB]
  /// Its peak resident memory when Total FETI started [MiB]: the model every process builds
  /// whole (mesh, loads, contact discretization) and the libraries, before any subdomain.
  double model_memory_mib = 0.0;
  /// The multipliers it holds in the QP at the end of the run (feti/dual_rows.hpp), and the
  /// rows of its subdomains that neighbours hold, exchanged in every product (ghosts).
  Index n_multipliers = 0;
  Index n_ghosts = 0;
};

/// How soft each subdomain is beyond its rigid motions (feti/softness.hpp, theory.md §8.9).
struct Softness {
  /// Per subdomain: lambda_7(K_s) / mean(diag K_s), its smallest eigenvalue beyond the six of its
  /// rigid motions relative to its typical stiffness [dimensionless]; estimated from above.
  std::vector<Real> relative;
  Index softest = -1;  ///< the subdomain of the smallest value (-1: none)
  Real median = 0.0;   ///< the median of `relative`
  /// median / relative[softest]: how many times softer than a typical subdomain the softest one
  /// is (1 with one subdomain).
  Real ratio = 1.0;
  /// The subdomains whose value is kNeckRatio (feti/softness.hpp) or more times below the
  /// median, ascending.
  std::vector<Index> necked;

  /// relative[softest], 0 without subdomains.
  Real softest_relative() const {
    return softest >= 0 ? relative[static_cast<size_t>(softest)] : 0.0;
  }
};

/// What the decomposition is: sizes, the interface, the coarse problem, times and memory.
struct FetiReport {
  Index n_subdomains = 0;
  Index n_split = 0;           ///< parts of the graph partition split into connected pieces
  std::string partition_note;  ///< how the partition was adjusted (empty: as asked)
  Index min_nodes = 0, max_nodes = 0;
  double mean_nodes = 0.0;
  /// Per tetrahedron of the mesh, its subdomain 0 .. n_subdomains - 1 (solution.vtu's cell
  /// field "subdomain").
  std::vector<Index> subdomain_of_tet;
  Softness softness;       ///< after the neck cuts, if any
  Index n_recut = 0;       ///< necked subdomains cut again with their neighbours, over the rounds
  Index recut_rounds = 0;  ///< rounds of such cuts (at most FetiOptions::neck_cuts)
  /// Subdomains that the cuts left as they were and that kept their factors (in the last round,
  /// summed over the processes).
  Index n_kept_factors = 0;
  Index n_torn = 0;               ///< torn dofs (3 per copy of a node)
  Index n_contact = 0;            ///< contact multipliers
  Index n_gluing = 0;             ///< gluing multipliers (the interface)
  Index n_dirichlet = 0;          ///< Dirichlet multipliers
  Index n_coarse = 0;             ///< rows of G: 6 per subdomain
  std::string row_scaling;        ///< "stiffness" or "uniform"
  std::string preconditioner;     ///< "none", "lumped" or "dirichlet"
  long n_preconditioner = 0;      ///< its applications (filled after the solve)
  double preconditioner_s = 0.0;  ///< their wall time [s], collective (filled after the solve)
  int threads = 1;                ///< threads of the subdomain loops
  double nnz_factors = 0.0;       ///< non-zeros of all the subdomains' factors
  double factor_mib = 0.0;        ///< their memory, 8 bytes per non-zero [MiB]
  double partition_s = 0.0;       ///< the graph partition [s]
  /// Assembly and factorization of every K_s, with the softness and any neck cuts (which factor
  /// them again), wall [s].
  double factorization_s = 0.0;
  double factorization_cpu_s = 0.0;  ///< the same, summed over the subdomains [s]
  double softness_s = 0.0;           ///< the subdomains' softness (feti/softness.hpp), wall [s]
  double operator_s = 0.0;           ///< the torn rows, G, h and e [s]
  long n_products = 0;               ///< products with F (filled after the solve)
  double products_s = 0.0;           ///< their subdomain solves on this process, wall [s]
  double sums_s = 0.0;               ///< their exchanges with other processes (§8.8), wall [s]
  long n_coarse_solves = 0;          ///< solves with G G^T (filled after the solve)
  double coarse_s = 0.0;             ///< their wall time and that of G G^T's decompositions [s]
  long qp_iterations = 0;            ///< MPGP steps over all QPs (filled after the solve)
  long smalse_outer_iterations = 0;  ///< SMALSE-M's outer steps over all QPs
  /// The certificate's check of the gluing and Dirichlet rows: the root mean square of their
  /// violation relative to that of the displacement, and its bound (100 qp_rtol).
  double gluing_residual = 0.0;
  double gluing_bound = 0.0;
  /// Why the contact search's free displacement (the gluing alone, theory.md §8.7) did not
  /// converge; empty when it did, or was not solved.
  std::string free_displacement_note;
  /// Peak resident memory at the end [MiB], the largest over the processes.
  double peak_memory_mib = 0.0;
  int n_ranks = 1;               ///< processes (MPI ranks) that share the subdomains
  std::vector<RankShare> ranks;  ///< per process, in rank order
};

}  // namespace fricon::feti

FRICON_ENUM_NAMES(fricon::feti::FetiPreconditioner, "solver.tfeti_preconditioner",
                  {feti::FetiPreconditioner::None, "none"},
                  {feti::FetiPreconditioner::Lumped, "lumped"},
                  {feti::FetiPreconditioner::Dirichlet, "dirichlet"});

FRICON_ENUM_NAMES(fricon::feti::RowScaling, "solver.tfeti_scaling",
                  {feti::RowScaling::Stiffness, "stiffness"},
                  {feti::RowScaling::Uniform, "uniform"});
