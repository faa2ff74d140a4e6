#pragma once
// contact: the slip bounds of the friction model (theory.md §2.6, §5.6), i.e. how the radius of
// each patch's friction disc follows from the state of the outer loop:
//   tresca   rho_R = (1/|R|) int_R F(phi_h) g dS            (a given slip bound g [Pa]);
//   coulomb  rho_R = lambda_n(R) (1/|R|) int_R F(phi_h) dS  (the patch's own contact pressure).
// One implementation per file (tresca_bounds.cpp, coulomb_bounds.cpp), chosen by FrictionModel.

#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// The friction model ([contact] model).
enum class FrictionModel {
  Tresca,   ///< given slip bound g: the paper's model
  Coulomb,  ///< slip bound F times the contact pressure
};

/// The keys of [contact] that only `model` takes ({"slip_bound"}, {"start_slip_bound"}).
std::span<const std::string_view> friction_model_parameters(FrictionModel model);

class SlipBounds {
 public:
  virtual ~SlipBounds() = default;
  virtual FrictionModel model() const = 0;
  /// Whether the radii depend on the normal multipliers, which the outer loop then iterates on.
  virtual bool uses_pressure() const = 0;
  /// The radii [Pa] per patch at outer iteration k (1-based) for nodal slips phi [m] (per surface
  /// node) and normal multipliers lambda_n [Pa] (per patch; read only if uses_pressure()).
  virtual VectorXd radii(int k, const VectorXd& phi, const VectorXd& lambda_n) const = 0;
  /// The mean coefficient of friction of each patch, (1/|R|) int_R F(phi_h) dS, exact for
  /// piecewise-linear F (radii.hpp).
  VectorXd mean_coefficients(const VectorXd& phi) const;

 protected:
  SlipBounds(const mesh::TetMesh& mesh, const ContactDiscretization& disc, const FrictionLaw& F)
      : mesh_(mesh), disc_(disc), F_(F) {}
  const mesh::TetMesh& mesh_;
  const ContactDiscretization& disc_;
  const FrictionLaw& F_;
};

/// Tresca bounds with the discretization's slip bound g per surface node.
std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactDiscretization& disc,
                                               const FrictionLaw& F);
/// Coulomb bounds. With `start_slip_bound` g0 [Pa], the first outer iteration is the Tresca
/// problem with g = g0 (theory.md §5.6); without, it is the frictionless problem (lambda_n = 0).
std::unique_ptr<SlipBounds> make_coulomb_bounds(const mesh::TetMesh& mesh,
                                                const ContactDiscretization& disc,
                                                const FrictionLaw& F,
                                                std::optional<Real> start_slip_bound);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::FrictionModel, "contact.model",
                  {contact::FrictionModel::Tresca, "tresca"},
                  {contact::FrictionModel::Coulomb, "coulomb"});
