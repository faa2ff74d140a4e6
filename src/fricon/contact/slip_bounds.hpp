#pragma once
// contact: the slip bounds of the friction model (theory.md §2.6, §5.6), i.e. how the radius of
// each patch's friction disc follows from the state of the outer loop:
//   tresca   rho_R = (1/|R|) int_R F(phi_h) g dS            (a given slip bound g [Pa]);
//   coulomb  rho_R = lambda_n(R) (1/|R|) int_R F(phi_h) dS  (the patch's own contact pressure).
// One implementation per file (tresca_bounds.cpp, coulomb_bounds.cpp), chosen by FrictionModel;
// with several contact pairs each pair's patches follow the pair's own model and law
// (pair_bounds.cpp, theory.md §5.7).

#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

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
  /// Whether some radii depend on the normal multipliers, which the outer loop then iterates on.
  virtual bool uses_pressure() const = 0;
  /// The radii [Pa] per patch at outer iteration k (1-based) for nodal slips phi [m] (per surface
  /// node) and normal multipliers lambda_n [Pa] (per patch; read only if uses_pressure()).
  virtual VectorXd radii(int k, const VectorXd& phi, const VectorXd& lambda_n) const = 0;
  /// The mean coefficient of friction of each patch, (1/|R|) int_R F(phi_h) dS, exact for
  /// piecewise-linear F (radii.hpp).
  virtual VectorXd mean_coefficients(const VectorXd& phi) const = 0;
  /// F(slip) at each surface node for nodal slips [m] (per surface node), one batch per law.
  virtual VectorXd nodal_coefficients(const VectorXd& slip) const = 0;
  /// Whether patch p's radius is F times its own pressure (Coulomb): the patches whose result
  /// the Coulomb certificate checks (theory.md §5.6).
  virtual bool coulomb_patch(Index p) const = 0;
  /// The laws F in use, one per pair that has patches, for reports and hints.
  virtual std::vector<const FrictionLaw*> laws() const = 0;
};

/// The bounds of one law F on some patches of a surface: what Tresca and Coulomb share.
class LawBounds : public SlipBounds {
 public:
  VectorXd mean_coefficients(const VectorXd& phi) const override;
  VectorXd nodal_coefficients(const VectorXd& slip) const override;
  std::vector<const FrictionLaw*> laws() const override { return {&F_}; }

 protected:
  /// On the patches `patches` of `surface`, with the nodal slip bounds g [Pa] (per surface node;
  /// read by Tresca only); every reference must outlive the bounds.
  LawBounds(const mesh::TetMesh& mesh, const ContactSurface& surface, Patches patches,
            const VectorXd& g, const FrictionLaw& F)
      : mesh_(mesh), surface_(surface), patches_(std::move(patches)), g_(g), F_(F) {}
  const mesh::TetMesh& mesh_;
  const ContactSurface& surface_;
  const Patches patches_;
  const VectorXd& g_;
  const FrictionLaw& F_;
};

/// Tresca bounds on `patches` of `surface` with the slip bound g [Pa] per surface node.
std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactSurface& surface, Patches patches,
                                               const VectorXd& g, const FrictionLaw& F);
/// Coulomb bounds on `patches` of `surface`. With `start_slip_bound` g0 [Pa], the first outer
/// iteration is the Tresca problem with g = g0 (theory.md §5.6); without, it is the
/// frictionless problem (lambda_n = 0).
std::unique_ptr<SlipBounds> make_coulomb_bounds(const mesh::TetMesh& mesh,
                                                const ContactSurface& surface, Patches patches,
                                                const FrictionLaw& F,
                                                std::optional<Real> start_slip_bound);

/// The same on every patch of a discretization (its slip bound g for Tresca).
std::unique_ptr<SlipBounds> make_tresca_bounds(const mesh::TetMesh& mesh,
                                               const ContactDiscretization& disc,
                                               const FrictionLaw& F);
std::unique_ptr<SlipBounds> make_coulomb_bounds(const mesh::TetMesh& mesh,
                                                const ContactDiscretization& disc,
                                                const FrictionLaw& F,
                                                std::optional<Real> start_slip_bound);

/// The friction of one contact pair: its model, its law F and (Coulomb) the start bound g0 [Pa].
struct PairFriction {
  FrictionModel model = FrictionModel::Tresca;
  std::unique_ptr<FrictionLaw> law;
  std::optional<Real> start_slip_bound;
};

/// The bounds of several contact pairs (theory.md §5.7): the patches and surface nodes of
/// disc's pair i (ContactDiscretization::patch_pair, ContactSurface::node_pair) follow
/// pairs[i]'s model and law; `pairs` has one entry per pair of disc.pairs, and the bounds own the
/// laws. A pair without patches in `disc` (a contact search left them out) is skipped.
std::unique_ptr<SlipBounds> make_pair_bounds(const mesh::TetMesh& mesh,
                                             const ContactDiscretization& disc,
                                             std::vector<PairFriction> pairs);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::FrictionModel, "contact.model",
                  {contact::FrictionModel::Tresca, "tresca"},
                  {contact::FrictionModel::Coulomb, "coulomb"});
