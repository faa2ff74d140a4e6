#include "fricon/driver/tresca_map.hpp"

#include <fmt/format.h>

#include "fricon/contact/radii.hpp"

namespace fricon::driver {

TrescaMap::TrescaMap(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                     const contact::ContactDiscretization& discretization,
                     const dual::DualOperator& Q, const contact::FrictionLaw& law,
                     const qp::MpgpOptions& qp, bool warm_start, PhaseTimes& times)
    : mesh_(mesh),
      dofs_(dofs),
      disc_(discretization),
      Q_(Q),
      law_(law),
      qp_(qp),
      warm_start_(warm_start),
      times_(times),
      apply_Q_(Q.as_qp_operator()),
      constraints_(qp::SeparableConstraints::contact_layout(discretization.n_patches())),
      lambda_(VectorXd::Zero(discretization.n_dual())) {}

std::vector<outer::StateBlock> TrescaMap::layout() const {
  return {{"phi", disc_.surface.n_nodes()}};
}

VectorXd TrescaMap::radii(const VectorXd& phi) const {
  return contact::patch_radii(mesh_, disc_.surface, disc_.patches, law_, phi, disc_.slip_bound);
}

outer::StepResult TrescaMap::apply(int k, const VectorXd& phi, VectorXd& image) {
  // @sect: the Tresca problem with the coefficient frozen at phi, in its dual form.
  radius_ = radii(phi);
  constraints_.set_disc_radii(radius_);
  if (!warm_start_) lambda_.setZero();
  {
    ScopedPhase phase(times_, "qp");
    last_qp_ = qp::solve_mpgp(apply_Q_, Q_.h(), constraints_, qp_, lambda_);
  }
  // @sect: the displacement on the contact surface, and its tangential slip.
  {
    ScopedPhase phase(times_, "recovery");
    Q_.contact_displacement(lambda_, w_);
  }
  image = contact::surface_displacement(disc_.surface, dofs_, w_).slip();

  switch (last_qp_.termination) {
    case qp::Termination::Converged:
      return {};
    case qp::Termination::UserStopped:
      return {outer::StepStatus::Interrupted, last_qp_.message};
    case qp::Termination::MaxIterations:
    case qp::Termination::NumericalFailure:
      break;
  }
  return {
      outer::StepStatus::Failed,
      fmt::format("the dual QP of outer iteration {} did not converge: {}", k, last_qp_.message)};
}

std::string TrescaMap::stall_hint() const {
  return fmt::format(
      "the friction law's Lipschitz constant {:.3g} 1/m may be too large for this problem, or "
      "qp_rtol too loose for outer_tol",
      law_.lipschitz());
}

}  // namespace fricon::driver
