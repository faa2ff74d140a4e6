#pragma once
// feti: the dual operator of Total FETI (docs/theory.md §8.3): F = B K^+ B^T over the contact
// multipliers and, after them, the equality multipliers of the gluing and Dirichlet rows
// (feti/torn_rows.hpp), with K = diag(K_s) over the torn dofs of the subdomains
// (feti/subdomains.hpp). Every product is a sum over the subdomains,
//
//   F x = sum_s B_s K_s^+ B_s^T x,
//
// run on a pool of threads, over this process's subdomains. In the QP each process holds its
// share of the multipliers (feti/dual_rows.hpp, dual::DualShare): a product fetches the rows of
// its subdomains that others hold and returns their sums to them (theory.md §8.8). The equality G
// lambda = e, G = R^T B^T and e = R^T f, carries the rigid motions of every subdomain (6 per
// subdomain: the natural coarse space), and the displacement is u = K^+ (f - B^T lambda) + R alpha,
// alpha = -mu of that equality, read at each node's owner copy (the copies agree to the gluing
// residual, which the certificate checks). To the contact solve it is one more dual::DualOperator:
// the QP layer sees the equality multipliers as free unknowns (qp::BlockKind::Free) and the
// equality through qp::CoarseSpace.

#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "fricon/dual/dual_operator.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/feti/dual_rows.hpp"
#include "fricon/feti/preconditioner.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/feti/subdomains.hpp"
#include "fricon/feti/torn_rows.hpp"

namespace fricon::feti {

class FetiOperator final : public dual::DualOperator {
 public:
  /// The operator of the factored `subdomains` (make_subdomains) and the rows `rows`
  /// (tear_rows, with the same subdomains); `owner_dof` (owner_dofs) and `dofs` (the whole
  /// model's) map the torn displacement to the model's free dofs. Computes h, G and e (one solve
  /// per subdomain). Products run on `threads` threads over the subdomains of this process's
  /// block of `ranks`, which must outlive the operator; every product, h and every displacement
  /// is collective over it.
  FetiOperator(std::vector<Subdomain> subdomains, TornRows rows,
               const std::vector<Index>& owner_dof, const fe::DofMap& dofs, int threads,
               const Ranks& ranks);

  ~FetiOperator() override;
  dual::DualOperatorKind kind() const override { return dual::DualOperatorKind::Implicit; }
  /// y = F x over all the multipliers (each process restricts x to its share, the share's product,
  /// then every share assembled): for what needs whole vectors (the certificate, ||F||).
  /// Collective.
  void apply(const VectorXd& x, VectorXd& y) const override;
  /// y = F x on this process's share (DualRows): x and y over its rows. Collective.
  void apply_share(const VectorXd& x, VectorXd& y) const;
  const dual::DualShare& share() const override;
  /// How the multipliers are shared out over the processes (rebuilt with the contact rows).
  const DualRows& dual_rows() const { return *dual_rows_; }
  void contact_displacement(const VectorXd& lambda, VectorXd& w) const override;
  VectorXd displacement(const VectorXd& lambda) const override;
  VectorXd rigid_displacement(const VectorXd& alpha) const override;
  /// A step of a loading path: the applied forces and prescribed displacements of `nodal`
  /// (required; f and u0 are not used) on the subdomains and the Dirichlet rows, the contact
  /// rows' `offset` [m^3]; h, e and u0 are recomputed (one solve per subdomain, collective).
  void set_load(const VectorXd& f, const VectorXd& offset, const VectorXd* u0 = nullptr,
                const dual::NodalLoad& nodal = {}) override;
  /// The contact rows replaced by B_contact [m^2] (over the model's free dofs; none: 0 rows) and
  /// their offset c [m^3]: the rows of the contact search's candidates (theory.md §8.7). The
  /// subdomains' factors, the equality rows and the preconditioner are kept; G, h and the share
  /// of the rows are formed again (no solve). The multipliers, hence size(), change with the
  /// rows.
  void set_contact_rows(const SparseMatrix& B_contact, const VectorXd& offset);
  Index n_equality() const override { return rows_.n_equality(); }
  /// M_E of set_preconditioner on this process's equality multipliers (of its share), counted
  /// and timed; empty without one.
  qp::Operator equality_preconditioner() const;
  /// The M_E that equality_preconditioner() applies (make_preconditioner; null: none).
  void set_preconditioner(std::unique_ptr<const Preconditioner> M) {
    preconditioner_ = std::move(M);
  }
  /// Applications of the preconditioner so far, and their wall time [s].
  long n_preconditioner() const { return n_preconditioner_; }
  double preconditioner_seconds() const { return preconditioner_s_; }
  /// y = sum over the subdomains s of B_s local_s(B_s^T x_s) on this process's share of the rows
  /// (x and y over them, DualRows): `local(s, i, v, out)` sets out from v (both over the local
  /// dofs of s, number i), on the threads, over this process's subdomains; the rows of its
  /// subdomains that other processes hold are fetched before and their sums returned after
  /// (collective). The form of every product with F (local = K_s^+) and of the preconditioners
  /// (local = K_s or its Schur complement). Adds the wall time of the local part and of the
  /// exchanges to *local_s and *sums_s.
  void sum_over_subdomains(const VectorXd& x, VectorXd& y,
                           const std::function<void(const Subdomain& s, Index i, const VectorXd& v,
                                                    VectorXd& out)>& local,
                           double* local_s, double* sums_s) const;
  Real gluing_residual(const VectorXd& lambda, const VectorXd& alpha) const override;
  const std::vector<Subdomain>& subdomains() const { return subdomains_; }
  /// The threads of the subdomain loops.
  int threads() const { return threads_; }
  const TornRows& rows() const { return rows_; }
  /// Products with F (apply) so far; each is one solve with every subdomain's factor.
  long n_products() const { return n_products_; }
  /// Wall time of the products so far [s]: the subdomains' solves of this process, and the
  /// exchanges with the other processes (zero alone).
  double products_seconds() const { return products_s_; }
  double sums_seconds() const { return sums_s_; }
  /// The processes that share the subdomains.
  const Ranks& ranks() const { return *ranks_; }

 private:
  /// body(s, i, thread) for every subdomain s (number i) of this process, on the threads.
  void for_own_subdomains(
      const std::function<void(const Subdomain& s, Index i, int thread)>& body) const;
  /// The torn displacement K^+ (f - B^T lambda) (+ R alpha when alpha is given).
  VectorXd torn_displacement(const VectorXd& lambda, const VectorXd* alpha) const;
  /// A torn field read at the owners' copies, over the model's free dofs.
  VectorXd to_free(const VectorXd& torn) const;
  /// h = B K^+ f - c, u0 and e = R^T f from the subdomains' loads (one solve per subdomain).
  void compute_load_terms();
  /// h = B K^+ f - c of the K^+ f already solved (no solve).
  void compute_h();

  std::vector<Subdomain> subdomains_;
  TornRows rows_;
  std::vector<Index> torn_of_free_;  ///< the owner's torn dof of each free dof of the model
  VectorXd u0_torn_;                 ///< K^+ f over the torn dofs [m]
  std::vector<Index> owner_dof_;     ///< the owner's torn dof of each component of each node
  int threads_ = 1;
  const Ranks* ranks_;
  std::pair<Index, Index> block_;        ///< this process's subdomains, [first, second)
  std::unique_ptr<DualRows> dual_rows_;  ///< this process's share of the multipliers
  RanksSpace space_;                     ///< the QP's reductions over the processes
  class Share;
  std::unique_ptr<const Share> share_;     ///< the QP's view of dual_rows_
  mutable std::vector<VectorXd> partial_;  ///< per thread: its sum of products
  mutable VectorXd extended_;              ///< x over this process's rows and ghosts
  std::unique_ptr<const Preconditioner> preconditioner_;
  mutable long n_preconditioner_ = 0;
  mutable double preconditioner_s_ = 0.0;
  mutable long n_products_ = 0;
  mutable double products_s_ = 0.0, sums_s_ = 0.0;
};

}  // namespace fricon::feti
