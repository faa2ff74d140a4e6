#include "fricon/feti/preconditioner.hpp"

#include "fricon/core/error.hpp"
#include "fricon/core/parallel_for.hpp"
#include "fricon/feti/feti_operator.hpp"

namespace fricon::feti {

InterfacePreconditioner::InterfacePreconditioner(const FetiOperator& F) : F_(F) {
  // This process's equality rows (they follow its contact rows, DualRows): the groups of rows
  // that share a dof are whole on one process, so that B_E B_E^T, block diagonal over them, is.
  // The gluing and Dirichlet rows are independent (one row per link of a node's chain of copies,
  // one per fixed component): B_E B_E^T is positive definite.
  const DualRows& share = F.dual_rows();
  n_equality_ = share.n_local() - share.n_local_contact();
  std::vector<Eigen::Triplet<Real, SparseIndex>> pick;
  for (Index k = 0; k < n_equality_; ++k)
    pick.emplace_back(k, share.owned()[static_cast<size_t>(share.n_local_contact() + k)], 1.0);
  SparseMatrix P(n_equality_, F.rows().n_rows());
  P.setFromTriplets(pick.begin(), pick.end());
  const SparseMatrix B_E = P * F.rows().B;
  SparseMatrix gram = B_E * B_E.transpose();
  gram.makeCompressed();
  row_gram_.compute(gram);
  if (row_gram_.info() != Eigen::Success)
    throw NumericalError("the preconditioner: B_E B_E^T is not positive definite");
}

void InterfacePreconditioner::apply(const VectorXd& x, VectorXd& y) const {
  FRICON_CHECK(x.size() == n_equality_, "M_E of " << x.size() << " for " << n_equality_);
  // t over this process's rows, zero on the contact rows, so that the sum over the subdomains is
  // B S B_E^T t_E; its equality rows are B_E S B_E^T t_E. (The contact rows are F's current
  // ones, which the contact search replaces: FetiOperator::set_contact_rows.)
  const DualRows& share = F_.dual_rows();
  VectorXd t = VectorXd::Zero(share.n_local()), St;
  t.tail(n_equality_) = row_gram_.solve(x);
  double local_s = 0.0, sums_s = 0.0;
  F_.sum_over_subdomains(
      t, St,
      [this](const Subdomain& s, Index i, const VectorXd& v, VectorXd& out) {
        local(s, i, v, out);
      },
      &local_s, &sums_s);
  y = row_gram_.solve(VectorXd(St.tail(n_equality_)));
}

std::vector<LocalMatrix> InterfacePreconditioner::reduced_stiffness(
    const StiffnessSource& stiffness,
    const std::function<void(const Subdomain& s, Index i, SparseMatrix& K)>& reduce) const {
  std::vector<LocalMatrix> reduced(F_.subdomains().size());
  const auto [first, last] = F_.ranks().block(static_cast<Index>(F_.subdomains().size()));
  parallel_for(last - first, F_.threads(), [&](Index k, int) {
    const Index i = first + k;
    const Subdomain& s = F_.subdomains()[static_cast<size_t>(i)];
    SparseMatrix K = stiffness(i);
    FRICON_CHECK(K.rows() == s.n_dofs() && K.cols() == s.n_dofs(),
                 "K_s of subdomain " << i << " is " << K.rows() << " x " << K.cols() << " for "
                                     << s.n_dofs() << " dofs");
    reduce(s, i, K);
    reduced[static_cast<size_t>(i)] = LocalMatrix(K);
  });
  return reduced;
}

std::vector<bool> equality_dofs(const Subdomain& s, Index n_contact) {
  std::vector<bool> on_equality(static_cast<size_t>(s.n_dofs()), false);
  const SparseMatrix Bt = s.B.transpose();  // column k: local row k of B_s
  for (Index k = 0; k < Bt.outerSize(); ++k)
    if (s.rows[static_cast<size_t>(k)] >= n_contact)
      for (SparseMatrix::InnerIterator it(Bt, k); it; ++it)
        on_equality[static_cast<size_t>(it.row())] = true;
  return on_equality;
}

std::unique_ptr<const Preconditioner> make_preconditioner(FetiPreconditioner kind,
                                                          const FetiOperator& F,
                                                          const StiffnessSource& stiffness) {
  switch (kind) {
    case FetiPreconditioner::Lumped:
      return make_lumped_preconditioner(F, stiffness);
    case FetiPreconditioner::Dirichlet:
      return make_dirichlet_preconditioner(F, stiffness);
    case FetiPreconditioner::None:
      break;
  }
  return nullptr;
}

}  // namespace fricon::feti
