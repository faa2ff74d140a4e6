// feti: the lumped preconditioner of Total FETI (docs/theory.md §8.5), on the equality
// multipliers (gluing and Dirichlet rows B_E):
//
//   M_E = (B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1,   K = diag(K_s),
//
// the subdomains' stiffnesses themselves where F = B K^+ B^T has their generalized inverses. A
// product costs one sparse product with every K_s of this process, reduced beforehand to the
// entries between its dofs on equality rows (keep_interface_stiffness), besides the two solves
// with B_E B_E^T of InterfacePreconditioner.

#include "fricon/feti/preconditioner.hpp"

namespace fricon::feti {

namespace {

class LumpedPreconditioner final : public InterfacePreconditioner {
 public:
  using InterfacePreconditioner::InterfacePreconditioner;

 private:
  void local(const Subdomain& s, Index, const VectorXd& v, VectorXd& out) const override {
    out = s.K * v;
  }
};

}  // namespace

std::unique_ptr<const Preconditioner> make_lumped_preconditioner(const FetiOperator& F) {
  return std::make_unique<LumpedPreconditioner>(F);
}

}  // namespace fricon::feti
