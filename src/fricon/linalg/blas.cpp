#include "fricon/linalg/blas.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

#include "fricon/core/error.hpp"

// The reference BLAS interface (Fortran calling convention, 32-bit integers as in Debian's
// OpenBLAS) and OpenBLAS's thread control, declared here rather than through a CBLAS header whose
// path depends on the BLAS variant installed.
extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a,
            const int* lda, double* x, const int* incx);
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a,
            const int* lda, const double* x, const int* incx, const double* beta, double* y,
            const int* incy);
void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy);
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* beta, double* c, const int* ldc);
}

namespace fricon::linalg {

namespace {
int blas_int(Index v) {
  FRICON_CHECK(v >= 0 && v <= std::numeric_limits<int>::max(),
               "dimension " << v << " does not fit the BLAS 32-bit integers");
  return static_cast<int>(v);
}
// Leading dimension: at least 1 even for empty blocks, as the BLAS requires.
int leading(Index stride, Index rows) {
  return blas_int(std::max<Index>({stride, rows, 1}));
}
}  // namespace

void set_threads(int n) {
  FRICON_CHECK(n >= 1, "the BLAS needs at least one thread, got " << n);
  openblas_set_num_threads(n);
}

int threads() {
  return openblas_get_num_threads();
}

namespace {
// The runnable tasks of the machine now, from the fourth field of /proc/loadavg
// ("0.52 0.58 0.59 3/312 4711": runnable/total); -1 if unreadable.
int runnable_tasks() {
  std::ifstream in("/proc/loadavg");
  double avg1 = 0, avg5 = 0, avg15 = 0;
  std::string tasks;
  if (!(in >> avg1 >> avg5 >> avg15 >> tasks)) return -1;
  int runnable = 0;
  const auto [end, ec] = std::from_chars(tasks.data(), tasks.data() + tasks.size(), runnable);
  return ec == std::errc{} ? runnable : -1;
}

// The threads of this process that are runnable now (state R in /proc/self/task/*/stat): this
// one and OpenBLAS's workers, which spin for a while after they start.
int own_runnable_threads() {
  int n = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream in(task.path() / "stat");
    std::string line;
    if (!std::getline(in, line)) continue;
    const auto close = line.rfind(')');  // "pid (comm) S ...": the state follows the name
    if (close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'R') ++n;
  }
  return std::max(n, 1);
}

// Samples of the count of other runnable tasks, the smallest kept: a kernel thread or a shell
// that is runnable for an instant must not count as a busy core.
constexpr int kLoadSamples = 5;
constexpr auto kLoadSampleInterval = std::chrono::milliseconds(2);
}  // namespace

int threads_for_load() {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  int others = cores;
  for (int k = 0; k < kLoadSamples && others > 0; ++k) {
    if (k > 0) std::this_thread::sleep_for(kLoadSampleInterval);
    const int runnable = runnable_tasks();
    if (runnable < 0) return cores;
    others = std::min(others, std::max(0, runnable - own_runnable_threads()));
  }
  return std::clamp(cores - others, 1, cores);
}

void choose_threads(int requested) {
  if (requested > 0) {
    set_threads(requested);
  } else if (std::getenv("OPENBLAS_NUM_THREADS") == nullptr) {
    set_threads(threads_for_load());
  }
}

namespace {
// The runs that hold a RunThreads, guarded by run_threads_mutex().
int active_runs = 0;
std::mutex& run_threads_mutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

RunThreads::RunThreads(int requested) {
  const std::lock_guard lock(run_threads_mutex());
  if (active_runs == 0) {
    choose_threads(requested);
    chose_ = true;
  }
  ++active_runs;
  count_ = threads();
}

RunThreads::~RunThreads() {
  const std::lock_guard lock(run_threads_mutex());
  --active_runs;
}

void solve_lower(ConstBlockRef L, BlockRef X, bool transpose) {
  FRICON_CHECK(L.rows() == L.cols() && X.rows() == L.rows(),
               "L " << L.rows() << " x " << L.cols() << ", X " << X.rows() << " rows");
  if (X.size() == 0) return;
  const int m = blas_int(X.rows()), n = blas_int(X.cols());
  const int lda = leading(L.outerStride(), L.rows()), ldb = leading(X.outerStride(), X.rows());
  const double one = 1.0;
  // One column: the level-2 routine (the level-3 one packs its operands, and may wake threads,
  // for what is a single pass over L).
  if (n == 1) {
    const int inc = 1;
    dtrsv_("L", transpose ? "T" : "N", "N", &m, L.data(), &lda, X.data(), &inc);
    return;
  }
  dtrsm_("L", "L", transpose ? "T" : "N", "N", &m, &n, &one, L.data(), &lda, X.data(), &ldb);
}

void subtract_product(ConstBlockRef A, ConstBlockRef B, BlockRef C, bool transpose_a) {
  const Index m = transpose_a ? A.cols() : A.rows(), k = transpose_a ? A.rows() : A.cols();
  FRICON_CHECK(k == B.rows() && C.rows() == m && C.cols() == B.cols(),
               "shapes " << A.rows() << "x" << A.cols() << (transpose_a ? "^T, " : ", ") << B.rows()
                         << "x" << B.cols() << ", " << C.rows() << "x" << C.cols());
  if (C.size() == 0 || k == 0) return;
  const int mi = blas_int(m), n = blas_int(C.cols()), ki = blas_int(k);
  const int lda = leading(A.outerStride(), A.rows()), ldb = leading(B.outerStride(), B.rows()),
            ldc = leading(C.outerStride(), C.rows());
  const double minus_one = -1.0, one = 1.0;
  if (n == 1) {  // one column: the level-2 routine, as in solve_lower
    const int rows = blas_int(A.rows()), cols = blas_int(A.cols()), inc = 1;
    dgemv_(transpose_a ? "T" : "N", &rows, &cols, &minus_one, A.data(), &lda, B.data(), &inc, &one,
           C.data(), &inc);
    return;
  }
  dgemm_(transpose_a ? "T" : "N", "N", &mi, &n, &ki, &minus_one, A.data(), &lda, B.data(), &ldb,
         &one, C.data(), &ldc);
}

void symmetric_product(const MatrixXd& A, const VectorXd& x, VectorXd& y) {
  FRICON_CHECK(A.rows() == A.cols() && x.size() == A.rows(),
               "A " << A.rows() << "x" << A.cols() << ", x " << x.size());
  y.resize(x.size());
  if (x.size() == 0) return;
  const int n = blas_int(x.size()), lda = leading(A.rows(), A.rows()), inc = 1;
  const double one = 1.0, zero = 0.0;
  dsymv_("L", &n, &one, A.data(), &lda, x.data(), &inc, &zero, y.data(), &inc);
}

void product(const MatrixXd& A, const VectorXd& x, VectorXd& y) {
  FRICON_CHECK(x.size() == A.cols(), "A " << A.rows() << "x" << A.cols() << ", x " << x.size());
  y.resize(A.rows());
  if (A.rows() == 0) return;
  if (A.cols() == 0) {
    y.setZero();
    return;
  }
  const int m = blas_int(A.rows()), n = blas_int(A.cols()), lda = leading(A.rows(), A.rows());
  const int inc = 1;
  const double one = 1.0, zero = 0.0;
  dgemv_("N", &m, &n, &one, A.data(), &lda, x.data(), &inc, &zero, y.data(), &inc);
}

void add_gram_lower(ConstBlockRef Y, BlockRef C) {
  FRICON_CHECK(C.rows() == C.cols() && C.rows() == Y.cols(),
               "Y " << Y.rows() << "x" << Y.cols() << ", C " << C.rows() << "x" << C.cols());
  if (C.size() == 0 || Y.rows() == 0) return;
  const int n = blas_int(Y.cols()), k = blas_int(Y.rows());
  const int lda = leading(Y.outerStride(), Y.rows()), ldc = leading(C.outerStride(), C.rows());
  const double one = 1.0;
  dsyrk_("L", "T", &n, &k, &one, Y.data(), &lda, &one, C.data(), &ldc);
}

}  // namespace fricon::linalg
