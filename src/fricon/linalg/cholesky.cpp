#include "fricon/linalg/cholesky.hpp"

#include <algorithm>
#include <mutex>
#include <optional>

#include <cholmod.h>
#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/shared_random.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::linalg {

static_assert(sizeof(SuiteSparse_long) == sizeof(SparseIndex),
              "SparseIndex must match CHOLMOD's long integer");

namespace {

// The supernodal structure of a CHOLMOD factor, read in place: supernode s holds the pivot
// columns super[s] .. super[s+1]-1; its column block is nrow x ncol at x + px[s] (column-major),
// with the pivot row indices rows[pi[s]] .. rows[pi[s+1]-1] (the first ncol are its own).
struct Supernodes {
  Index n = 0, count = 0;
  const SuiteSparse_long *perm, *super, *pi, *px, *rows;
  const Real* x;
  std::vector<Index> pinv;      // dof -> pivot
  std::vector<Index> super_of;  // pivot -> supernode
  std::vector<Index> parent;    // supernode -> parent supernode, -1 at a root

  explicit Supernodes(const cholmod_factor* L)
      : n(static_cast<Index>(L->n)),
        count(static_cast<Index>(L->nsuper)),
        perm(static_cast<const SuiteSparse_long*>(L->Perm)),
        super(static_cast<const SuiteSparse_long*>(L->super)),
        pi(static_cast<const SuiteSparse_long*>(L->pi)),
        px(static_cast<const SuiteSparse_long*>(L->px)),
        rows(static_cast<const SuiteSparse_long*>(L->s)),
        x(static_cast<const Real*>(L->x)),
        pinv(static_cast<size_t>(n)),
        super_of(static_cast<size_t>(n)),
        parent(static_cast<size_t>(count), -1) {
    for (Index k = 0; k < n; ++k)
      pinv[static_cast<size_t>(perm[k])] = k;
    for (Index s = 0; s < count; ++s)
      for (Index k = super[s]; k < super[s + 1]; ++k)
        super_of[static_cast<size_t>(k)] = s;
    for (Index s = 0; s < count; ++s)
      if (nrow(s) > ncol(s)) parent[static_cast<size_t>(s)] = super_of[idx(rows[pi[s] + ncol(s)])];
  }
  static size_t idx(Index i) { return static_cast<size_t>(i); }
  Index ncol(Index s) const { return super[s + 1] - super[s]; }
  Index nrow(Index s) const { return pi[s + 1] - pi[s]; }
  Eigen::Map<const MatrixXd> block(Index s) const {
    return Eigen::Map<const MatrixXd>(x + px[s], nrow(s), ncol(s));
  }
  Index supernode_of_dof(Index dof) const { return super_of[idx(pinv[idx(dof)])]; }
};

}  // namespace

struct CholeskyFactor::Impl {
  cholmod_common common{};
  cholmod_factor* L = nullptr;
  std::optional<Supernodes> supernodes;  // of L, when it is supernodal
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
// Columns per block of the backward sweep of inverse_gram_and_rows: enough for the BLAS's level 3,
// few enough that a block of the reached rows stays small (reach rows x 128 x 8 bytes).
constexpr Index kBackwardBlockColumns = 128;

// A symmetric sparsity pattern in compressed columns, both triangles stored.
struct Pattern {
  SuiteSparse_long n = 0;
  const SuiteSparse_long* p = nullptr;
  const SuiteSparse_long* i = nullptr;
};

// Fill-reducing ordering of a symmetric pattern through its compressed graph. Consecutive
// columns with identical patterns (the displacement components of one mesh node) are merged into
// one vertex; the quotient graph, a third the size with a ninth of the edges for 3D elasticity, is
// ordered by CHOLMOD's nested dissection (METIS bisection, CAMD on the leaves), and every vertex
// is expanded back into its columns. Returns the permutation (new position -> column).
std::vector<SuiteSparse_long> compressed_nested_dissection(const Pattern& a, cholmod_common* c) {
  const SuiteSparse_long n = a.n;
  auto same_pattern = [&a](SuiteSparse_long j, SuiteSparse_long k) {
    return a.p[j + 1] - a.p[j] == a.p[k + 1] - a.p[k] &&
           std::equal(a.i + a.p[j], a.i + a.p[j + 1], a.i + a.p[k]);
  };
  // Supervariables: first column of each, and the supervariable of each column.
  std::vector<SuiteSparse_long> first, of(static_cast<size_t>(n));
  for (SuiteSparse_long j = 0; j < n; ++j) {
    if (j == 0 || !same_pattern(j, j - 1)) first.push_back(j);
    of[static_cast<size_t>(j)] = static_cast<SuiteSparse_long>(first.size()) - 1;
  }
  const auto nv = static_cast<SuiteSparse_long>(first.size());
  first.push_back(n);
  // The quotient graph: vertex v is adjacent to the supervariables of its first column's rows.
  std::vector<SuiteSparse_long> gp{0}, gi;
  gp.reserve(static_cast<size_t>(nv) + 1);
  for (SuiteSparse_long v = 0; v < nv; ++v) {
    const SuiteSparse_long j = first[static_cast<size_t>(v)];
    for (SuiteSparse_long q = a.p[j]; q < a.p[j + 1]; ++q)
      if (of[static_cast<size_t>(a.i[q])] != v) gi.push_back(of[static_cast<size_t>(a.i[q])]);
    std::sort(gi.begin() + gp.back(), gi.end());
    gi.erase(std::unique(gi.begin() + gp.back(), gi.end()), gi.end());
    gp.push_back(static_cast<SuiteSparse_long>(gi.size()));
  }
  cholmod_sparse G{};
  G.nrow = G.ncol = static_cast<size_t>(nv);
  G.nzmax = gi.size();
  G.p = gp.data();
  G.i = gi.data();
  G.stype = -1;  // symmetric; CHOLMOD reads the lower triangle
  G.itype = CHOLMOD_LONG;
  G.xtype = CHOLMOD_PATTERN;
  G.dtype = CHOLMOD_DOUBLE;
  G.sorted = 1;
  G.packed = 1;
  std::vector<SuiteSparse_long> order(static_cast<size_t>(nv)), cparent(static_cast<size_t>(nv)),
      cmember(static_cast<size_t>(nv));
  // METIS seeds and draws from the C library's random sequence (core/shared_random.hpp).
  std::unique_lock random_lock(shared_random_mutex());
  const SuiteSparse_long n_components =
      nv > 0 ? cholmod_l_nested_dissection(&G, nullptr, 0, order.data(), cparent.data(),
                                           cmember.data(), c)
             : 0;
  random_lock.unlock();
  if (n_components < 0)
    throw NumericalError(fmt::format(
        "nested dissection ordering of K failed (CHOLMOD status {}, {} vertices)", c->status, nv));
  std::vector<SuiteSparse_long> perm;
  perm.reserve(static_cast<size_t>(n));
  for (SuiteSparse_long v : order)
    for (SuiteSparse_long j = first[static_cast<size_t>(v)]; j < first[static_cast<size_t>(v) + 1];
         ++j)
      perm.push_back(j);
  return perm;
}

// K as CHOLMOD reads it (a view: no copy), symmetric with its lower triangle used.
cholmod_sparse cholmod_view(const SparseMatrix& K) {
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(K.rows());
  A.nzmax = static_cast<size_t>(K.nonZeros());
  A.p = const_cast<SparseIndex*>(K.outerIndexPtr());
  A.i = const_cast<SparseIndex*>(K.innerIndexPtr());
  A.x = const_cast<Real*>(K.valuePtr());
  A.stype = -1;
  A.itype = CHOLMOD_LONG;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

// The fill-reducing ordering given to CHOLMOD: nested dissection of the compressed graph of K
// (it did fewer flops and took less time than CHOLMOD's default, AMD then METIS on the scalar
// graph, when compared on the paper's brick). With `last`, the other dofs are ordered so on
// their own block K11 and the constrained dofs follow; CAMD with constraint sets was measured at
// twice the fill on the paper's brick.
std::vector<SuiteSparse_long> fill_reducing_order(const SparseMatrix& K,
                                                  const std::vector<Index>& last,
                                                  cholmod_common* c) {
  const Index n = K.rows();
  if (last.empty())
    return compressed_nested_dissection({n, K.outerIndexPtr(), K.innerIndexPtr()}, c);
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
    // The pattern of K11 in compressed columns (both triangles, as stored in K).
    std::vector<SuiteSparse_long> p11{0}, i11;
    for (SuiteSparse_long j : first) {
      for (SparseIndex q = K.outerIndexPtr()[j]; q < K.outerIndexPtr()[j + 1]; ++q) {
        const SuiteSparse_long r = position[static_cast<size_t>(K.innerIndexPtr()[q])];
        if (r >= 0) i11.push_back(r);
      }
      p11.push_back(static_cast<SuiteSparse_long>(i11.size()));
    }
    for (SuiteSparse_long k : compressed_nested_dissection(
             {static_cast<SuiteSparse_long>(first.size()), p11.data(), i11.data()}, c))
      perm.push_back(first[static_cast<size_t>(k)]);
  }
  perm.insert(perm.end(), last.begin(), last.end());
  return perm;
}

// Whether the factor's order ends with the dofs `last`.
bool trailing_is_last(const cholmod_factor* L, const std::vector<Index>& last) {
  const auto* P = static_cast<const SuiteSparse_long*>(L->Perm);
  const Index n = static_cast<Index>(L->n), m = static_cast<Index>(last.size());
  std::vector<Index> trailing(P + (n - m), P + n), sorted_last = last;
  std::sort(trailing.begin(), trailing.end());
  std::sort(sorted_last.begin(), sorted_last.end());
  return trailing == sorted_last;
}

// The dofs of the trailing block in pivot order: the constrained dofs, last (checked).
std::vector<Index> trailing_dofs(const cholmod_factor* L, const std::vector<Index>& last) {
  const auto* P = static_cast<const SuiteSparse_long*>(L->Perm);
  const Index n = static_cast<Index>(L->n), m = static_cast<Index>(last.size());
  std::vector<Index> trailing(P + (n - m), P + n);
  std::vector<Index> sorted_trailing = trailing, sorted_last = last;
  std::sort(sorted_trailing.begin(), sorted_trailing.end());
  std::sort(sorted_last.begin(), sorted_last.end());
  FRICON_CHECK(sorted_trailing == sorted_last,
               "the constrained ordering did not put the " << m << " dofs last");
  return trailing;
}

}  // namespace

void CholeskyFactor::factorize(const SparseMatrix& K) {
  factorize(K, {});
}

void CholeskyFactor::factorize(const SparseMatrix& K, const std::vector<Index>& last) {
  FRICON_CHECK(K.rows() == K.cols(), "K is " << K.rows() << " x " << K.cols());
  FRICON_CHECK(K.isCompressed(), "K must be compressed");
  cholmod_common* c = &impl_->common;
  impl_->supernodes.reset();
  if (impl_->L) cholmod_l_free_factor(&impl_->L, c);
  info_ = CholeskyInfo{};
  info_.n = K.rows();
  info_.nnz_K = K.nonZeros();
  cholmod_sparse A = cholmod_view(K);

  // @sect: symbolic analysis with the given ordering.
  std::vector<SuiteSparse_long> perm = fill_reducing_order(K, last, c);
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_GIVEN;
  c->postorder = 1;
  impl_->L = cholmod_l_analyze_p(&A, perm.data(), nullptr, 0, c);
  // Postordering keeps a connected trailing block last (it is the root chain of the elimination
  // tree), but not one spread over several bodies, whose trees it visits one after the other:
  // then the given order is kept as it is.
  if (impl_->L && !last.empty() && !trailing_is_last(impl_->L, last)) {
    cholmod_l_free_factor(&impl_->L, c);
    c->postorder = 0;
    impl_->L = cholmod_l_analyze_p(&A, perm.data(), nullptr, 0, c);
    c->postorder = 1;
  }
  c->nmethods = 0;
  if (!impl_->L || c->status < CHOLMOD_OK)
    throw NumericalError(
        fmt::format("Cholesky analysis of K failed (CHOLMOD status {}, n = {}, nnz = {})",
                    c->status, info_.n, info_.nnz_K));
  trailing_order_ = last.empty() ? std::vector<Index>{} : trailing_dofs(impl_->L, last);

  // @sect: numerical factorization, and the checks that K was positive definite.
  cholmod_l_factorize(&A, impl_->L, c);
  if (c->status == CHOLMOD_NOT_POSDEF)
    throw NumericalError(fmt::format(
        "the stiffness matrix K (n = {}, nnz = {}) is not positive definite: the Cholesky "
        "factorization broke down at column {} of the permuted matrix",
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
        "condition estimate {:.2e}): it is not positive definite",
        info_.n, info_.nnz_K, info_.rcond));
  info_.nnz_L = c->lnz;
  info_.blas_threads = threads();
  info_.flops = c->fl;
  info_.supernodal = impl_->L->is_super != 0;
  info_.ordering = last.empty() ? "nested dissection of the node graph"
                                : "nested dissection, constrained dofs last";
  if (info_.supernodal) impl_->supernodes.emplace(impl_->L);
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

// What the forward sweep of inverse_gram leaves when asked to keep it: per supernode, the
// columns of B it carries (sorted) and its rows of Y = L^-1 P B on those columns.
struct CholeskyFactor::KeptForward {
  std::vector<std::vector<Index>> cols;
  std::vector<MatrixXd> Y;
};

MatrixXd CholeskyFactor::inverse_gram(const SparseMatrix& B,
                                      const std::function<void()>& poll) const {
  return forward_gram(B, poll, nullptr);
}

MatrixXd CholeskyFactor::forward_gram(const SparseMatrix& B, const std::function<void()>& poll,
                                      KeptForward* kept) const {
  FRICON_CHECK(impl_->supernodes, "inverse_gram needs a supernodal factor");
  FRICON_CHECK(B.rows() == info_.n, "B has " << B.rows() << " rows, K has " << info_.n);
  const Supernodes& sn = *impl_->supernodes;
  const Index k = B.cols();
  auto at = [](auto& v, Index i) -> auto& {
    return v[static_cast<size_t>(i)];
  };

  // Columns of B carried by each supernode: those with a non-zero in it, and all its children's.
  // Supernodes are numbered children first, so one ascending pass closes the sets.
  std::vector<std::vector<Index>> cols(static_cast<size_t>(sn.count));
  for (Index j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      at(cols, sn.supernode_of_dof(it.row())).push_back(j);
  for (Index s = 0; s < sn.count; ++s) {
    auto& c = at(cols, s);
    if (c.empty()) continue;
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    const Index p = at(sn.parent, s);
    if (p >= 0) at(cols, p).insert(at(cols, p).end(), c.begin(), c.end());
  }
  // Position of column j in a sorted column set (j must be in it).
  auto position = [](const std::vector<Index>& c, Index j) {
    return static_cast<Index>(std::lower_bound(c.begin(), c.end(), j) - c.begin());
  };

  // Y restricted to supernode s and its columns: ncol(s) x cols[s].size(), created on first use.
  std::vector<MatrixXd> Y(static_cast<size_t>(sn.count));
  auto block_of = [&](Index s) -> MatrixXd& {
    MatrixXd& y = at(Y, s);
    if (y.size() == 0) y = MatrixXd::Zero(sn.ncol(s), static_cast<Index>(at(cols, s).size()));
    return y;
  };
  for (Index j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it) {
      const Index pivot = at(sn.pinv, it.row()), s = at(sn.super_of, pivot);
      block_of(s)(pivot - sn.super[s], position(at(cols, s), j)) += it.value();
    }

  MatrixXd Q = MatrixXd::Zero(k, k);
  MatrixXd update, gram;
  std::vector<Index> map;
  for (Index s = 0; s < sn.count; ++s) {
    const std::vector<Index>& c = at(cols, s);
    if (c.empty()) continue;
    if (poll) poll();
    const Index ncol = sn.ncol(s), nbelow = sn.nrow(s) - ncol, nc = static_cast<Index>(c.size());
    const auto Ls = sn.block(s);
    MatrixXd& y = block_of(s);
    solve_lower(Ls.topRows(ncol), y);
    // This supernode's share of Y^T Y, into Q's lower triangle (c is sorted, so the lower
    // triangle of the small Gram matrix lands in Q's lower triangle).
    if (nc == k) {
      add_gram_lower(y, Q);
    } else {
      gram.setZero(nc, nc);
      add_gram_lower(y, gram);
      for (Index b = 0; b < nc; ++b)
        for (Index a = b; a < nc; ++a)
          Q(at(c, a), at(c, b)) += gram(a, b);
    }
    // The update of the rows below, -L(below, s) y, scattered into the ancestors' blocks.
    if (nbelow > 0) {
      update.setZero(nbelow, nc);
      subtract_product(Ls.bottomRows(nbelow), y, update);
      for (Index i = 0; i < nbelow;) {
        const Index t = at(sn.super_of, sn.rows[sn.pi[s] + ncol + i]);
        Index i_end = i;
        while (i_end < nbelow && at(sn.super_of, sn.rows[sn.pi[s] + ncol + i_end]) == t)
          ++i_end;
        const std::vector<Index>& ct = at(cols, t);
        map.resize(static_cast<size_t>(nc));
        auto from = ct.begin();
        for (Index a = 0; a < nc; ++a) {
          from = std::lower_bound(from, ct.end(), at(c, a));
          at(map, a) = static_cast<Index>(from - ct.begin());
        }
        MatrixXd& yt = block_of(t);
        for (Index a = 0; a < nc; ++a) {
          const Index col = at(map, a);
          for (Index r = i; r < i_end; ++r)
            yt(sn.rows[sn.pi[s] + ncol + r] - sn.super[t], col) += update(r, a);
        }
        i = i_end;
      }
    }
    if (!kept) at(Y, s) = MatrixXd();  // done with this supernode's rows of Y
  }
  n_solves_ += k;
  if (kept) *kept = {std::move(cols), std::move(Y)};
  return Q.selfadjointView<Eigen::Lower>();
}

CholeskyFactor::GramAndRows CholeskyFactor::inverse_gram_and_rows(
    const SparseMatrix& B, const Reach& reach, const std::vector<Index>& rows,
    const std::function<void()>& poll) const {
  KeptForward forward;
  GramAndRows out;
  out.gram = forward_gram(B, poll, &forward);
  const Supernodes& sn = *impl_->supernodes;
  auto at = [](auto& v, Index i) -> auto& {
    return v[static_cast<size_t>(i)];
  };
  // Compact rows: pivot p of the reach is row at(place, p) of a block (-1 off the reach); the
  // pivots of a supernode are consecutive, the first at at(place, super[s]).
  std::vector<Index> place(static_cast<size_t>(sn.n), -1);
  for (size_t i = 0; i < reach.rows.size(); ++i)
    at(place, reach.rows[i]) = static_cast<Index>(i);
  for (Index s = 0; s < sn.count; ++s)
    FRICON_CHECK(at(forward.cols, s).empty() || at(place, sn.super[s]) >= 0,
                 "inverse_gram_and_rows: B has a non-zero off the reach (supernode " << s << ")");
  std::vector<Index> out_rows;
  for (Index dof : rows) {
    const Index i = at(place, at(sn.pinv, dof));
    FRICON_CHECK(i >= 0, "inverse_gram_and_rows: row dof " << dof << " is off the reach");
    out_rows.push_back(i);
  }

  const Index n_reach = static_cast<Index>(reach.rows.size()), k = B.cols();
  out.rows.resize(static_cast<Index>(rows.size()), k);
  MatrixXd Z, below;
  for (Index first = 0; first < k; first += kBackwardBlockColumns) {
    const Index m = std::min(kBackwardBlockColumns, k - first);
    // Z = Y on the block's columns, then L^T Z = Z over the reach, supernodes descending: each
    // gathers its ancestors' rows.
    Z.setZero(n_reach, m);
    for (Index s : reach.supernodes) {
      const std::vector<Index>& c = at(forward.cols, s);
      const Index z0 = at(place, sn.super[s]);
      for (auto a = std::lower_bound(c.begin(), c.end(), first); a != c.end() && *a < first + m;
           ++a)
        Z.col(*a - first).segment(z0, sn.ncol(s)) = at(forward.Y, s).col(a - c.begin());
    }
    for (auto it = reach.supernodes.rbegin(); it != reach.supernodes.rend(); ++it) {
      if (poll) poll();
      const Index s = *it, ncol = sn.ncol(s), nbelow = sn.nrow(s) - ncol,
                  z0 = at(place, sn.super[s]);
      const auto Ls = sn.block(s);
      auto Zs = Z.middleRows(z0, ncol);
      if (nbelow > 0) {
        below.resize(nbelow, m);
        for (Index i = 0; i < nbelow; ++i)
          below.row(i) = Z.row(at(place, sn.rows[sn.pi[s] + ncol + i]));
        subtract_product(Ls.bottomRows(nbelow), below, Zs, /*transpose_a=*/true);
      }
      solve_lower(Ls.topRows(ncol), Zs, /*transpose=*/true);
    }
    for (size_t r = 0; r < out_rows.size(); ++r)
      out.rows.block(static_cast<Index>(r), first, 1, m) = Z.row(out_rows[r]);
  }
  return out;
}

CholeskyFactor::Reach CholeskyFactor::reach(const std::vector<Index>& dofs) const {
  FRICON_CHECK(impl_->supernodes, "reach needs a supernodal factor");
  const Supernodes& sn = *impl_->supernodes;
  std::vector<char> on(static_cast<size_t>(sn.count), 0);
  for (Index d : dofs) {
    FRICON_CHECK(d >= 0 && d < sn.n, "dof " << d << " out of range " << sn.n);
    on[static_cast<size_t>(sn.supernode_of_dof(d))] = 1;
  }
  Reach r;
  for (Index s = 0; s < sn.count; ++s) {
    if (!on[static_cast<size_t>(s)]) continue;
    r.supernodes.push_back(s);
    for (Index k = sn.super[s]; k < sn.super[s + 1]; ++k)
      r.rows.push_back(k);
    const Index p = sn.parent[static_cast<size_t>(s)];
    if (p >= 0) on[static_cast<size_t>(p)] = 1;
  }
  return r;
}

void CholeskyFactor::solve_on_reach(const Reach& reach, VectorXd& x) const {
  reach_solve(reach, x, /*everywhere=*/false);
}

void CholeskyFactor::solve_from_reach(const Reach& reach, VectorXd& x) const {
  reach_solve(reach, x, /*everywhere=*/true);
}

void CholeskyFactor::reach_solve(const Reach& reach, VectorXd& x, bool everywhere) const {
  FRICON_CHECK(impl_->supernodes, "a solve from the reach needs a supernodal factor");
  FRICON_CHECK(x.size() == info_.n, "x has " << x.size() << " entries, K has " << info_.n);
  const Supernodes& sn = *impl_->supernodes;
  VectorXd z = VectorXd::Zero(sn.n), below;
  for (Index k : reach.rows)
    z(k) = x(sn.perm[k]);
  // L z = P x over the reach: its supernodes in ascending order, updates into their ancestors
  // (off the reach z stays zero).
  for (Index s : reach.supernodes) {
    const Index k1 = sn.super[s], ncol = sn.ncol(s), nbelow = sn.nrow(s) - ncol;
    const auto Ls = sn.block(s);
    auto zs = z.segment(k1, ncol);
    solve_lower(Ls.topRows(ncol), zs);
    if (nbelow == 0) continue;
    below.setZero(nbelow);
    subtract_product(Ls.bottomRows(nbelow), zs, below);  // below = -L(below, s) z_s
    for (Index i = 0; i < nbelow; ++i)
      z(sn.rows[sn.pi[s] + ncol + i]) += below(i);
  }
  // L^T z = z, in descending order: each supernode needs only its ancestors, all on the reach
  // when the reach is closed upwards; everywhere: every supernode.
  auto backward = [&](Index s) {
    const Index k1 = sn.super[s], ncol = sn.ncol(s), nbelow = sn.nrow(s) - ncol;
    const auto Ls = sn.block(s);
    auto zs = z.segment(k1, ncol);
    if (nbelow > 0) {
      below.resize(nbelow);
      for (Index i = 0; i < nbelow; ++i)
        below(i) = z(sn.rows[sn.pi[s] + ncol + i]);
      subtract_product(Ls.bottomRows(nbelow), below, zs, /*transpose_a=*/true);
    }
    solve_lower(Ls.topRows(ncol), zs, /*transpose=*/true);
  };
  if (everywhere) {
    for (Index s = sn.count - 1; s >= 0; --s)
      backward(s);
    for (Index k = 0; k < sn.n; ++k)
      x(sn.perm[k]) = z(k);
  } else {
    for (auto it = reach.supernodes.rbegin(); it != reach.supernodes.rend(); ++it)
      backward(*it);
    x.setZero();
    for (Index k : reach.rows)
      x(sn.perm[k]) = z(k);
  }
  ++n_solves_;
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

namespace fricon::linalg {

std::vector<Index> nested_dissection(const std::vector<SparseIndex>& start,
                                     const std::vector<SparseIndex>& adjacent) {
  FRICON_CHECK(!start.empty() && start.back() == static_cast<SparseIndex>(adjacent.size()),
               "nested_dissection: inconsistent graph arrays");
  const auto n = static_cast<SuiteSparse_long>(start.size() - 1);
  cholmod_common common{};
  cholmod_l_start(&common);
  common.print = 0;
  common.error_handler = nullptr;
  std::vector<SuiteSparse_long> order;
  try {
    order =
        compressed_nested_dissection({n, reinterpret_cast<const SuiteSparse_long*>(start.data()),
                                      reinterpret_cast<const SuiteSparse_long*>(adjacent.data())},
                                     &common);
  } catch (...) {
    cholmod_l_finish(&common);
    throw;
  }
  cholmod_l_finish(&common);
  return {order.begin(), order.end()};
}

}  // namespace fricon::linalg
