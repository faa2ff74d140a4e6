#pragma once
// linalg: the few dense kernels fricon needs at full speed, handed to the BLAS CHOLMOD is linked
// to (OpenBLAS, multithreaded). Eigen's own kernels run on one core without the machine's vector
// extensions; on the dense blocks of the dual operator OpenBLAS is several times faster.
// Blocks are Eigen column-major views, so sub-blocks of larger matrices can be passed in place.

#include "fricon/core/types.hpp"

namespace fricon::linalg {

using ConstBlockRef = Eigen::Ref<const MatrixXd, 0, Eigen::OuterStride<>>;
using BlockRef = Eigen::Ref<MatrixXd, 0, Eigen::OuterStride<>>;

/// Sets the number of threads of the BLAS (OpenBLAS), for every later call in the process,
/// including CHOLMOD's. n >= 1. By default OpenBLAS uses one thread per core (or the environment
/// variable OPENBLAS_NUM_THREADS): the fastest on an idle machine, but its threads wait by
/// spinning, and next to other busy processes that costs several times the work
/// (docs/benchmarks.md): there one thread is the better choice.
void set_threads(int n);
/// The number of threads the BLAS uses.
int threads();

/// Threads for the machine's present load: the cores not taken by other processes' runnable tasks
/// (the instantaneous count of /proc/loadavg less this process's runnable threads, the smallest
/// of a few samples 2 ms apart), at least 1 and at most the number of cores. On a busy
/// machine this is 1, where spinning BLAS threads would steal time from the working one.
int threads_for_load();

/// The threads of a run: `requested` if > 0, else those of OPENBLAS_NUM_THREADS as OpenBLAS read
/// it when that variable is set, else threads_for_load(). Sets them (set_threads).
void choose_threads(int requested);

/// The BLAS threads of one run, held for the run's lifetime, for callers that may run several
/// solves at once (fricon.solve from Python threads, docs/python.md). OpenBLAS has one thread count
/// for the whole process (Debian 12's 0.3.21 has no count per calling thread), and changing it
/// while another thread is inside a BLAS call races with that call. So only the first of
/// overlapping runs sets it: constructing a RunThreads while no other exists calls
/// choose_threads(requested); while one exists, a new run shares the count in force, whatever it
/// requested (count() says which). Thread-safe.
class RunThreads {
 public:
  /// requested: as choose_threads (> 0: that many; else OPENBLAS_NUM_THREADS or the load's).
  explicit RunThreads(int requested);
  ~RunThreads();
  RunThreads(const RunThreads&) = delete;
  RunThreads& operator=(const RunThreads&) = delete;

  /// The BLAS threads of this run (threads() once it was set up).
  int count() const { return count_; }
  /// Whether this run set the count (no other run held one), rather than sharing it.
  bool chose() const { return chose_; }

 private:
  int count_ = 1;
  bool chose_ = false;
};

/// The BLAS threads as they were at construction, set again at destruction (a run that changes
/// them for its own phases gives them back).
class KeepThreads {
 public:
  KeepThreads() : count_(threads()) {}
  ~KeepThreads() { set_threads(count_); }
  KeepThreads(const KeepThreads&) = delete;
  KeepThreads& operator=(const KeepThreads&) = delete;

 private:
  int count_;
};

/// X <- L^-1 X, or L^-T X when `transpose`. L is square and lower triangular (its strict upper
/// part is not read), X has L.rows() rows.
void solve_lower(ConstBlockRef L, BlockRef X, bool transpose = false);

/// C <- C - op(A) B, op(A) = A (k = A.cols()) or A^T when `transpose_a` (k = A.rows()); op(A) is
/// m x k, B k x n, C m x n.
void subtract_product(ConstBlockRef A, ConstBlockRef B, BlockRef C, bool transpose_a = false);

/// y = A x for a symmetric A of which only the lower triangle is read (BLAS dsymv: it reads half
/// of A, which is what a product with a large dense A costs).
void symmetric_product(const MatrixXd& A, const VectorXd& x, VectorXd& y);

/// y = A x for a general dense A (BLAS dgemv); y is resized to A.rows().
void product(const MatrixXd& A, const VectorXd& x, VectorXd& y);

/// Lower triangle of C <- lower triangle of C + Y^T Y, with Y m x k and C k x k. The strict upper
/// part of C is not touched.
void add_gram_lower(ConstBlockRef Y, BlockRef C);

}  // namespace fricon::linalg
