#include "fricon/parallel/mpi/mumps_factor.hpp"

#include <dmumps_c.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

namespace {

// The MUMPS job codes and control parameters used here (MUMPS 5.5 users' guide §5-6).
constexpr MUMPS_INT kJobInit = -1, kJobEnd = -2, kJobAnalyse = 1, kJobFactorize = 2, kJobSolve = 3;
constexpr MUMPS_INT kSymmetricDefinite = 1, kSymmetricGeneral = 2;
// ICNTL(14): percentage of extra workspace; doubled when a factorization runs short.
constexpr MUMPS_INT kWorkspaceRelaxation = 30;
constexpr int kFactorizationAttempts = 4;

int& icntl(DMUMPS_STRUC_C& id, int k) {
  return id.icntl[k - 1];
}
int infog(const DMUMPS_STRUC_C& id, int k) {
  return id.infog[k - 1];
}

// INFOG(k) that counts entries: negative values are millions.
double count(const DMUMPS_STRUC_C& id, int k) {
  const int v = infog(id, k);
  return v >= 0 ? static_cast<double>(v) : -1e6 * static_cast<double>(v);
}

// MUMPS counts memory in MB of 10^6 bytes (INFO(15), INFO(16), ICNTL(23)); fricon reports MiB.
constexpr double kMibPerMumpsMb = 1.0e6 / (1024.0 * 1024.0);

bool workspace_too_small(int code) {
  return code == -8 || code == -9 || code == -14 || code == -15 || (code <= -17 && code >= -20);
}

std::string meaning(int code) {
  if (code == -10) return "the matrix is numerically singular (K not positive definite?)";
  if (code == -5 || code == -7 || code == -13)
    return "not enough memory on a rank (use more ranks, or ranks with more memory)";
  if (workspace_too_small(code)) return "the workspace was too small";
  return "see the MUMPS users' guide, section 8";
}

std::string ordering_name(int code) {
  switch (code) {
    case 0:
      return "AMD (MUMPS)";
    case 1:
      return "given";
    case 2:
      return "AMF (MUMPS)";
    case 3:
      return "SCOTCH (MUMPS)";
    case 4:
      return "PORD (MUMPS)";
    case 5:
      return "METIS (MUMPS)";
    case 6:
      return "QAMD (MUMPS)";
    default:
      return fmt::format("MUMPS ordering {}", code);
  }
}

void check_phase(const DMUMPS_STRUC_C& id, const char* phase) {
  if (infog(id, 1) >= 0) return;
  throw AgreedError<NumericalError>(fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}: {}",
                                                phase, infog(id, 1), infog(id, 2),
                                                meaning(infog(id, 1))));
}

// Before the numerical factorization: the analysis's estimate of the largest rank's memory
// against the limit. INFOG is global, so every rank throws the same error.
void check_estimate(const DMUMPS_STRUC_C& id, const MemoryLimit& limit) {
  const double largest_mib = infog(id, 16) * kMibPerMumpsMb;
  if (limit.mib <= 0.0 || largest_mib <= limit.mib) return;
  throw AgreedError<NumericalError>(fmt::format(
      "{}: {}: MUMPS's analysis estimates {:.1f} MiB for the factorization on its largest rank, "
      "more than the limit of {:.1f} MiB per rank; run on more ranks (the memory per rank falls "
      "with them, docs/parallel.md) or raise the limit",
      limit.where, limit.key, largest_mib, limit.mib));
}

}  // namespace

struct MumpsFactor::Impl {
  DMUMPS_STRUC_C id{};
  std::vector<MUMPS_INT> schur_vars;
  std::vector<MUMPS_INT> perm_in;  // position (from 1) of each variable in the given order
  void call(MUMPS_INT job) {
    id.job = job;
    dmumps_c(&id);
  }

  // An instance on comm for a matrix of order n, silent, with distributed entries.
  void initialize(MPI_Comm comm, Index n, bool indefinite) {
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id.par = 1;  // rank 0 works too
    id.sym = indefinite ? kSymmetricGeneral : kSymmetricDefinite;
    call(kJobInit);
    check_phase(id, "initialisation");
    icntl(id, 1) = icntl(id, 2) = icntl(id, 3) = -1;  // no messages
    icntl(id, 4) = 0;
    icntl(id, 7) = 7;  // ordering: MUMPS's automatic choice
    icntl(id, 14) = kWorkspaceRelaxation;
    icntl(id, 18) = 3;  // distributed entries: each rank gives its own
    icntl(id, 28) = 1;  // sequential analysis (Debian's MUMPS has no parallel ordering tool)
    id.n = static_cast<MUMPS_INT>(n);
  }

  // This rank's entries, counted from 1 as MUMPS does (they must live until released).
  void give_entries(LocalEntries& entries) {
    for (int& r : entries.rows)
      ++r;
    for (int& c : entries.cols)
      ++c;
    id.nnz_loc = static_cast<MUMPS_INT8>(entries.size());
    id.irn_loc = entries.rows.data();
    id.jcn_loc = entries.cols.data();
    id.a_loc = entries.values.data();
  }
  void release_entries() {
    id.irn_loc = id.jcn_loc = nullptr;
    id.a_loc = nullptr;
  }

  // What rank 0 allocates for MUMPS before its first call, so that a failure here can be agreed
  // on (collectively): the dense S (n_schur x n_schur, the last n_schur of the variables being
  // the Schur variables) and their list, and PERM_IN from `order` (the elimination order of the
  // first n_free variables, the others following; empty: MUMPS chooses).
  void prepare(const std::vector<Index>& order, Index n_free, Index n_schur, int rank,
               MatrixXd& schur) {
    if (rank != 0) return;
    schur_vars.resize(static_cast<std::size_t>(n_schur));
    for (Index k = 0; k < n_schur; ++k)
      schur_vars[static_cast<std::size_t>(k)] = static_cast<MUMPS_INT>(n_free + k + 1);
    if (n_schur > 0) schur.setZero(n_schur, n_schur);
    if (order.empty()) return;
    FRICON_CHECK(static_cast<Index>(order.size()) == n_free,
                 "order of " << order.size() << " variables, expected " << n_free);
    const Index n = n_free + n_schur;
    perm_in.assign(static_cast<std::size_t>(n), 0);
    for (std::size_t k = 0; k < order.size(); ++k)
      perm_in[static_cast<std::size_t>(order[k])] = static_cast<MUMPS_INT>(k + 1);
    for (Index k = n_free; k < n; ++k)
      perm_in[static_cast<std::size_t>(k)] = static_cast<MUMPS_INT>(k + 1);
  }

  // The last n_schur of the n variables as Schur variables, S centralized into `schur` (rank 0,
  // allocated by prepare()).
  void request_schur(Index n_schur, int rank, MatrixXd& schur) {
    icntl(id, 19) = 1;
    id.size_schur = static_cast<MUMPS_INT>(n_schur);
    if (rank != 0) return;
    id.listvar_schur = schur_vars.data();
    id.schur = schur.data();
  }

  // Rank 0's order from prepare(), if any (rank 0 decides whether there is one). Returns
  // whether an order was given.
  bool give_order(int rank, MPI_Comm comm) {
    int given = rank == 0 && !perm_in.empty();
    MPI_Bcast(&given, 1, MPI_INT, 0, comm);
    if (!given) return false;
    icntl(id, 7) = 1;  // the order given in PERM_IN (on rank 0)
    if (rank == 0) id.perm_in = perm_in.data();
    return true;
  }

  // The numerical factorization, within `limit` (ICNTL(23)); the workspace is enlarged and the
  // factorization repeated when it runs short.
  void factorize(const MemoryLimit& limit) {
    if (limit.mib > 0.0)
      icntl(id, 23) = std::max(1, static_cast<int>(std::floor(limit.mib / kMibPerMumpsMb)));
    for (int attempt = 1;; ++attempt) {
      call(kJobFactorize);
      if (!workspace_too_small(infog(id, 1)) || attempt == kFactorizationAttempts) break;
      icntl(id, 14) *= 2;
    }
    if (limit.mib > 0.0 && workspace_too_small(infog(id, 1)))
      throw AgreedError<NumericalError>(fmt::format(
          "{}: {}: the MUMPS factorization needs more than the limit of {:.0f} MiB per rank "
          "(INFOG(1) = {}, INFOG(2) = {}); run on more ranks or raise the limit",
          limit.where, limit.key, limit.mib, infog(id, 1), infog(id, 2)));
    check_phase(id, "factorization");
  }
};

namespace {

// MUMPS returns one triangle of the symmetric S; both, in place.
void complete_symmetric(MatrixXd& S) {
  const bool lower = S.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().isZero(0.0);
  const MatrixXd T = lower ? MatrixXd(S.triangularView<Eigen::Lower>())
                           : MatrixXd(S.triangularView<Eigen::Upper>());
  S = T + T.transpose();
  S.diagonal() = T.diagonal();
}

}  // namespace

MumpsFactor::MumpsFactor(MPI_Comm comm, Index n_free, Index n_schur, LocalEntries entries,
                         const std::vector<Index>& order, const MemoryLimit& limit)
    : comm_(comm), n_free_(n_free) {
  MPI_Comm_rank(comm_, &rank_);
  // A failure of one rank alone is agreed on before MUMPS's first call (what rank 0 allocates
  // for it); between MUMPS's calls, which are collective, MUMPS's own failures are seen by every
  // rank (INFOG is global: each releases MUMPS and throws them, Agreed), and any other ends the
  // job (docs/parallel.md, "When a rank fails").
  collectively(
      [&] {
        test_fault("analysis");
        impl_ = std::make_unique<Impl>();
        impl_->prepare(order, n_free, n_schur, rank_, schur_);
      },
      comm_);
  Impl& m = *impl_;
  or_abort([&] { m.initialize(comm_, n_free + n_schur, n_schur > 0); }, comm_);
  try {
    m.give_entries(entries);
    if (n_schur > 0) m.request_schur(n_schur, rank_, schur_);
    const bool given_order = m.give_order(rank_, comm_);
    const Stopwatch analysis;
    m.call(kJobAnalyse);
    check_phase(m.id, "analysis");
    const double analysis_s = analysis.seconds();
    check_estimate(m.id, limit);
    test_fault("factorize");
    const Stopwatch factorization;
    m.factorize(limit);
    double given = static_cast<double>(entries.size());
    MPI_Allreduce(MPI_IN_PLACE, &given, 1, MPI_DOUBLE, MPI_SUM, comm_);
    info_ = {m.id.n,
             n_schur,
             given,
             count(m.id, 29),
             m.id.rinfog[2],
             given_order ? "nested dissection of the node graph (given to MUMPS)"
                         : ordering_name(infog(m.id, 7)),
             m.id.info[15] * kMibPerMumpsMb,
             m.id.info[14] * kMibPerMumpsMb,
             infog(m.id, 16) * kMibPerMumpsMb,
             analysis_s,
             factorization.seconds()};
    // The entries are no longer needed (no iterative refinement): free them now.
    m.release_entries();
    entries = LocalEntries{};
    m.id.schur = nullptr;
    // Rank 0 alone completes S (its temporaries are two more n_schur^2 matrices): agreed.
    collectively(
        [&] {
          test_fault("schur");
          if (n_schur > 0 && rank_ == 0) complete_symmetric(schur_);
        },
        comm_);
  } catch (...) {
    abort_unless_agreed(comm_);
    m.call(kJobEnd);
    throw;
  }
}

MumpsFactor::~MumpsFactor() {
  impl_->call(kJobEnd);
}

MatrixXd MumpsFactor::solve_distributed(const std::vector<Index>& rows, MatrixXd rhs,
                                        int n_rhs) const {
  DMUMPS_STRUC_C& id = impl_->id;
  FRICON_CHECK(rhs.rows() == static_cast<Index>(rows.size()) && rhs.cols() == n_rhs,
               "solve_distributed: right-hand sides " << rhs.rows() << " x " << rhs.cols()
                                                      << ", expected " << rows.size() << " x "
                                                      << n_rhs);
  // A rank that gives no rows still passes allocated arrays (MUMPS checks that they exist).
  std::vector<MUMPS_INT> given(std::max<std::size_t>(rows.size(), 1), 1);
  for (std::size_t k = 0; k < rows.size(); ++k)
    given[k] = static_cast<MUMPS_INT>(rows[k] + 1);
  if (rhs.size() == 0) rhs.setZero(1, n_rhs);
  const int n_mine = id.info[22];  // INFO(23): pivots of this rank
  MatrixXd solution(std::max(n_mine, 1), n_rhs);
  std::vector<MUMPS_INT> solution_rows(static_cast<std::size_t>(std::max(n_mine, 1)));
  id.icntl[25] = 0;   // ICNTL(26) = 0: with Schur variables, solve the interior problem (K)
  id.icntl[19] = 10;  // ICNTL(20) = 10: dense right-hand sides, distributed by rows
  id.icntl[20] = 1;   // ICNTL(21) = 1: solution distributed as MUMPS holds its pivots
  id.nrhs = n_rhs;
  id.nloc_rhs = static_cast<MUMPS_INT>(rows.size());
  id.lrhs_loc = std::max<MUMPS_INT>(id.nloc_rhs, 1);
  id.irhs_loc = given.data();
  id.rhs_loc = rhs.data();
  id.lsol_loc = std::max(n_mine, 1);
  id.sol_loc = solution.data();
  id.isol_loc = solution_rows.data();
  impl_->call(kJobSolve);
  id.irhs_loc = id.isol_loc = nullptr;
  id.rhs_loc = id.sol_loc = nullptr;
  check_phase(id, "solve");
  // Of the Schur variables (the multipliers) only the free dofs are kept.
  std::vector<Index> keep;
  solution_rows_.clear();
  for (int k = 0; k < n_mine; ++k)
    if (const Index row = solution_rows[static_cast<std::size_t>(k)] - 1; row < n_free_) {
      keep.push_back(k);
      solution_rows_.push_back(row);
    }
  return solution(keep, Eigen::all);
}

}  // namespace fricon::parallel
