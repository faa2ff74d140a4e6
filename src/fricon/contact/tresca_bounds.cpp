// contact: Tresca's slip bounds, rho_R = (1/|R|) int_R F(phi_h) g_h dS (theory.md §2.6).
#include "fricon/contact/radii.hpp"
#include "fricon/contact/slip_bounds.hpp"

namespace fricon::contact {

std::span<const std::string_view> friction_model_parameters(FrictionModel model) {
  static constexpr std::array<std::string_view, 1> kTresca{"slip_bound"},
      kCoulomb{"start_slip_bound"};
  return model == FrictionModel::Tresca ? std::span<const std::string_view>(kTresca)
                                        : std::span<const std::string_view>(kCoulomb);
}

VectorXd LawBounds::mean_coefficients(const VectorXd& phi) const {
  return patch_radii(mesh_, surface_, patches_, F_, phi, VectorXd::Ones(surface_.n_nodes()));
}

VectorXd LawBounds::nodal_coefficients(const VectorXd& slip) const {
  VectorXd F(slip.size());
  F_.evaluate(std::span<const Real>(slip.data(), static_cast<size_t>(slip.size())),
              std::span<Real>(F.data(), static_cast<size_t>(F.size())));
  return F;
}

namespace {

class TrescaBounds final : public LawBounds {
 public:
  TrescaBounds(const mesh::TetMesh& mesh, const ContactSurface& surface, Patches patches,
               const VectorXd& g, const FrictionLaw& F)
      : LawBounds(mesh, surface, std::move(patches), g, F) {}
  bool uses_pressure() const override { return false; }
  bool coulomb_patch(Index) const override { return false; }
  VectorXd radii(int, const VectorXd& phi, const VectorXd&) const override {
    return patch_radii(mesh_, surface_, patches_, F_, phi, g_);
  }
};

}  // namespace

std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactSurface& surface, Patches patches,
                                               const VectorXd& g, const FrictionLaw& F) {
  return std::make_unique<TrescaBounds>(mesh, surface, std::move(patches), g, F);
}

std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactDiscretization& disc,
                                               const FrictionLaw& F) {
  return make_tresca_bounds(mesh, disc.surface, disc.patches, disc.slip_bound, F);
}

}  // namespace fricon::contact
