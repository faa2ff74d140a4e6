#pragma once
// qp: SMALSE-M, Dostal's semi-monotonic augmented Lagrangian method for a QP with bound and disc
// constraints and linear equalities (docs/theory.md §4.6; Dostal, "Optimal Quadratic Programming
// Algorithms", 2009, ch. 9):
//
//   min q(x) = 1/2 x^T A x - b^T x   subject to x in Omega (qp/constraints.hpp) and G x = e,
//
// G the free rigid motions of floating bodies, or of every subdomain of Total FETI (theory.md
// §8.3). Each outer step minimizes the
// augmented Lagrangian
//
//   L(x, mu, rho) = q(x) + mu^T (G x - e) + rho/2 ||G x - e||^2
//
// over Omega by MPGP (qp/mpgp.hpp) to the adaptive precision ||g^P|| <= min(M ||G x - e||, eta),
// then updates mu += rho (G x - e), and divides M by beta when L did not increase by at least
// rho/2 ||G x - e||^2. The rows of G are first made orthonormal (over the multipliers that are
// not pinned to zero), so that G^T G is the orthogonal projector Q = I - P onto their span and
// A + rho Q stays as well conditioned as A for rho ~ ||A||. The orthonormal rows are never
// formed: every product goes through G and S^+ = (G G^T)^+ (qp/coarse_space.hpp), so that G may
// be large and sparse.
//
// When no x in Omega satisfies G x = e (a load that contact cannot carry), the residual G x - e
// stops decreasing; the solver then solves the phase-one problem min ||G x - e|| over Omega
// (products with G only) and, if its shortest residual d = e - G x1 is not small, reports the
// certificate of infeasibility (Farkas): d^T e > d^T G x1 = sup over Omega of d^T G x.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "fricon/core/types.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/operator.hpp"

namespace fricon::qp {

/// G x = e: m rows over the n unknowns of the QP; G sparse (a few dense rows for floating bodies,
/// 6 sparse rows per subdomain for Total FETI, theory.md §8.3).
struct EqualityConstraint {
  SparseMatrix G;     ///< m x n
  Eigen::VectorXd e;  ///< m
};

struct SmalseOptions {
  /// rho = rho_factor ||A|| (with the projector ||P A P||), the penalty. Default 0.3 (measured
  /// on examples/floating, bench/floating_bench.py, theory.md §4.6; Total FETI takes 1,
  /// dual::kEqualityPenaltyFactor); range > 0.
  double rho_factor = 0.3;
  /// M_0 = M_factor ||A||, the initial ratio of the inner precision to ||G x - e||. Default 0.3
  /// (measured likewise); range > 0.
  double M_factor = 0.3;
  /// M is divided by beta when L fails to increase enough. Default 10; range > 1.
  double beta = 10.0;
  /// eta = eta_factor times the reference of the stopping test: the cap of the inner
  /// precision. Default 0.1; range > 0.
  double eta_factor = 0.1;
  /// Stop when ||G x - e|| <= equality_tolerance max(||e||, ||G x||) (besides the gradient test
  /// of the inner options at the last inner solve). Default 1e-8; range > 0.
  double equality_tolerance = 1e-8;
  /// Cap on the outer steps. Default 200; range >= 1.
  int max_outer = 200;
  /// The load along row directions of G that act on no multiplier free to move (only on discs
  /// pinned to zero): false (default) refuses a nonzero one as infeasible; true drops it, e.g.
  /// in the first, frictionless step of Coulomb's successive approximations, whose pressures only
  /// start the iteration (theory.md §5.8).
  bool drop_unresisted_load = false;
  /// Solve with the projected Hessian P A P + rho G^T G, P = I - G^T G (rows made orthonormal),
  /// and the linear term P (b - A G^T e): the same QP on the affine set G x = e, with the part of
  /// A along the rows of G left out (theory.md §4.6). Default true.
  bool projector = true;
  /// With the projector: take the penalty, M and MPGP's step length from ||P A P|| rather than
  /// ||A|| (Total FETI, theory.md §4.6): a generalized inverse inflates A along the rows of G (F
  /// along the subdomains' rigid motions), and a step length from ||A|| crawls. Default false
  /// (the floating bodies' measured defaults are relative to ||A||).
  bool projected_norm = false;
  /// ||P A P|| if already known for the same rows (SmalseReport::norm_projected of an earlier
  /// solve); 0 estimates it by the power method when projected_norm is set.
  double norm_projected = 0.0;

  /// Throws InputError naming the first field out of range.
  void validate() const;
};

/// How an infeasible equality shows: a direction d of the m rows (the certificate) with the load
/// along it, d^T e, exceeding what Omega can give, sup { d^T G x : x in Omega }.
struct Infeasibility {
  Eigen::VectorXd direction;  ///< d, m entries
  double applied = 0.0;       ///< d^T e
  double carried = 0.0;       ///< sup over Omega of d^T G x (finite)
};

struct SmalseReport {
  QpTermination termination = QpTermination::NumericalFailure;
  std::string message;  ///< one sentence: why the solver stopped
  int outer_iterations = 0;
  int iterations = 0;           ///< MPGP steps over all inner solves
  MpgpSteps steps;              ///< the same by kind
  long n_products = 0;          ///< products with A over all inner solves (power method excluded)
  long n_preconditioner = 0;    ///< applications of the inner preconditioner, over all inner solves
  double rho = 0.0;             ///< the penalty used
  double norm_projected = 0.0;  ///< ||P A P|| used with the projector (0 without)
  double equality_residual = 0.0;  ///< qp::equality_residual at the end
  /// The floor of the residual's scale (qp::equality_residual's `floor`, in the units of e): the
  /// magnitudes of G x's terms for a multiplier vector of the size the gradient test resolves,
  /// r_ref / ||A|| spread evenly over the unknowns. It keeps the measure finite where the
  /// solution is x = 0 but the data are not (theory.md §4.6).
  double equality_floor = 0.0;
  double norm_gp = 0.0;         ///< ||g^P|| of the augmented Lagrangian at the end
  double reference_norm = 0.0;  ///< the reference of the gradient test
  /// Set when the equality cannot be met in Omega (termination NumericalFailure).
  bool infeasible = false;
  Infeasibility infeasibility;
  /// Rows of G that act only on multipliers pinned to zero (directions of the m rows, as columns):
  /// their amplitude is not determined by the QP; the solution has none of it (least norm).
  Eigen::MatrixXd undetermined;
  MpgpReport last_inner;     ///< the report of the last inner MPGP solve
  long n_coarse_solves = 0;  ///< solves with the coarse problem G G^T (qp/coarse_space.hpp)
  double coarse_s = 0.0;     ///< their wall time and that of its decomposition [s]
  double seconds = 0.0;
};

/// ||G x - e|| / max(||e||, || |G| |x| ||, floor) (0 when all are 0): relative to the load and to
/// the magnitudes of the terms of G x, so that a load-free equality (e = 0) is measured too, and
/// at least to `floor` (>= 0, SmalseReport::equality_floor), so that an x that tends to 0 is not
/// measured against itself alone. x and G's columns are this process's part in `space`
/// (collective there).
double equality_residual(const EqualityConstraint& eq, const Eigen::VectorXd& x, double floor = 0.0,
                         const DualSpace& space = whole_space());

/// Whether G x = e can be met for some x in Omega, decided without A (the rows of G made
/// orthonormal over the multipliers free to move, then phase one, as solve_smalse does when it
/// stagnates): the certificate of infeasibility, or none when the shortest residual is at most
/// max(1e-6, tolerance) ||e|| (in the orthonormal rows). Costs products with G only.
std::optional<Infeasibility> balance_certificate(const EqualityConstraint& eq,
                                                 const SeparableConstraints& c, double tolerance);

/// Solves the QP above. x: in, the initial guess; out, the last iterate. mu: in, the initial
/// multipliers of the equality (m entries, or empty for zero); out, the last ones, in the rows
/// of G as given (so that the gradient of the Lagrangian is A x - b + G^T mu). `inner` are the
/// MPGP options (its tolerance is the gradient test; its norm_A must be ||A|| > 0 or 0 to
/// estimate it). With inner.space, b, x, c and the columns of G are this process's part of the
/// unknowns and e and mu are whole on every process: collective there. Throws InputError on bad
/// sizes or options.
SmalseReport solve_smalse(const Operator& A, const Eigen::VectorXd& b,
                          const SeparableConstraints& c, const EqualityConstraint& eq,
                          const SmalseOptions& opt, const MpgpOptions& inner, Eigen::VectorXd& x,
                          Eigen::VectorXd& mu);

}  // namespace fricon::qp
