#include "fricon/linalg/blas.hpp"

#include <algorithm>
#include <limits>

#include "fricon/core/error.hpp"

// The reference BLAS interface (Fortran calling convention, 32-bit integers as in Debian's
// OpenBLAS), declared here rather than through a CBLAS header whose path depends on the BLAS
// variant installed.
extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc);
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

void solve_lower(ConstBlockRef L, BlockRef X, bool transpose) {
  FRICON_CHECK(L.rows() == L.cols() && X.rows() == L.rows(),
               "L " << L.rows() << " x " << L.cols() << ", X " << X.rows() << " rows");
  if (X.size() == 0) return;
  const int m = blas_int(X.rows()), n = blas_int(X.cols());
  const int lda = leading(L.outerStride(), L.rows()), ldb = leading(X.outerStride(), X.rows());
  const double one = 1.0;
  dtrsm_("L", "L", transpose ? "T" : "N", "N", &m, &n, &one, L.data(), &lda, X.data(), &ldb);
}

void subtract_product(ConstBlockRef A, ConstBlockRef B, BlockRef C) {
  FRICON_CHECK(A.cols() == B.rows() && C.rows() == A.rows() && C.cols() == B.cols(),
               "shapes " << A.rows() << "x" << A.cols() << ", " << B.rows() << "x" << B.cols()
                         << ", " << C.rows() << "x" << C.cols());
  if (C.size() == 0 || A.cols() == 0) return;
  const int m = blas_int(C.rows()), n = blas_int(C.cols()), k = blas_int(A.cols());
  const int lda = leading(A.outerStride(), A.rows()), ldb = leading(B.outerStride(), B.rows()),
            ldc = leading(C.outerStride(), C.rows());
  const double minus_one = -1.0, one = 1.0;
  dgemm_("N", "N", &m, &n, &k, &minus_one, A.data(), &lda, B.data(), &ldb, &one, C.data(), &ldc);
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
