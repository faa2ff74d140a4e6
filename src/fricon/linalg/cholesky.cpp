#include "fricon/linalg/cholesky.hpp"

#include <cholmod.h>
#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::linalg {

static_assert(sizeof(SuiteSparse_long) == sizeof(SparseIndex),
              "SparseIndex must match CHOLMOD's long integer");

struct CholeskyFactor::Impl {
  cholmod_common common{};
  cholmod_factor* L = nullptr;
  Impl() {
    cholmod_l_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    if (L) cholmod_l_free_factor(&L, &common);
    cholmod_l_finish(&common);
  }
};

CholeskyFactor::CholeskyFactor() : impl_(std::make_unique<Impl>()) {}
CholeskyFactor::~CholeskyFactor() = default;
CholeskyFactor::CholeskyFactor(CholeskyFactor&&) noexcept = default;
CholeskyFactor& CholeskyFactor::operator=(CholeskyFactor&&) noexcept = default;

namespace {
// Below this reciprocal condition estimate K is treated as singular. Well-posed elasticity
// matrices of a million unknowns stay above 1e-10.
constexpr double kSingularRcond = 1e-13;

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL:
      return "natural";
    case CHOLMOD_GIVEN:
      return "given";
    case CHOLMOD_AMD:
      return "AMD";
    case CHOLMOD_METIS:
      return "METIS";
    case CHOLMOD_NESDIS:
      return "NESDIS";
    case CHOLMOD_COLAMD:
      return "COLAMD";
    case CHOLMOD_POSTORDERED:
      return "postordered";
    default:
      return "unknown";
  }
}
}  // namespace

void CholeskyFactor::factorize(const SparseMatrix& K) {
  FRICON_CHECK(K.rows() == K.cols(), "K is " << K.rows() << " x " << K.cols());
  FRICON_CHECK(K.isCompressed(), "K must be compressed");
  cholmod_common* c = &impl_->common;
  if (impl_->L) cholmod_l_free_factor(&impl_->L, c);
  info_ = CholeskyInfo{};
  info_.n = K.rows();
  info_.nnz_K = K.nonZeros();

  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(K.rows());
  A.nzmax = static_cast<size_t>(K.nonZeros());
  A.p = const_cast<SparseIndex*>(K.outerIndexPtr());
  A.i = const_cast<SparseIndex*>(K.innerIndexPtr());
  A.x = const_cast<Real*>(K.valuePtr());
  A.stype = -1;  // symmetric, lower triangle used
  A.itype = CHOLMOD_LONG;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;

  impl_->L = cholmod_l_analyze(&A, c);
  if (!impl_->L || c->status < CHOLMOD_OK)
    throw NumericalError(
        fmt::format("Cholesky analysis of K failed (CHOLMOD status {}, n = {}, nnz = {})",
                    c->status, info_.n, info_.nnz_K));
  cholmod_l_factorize(&A, impl_->L, c);
  if (c->status == CHOLMOD_NOT_POSDEF)
    throw NumericalError(fmt::format(
        "the stiffness matrix K (n = {}, nnz = {}) is not positive definite: the Cholesky "
        "factorization broke down at column {} of the permuted matrix. Is the body clamped "
        "(a [[dirichlet]] boundary that removes all rigid motions)?",
        info_.n, info_.nnz_K, impl_->L->minor));
  if (c->status < CHOLMOD_OK)
    throw NumericalError(fmt::format(
        "Cholesky factorization of K failed (CHOLMOD status {}, n = {}, nnz = {}): out of memory?",
        c->status, info_.n, info_.nnz_K));
  // A singular K (a free body) often factorizes in floating point with tiny pivots instead of
  // failing; CHOLMOD's reciprocal condition estimate (min/max diagonal of L, squared) exposes it.
  info_.rcond = cholmod_l_rcond(impl_->L, c);
  if (!(info_.rcond > kSingularRcond))
    throw NumericalError(fmt::format(
        "the stiffness matrix K (n = {}, nnz = {}) is singular to working precision (reciprocal "
        "condition estimate {:.2e}): it is not positive definite. Is the body clamped (a "
        "[[dirichlet]] boundary that removes all rigid motions)?",
        info_.n, info_.nnz_K, info_.rcond));
  info_.nnz_L = c->lnz;
  info_.flops = c->fl;
  info_.supernodal = impl_->L->is_super != 0;
  info_.ordering = ordering_name(impl_->L->ordering);
}

MatrixXd CholeskyFactor::solve(const MatrixXd& B) const {
  FRICON_CHECK(impl_->L, "solve() before factorize()");
  FRICON_CHECK(B.rows() == info_.n,
               "right-hand side has " << B.rows() << " rows, K has " << info_.n);
  cholmod_common* c = &impl_->common;
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(B.rows());
  b.ncol = static_cast<size_t>(B.cols());
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<Real*>(B.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, impl_->L, &b, c);
  if (!x || c->status < CHOLMOD_OK) {
    if (x) cholmod_l_free_dense(&x, c);
    throw NumericalError(
        fmt::format("Cholesky solve failed (CHOLMOD status {}, n = {})", c->status, info_.n));
  }
  MatrixXd X = Eigen::Map<const MatrixXd>(static_cast<const Real*>(x->x), B.rows(), B.cols());
  cholmod_l_free_dense(&x, c);
  n_solves_ += B.cols();
  return X;
}

VectorXd CholeskyFactor::solve(const VectorXd& b) const {
  return solve(MatrixXd(Eigen::Map<const MatrixXd>(b.data(), b.size(), 1))).col(0);
}

}  // namespace fricon::linalg
