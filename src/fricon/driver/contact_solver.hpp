#pragma once
// driver: the frictional contact solve (method.md §2.6 and §3) on top of the elastic model:
//   contact discretization (surface, patches T_H, B, stability check)
//   -> the dual QP data Q = B K^-1 B^T and h = B K^-1 f (Q applied implicitly through the factor
//      of K, or formed densely once)
//   -> successive approximations: phi^0 = 0; for k = 1, 2, ...: radii from phi^(k-1), dual QP by
//      MPGP (warm-started), w = K^-1 (f - B^T lambda), phi^k = ||w_t|| at the surface nodes,
//      err(k) = ||phi^k - phi^(k-1)|| / ||phi^k||, stop when err(k) <= outer_tol.

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

/// One outer iteration (a Tresca problem with a frozen coefficient).
struct OuterIteration {
  int k = 0;
  Real err = 0.0;         ///< err(k) = ||phi^k - phi^(k-1)|| / ||phi^k||
  int qp_iterations = 0;  ///< MPGP steps
  long qp_products = 0;   ///< products with Q in this QP (n_mult contribution)
  Real qp_rel_gp = 0.0;   ///< final ||g^P|| / ||h||
  std::string qp_termination;
  double seconds = 0.0;  ///< wall time of this outer iteration [s]
};

struct ContactReport {
  std::string boundary;
  std::string friction_law;
  std::string dual_operator;  ///< "implicit" or "dense" (what was used)
  Index n_patches = 0;
  Index n_dual = 0;  ///< 3 n_patches (the paper's n_d)
  Index n_surface_nodes = 0;
  Index n_contact_nodes = 0;   ///< surface nodes that are not Dirichlet nodes
  Real stability_ratio = 0.0;  ///< sigma_min / sigma_max of B (condition (5.1))
  Real norm_Q = 0.0;           ///< power-method estimate of ||Q|| [m/Pa]
  int outer_iterations = 0;
  long n_mult = 0;         ///< products with Q over all QPs (the paper's n_mult)
  long qp_iterations = 0;  ///< MPGP steps over all QPs
  long n_kinv = 0;         ///< solves with the factor of K, all of them
  std::vector<Real> err_history;
  std::vector<OuterIteration> history;
  // The paper's measures of the last iterate (method.md §5), with w_n = w.n on the surface:
  Real wn_pos_l2 = 0.0;           ///< ||max(0, w_n)|| in L2(surface), P1 interpolant [m^2]
  Real wn_pos_inf = 0.0;          ///< max over surface nodes of max(0, w_n) [m]
  Real max_neg_wn = 0.0;          ///< max of -w_n (lift-off) [m]
  Real max_wt = 0.0;              ///< max ||w_t|| [m]
  Real max_lambda_n = 0.0;        ///< [Pa]
  Real max_lambda_t = 0.0;        ///< max ||lambda_t|| [Pa]
  Real total_normal_force = 0.0;  ///< sum lambda_n |R_p| [N]
  qp::KktResiduals kkt;           ///< of the last QP, with g = Q lambda - h applied through K^-1
  /// ||Psi(phi) - phi|| / ||phi|| at the returned phi (the last err, which compares
  /// phi^k = Psi(phi^(k-1)) with phi^(k-1)).
  Real fixed_point_residual = 0.0;
  /// Observed contraction factor of the successive approximations: geometric mean of
  /// err(k)/err(k-1) over the last iterations (0 if fewer than three).
  Real contraction_ratio = 0.0;
};

/// Fields on the contact surface, per surface node and per patch.
struct ContactFields {
  contact::ContactSurface surface;
  contact::Patches patches;
  VectorXd lambda;        ///< multipliers (lambda_n, lambda_t1, lambda_t2) per patch [Pa]
  VectorXd radius;        ///< slip bounds rho_p used by the last QP [Pa]
  VectorXd phi;           ///< phi per surface node used for the last radii [m]
  VectorXd wn, wt1, wt2;  ///< components of the displacement w per surface node [m]
  VectorXd F;             ///< F(||w_t||) per surface node
  VectorXd slip_bound;    ///< g per surface node [Pa]
};

/// The dual problem of the first outer iteration (for --dump-dual): minimise 1/2 l^T Q l - l^T h
/// over l_n >= 0, ||l_t|| <= radius per patch, unknowns ordered (n, t1, t2) per patch.
struct DualSnapshot {
  MatrixXd Q;           ///< 3m x 3m, symmetric positive definite [m/Pa]
  VectorXd h;           ///< 3m [m^3]
  VectorXd radius;      ///< m slip bounds [Pa]
  VectorXd patch_area;  ///< m patch areas [m^2]
  std::string source;   ///< problem it came from
};

/// How a run reports progress and what it keeps besides the solution.
struct RunOptions {
  /// Keep the dual problem of the first outer iteration (ContactOutcome::first_dual).
  bool keep_first_dual = false;
  /// Called after every outer iteration (the monitor line of `fricon solve`).
  std::function<void(const OuterIteration&)> on_outer_iteration;
  /// Called after every MPGP step of every QP (verbose progress); return false to stop.
  std::function<bool(const qp::MpgpIteration&)> on_qp_iteration;
  /// Called when a phase starts ("assembly", "factorize", ...) so that long phases are visible.
  std::function<void(const std::string& phase)> on_phase_start;
  /// If set and true, the run stops at the next QP step (e.g. set by a SIGINT handler) and
  /// returns what it has, not converged.
  const std::atomic<bool>* stop_requested = nullptr;
};

struct ContactOutcome {
  bool converged = false;
  std::string message;
  ContactReport report;
  ContactFields fields;
  VectorXd w;  ///< displacement over the free dofs of the last inner solve [m]
  Vec3 contact_force = Vec3::Zero();       ///< -sum of B^T lambda over free dofs, per direction [N]
  Real linear_residual = 0.0;              ///< ||K w - f + B^T lambda|| / ||f||
  std::optional<DualSnapshot> first_dual;  ///< if RunOptions::keep_first_dual
};

/// Runs the contact solve for `problem.contact` on the built model; phases are timed into
/// `times` ("contact", "dual", "qp", "recovery"). Throws InputError/NumericalError for ill-posed
/// input (missing surface, unstable partition). Non-convergence is returned, not thrown.
ContactOutcome solve_contact(const Problem& problem, const Model& model, PhaseTimes& times,
                             const RunOptions& options = {});

/// The free dofs of the contact surface's nodes (the columns B can touch).
std::vector<Index> contact_dofs(const Problem& problem, const Model& model);

/// Whether to factor K with the contact dofs last (dual operator "schur").
bool wants_schur(const Problem& problem);

/// The dual operator a run uses: the requested one, or for "auto" "forward" while the dense Q
/// (n_dual^2 entries) is no larger than the factor of K or n_dual <= 6000, else "implicit".
std::string dual_operator_for(const Problem& problem, const linalg::CholeskyFactor& factor,
                              Index n_dual);

/// The friction law described by the options.
std::unique_ptr<contact::FrictionLaw> make_friction_law(const FrictionOptions& options);

}  // namespace fricon::driver
