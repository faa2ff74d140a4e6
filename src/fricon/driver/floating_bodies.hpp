#pragma once
// driver: the bodies of a model in words, for `fricon check`, the summary and report.json, and
// the refusal of a load that contact cannot carry (theory.md §2.10). A floating body's free
// motions are found from its Dirichlet conditions (fe/floating.hpp); their amplitudes come from
// the multipliers of the dual QP's equality G lambda = e (dual/dual_operator.hpp).

#include <string>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/core/error.hpp"
#include "fricon/core/types.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::driver {

/// One connected body of the mesh.
struct BodyReport {
  Index index = 0;
  std::string description;  ///< mesh::describe_body: regions, node count, bounding box
  /// Its free rigid motions (fe::describe_motion), empty for a body its Dirichlet conditions
  /// hold.
  std::vector<std::string> free_motions;
  /// After a solve: the amplitude of each free motion [m of a translation, rad of a rotation]
  /// in the body's displacement, its rigid part (the least-squares fit of the free motions to the
  /// displacement over the body's free dofs); empty before.
  std::vector<Real> amplitudes;
  /// Motions that no contact force resists (frictionless contact leaves the sliding motions
  /// free): the solution takes the one of least norm, zero amplitude in them.
  std::vector<std::string> undetermined;
};

/// One line of text for a body: held by its Dirichlet conditions, or floating with its free
/// motions (and their amplitudes after a solve, and which are undetermined).
std::string body_line(const BodyReport& body);

/// Every body of the model, with the free motions of those that float.
std::vector<BodyReport> describe_bodies(const Model& model);

/// describe_bodies with the amplitudes of the free motions in the displacement u [m] over the
/// free dofs, and the undetermined motions (columns over the free motions,
/// qp::SmalseReport::undetermined; empty: none).
std::vector<BodyReport> describe_bodies(const Model& model, const VectorXd& u,
                                        const MatrixXd& undetermined);

/// The check, before any factorization, that contact can balance the load on the floating bodies
/// of `model` (theory.md §2.10): with frictionless or Tresca pairs only, whose slip bounds at zero
/// slip are known, and in a static run (a loading path's loads change with the step), G = R^T B^T
/// and e = R^T f need no solve with K, and phase one (qp::balance_certificate) decides. Throws
/// UnbalancedLoad as refuse_unbalanced_load does; a load it passes may still be refused by the
/// solve (a slip bound that weakens with the slip, Coulomb's pressures).
void check_balance(const Problem& problem, const Model& model,
                   const contact::ContactDiscretization& disc);

/// The InputError of a load that contact cannot carry (a contact search that left patches out
/// catches it and tries every patch).
class UnbalancedLoad : public InputError {
 public:
  using InputError::InputError;
};

/// Throws UnbalancedLoad for a load that contact cannot carry, from the certificate of the QP's
/// infeasible equality: the body, the free motion along which the load exceeds what contact and
/// friction can carry, and the two figures (a force [N] or a moment [N m]).
[[noreturn]] void refuse_unbalanced_load(const Problem& problem, const Model& model,
                                         const qp::Infeasibility& certificate);

}  // namespace fricon::driver
