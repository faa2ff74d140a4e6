#include "fricon/feti/feti_operator.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "fricon/core/error.hpp"
#include "fricon/core/parallel_for.hpp"
#include "fricon/core/timer.hpp"

namespace fricon::feti {

namespace {

using Triplet = Eigen::Triplet<Real, SparseIndex>;

// x at the rows of a subdomain.
VectorXd gather(const VectorXd& x, const std::vector<Index>& rows) {
  VectorXd local(static_cast<Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k)
    local(static_cast<Index>(k)) = x(rows[k]);
  return local;
}

// y at the rows of a subdomain += local.
void scatter_add(const VectorXd& local, const std::vector<Index>& rows, VectorXd& y) {
  for (std::size_t k = 0; k < rows.size(); ++k)
    y(rows[k]) += local(static_cast<Index>(k));
}

// G = R^T B^T: six rows per subdomain, over the dual rows it touches.
SparseMatrix coarse_rows(const std::vector<Subdomain>& subdomains, Index n_dual) {
  std::vector<Triplet> entries;
  for (std::size_t i = 0; i < subdomains.size(); ++i) {
    const Subdomain& s = subdomains[i];
    const MatrixXd G_s = s.R.transpose() * s.B.transpose();  // 6 x rows
    for (Index k = 0; k < G_s.cols(); ++k)
      for (Index j = 0; j < kSubdomainMotions; ++j)
        if (G_s(j, k) != 0.0)
          entries.emplace_back(kSubdomainMotions * static_cast<Index>(i) + j,
                               s.rows[static_cast<size_t>(k)], G_s(j, k));
  }
  SparseMatrix G(kSubdomainMotions * static_cast<Index>(subdomains.size()), n_dual);
  G.setFromTriplets(entries.begin(), entries.end());
  G.makeCompressed();
  return G;
}

}  // namespace

// The QP's view of the operator's share of the rows (dual::DualShare).
class FetiOperator::Share final : public dual::DualShare {
 public:
  explicit Share(const FetiOperator& F) : F_(F) {}
  const qp::DualSpace& space() const override { return F_.space_; }
  Index size() const override { return F_.dual_rows_->n_local(); }
  Index n_contact() const override { return F_.dual_rows_->n_local_contact(); }
  VectorXd restrict(const VectorXd& whole) const override { return F_.dual_rows_->restrict(whole); }
  SparseMatrix restrict_columns(const SparseMatrix& G) const override {
    return F_.dual_rows_->restrict_columns(G);
  }
  VectorXd assemble(const VectorXd& part) const override { return F_.dual_rows_->assemble(part); }
  void apply(const VectorXd& x, VectorXd& y) const override { F_.apply_share(x, y); }
  qp::Operator equality_preconditioner() const override { return F_.equality_preconditioner(); }

 private:
  const FetiOperator& F_;
};

FetiOperator::~FetiOperator() = default;

FetiOperator::FetiOperator(std::vector<Subdomain> subdomains, TornRows rows,
                           const std::vector<Index>& owner_dof, const fe::DofMap& dofs, int threads,
                           const Ranks& ranks)
    : subdomains_(std::move(subdomains)),
      rows_(std::move(rows)),
      owner_dof_(owner_dof),
      threads_(std::max(threads, 1)),
      ranks_(&ranks),
      block_(ranks.block(static_cast<Index>(subdomains_.size()))),
      dual_rows_(std::make_unique<DualRows>(subdomains_, rows_, ranks)),
      space_(ranks),
      share_(std::make_unique<Share>(*this)) {
  torn_of_free_ = torn_of_free(owner_dof, dofs);
  partial_.assign(static_cast<size_t>(threads_), VectorXd());
  G_ = coarse_rows(subdomains_, rows_.n_rows());
  compute_load_terms();
}

void FetiOperator::set_load(const VectorXd& f, const VectorXd& offset, const VectorXd* u0,
                            const dual::NodalLoad& nodal) {
  (void)f;
  (void)u0;
  FRICON_CHECK(nodal.applied != nullptr && nodal.prescribed != nullptr,
               "FetiOperator::set_load needs the nodal load");
  FRICON_CHECK(offset.size() == rows_.n_contact,
               "set_load: an offset of " << offset.size() << " for " << rows_.n_contact);
  const Index n_nodes = static_cast<Index>(owner_dof_.size()) / 3;
  // Both fields on the owners' copies, over the torn dofs.
  VectorXd applied = VectorXd::Zero(rows_.B.cols()), prescribed = applied;
  for (Index a = 0; a < n_nodes; ++a)
    for (int c = 0; c < 3; ++c) {
      const Index dof = owner_dof_[static_cast<size_t>(3 * a + c)];
      applied(dof) = (*nodal.applied)(c, a);
      prescribed(dof) = (*nodal.prescribed)(c, a);
    }
  for (Subdomain& s : subdomains_)
    s.f = applied.segment(s.first_dof, s.n_dofs());
  // c = (offset, 0 on the gluing rows, the Dirichlet rows' scaled values B_D u_p).
  const Index first_dirichlet = rows_.n_contact + rows_.n_gluing;
  rows_.c.head(rows_.n_contact) = offset;
  rows_.c.tail(rows_.n_dirichlet) =
      rows_.B.middleRows(first_dirichlet, rows_.n_dirichlet) * prescribed;
  compute_load_terms();
}

void FetiOperator::set_contact_rows(const SparseMatrix& B_contact, const VectorXd& offset) {
  replace_contact_rows(rows_, torn_of_free_, B_contact, offset);
  attach_rows(rows_.B, subdomains_);
  dual_rows_ = std::make_unique<DualRows>(subdomains_, rows_, *ranks_);
  G_ = coarse_rows(subdomains_, rows_.n_rows());
  compute_h();
}

const dual::DualShare& FetiOperator::share() const {
  return *share_;
}

void FetiOperator::for_own_subdomains(
    const std::function<void(const Subdomain& s, Index i, int thread)>& body) const {
  const auto [first, last] = block_;
  parallel_for(last - first, threads_, [&](Index k, int thread) {
    body(subdomains_[static_cast<size_t>(first + k)], first + k, thread);
  });
}

void FetiOperator::compute_load_terms() {
  e_.resize(kSubdomainMotions * static_cast<Index>(subdomains_.size()));
  for (std::size_t i = 0; i < subdomains_.size(); ++i)
    e_.segment<kSubdomainMotions>(kSubdomainMotions * static_cast<Index>(i)) =
        subdomains_[i].R.transpose() * subdomains_[i].f;
  u0_torn_ = VectorXd::Zero(rows_.B.cols());
  for_own_subdomains([&](const Subdomain& s, Index, int) {
    u0_torn_.segment(s.first_dof, s.n_dofs()) = s.factor.solve(s.f);
  });
  ranks_->sum(u0_torn_);
  u0_ = to_free(u0_torn_);
  ++n_kinv_;
  compute_h();
}

void FetiOperator::compute_h() {
  h_ = VectorXd::Zero(rows_.n_rows());
  for (const Subdomain& s : subdomains_)
    scatter_add(s.B * u0_torn_.segment(s.first_dof, s.n_dofs()), s.rows, h_);
  h_ -= rows_.c;
}

void FetiOperator::sum_over_subdomains(
    const VectorXd& x, VectorXd& y,
    const std::function<void(const Subdomain& s, Index i, const VectorXd& v, VectorXd& out)>& local,
    double* local_s, double* sums_s) const {
  FRICON_CHECK(x.size() == dual_rows_->n_local(),
               "a share of " << x.size() << " rows for " << dual_rows_->n_local());
  Stopwatch watch;
  dual_rows_->fetch_ghosts(x, extended_);
  *sums_s += watch.seconds();
  watch.restart();
  const Index n = dual_rows_->n_extended();
  for (VectorXd& p : partial_)
    p.setZero(n);
  for_own_subdomains([&](const Subdomain& s, Index i, int thread) {
    const std::vector<Index>& rows = dual_rows_->extended_rows(i);
    VectorXd out;
    local(s, i, VectorXd(s.B.transpose() * gather(extended_, rows)), out);
    scatter_add(s.B * out, rows, partial_[static_cast<size_t>(thread)]);
  });
  for (std::size_t t = 1; t < partial_.size(); ++t)
    partial_[0] += partial_[t];
  *local_s += watch.seconds();
  watch.restart();
  dual_rows_->return_ghosts(partial_[0], y);
  *sums_s += watch.seconds();
}

void FetiOperator::apply(const VectorXd& x, VectorXd& y) const {
  FRICON_CHECK(x.size() == size(), "F x of " << x.size() << " for " << size());
  VectorXd y_share;
  apply_share(dual_rows_->restrict(x), y_share);
  y = dual_rows_->assemble(y_share);
}

void FetiOperator::apply_share(const VectorXd& x, VectorXd& y) const {
  sum_over_subdomains(
      x, y,
      [](const Subdomain& s, Index, const VectorXd& v, VectorXd& out) { out = s.factor.solve(v); },
      &products_s_, &sums_s_);
  ++n_products_;
  ++n_kinv_;
}

qp::Operator FetiOperator::equality_preconditioner() const {
  if (!preconditioner_) return {};
  return [this](const VectorXd& x, VectorXd& y) {
    const Stopwatch watch;
    preconditioner_->apply(x, y);
    preconditioner_s_ += watch.seconds();
    ++n_preconditioner_;
  };
}

VectorXd FetiOperator::torn_displacement(const VectorXd& lambda, const VectorXd* alpha) const {
  FRICON_CHECK(lambda.size() == size(), "lambda of " << lambda.size() << " for " << size());
  VectorXd u = VectorXd::Zero(rows_.B.cols());
  for_own_subdomains([&](const Subdomain& s, Index i, int) {
    VectorXd u_s = s.factor.solve(VectorXd(s.f - s.B.transpose() * gather(lambda, s.rows)));
    if (alpha) u_s += s.R * alpha->segment<kSubdomainMotions>(kSubdomainMotions * i);
    u.segment(s.first_dof, s.n_dofs()) = u_s;
  });
  ranks_->sum(u);  // each torn dof is one process's: the sum is exact
  ++n_kinv_;
  return u;
}

VectorXd FetiOperator::to_free(const VectorXd& torn) const {
  VectorXd u(static_cast<Index>(torn_of_free_.size()));
  for (std::size_t k = 0; k < torn_of_free_.size(); ++k)
    u(static_cast<Index>(k)) = torn(torn_of_free_[k]);
  return u;
}

void FetiOperator::contact_displacement(const VectorXd& lambda, VectorXd& w) const {
  w = displacement(lambda);
}

VectorXd FetiOperator::displacement(const VectorXd& lambda) const {
  return to_free(torn_displacement(lambda, nullptr));
}

VectorXd FetiOperator::rigid_displacement(const VectorXd& alpha) const {
  FRICON_CHECK(alpha.size() == n_motions(),
               "rigid_displacement: " << alpha.size() << " amplitudes for " << n_motions());
  VectorXd u(rows_.B.cols());
  for (std::size_t i = 0; i < subdomains_.size(); ++i) {
    const Subdomain& s = subdomains_[i];
    u.segment(s.first_dof, s.n_dofs()) =
        s.R * alpha.segment<kSubdomainMotions>(kSubdomainMotions * static_cast<Index>(i));
  }
  return to_free(u);
}

Real FetiOperator::gluing_residual(const VectorXd& lambda, const VectorXd& alpha) const {
  const VectorXd u = torn_displacement(lambda, &alpha);
  const Index first = rows_.n_contact, n = rows_.n_equality();
  if (n == 0 || u.size() == 0) return 0.0;
  // The rows are scaled by sqrt(k) [sqrt(N/m)]: back to metres, row by row, by the scale of the
  // row (its largest entry).
  const SparseMatrix Bt = SparseMatrix(rows_.B.middleRows(first, n).transpose());
  const VectorXd r = rows_.B.middleRows(first, n) * u - rows_.c.segment(first, n);
  Real sum2 = 0.0;
  for (Index k = 0; k < Bt.outerSize(); ++k) {
    Real scale = 0.0;
    for (SparseMatrix::InnerIterator it(Bt, k); it; ++it)
      scale = std::max(scale, std::abs(it.value()));
    if (scale > 0.0) sum2 += (r(k) / scale) * (r(k) / scale);
  }
  // Root mean squares, of the mismatch over the rows and of u over the torn dofs: the measure
  // the QP's gradient test bounds (a 2-norm), independent of the mesh's size (theory.md §8.6).
  const Real mismatch = std::sqrt(sum2 / static_cast<Real>(n));
  const Real size = u.norm() / std::sqrt(static_cast<Real>(u.size()));
  return size > 0.0 ? mismatch / size : mismatch;
}

}  // namespace fricon::feti
