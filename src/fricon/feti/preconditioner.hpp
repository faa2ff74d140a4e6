#pragma once
// feti: what approximates the inverse of F's block on the equality multipliers, F_EE, in MPGP's
// preconditioning in face (docs/theory.md §8.5; qp::MpgpOptions::preconditioner). Both kinds have
// the form
//
//   M_E = (B_E B_E^T)^-1 B_E S B_E^T (B_E B_E^T)^-1,   S = diag(S_s),
//
// (InterfacePreconditioner below) and differ in S_s, one implementation per file:
//   lumped_preconditioner.cpp     S_s = K_s
//   dirichlet_preconditioner.cpp  S_s = K_s's Schur complement on its equality rows' dofs
// chosen once, by solver.tfeti_preconditioner (FetiPreconditioner).

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/SparseCholesky>

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
  /// y = M_E x; x and y over this process's equality multipliers (F.dual_rows(): its rows after
  /// its contact rows; y is overwritten). Collective over the
  /// processes that share the subdomains, as a product with F.
  virtual void apply(const VectorXd& x, VectorXd& y) const = 0;
};

/// A sparse matrix over one subdomain's local dofs, which 32-bit indices address: what the
/// preconditioners keep of K_s and their factors, at 12 rather than 16 bytes per non-zero.
using LocalMatrix = Eigen::SparseMatrix<Real, Eigen::ColMajor, int>;

/// K_s [N/m] of subdomain i of F, both triangles, over its local dofs (subdomain_stiffness of its
/// tetrahedra). A preconditioner asks for it once per subdomain of this process, on the
/// subdomain threads, and keeps only what it reads, so that at most one whole K_s per thread
/// is alive beside the factors.
using StiffnessSource = std::function<SparseMatrix(Index i)>;

/// M_E = (B_E B_E^T)^-1 B_E S B_E^T (B_E B_E^T)^-1 with S = diag(S_s) given by local().
/// (B_E B_E^T)^-1 on both sides makes M_E invariant to the scaling of the rows (a row scaled by w
/// has F's entries times w and M_E's divided by w) and accounts for the chains of gluing rows at
/// a node of three or more copies, which are not orthogonal. B_E B_E^T is block diagonal, one
/// small block per node and component (its chain of gluing rows and its Dirichlet row), so that
/// its sparse LDL^T (Eigen's, minimum degree) has no fill; each process holds the blocks of its
/// own rows (feti/dual_rows.hpp keeps a block on one process).
class InterfacePreconditioner : public Preconditioner {
 public:
  /// Factors B_E B_E^T of F's rows; F must outlive it, and may change its contact rows
  /// (FetiOperator::set_contact_rows), not its equality rows. Throws NumericalError if B_E B_E^T
  /// is singular.
  explicit InterfacePreconditioner(const FetiOperator& F);
  /// Two solves with B_E B_E^T and one sum over the subdomains of local() (collective).
  void apply(const VectorXd& x, VectorXd& y) const final;

 protected:
  /// out = S_s v for subdomain s (number i, one of this process's), v and out over its local
  /// dofs; v is zero off its equality rows' dofs. Called on the subdomain threads.
  virtual void local(const Subdomain& s, Index i, const VectorXd& v, VectorXd& out) const = 0;
  /// Per subdomain of this process, stiffness(i) once `reduce(s, i, K)` has cut it to what
  /// local() reads (and taken from it what else it needs), with 32-bit indices; empty for the
  /// others'. Runs on the subdomain threads.
  std::vector<LocalMatrix> reduced_stiffness(
      const StiffnessSource& stiffness,
      const std::function<void(const Subdomain& s, Index i, SparseMatrix& K)>& reduce) const;
  const FetiOperator& F_;

 private:
  Index n_equality_ = 0;  ///< this process's equality rows, which follow its contact rows
  Eigen::SimplicialLDLT<SparseMatrix> row_gram_;  ///< of B_E B_E^T
};

/// The preconditioner `kind` of F (null for FetiPreconditioner::None), from the subdomains'
/// stiffnesses `stiffness`; F must outlive it. The lumped one keeps of each K_s the entries
/// between interface dofs; the Dirichlet one those that touch the interface, and the factor of
/// the interior's block. Collective.
std::unique_ptr<const Preconditioner> make_preconditioner(FetiPreconditioner kind,
                                                          const FetiOperator& F,
                                                          const StiffnessSource& stiffness);

/// Which of subdomain s's local dofs are on equality rows (B_s's rows numbered from `n_contact`
/// on, attach_rows): the dofs on which M_E's S_s acts.
std::vector<bool> equality_dofs(const Subdomain& s, Index n_contact);

/// The lumped preconditioner (lumped_preconditioner.cpp).
std::unique_ptr<const Preconditioner> make_lumped_preconditioner(const FetiOperator& F,
                                                                 const StiffnessSource& stiffness);
/// The Dirichlet preconditioner (dirichlet_preconditioner.cpp).
std::unique_ptr<const Preconditioner> make_dirichlet_preconditioner(
    const FetiOperator& F, const StiffnessSource& stiffness);

}  // namespace fricon::feti
