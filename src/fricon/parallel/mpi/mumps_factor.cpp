#include "fricon/parallel/mpi/mumps_factor.hpp"

#include <dmumps_c.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"

namespace fricon::parallel {

namespace {

// The MUMPS job codes and control parameters used here (MUMPS 5.5 users' guide §5-6).
constexpr MUMPS_INT kJobInit = -1, kJobEnd = -2, kJobAnalyse = 1, kJobFactorize = 2, kJobSolve = 3;
constexpr MUMPS_INT kSymmetricDefinite = 1, kSymmetricGeneral = 2;
// ICNTL(14): percentage of extra workspace; doubled when a factorization runs short.
constexpr MUMPS_INT kWorkspaceRelaxation = 30;
constexpr int kFactorizationAttempts = 4;

// The commands rank 0 sends the ranks waiting in serve().
enum Command : int { kSolve = 1, kFinish = 2, kFail = 3 };

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
  throw NumericalError(fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}: {}", phase,
                                   infog(id, 1), infog(id, 2), meaning(infog(id, 1))));
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
};

MumpsFactor::MumpsFactor(MPI_Comm comm, Index n_free, Index n_schur, LocalEntries entries,
                         const std::vector<Index>& order)
    : impl_(std::make_unique<Impl>()), comm_(comm), n_free_(n_free) {
  MPI_Comm_rank(comm_, &rank_);
  DMUMPS_STRUC_C& id = impl_->id;
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm_));
  id.par = 1;  // rank 0 works too
  id.sym = n_schur > 0 ? kSymmetricGeneral : kSymmetricDefinite;
  impl_->call(kJobInit);
  check_phase(id, "initialisation");
  icntl(id, 1) = icntl(id, 2) = icntl(id, 3) = -1;  // no messages
  icntl(id, 4) = 0;
  icntl(id, 7) = 7;  // ordering: MUMPS's automatic choice
  icntl(id, 14) = kWorkspaceRelaxation;
  icntl(id, 18) = 3;  // distributed entries: each rank gives its own
  icntl(id, 28) = 1;  // sequential analysis (Debian's MUMPS has no parallel ordering tool)
  const Index n = n_free + n_schur;
  id.n = static_cast<MUMPS_INT>(n);
  for (int& r : entries.rows)
    ++r;  // MUMPS counts from 1
  for (int& c : entries.cols)
    ++c;
  id.nnz_loc = static_cast<MUMPS_INT8>(entries.size());
  id.irn_loc = entries.rows.data();
  id.jcn_loc = entries.cols.data();
  id.a_loc = entries.values.data();
  if (n_schur > 0) {
    icntl(id, 19) = 1;  // Schur complement, centralized on rank 0
    id.size_schur = static_cast<MUMPS_INT>(n_schur);
    if (rank_ == 0) {
      impl_->schur_vars.resize(static_cast<std::size_t>(n_schur));
      for (Index k = 0; k < n_schur; ++k)
        impl_->schur_vars[static_cast<std::size_t>(k)] = static_cast<MUMPS_INT>(n_free + k + 1);
      id.listvar_schur = impl_->schur_vars.data();
      schur_.setZero(n_schur, n_schur);
      id.schur = schur_.data();
    }
  }
  int given_order = rank_ == 0 && !order.empty();
  MPI_Bcast(&given_order, 1, MPI_INT, 0, comm_);
  if (given_order) {
    icntl(id, 7) = 1;  // the order given in PERM_IN (on rank 0)
    if (rank_ == 0) {
      FRICON_CHECK(static_cast<Index>(order.size()) == n_free,
                   "order of " << order.size() << " variables, expected " << n_free);
      impl_->perm_in.assign(static_cast<std::size_t>(n), 0);
      for (std::size_t k = 0; k < order.size(); ++k)
        impl_->perm_in[static_cast<std::size_t>(order[k])] = static_cast<MUMPS_INT>(k + 1);
      for (Index k = n_free; k < n; ++k)
        impl_->perm_in[static_cast<std::size_t>(k)] = static_cast<MUMPS_INT>(k + 1);
      id.perm_in = impl_->perm_in.data();
    }
  }
  const Stopwatch analysis;
  impl_->call(kJobAnalyse);
  check_phase(id, "analysis");
  const double analysis_s = analysis.seconds();
  const Stopwatch factorization;
  for (int attempt = 1;; ++attempt) {
    impl_->call(kJobFactorize);
    if (!workspace_too_small(infog(id, 1)) || attempt == kFactorizationAttempts) break;
    icntl(id, 14) *= 2;
  }
  check_phase(id, "factorization");
  double given = static_cast<double>(entries.size());
  MPI_Allreduce(MPI_IN_PLACE, &given, 1, MPI_DOUBLE, MPI_SUM, comm_);
  info_ = {n,
           n_schur,
           given,
           count(id, 29),
           id.rinfog[2],
           given_order ? "nested dissection of the node graph (given to MUMPS)"
                       : ordering_name(infog(id, 7)),
           static_cast<double>(id.info[15]),
           analysis_s,
           factorization.seconds()};
  // The entries are no longer needed (no iterative refinement): free them now.
  id.irn_loc = id.jcn_loc = nullptr;
  id.a_loc = nullptr;
  entries = LocalEntries{};
  if (n_schur > 0 && rank_ == 0) {
    // MUMPS returns one triangle of the symmetric S; complete it.
    const bool lower = schur_.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().isZero(0.0);
    const MatrixXd T = lower ? MatrixXd(schur_.triangularView<Eigen::Lower>())
                             : MatrixXd(schur_.triangularView<Eigen::Upper>());
    schur_ = T + T.transpose();
    schur_.diagonal() = T.diagonal();
  }
  id.schur = nullptr;
}

MumpsFactor::~MumpsFactor() {
  impl_->call(kJobEnd);
}

void MumpsFactor::run_solve(int n_rhs, double* rhs) const {
  DMUMPS_STRUC_C& id = impl_->id;
  id.icntl[25] = 0;  // ICNTL(26) = 0: with Schur variables, solve the interior problem (K)
  id.icntl[19] = 0;  // ICNTL(20) = 0: dense right-hand sides on rank 0
  id.icntl[20] = 0;  // ICNTL(21) = 0: solution on rank 0
  id.nrhs = n_rhs;
  id.lrhs = id.n;
  id.rhs = rhs;
  impl_->call(kJobSolve);
}

MatrixXd MumpsFactor::solve(const Eigen::Ref<const MatrixXd>& b) const {
  FRICON_CHECK(rank_ == 0, "MumpsFactor::solve is called by rank 0");
  FRICON_CHECK(b.rows() == n_free_, "solve: " << b.rows() << " rows, expected " << n_free_);
  const int n_rhs = static_cast<int>(b.cols());
  send_command(kSolve, n_rhs);
  // The right-hand sides over all n variables (MUMPS ignores the Schur variables' entries).
  MatrixXd rhs = MatrixXd::Zero(impl_->id.n, b.cols());
  rhs.topRows(n_free_) = b;
  run_solve(n_rhs, rhs.data());
  check_phase(impl_->id, "solve");
  rhs.conservativeResize(n_free_, Eigen::NoChange);
  return rhs;
}

VectorXd MumpsFactor::solve(const VectorXd& b) const {
  return solve(Eigen::Ref<const MatrixXd>(b)).col(0);
}

namespace {

// Waits for rank 0's next command without spinning: a blocking MPI_Bcast busy-polls a core,
// which rank 0's QP and BLAS threads need while the other ranks only wait (rank 0 may work
// for minutes between two solves). Polling every kIdlePoll adds that much latency per command.
constexpr auto kIdlePoll = std::chrono::microseconds(200);

void receive_command(int (&command)[2], MPI_Comm comm) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(command, 2, MPI_INT, 0, comm, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(kIdlePoll);
  }
}

}  // namespace

int MumpsFactor::serve() const {
  FRICON_CHECK(rank_ != 0, "MumpsFactor::serve is called by the ranks other than 0");
  for (;;) {
    int command[2] = {0, 0};
    receive_command(command, comm_);
    switch (command[0]) {
      case kSolve:
        // A failure shows on every rank; rank 0 reports it and ends the serve with fail().
        run_solve(command[1], nullptr);
        break;
      case kFinish:
        return command[1];
      case kFail: {
        ErrorPacket error;
        broadcast(error, 0, comm_);
        raise(error);
      }
      default:
        throw Error(fmt::format("MumpsFactor::serve: unknown command {}", command[0]));
    }
  }
}

void MumpsFactor::send_command(int command, int argument) const {
  int message[2] = {command, argument};
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(message, 2, MPI_INT, 0, comm_, &request);
  MPI_Wait(&request, MPI_STATUS_IGNORE);
}

void MumpsFactor::finish(int status) const {
  send_command(kFinish, status);
}

void MumpsFactor::fail(const ErrorPacket& error) const {
  send_command(kFail, 0);
  ErrorPacket copy = error;
  broadcast(copy, 0, comm_);
}

}  // namespace fricon::parallel
