#pragma once
// feti: what approximates the inverse of F's block on the equality multipliers, F_EE, in MPGP's
// preconditioning in face (docs/theory.md §8.5; qp::MpgpOptions::preconditioner), one
// implementation per file:
//   lumped_preconditioner.cpp  (B_E B_E^T)^-1 B_E K B_E^T (B_E B_E^T)^-1
// chosen once, by solver.tfeti_preconditioner (FetiPreconditioner).

#include <memory>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/feti/subdomains.hpp"

namespace fricon::feti {

class FetiOperator;

/// M_E, a symmetric positive definite approximation of F_EE^-1 over the equality multipliers
/// (gluing and Dirichlet, in the rows' scaling).
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  /// y = M_E x; x and y have F.n_equality() entries (y is overwritten). Collective over the
  /// processes that share the subdomains, as a product with F.
  virtual void apply(const VectorXd& x, VectorXd& y) const = 0;
};

/// The preconditioner `kind` of F (null for FetiPreconditioner::None); F must outlive it. The
/// lumped one needs the subdomains' stiffnesses (make_subdomains with keep_stiffness). Collective.
std::unique_ptr<const Preconditioner> make_preconditioner(FetiPreconditioner kind,
                                                          const FetiOperator& F);

/// K_s of each subdomain that keeps it (Subdomain::K) reduced to the entries between its dofs on
/// the equality rows (B_s's rows numbered from `n_contact` on, attach_rows): all that
/// B_E K B_E^T reads, a fraction of K_s.
void keep_interface_stiffness(std::vector<Subdomain>& subdomains, Index n_contact);

/// The lumped preconditioner (lumped_preconditioner.cpp).
std::unique_ptr<const Preconditioner> make_lumped_preconditioner(const FetiOperator& F);

}  // namespace fricon::feti
