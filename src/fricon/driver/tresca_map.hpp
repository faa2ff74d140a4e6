#pragma once
// driver: the map Psi of the successive approximations (theory.md §5.1, §5.6): one Tresca step.
// From the state (the nodal slips phi, and for Coulomb the patch pressures lambda_n): the radii
// by the model's slip bounds (contact/slip_bounds.hpp), the dual QP with those radii by MPGP
// warm-started from the previous multipliers (qp/mpgp.hpp), the displacement on the contact dofs
// (dual/dual_operator.hpp), and the new state: phi = ||w_t|| at the surface nodes (and the new
// lambda_n). The outer loop (outer/outer_loop.hpp) iterates it.

#include <functional>
#include <string>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/slip_bounds.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/scaling.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::driver {

/// What the last step of a loading path left on the contact surface (theory.md §2.9): the slip
/// of a step is measured from it. Empty vectors (a static run): no history.
struct SlipHistory {
  VectorXd wt1, wt2;     ///< tangential displacement per surface node at the last step's end [m]
  VectorXd accumulated;  ///< accumulated slip s per surface node [m]

  bool empty() const { return accumulated.size() == 0; }
  /// The slip the coefficient is evaluated at, per surface node [m], for this step's
  /// displacement d: s + ||w_t - w_t^prev|| along a path (from s = 0, w_t^prev = 0 at its first
  /// step), the increment counted only at the nodes `in_contact` marks (empty: every node;
  /// nodes_in_contact).
  VectorXd slips(const contact::SurfaceDisplacement& d, const std::vector<bool>& in_contact) const;
};

/// A patch carries a contact pressure when its lambda_n exceeds this share of the largest
/// lambda_n (round-off of a pressure that is zero), and the pressure floor of
/// separation_threshold.
inline constexpr Real kContactPressureShare = 1e-12;

/// The contact pressure [Pa] at or below which a patch is separated: the larger of
/// kContactPressureShare times the largest lambda_n [Pa] and `pressure_floor` [Pa] (along a
/// loading path, the accuracy of the step's pressures: outer_tol times the path's pressure
/// scale, theory.md §2.9; 0 in a static run).
Real separation_threshold(Real largest_lambda_n, Real pressure_floor);

/// Per surface node: whether friction acts on it, so that its slip accumulates along a loading
/// path (theory.md §2.9). Empty (every node) when the slip bound does not depend on the pressure
/// (`uses_pressure` false: Tresca, whose given g stands for a known normal stress); for Coulomb
/// the nodes of the patches whose lambda_n (multipliers `lambda` [Pa], (n, t1, t2) per patch)
/// exceeds separation_threshold(largest lambda_n, `pressure_floor` [Pa]).
std::vector<bool> nodes_in_contact(const contact::ContactDiscretization& disc,
                                   const VectorXd& lambda, bool uses_pressure, Real pressure_floor);

class TrescaMap final : public outer::FixedPointMap {
 public:
  /// Every reference must outlive the map. Each QP is solved in the variables scaled by
  /// `scaling` (theory.md §4.5; qp::BlockScaling::identity for none), over every multiplier of
  /// Q (Q.size(): the contact ones, then Q's equality multipliers); `qp` carries the QP's
  /// tolerance, limit, variant, ||D Q D|| and monitor; `warm_start` false starts every QP from
  /// zero. Phases "qp" and "recovery" are timed into `times`.
  TrescaMap(const fe::DofMap& dofs, const contact::ContactDiscretization& discretization,
            const dual::DualOperator& Q, const contact::SlipBounds& bounds,
            const qp::BlockScaling& scaling, const qp::MpgpOptions& qp, bool warm_start,
            PhaseTimes& times);

  /// {"phi": surface nodes}, and for Coulomb {"lambda_n": patches} after it.
  std::vector<outer::StateBlock> layout() const override;
  outer::MapStep apply(int k, const VectorXd& state, VectorXd& image) override;
  std::string stall_hint() const override;

  /// The radii [Pa] at iteration k for a state (those of the first QP for the zero state).
  VectorXd radii(int k, const VectorXd& state) const;
  /// The slips phi [m] of a state (its first block).
  VectorXd slips(const VectorXd& state) const;

  // The state after the last application.
  const VectorXd& lambda() const { return lambda_; }  ///< multipliers [Pa], (n, t1, t2) per patch
  /// Every multiplier of the QP: lambda() and after it the operator's equality multipliers
  /// (dual::DualOperator::n_equality; none but Total FETI's).
  const VectorXd& all_lambda() const { return all_lambda_; }
  const VectorXd& radius() const { return radius_; }  ///< radii of the last QP [Pa]
  /// Displacement of the last QP, exact on the contact dofs only [m].
  const VectorXd& w() const { return w_; }
  /// The last QP's report: MPGP's, or with floating bodies SMALSE-M's totals in MPGP's fields
  /// (iterations and products of all its inner solves, its termination and message).
  const qp::MpgpReport& last_qp() const { return last_qp_; }
  /// With floating bodies (Q.n_motions() > 0): the last SMALSE-M report.
  const qp::SmalseReport& last_smalse() const { return last_smalse_; }
  /// The amplitudes alpha of the floating bodies' free motions after the last QP (-mu of the
  /// equality G lambda = e, theory.md §2.10); empty without floating bodies.
  const VectorXd& alpha() const { return alpha_; }
  /// Called with the certificate when a QP's equality cannot be met (a load that contact cannot
  /// carry); it should throw. Without one, the step fails with the QP's message.
  void set_infeasibility_handler(std::function<void(const qp::Infeasibility&)> handler) {
    on_infeasible_ = std::move(handler);
  }
  /// The feasible set of the QP over all_lambda() (the equality multipliers free).
  const qp::SeparableConstraints& constraints() const { return constraints_; }
  const qp::BlockScaling& scaling() const { return scaling_; }
  /// Starts the next QP from these contact multipliers [Pa] (a warm start from another solve);
  /// the equality multipliers keep their values.
  void set_lambda(const VectorXd& lambda);
  /// The relative tolerance of the QPs from now on (MpgpOptions::rel_tolerance), > 0.
  /// With equality multipliers (Total FETI) the QPs are solved to dual::kEqualityToleranceShare of
  /// it (theory.md §8.6).
  void set_qp_tolerance(Real rel_tolerance);
  /// Measures the slips from a loading path's last step (null: none); must outlive the map.
  void set_history(const SlipHistory* history) { history_ = history; }
  /// The floor `scale` [Pa] of the pressures' norm their change is relative to
  /// (StateBlock::scale of "lambda_n"; theory.md §2.9): along a loading path the largest
  /// ||lambda|| of the earlier steps, so that a step unloaded to lambda = 0 converges; and the
  /// pressure `floor` [Pa] below which a patch is separated (separation_threshold). 0 (a static
  /// run): none.
  void set_pressure_scale(Real scale, Real floor) {
    pressure_scale_ = scale;
    pressure_floor_ = floor;
  }

 private:
  const fe::DofMap& dofs_;
  const contact::ContactDiscretization& disc_;
  /// The QP of outer iteration k with the floating bodies' equality, by SMALSE-M (sets
  /// last_qp_, mu_ and alpha_).
  void solve_with_equality(int k);

  const dual::DualOperator& Q_;
  const contact::SlipBounds& bounds_;
  const qp::BlockScaling& scaling_;
  qp::MpgpOptions qp_;
  bool warm_start_;
  PhaseTimes& times_;
  qp::Operator apply_Q_;
  qp::SeparableConstraints constraints_;
  VectorXd lambda_, all_lambda_, radius_, w_;
  qp::MpgpReport last_qp_;
  qp::SmalseReport last_smalse_;
  VectorXd mu_, alpha_;
  Real norm_projected_ = 0.0;  ///< ||P A P|| of the last SMALSE-M solve (qp::SmalseOptions)
  Index pinned_ = -1;          ///< the discs pinned to zero at that solve
  std::function<void(const qp::Infeasibility&)> on_infeasible_;
  const SlipHistory* history_ = nullptr;
  Real pressure_scale_ = 0.0, pressure_floor_ = 0.0;
};

}  // namespace fricon::driver
