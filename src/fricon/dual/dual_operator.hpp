#pragma once
// dual: the dual Hessian Q = B K^-1 B^T and everything the outer loop asks of it (theory.md §3):
// products with Q, Q itself when an operator forms it, h = B K^-1 f, and the displacement
// w = K^-1 (f - B^T lambda) on the contact dofs (inside the outer loop) and everywhere (once at
// the end). One implementation per file, chosen by DualOperatorKind:
//   implicit_operator.cpp  each product is a solve with the factor of K (the paper's way)
//   forward_operator.cpp   Q formed by a forward sweep over the reach of the contact dofs
//   schur_operator.cpp     Q from the trailing block of a factor ordered with the contact dofs last
// An operator may need a particular factorization of K (schur does); the driver asks for it with
// factorization_request() before it factorizes, so nothing else knows about orderings.
// The distributed backend's operator (MUMPS, parallel/mpi/) implements the same interface.

#include <functional>
#include <memory>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/dual/dual_operator_kind.hpp"
#include "fricon/dual/dual_share.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/qp/operator.hpp"

namespace fricon::dual {

/// What an operator needs of the factorization of K.
struct FactorizationRequest {
  /// Dofs to order after all others, so that the trailing block of the factor is the Cholesky
  /// factor of the Schur complement onto them; empty for the default (nested dissection) order.
  std::vector<Index> last;
};

/// The request of operator `kind` (schur: the contact dofs last; the others: nothing).
FactorizationRequest factorization_request(DualOperatorKind kind,
                                           const std::vector<Index>& contact_dofs);

/// What an operator is built from; every reference must outlive the operator.
/// A load as nodal fields (3 x n_nodes), for a dual operator on the mesh's nodes rather than on
/// the free dofs of one K (Total FETI, theory.md §8): the applied forces [N] at every component,
/// fixed ones too, and the prescribed displacements [m].
struct NodalLoad {
  const Eigen::Matrix<Real, 3, Eigen::Dynamic>* applied = nullptr;
  const Eigen::Matrix<Real, 3, Eigen::Dynamic>* prescribed = nullptr;
};

struct DualInput {
  const linalg::CholeskyFactor& factor;    ///< of K, built with factorization_request(kind)
  const SparseMatrix& B;                   ///< n_dual x n_free [m^2]
  const VectorXd& f;                       ///< load over the free dofs [N]
  const std::vector<Index>& contact_dofs;  ///< the free dofs of the contact surface's nodes
  /// Called while Q is being formed (it may throw fricon::Interrupted to stop); optional.
  std::function<void()> poll;
  /// c [m^3], the constant part of the constraints B w <= c (normal rows: the initial gap; see
  /// contact::ContactDiscretization::offset), so that h = B K^-1 f - c; null: zero.
  const VectorXd* offset = nullptr;
  /// u0 = K^-1 f if already solved (the contact search's), else null: the operator solves it.
  const VectorXd* free_solution = nullptr;
  /// How many recoveries of the contact displacement the caller expects (a loading path: some per
  /// step, theory.md §2.9). An operator that would recover it by a solve each time may form the
  /// contact rows of K^-1 B^T once instead, when that costs less than the solves, so that each
  /// recovery is a product with them (the forward operator does). 0: a static run's handful.
  long expected_recoveries = 0;
  /// The free rigid motions of floating bodies over the free dofs (n_free x m, K R = 0,
  /// fe::FloatingBodies::R), the factor then being of the regularized K (a generalized inverse
  /// K^+); null or empty: every body is held (theory.md §2.10).
  const SparseMatrix* R = nullptr;
};

/// The dual problem's operator, whatever factors K: CHOLMOD here (FactorDualOperator), MUMPS
/// across MPI ranks in parallel/mpi/ (docs/theory.md §3.3).
/// The share of solver.qp_rtol to which a QP with equality multipliers is solved (Total FETI,
/// theory.md §8.6): 100 qp_rtol bounds the certificate's gluing residual with this share.
inline constexpr Real kEqualityToleranceShare = 1e-1;

/// The penalty of SMALSE-M (qp::SmalseOptions::rho_factor, times ||P Q P||) for a QP with
/// equality multipliers (Total FETI, theory.md §4.6, §8.6): 1, so that P Q P + rho (I - P) keeps
/// the norm of P Q P; on the paper's brick it needed fewer products than the floating bodies' 0.3.
inline constexpr Real kEqualityPenaltyFactor = 1.0;

/// The relative change at which the power iterations stop for a QP with equality multipliers
/// (Total FETI; qp::MpgpOptions::power_tolerance): ||P Q P||, from which SMALSE-M takes its
/// penalty and step length (an estimate low by 1e-3 still leaves the step 1.95/||P Q P|| below
/// 2/||P Q P||), and ||Q||, which only scales the Coulomb residual there. On a mesh of many
/// subdomains the top eigenvalues are close and the power iteration converges slowly: at the
/// direct solver's 1e-8 and 1e-10 it took up to its caps of 100 and 200 products with F on the
/// brick, more than the QP itself without contact (docs/benchmarks.md).
inline constexpr Real kEqualityPowerTolerance = 1e-4;

class DualOperator {
 public:
  virtual ~DualOperator() = default;
  DualOperator(const DualOperator&) = delete;
  DualOperator& operator=(const DualOperator&) = delete;

  virtual DualOperatorKind kind() const = 0;
  /// n_dual, the number of multipliers.
  Index size() const { return h_.size(); }
  /// h = B K^-1 f - c [m^3] (c = DualInput::offset).
  const VectorXd& h() const { return h_; }
  /// u0 = K^-1 f over the free dofs [m].
  const VectorXd& u0() const { return u0_; }

  /// y = Q x [m^3/Pa times the unit of x]; y arrives sized like x and is overwritten.
  virtual void apply(const VectorXd& x, VectorXd& y) const = 0;
  /// Q [m^3/Pa] when the operator forms it, else null.
  virtual const MatrixXd* dense() const { return nullptr; }
  /// w = K^-1 (f - B^T lambda) on the contact dofs; w is sized n_free on return and its other
  /// entries are left as they were (exact on every dof pivoted on the contact dofs' reach).
  virtual void contact_displacement(const VectorXd& lambda, VectorXd& w) const = 0;
  /// w = K^-1 (f - B^T lambda) over all free dofs: one solve with the factor (with floating
  /// bodies K^+ (f - B^T lambda), to which their rigid_displacement is added).
  virtual VectorXd displacement(const VectorXd& lambda) const = 0;
  /// Another load on the same K and B (a step of a loading path, theory.md §2.9): f [N] over the
  /// free dofs and the offset c [m^3]; u0 = K^-1 f (one solve, or `u0` when given) and h are
  /// recomputed, Q is kept. An operator on the mesh's nodes (Total FETI) takes the load from
  /// `nodal` instead, which it then requires. Throws Error for an operator that cannot (the
  /// distributed one).
  virtual void set_load(const VectorXd& f, const VectorXd& offset, const VectorXd* u0 = nullptr,
                        const NodalLoad& nodal = {});

  /// The multipliers as this process holds them for the QP, with their products (dual/
  /// dual_share.hpp): all of them here (WholeShare), unless the operator shares them out over
  /// processes (Total FETI, theory.md §8.8), whose share also carries the preconditioner M_E of
  /// its equality multipliers (theory.md §8.5).
  virtual const DualShare& share() const;
  /// Q as a dense matrix: dense() if formed, else n_dual products with unit vectors.
  MatrixXd to_dense() const;
  /// The operator as the QP layer applies it.
  qp::Operator as_qp_operator() const;
  /// Solves with the factor of K done by this operator so far (a block of m columns counts m).
  long n_kinv() const { return n_kinv_; }

  // The equality constraint G lambda = e of floating bodies (theory.md §2.10): the contact
  // forces balance the load on every free rigid motion. Without floating bodies m = 0.
  /// m, the number of free rigid motions.
  Index n_motions() const { return G_.rows(); }
  /// G = R^T B^T [m^2 per unit amplitude], m x n_dual.
  const SparseMatrix& G() const { return G_; }
  /// e = R^T f [N per unit amplitude: N of a translation, N m of a rotation].
  const VectorXd& e() const { return e_; }
  /// R alpha over the free dofs [m]: the rigid displacement of amplitudes alpha (m entries).
  virtual VectorXd rigid_displacement(const VectorXd& alpha) const;

  // Equality multipliers (Total FETI, theory.md §8): an operator may append, after the
  // n_dual - n_equality() contact multipliers, multipliers of equality rows of its own B (the
  // gluing and Dirichlet rows of the subdomains), free of any bound. h, Q and G cover them; the
  // contact discretization knows only the contact ones.
  /// The number of equality multipliers (0: none, every multiplier is a contact one).
  /// Their gradient is the violation of the equality rows, the error of the displacement itself:
  /// a QP with them is solved to kEqualityToleranceShare of the asked relative tolerance, so that
  /// the displacement is as accurate as the contact multipliers' (theory.md §8.6).
  virtual Index n_equality() const { return 0; }
  /// The contact multipliers, size() - n_equality().
  Index n_contact() const { return size() - n_equality(); }
  /// The violation of the equality rows by the displacement of multipliers lambda and rigid
  /// amplitudes alpha: its root mean square over the rows [m] relative to that of the
  /// displacement (0 without equality rows).
  virtual Real gluing_residual(const VectorXd& lambda, const VectorXd& alpha) const {
    (void)lambda;
    (void)alpha;
    return 0.0;
  }

 protected:
  DualOperator() = default;
  /// Stores u0 = K^-1 f (solved by the implementation) and h = B u0 - c (c: offset, or zero).
  void set_free_solution(VectorXd u0, const SparseMatrix& B, const VectorXd* offset);
  /// Stores G = R^T B^T (once) and e = R^T f (R null or empty: none).
  void set_equality(const SparseMatrix* R, const SparseMatrix& B, const VectorXd& f);
  VectorXd h_, u0_;
  SparseMatrix G_;
  VectorXd e_;
  const SparseMatrix* R_ = nullptr;
  mutable long n_kinv_ = 0;

 private:
  mutable std::unique_ptr<DualShare> whole_share_;  ///< share()'s default, made at the first call
};

/// The operators on a CHOLMOD factor of K (implicit, forward, schur): u0 and the displacement
/// are solves with DualInput::factor.
class FactorDualOperator : public DualOperator {
 public:
  VectorXd displacement(const VectorXd& lambda) const override;
  void set_load(const VectorXd& f, const VectorXd& offset, const VectorXd* u0 = nullptr,
                const NodalLoad& nodal = {}) override;

 protected:
  /// Computes u0 and h (one solve).
  explicit FactorDualOperator(const DualInput& input);
  /// Called after set_load changed u0: an operator that keeps a part of u0 updates it.
  virtual void load_changed() {}
  DualInput in_;
  VectorXd f_;  ///< the load [N] (in_.f until set_load)
};

/// The operator of `kind` (Auto resolved by resolve()). Throws Error if the factor was not built
/// with factorization_request(kind), and whatever `poll` throws.
std::unique_ptr<DualOperator> make_dual_operator(DualOperatorKind kind, const DualInput& input);

/// The implementations, one per file (used by make_dual_operator).
std::unique_ptr<DualOperator> make_implicit_operator(const DualInput& input);
std::unique_ptr<DualOperator> make_forward_operator(const DualInput& input);
std::unique_ptr<DualOperator> make_schur_operator(const DualInput& input);

}  // namespace fricon::dual
