// feti: the lumped preconditioner of Total FETI (docs/theory.md §8.5), on the equality
// multipliers (gluing and Dirichlet rows B_E):
//
//   M_E = (B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1,   K = diag(K_s),
//
// the subdomains' stiffnesses themselves where F = B K^+ B^T has their generalized inverses.
// (B_E B_E^T)^-1 on both sides makes M_E invariant to the scaling of the rows (a row scaled by w
// has F's entries times w and M_E's divided by w) and accounts for the chains of gluing rows at
// a node of three or more copies, which are not orthogonal. A product costs one sparse product
// with every K_s of this process (summed over the processes, as a product with F is) and two
// solves with the factor of B_E B_E^T, held by every process as the coarse problem is. B_E B_E^T
// is block diagonal, one small block per node and component (its chain of gluing rows and its
// Dirichlet row), so that its sparse LDL^T (Eigen's, minimum degree) has no fill and a solve
// costs a few operations per row.

#include <Eigen/SparseCholesky>

#include "fricon/core/error.hpp"
#include "fricon/feti/feti_operator.hpp"
#include "fricon/feti/preconditioner.hpp"

namespace fricon::feti {

namespace {

class LumpedPreconditioner final : public Preconditioner {
 public:
  explicit LumpedPreconditioner(const FetiOperator& F)
      : F_(F), n_contact_(F.rows().n_contact), n_equality_(F.rows().n_equality()) {
    const auto [first, last] = F.ranks().block(static_cast<Index>(F.subdomains().size()));
    for (Index i = first; i < last; ++i) {
      const Subdomain& s = F.subdomains()[static_cast<size_t>(i)];
      FRICON_CHECK(s.K.rows() == s.n_dofs(),
                   "the lumped preconditioner needs K_s of subdomain " << i);
    }
    // The gluing and Dirichlet rows are independent (one row per link of a node's chain of
    // copies, one per fixed component): B_E B_E^T is positive definite.
    const SparseMatrix B_E = F.rows().B.middleRows(n_contact_, n_equality_);
    SparseMatrix gram = B_E * B_E.transpose();
    gram.makeCompressed();
    row_gram_.compute(gram);
    if (row_gram_.info() != Eigen::Success)
      throw NumericalError("the lumped preconditioner: B_E B_E^T is not positive definite");
  }

  void apply(const VectorXd& x, VectorXd& y) const override {
    FRICON_CHECK(x.size() == n_equality_, "M_E of " << x.size() << " for " << n_equality_);
    // t over all rows of B, zero on the contact rows, so that the sum over the subdomains is
    // B K B_E^T t_E; its equality rows are B_E K B_E^T t_E.
    VectorXd t = VectorXd::Zero(n_contact_ + n_equality_), Kt;
    t.tail(n_equality_) = row_gram_.solve(x);
    double local_s = 0.0, sums_s = 0.0;
    F_.sum_over_subdomains(
        t, Kt, [](const Subdomain& s, const VectorXd& v, VectorXd& out) { out = s.K * v; },
        &local_s, &sums_s);
    y = row_gram_.solve(VectorXd(Kt.tail(n_equality_)));
  }

 private:
  const FetiOperator& F_;
  Index n_contact_, n_equality_;
  Eigen::SimplicialLDLT<SparseMatrix> row_gram_;  ///< of B_E B_E^T
};

}  // namespace

void keep_interface_stiffness(std::vector<Subdomain>& subdomains, Index n_contact) {
  for (Subdomain& s : subdomains) {
    if (s.K.rows() == 0) continue;
    std::vector<bool> on_interface(static_cast<size_t>(s.n_dofs()), false);
    const SparseMatrix Bt = s.B.transpose();  // column k: local row k of B_s
    for (Index k = 0; k < Bt.outerSize(); ++k)
      if (s.rows[static_cast<size_t>(k)] >= n_contact)
        for (SparseMatrix::InnerIterator it(Bt, k); it; ++it)
          on_interface[static_cast<size_t>(it.row())] = true;
    s.K.prune([&](Index i, Index j, Real) {
      return on_interface[static_cast<size_t>(i)] && on_interface[static_cast<size_t>(j)];
    });
  }
}

std::unique_ptr<const Preconditioner> make_lumped_preconditioner(const FetiOperator& F) {
  return std::make_unique<LumpedPreconditioner>(F);
}

}  // namespace fricon::feti
