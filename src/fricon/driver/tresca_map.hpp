#pragma once
// driver: the map Psi of the paper's successive approximations (theory.md §5.1), on the nodal
// slips phi of the contact surface: radii from phi (contact/radii.hpp), the dual QP with those
// radii by MPGP warm-started from the previous multipliers (qp/mpgp.hpp), the displacement on the
// contact dofs (dual/dual_operator.hpp), and phi = ||w_t|| at the surface nodes. The outer loop
// (outer/outer_loop.hpp) iterates it.

#include <string>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

class TrescaMap final : public outer::FixedPointMap {
 public:
  /// Every reference must outlive the map. `qp` carries the QP's tolerance, limit, variant,
  /// ||Q|| and monitor; `warm_start` false starts every QP from zero. Phases "qp" and
  /// "recovery" are timed into `times`.
  TrescaMap(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
            const contact::ContactDiscretization& discretization, const dual::DualOperator& Q,
            const contact::FrictionLaw& law, const qp::MpgpOptions& qp, bool warm_start,
            PhaseTimes& times);

  std::vector<outer::StateBlock> layout() const override;
  outer::StepResult apply(int k, const VectorXd& phi, VectorXd& image) override;
  std::string stall_hint() const override;

  /// The radii [Pa] for nodal slips phi [m] (those of the first QP for phi = 0).
  VectorXd radii(const VectorXd& phi) const;

  // The state after the last application.
  const VectorXd& lambda() const { return lambda_; }  ///< multipliers [Pa], (n, t1, t2) per patch
  const VectorXd& radius() const { return radius_; }  ///< radii of the last QP [Pa]
  /// Displacement of the last QP, exact on the contact dofs only [m].
  const VectorXd& w() const { return w_; }
  const qp::MpgpReport& last_qp() const { return last_qp_; }
  const qp::SeparableConstraints& constraints() const { return constraints_; }

 private:
  const mesh::TetMesh& mesh_;
  const fe::DofMap& dofs_;
  const contact::ContactDiscretization& disc_;
  const dual::DualOperator& Q_;
  const contact::FrictionLaw& law_;
  qp::MpgpOptions qp_;
  bool warm_start_;
  PhaseTimes& times_;
  qp::Operator apply_Q_;
  qp::SeparableConstraints constraints_;
  VectorXd lambda_, radius_, w_;
  qp::MpgpReport last_qp_;
};

}  // namespace fricon::driver
