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

VectorXd SlipBounds::mean_coefficients(const VectorXd& phi) const {
  return patch_radii(mesh_, disc_.surface, disc_.patches, F_, phi,
                     VectorXd::Ones(disc_.surface.n_nodes()));
}

namespace {

class TrescaBounds final : public SlipBounds {
 public:
  TrescaBounds(const mesh::TetMesh& mesh, const ContactDiscretization& disc, const FrictionLaw& F)
      : SlipBounds(mesh, disc, F) {}
  FrictionModel model() const override { return FrictionModel::Tresca; }
  bool uses_pressure() const override { return false; }
  VectorXd radii(int, const VectorXd& phi, const VectorXd&) const override {
    return patch_radii(mesh_, disc_.surface, disc_.patches, F_, phi, disc_.slip_bound);
  }
};

}  // namespace

std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactDiscretization& disc,
                                               const FrictionLaw& F) {
  return std::make_unique<TrescaBounds>(mesh, disc, F);
}

}  // namespace fricon::contact
