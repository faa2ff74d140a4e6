// contact: Coulomb's slip bounds, rho_R = lambda_n(R) (1/|R|) int_R F(phi_h) dS: the paper's
// (5.3) with g replaced by the patch's own contact pressure (theory.md §5.6).
#include "fricon/contact/radii.hpp"
#include "fricon/contact/slip_bounds.hpp"

namespace fricon::contact {

namespace {

class CoulombBounds final : public LawBounds {
 public:
  CoulombBounds(const mesh::TetMesh& mesh, const ContactSurface& surface, Patches patches,
                const FrictionLaw& F, std::optional<Real> start_slip_bound)
      : LawBounds(mesh, surface, std::move(patches), no_slip_bound_, F), start_(start_slip_bound) {}
  bool uses_pressure() const override { return true; }
  bool coulomb_patch(Index) const override { return true; }

  VectorXd radii(int k, const VectorXd& phi, const VectorXd& lambda_n) const override {
    const VectorXd F_R = mean_coefficients(phi);
    if (k == 1 && start_) return *start_ * F_R;  // the Tresca problem with g = g0
    // A negative normal multiplier is infeasible; it can only come from a stopped QP.
    return F_R.cwiseProduct(lambda_n.cwiseMax(0.0));
  }

 private:
  inline static const VectorXd no_slip_bound_{};  // Coulomb reads no g
  std::optional<Real> start_;
};

}  // namespace

std::unique_ptr<SlipBounds> make_coulomb_bounds(const mesh::TetMesh& mesh,
                                                const ContactSurface& surface, Patches patches,
                                                const FrictionLaw& F,
                                                std::optional<Real> start_slip_bound) {
  return std::make_unique<CoulombBounds>(mesh, surface, std::move(patches), F, start_slip_bound);
}

std::unique_ptr<SlipBounds> make_coulomb_bounds(const mesh::TetMesh& mesh,
                                                const ContactDiscretization& disc,
                                                const FrictionLaw& F,
                                                std::optional<Real> start_slip_bound) {
  return make_coulomb_bounds(mesh, disc.surface, disc.patches, F, start_slip_bound);
}

}  // namespace fricon::contact
