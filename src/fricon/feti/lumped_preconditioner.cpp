// feti: the lumped preconditioner of Total FETI (docs/theory.md §8.5), on the equality
// multipliers (gluing and Dirichlet rows B_E):
//
//   M_E = (B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1,   K = diag(K_s),
//
// the subdomains' stiffnesses themselves where F = B K^+ B^T has their generalized inverses. A
// product costs one sparse product with every K_s of this process, reduced beforehand to the
// entries between its dofs on equality rows (all that B_E K B_E^T reads), besides the two solves
// with B_E B_E^T of InterfacePreconditioner.

#include "fricon/feti/feti_operator.hpp"
#include "fricon/feti/preconditioner.hpp"

namespace fricon::feti {

namespace {

class LumpedPreconditioner final : public InterfacePreconditioner {
 public:
  LumpedPreconditioner(const FetiOperator& F, const StiffnessSource& stiffness)
      : InterfacePreconditioner(F),
        K_(reduced_stiffness(stiffness, [&](const Subdomain& s, Index, SparseMatrix& K) {
          const std::vector<bool> on_interface = equality_dofs(s, F.rows().n_contact);
          K.prune([&](Index r, Index c, Real) {
            return on_interface[static_cast<size_t>(r)] && on_interface[static_cast<size_t>(c)];
          });
        })) {}

 private:
  void local(const Subdomain&, Index i, const VectorXd& v, VectorXd& out) const override {
    out = K_[static_cast<size_t>(i)] * v;
  }

  std::vector<LocalMatrix> K_;  ///< per subdomain: K_bb; only this process's are filled
};

}  // namespace

std::unique_ptr<const Preconditioner> make_lumped_preconditioner(const FetiOperator& F,
                                                                 const StiffnessSource& stiffness) {
  return std::make_unique<LumpedPreconditioner>(F, stiffness);
}

}  // namespace fricon::feti
