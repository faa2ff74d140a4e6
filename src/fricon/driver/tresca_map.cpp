#include "fricon/driver/tresca_map.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::driver {

namespace {
// The relative residual of G lambda = e asked of SMALSE-M, as a share of qp_rtol: the precision
// the gradient test gives it (theory.md §4.6).
constexpr Real kEqualityShare = 1.0;
}  // namespace

VectorXd SlipHistory::slips(const contact::SurfaceDisplacement& d,
                            const std::vector<bool>& in_contact) const {
  // The increment since the last step (the first step's from the zero state), counted only
  // where the node is in contact.
  VectorXd s = empty() ? d.slip() : VectorXd(accumulated);
  for (Index k = 0; k < s.size(); ++k) {
    const bool touching = in_contact.empty() || in_contact[static_cast<size_t>(k)];
    if (empty())
      s(k) = touching ? s(k) : 0.0;
    else if (touching)
      s(k) += std::hypot(d.wt1(k) - wt1(k), d.wt2(k) - wt2(k));
  }
  return s;
}

Real separation_threshold(Real largest_lambda_n, Real pressure_floor) {
  return std::max(kContactPressureShare * largest_lambda_n, pressure_floor);
}

std::vector<bool> nodes_in_contact(const contact::ContactDiscretization& disc,
                                   const VectorXd& lambda, bool uses_pressure,
                                   Real pressure_floor) {
  if (!uses_pressure) return {};
  Real largest = 0.0;
  for (Index p = 0; p < disc.n_patches(); ++p)
    largest = std::max(largest, lambda(3 * p));
  const Real threshold = separation_threshold(largest, pressure_floor);
  std::vector<bool> in_contact(static_cast<size_t>(disc.surface.n_nodes()), false);
  for (Index p = 0; p < disc.n_patches(); ++p) {
    if (!(lambda(3 * p) > threshold)) continue;
    for (Index face : disc.patches.faces[static_cast<size_t>(p)])
      for (Index v = 0; v < disc.surface.face_nodes.rows(); ++v)
        in_contact[static_cast<size_t>(disc.surface.face_nodes(v, face))] = true;
  }
  return in_contact;
}

TrescaMap::TrescaMap(const fe::DofMap& dofs, const contact::ContactDiscretization& discretization,
                     const dual::DualOperator& Q, const contact::SlipBounds& bounds,
                     const qp::BlockScaling& scaling, const qp::MpgpOptions& qp, bool warm_start,
                     PhaseTimes& times)
    : dofs_(dofs),
      disc_(discretization),
      Q_(Q),
      bounds_(bounds),
      scaling_(scaling),
      qp_(qp),
      warm_start_(warm_start),
      times_(times),
      apply_Q_(Q.as_qp_operator()),
      constraints_(qp::SeparableConstraints::contact_layout(discretization.n_patches())),
      lambda_(VectorXd::Zero(discretization.n_dual())),
      all_lambda_(VectorXd::Zero(Q.size())) {
  // The operator's equality multipliers (Total FETI's gluing and Dirichlet rows) follow the
  // contact ones, free of any bound (theory.md §8.3).
  FRICON_CHECK(Q.n_contact() == discretization.n_dual() && scaling.size() == Q.size(),
               "an operator of " << Q.n_contact() << " contact multipliers and a scaling of "
                                 << scaling.size() << " for " << discretization.n_dual());
  constraints_.append_free(Q.n_equality());
  if (Q.n_equality() > 0) qp_.power_tolerance = dual::kEqualityPowerTolerance;
  set_qp_tolerance(qp.rel_tolerance);
}

void TrescaMap::set_qp_tolerance(Real rel_tolerance) {
  qp_.rel_tolerance =
      Q_.n_equality() > 0 ? dual::kEqualityToleranceShare * rel_tolerance : rel_tolerance;
}

void TrescaMap::set_lambda(const VectorXd& lambda) {
  FRICON_CHECK(lambda.size() == lambda_.size(),
               "lambda of " << lambda.size() << " for " << lambda_.size() << " multipliers");
  lambda_ = lambda;
  all_lambda_.head(lambda_.size()) = lambda_;
}

std::vector<outer::StateBlock> TrescaMap::layout() const {
  std::vector<outer::StateBlock> blocks{{"phi", disc_.surface.n_nodes()}};
  if (bounds_.uses_pressure()) blocks.push_back({"lambda_n", disc_.n_patches(), pressure_scale_});
  return blocks;
}

VectorXd TrescaMap::slips(const VectorXd& state) const {
  return state.head(disc_.surface.n_nodes());
}

VectorXd TrescaMap::radii(int k, const VectorXd& state) const {
  const VectorXd lambda_n = bounds_.uses_pressure() ? VectorXd(state.tail(disc_.n_patches()))
                                                    : VectorXd::Zero(disc_.n_patches());
  return bounds_.radii(k, slips(state), lambda_n);
}

void TrescaMap::solve_with_equality(int k) {
  // The first step of Coulomb's iteration (every radius 0) balances only what pressure can; the
  // pressures it finds start the iteration (theory.md §5.8).
  qp::SmalseOptions options;
  options.drop_unresisted_load = k == 1 && bounds_.uses_pressure() && radius_.maxCoeff() <= 0.0;
  // The balance as precise as the QP's gradient test (theory.md §4.6).
  options.equality_tolerance = kEqualityShare * qp_.rel_tolerance;
  if (Q_.n_equality() > 0) {
    options.rho_factor = dual::kEqualityPenaltyFactor;
    options.projected_norm = true;
  }
  if (!warm_start_) mu_.resize(0);
  // ||P A P|| once for a projector: it changes only with the discs pinned to zero.
  const auto pinned = static_cast<Index>((radius_.array() == 0.0).count());
  if (pinned != pinned_) norm_projected_ = 0.0;
  options.norm_projected = norm_projected_;
  // On the multipliers this process holds (all of them but under Total FETI's MPI, theory.md
  // §8.8).
  last_smalse_ = dual::solve_shared_smalse(Q_, constraints_, scaling_, {Q_.G(), Q_.e()}, options,
                                           qp_, all_lambda_, mu_);
  alpha_ = -mu_;
  norm_projected_ = last_smalse_.norm_projected;
  pinned_ = pinned;
  if (last_smalse_.infeasible && on_infeasible_) on_infeasible_(last_smalse_.infeasibility);
  last_qp_ = last_smalse_.last_inner;
  last_qp_.termination = last_smalse_.termination;
  last_qp_.message = last_smalse_.message;
  last_qp_.iterations = last_smalse_.iterations;
  last_qp_.n_cg = static_cast<int>(last_smalse_.steps.cg);
  last_qp_.n_expansion = static_cast<int>(last_smalse_.steps.expansion);
  last_qp_.n_proportioning = static_cast<int>(last_smalse_.steps.proportioning);
  last_qp_.n_products = last_smalse_.n_products;
}

outer::MapStep TrescaMap::apply(int k, const VectorXd& state, VectorXd& image) {
  // @sect: the Tresca problem with the slip bounds frozen at the state, in its dual form.
  radius_ = radii(k, state);
  constraints_.set_disc_radii(radius_);
  if (!warm_start_) all_lambda_.setZero();
  {
    ScopedPhase phase(times_, "qp");
    if (Q_.n_motions() == 0)
      last_qp_ = qp::solve_mpgp_scaled(apply_Q_, Q_.h(), constraints_, scaling_, qp_, all_lambda_);
    else
      solve_with_equality(k);
    lambda_ = all_lambda_.head(lambda_.size());
  }
  // @sect: the displacement on the contact surface (with the floating bodies' rigid motions),
  // and its tangential slip.
  {
    ScopedPhase phase(times_, "recovery");
    Q_.contact_displacement(all_lambda_, w_);
    if (Q_.n_motions() > 0) w_ += Q_.rigid_displacement(alpha_);
  }
  // @sect: the new state: the slips, and for Coulomb the new pressures.
  const contact::SurfaceDisplacement d = contact::surface_displacement(disc_.surface, dofs_, w_);
  const VectorXd phi =
      history_ ? history_->slips(
                     d, nodes_in_contact(disc_, lambda_, bounds_.uses_pressure(), pressure_floor_))
               : d.slip();
  image.resize(state.size());
  image.head(phi.size()) = phi;
  if (bounds_.uses_pressure())
    for (Index p = 0; p < disc_.n_patches(); ++p)
      image(phi.size() + p) = lambda_(3 * p);

  switch (last_qp_.termination) {
    case qp::QpTermination::Converged:
      return {};
    case qp::QpTermination::UserStopped:
      return {outer::StepStatus::Interrupted, last_qp_.message};
    case qp::QpTermination::MaxIterations:
    case qp::QpTermination::NumericalFailure:
      break;
  }
  return {
      outer::StepStatus::Failed,
      fmt::format("the dual QP of outer iteration {} did not converge: {}", k, last_qp_.message)};
}

std::string TrescaMap::stall_hint() const {
  // The law that limits the contraction: one of unknown Lipschitz constant (an expression or
  // function law, lipschitz() NaN) first, else the one of the largest constant.
  const contact::FrictionLaw* worst = nullptr;
  for (const contact::FrictionLaw* law : bounds_.laws())
    if (!worst || !std::isfinite(law->lipschitz()) ||
        (std::isfinite(worst->lipschitz()) && law->lipschitz() > worst->lipschitz()))
      worst = law;
  if (!worst) return "qp_rtol may be too loose for outer_tol";
  // A constant coefficient does not vary with the slip: only the Coulomb coupling of the radii
  // to the pressures is left to blame (theory.md §5.6).
  if (worst->lipschitz() == 0.0)
    return bounds_.uses_pressure()
               ? fmt::format(
                     "with the constant coefficient {} the Coulomb problem may have several "
                     "solutions or its successive approximations may not contract (a large "
                     "coefficient), or qp_rtol is too loose for outer_tol",
                     worst->describe())
               : "qp_rtol may be too loose for outer_tol";
  if (!std::isfinite(worst->lipschitz()))
    return fmt::format(
        "the friction law {} may vary too fast with the slip for the successive approximations "
        "to contract (its Lipschitz constant is not known), or qp_rtol too loose for outer_tol",
        worst->describe());
  return fmt::format(
      "the friction law's Lipschitz constant {:.3g} 1/m may be too large for this problem, or "
      "qp_rtol too loose for outer_tol",
      worst->lipschitz());
}

}  // namespace fricon::driver
