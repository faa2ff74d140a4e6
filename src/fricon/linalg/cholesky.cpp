#include "fricon/linalg/cholesky.hpp"

#include <algorithm>

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
  factorize(K, {});
}

void CholeskyFactor::factorize(const SparseMatrix& K, const std::vector<Index>& last) {
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

  trailing_order_.clear();
  if (last.empty()) {
    c->nmethods = 0;  // CHOLMOD's default strategy (AMD, METIS when it pays)
    c->postorder = 1;
    impl_->L = cholmod_l_analyze(&A, c);
  } else {
    // The dofs that are not constrained are ordered by METIS nested dissection on their own
    // block K11 (the fill-reducing ordering CHOLMOD prefers for these meshes); the constrained
    // dofs follow. CAMD with constraint sets was measured at twice the fill on the paper's brick.
    const Index n = info_.n;
    std::vector<bool> is_last(static_cast<size_t>(n), false);
    for (Index k : last) {
      FRICON_CHECK(k >= 0 && k < n, "constrained dof " << k << " out of range " << n);
      is_last[static_cast<size_t>(k)] = true;
    }
    std::vector<SuiteSparse_long> first, position(static_cast<size_t>(n), -1);
    for (Index k = 0; k < n; ++k)
      if (!is_last[static_cast<size_t>(k)]) {
        position[static_cast<size_t>(k)] = static_cast<SuiteSparse_long>(first.size());
        first.push_back(k);
      }
    std::vector<SuiteSparse_long> perm;
    perm.reserve(static_cast<size_t>(n));
    if (!first.empty()) {
      // K11 in compressed columns (lower and upper parts as stored in K).
      std::vector<SuiteSparse_long> p11{0}, i11;
      std::vector<Real> x11;
      for (SuiteSparse_long j : first) {
        for (SparseIndex q = K.outerIndexPtr()[j]; q < K.outerIndexPtr()[j + 1]; ++q) {
          const SuiteSparse_long r = position[static_cast<size_t>(K.innerIndexPtr()[q])];
          if (r < 0) continue;
          i11.push_back(r);
          x11.push_back(K.valuePtr()[q]);
        }
        p11.push_back(static_cast<SuiteSparse_long>(i11.size()));
      }
      cholmod_sparse A11 = A;
      A11.nrow = A11.ncol = first.size();
      A11.nzmax = i11.size();
      A11.p = p11.data();
      A11.i = i11.data();
      A11.x = x11.data();
      std::vector<SuiteSparse_long> perm11(first.size());
      if (!cholmod_l_metis(&A11, nullptr, 0, 1, perm11.data(), c))
        throw NumericalError(fmt::format("METIS ordering of K failed (CHOLMOD status {}, n = {})",
                                         c->status, first.size()));
      for (SuiteSparse_long k : perm11)
        perm.push_back(first[static_cast<size_t>(k)]);
    }
    perm.insert(perm.end(), last.begin(), last.end());
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    c->postorder = 0;
    impl_->L = cholmod_l_analyze_p(&A, perm.data(), nullptr, 0, c);
    c->nmethods = 0;
    c->postorder = 1;
    if (impl_->L) {
      const auto* P = static_cast<const SuiteSparse_long*>(impl_->L->Perm);
      const Index m = static_cast<Index>(last.size());
      trailing_order_.assign(P + (n - m), P + n);
      std::vector<Index> a = trailing_order_, b = last;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      FRICON_CHECK(a == b, "the constrained ordering did not put the " << m << " dofs last");
    }
  }
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

MatrixXd CholeskyFactor::trailing_factor() const {
  FRICON_CHECK(impl_->L && !trailing_order_.empty(), "no trailing block: use factorize(K, last)");
  const cholmod_factor* L = impl_->L;
  FRICON_CHECK(L->is_super, "the factor is not supernodal");
  const Index n = info_.n, m = static_cast<Index>(trailing_order_.size()), first = n - m;
  const auto* super = static_cast<const SuiteSparse_long*>(L->super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L->pi);
  const auto* px = static_cast<const SuiteSparse_long*>(L->px);
  const auto* rows = static_cast<const SuiteSparse_long*>(L->s);
  const auto* x = static_cast<const Real*>(L->x);
  MatrixXd L22 = MatrixXd::Zero(m, m);
  for (size_t sn = 0; sn < L->nsuper; ++sn) {
    const Index k1 = super[sn], k2 = super[sn + 1];
    if (k2 <= first) continue;
    const Index nsrow = pi[sn + 1] - pi[sn];
    for (Index jj = 0; jj < k2 - k1; ++jj) {
      const Index col = k1 + jj;
      if (col < first) continue;
      // Column col of the supernode: rows rows[pi + ii], values x[px + ii + jj nsrow], ii >= jj.
      for (Index ii = jj; ii < nsrow; ++ii)
        L22(rows[pi[sn] + ii] - first, col - first) = x[px[sn] + ii + jj * nsrow];
    }
  }
  return L22;
}

CholeskyFactor::ForwardSolution CholeskyFactor::forward_solve(const SparseMatrix& B) const {
  FRICON_CHECK(impl_->L && impl_->L->is_super, "forward_solve needs a supernodal factor");
  FRICON_CHECK(B.rows() == info_.n, "B has " << B.rows() << " rows, K has " << info_.n);
  const cholmod_factor* L = impl_->L;
  const Index n = info_.n;
  const auto nsuper = static_cast<Index>(L->nsuper);
  const auto* perm = static_cast<const SuiteSparse_long*>(L->Perm);
  const auto* super = static_cast<const SuiteSparse_long*>(L->super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L->pi);
  const auto* px = static_cast<const SuiteSparse_long*>(L->px);
  const auto* ls = static_cast<const SuiteSparse_long*>(L->s);
  const auto* lx = static_cast<const Real*>(L->x);

  std::vector<Index> pinv(static_cast<size_t>(n)), super_of(static_cast<size_t>(n));
  for (Index k = 0; k < n; ++k)
    pinv[static_cast<size_t>(perm[k])] = k;
  for (Index sn = 0; sn < nsuper; ++sn)
    for (Index k = super[sn]; k < super[sn + 1]; ++k)
      super_of[static_cast<size_t>(k)] = sn;

  // Supernodes reached: those holding a non-zero of P B, and every supernode they update.
  std::vector<char> touched(static_cast<size_t>(nsuper), 0);
  for (Index j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      touched[static_cast<size_t>(
          super_of[static_cast<size_t>(pinv[static_cast<size_t>(it.row())])])] = 1;
  for (Index sn = 0; sn < nsuper; ++sn) {
    if (!touched[static_cast<size_t>(sn)]) continue;
    const Index ncol = super[sn + 1] - super[sn];
    for (Index q = pi[sn] + ncol; q < pi[sn + 1]; ++q)
      touched[static_cast<size_t>(super_of[static_cast<size_t>(ls[q])])] = 1;
  }
  ForwardSolution out;
  std::vector<Index> compact(static_cast<size_t>(n), -1);
  for (Index sn = 0; sn < nsuper; ++sn)
    if (touched[static_cast<size_t>(sn)])
      for (Index k = super[sn]; k < super[sn + 1]; ++k) {
        compact[static_cast<size_t>(k)] = static_cast<Index>(out.rows.size());
        out.rows.push_back(k);
      }
  MatrixXd& X = out.Y;
  X = MatrixXd::Zero(static_cast<Index>(out.rows.size()), B.cols());
  for (Index j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      X(compact[static_cast<size_t>(pinv[static_cast<size_t>(it.row())])], j) += it.value();

  // Supernodal forward substitution over the reached supernodes: diagonal block solve, then the
  // update of the rows below, scattered through `compact`.
  MatrixXd update;
  for (Index sn = 0; sn < nsuper; ++sn) {
    if (!touched[static_cast<size_t>(sn)]) continue;
    const Index k1 = super[sn], ncol = super[sn + 1] - k1, nrow = pi[sn + 1] - pi[sn];
    const Eigen::Map<const MatrixXd> Ls(lx + px[sn], nrow, ncol);
    auto X1 = X.middleRows(compact[static_cast<size_t>(k1)], ncol);
    Ls.topRows(ncol).triangularView<Eigen::Lower>().solveInPlace(X1);
    if (nrow == ncol) continue;
    update.noalias() = Ls.bottomRows(nrow - ncol) * X1;
    for (Index i = 0; i < nrow - ncol; ++i)
      X.row(compact[static_cast<size_t>(ls[pi[sn] + ncol + i])]) -= update.row(i);
  }
  n_solves_ += B.cols();
  return out;
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
