#pragma once
// driver: the frictional contact solve on a factored model (theory.md §3-5), as named steps:
//   the friction law and ||Q||  ->  the successive approximations of Tresca problems
//   (driver/tresca_map.hpp iterated by outer/outer_loop.hpp)  ->  the displacement of the whole
//   body and the certificate of the final QP  ->  the paper's measures of the result.
// The contact discretization and the dual operator are built before (driver/run.cpp) and passed
// in, so that any operator (a test's too) can be plugged in.

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/contact/slip_bounds.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/driver/run_options.hpp"
#include "fricon/driver/tresca_map.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/dual_problem.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

/// A run whose final KKT residuals exceed this multiple of qp_rtol is not converged
/// (theory.md §5.5): the QP's own stopping test would put them below about qp_rtol.
inline constexpr Real kCertificateFactor = 100.0;
/// A Coulomb fixed point whose natural-map residual exceeds solver.certificate_tol takes further
/// steps with the QP and outer tolerances divided by this, warm-started (theory.md §5.6)...
inline constexpr Real kCertificateRefinementFactor = 1e-2;
/// ... at most this many times; a run still above is not converged ("certificate failed").
inline constexpr int kMaxCertificateRefinements = 3;

/// How a patch ends up (patches.csv, contact.vtu).
enum class PatchState {
  Separated,  ///< no contact pressure (lambda_n = 0)
  Stick,      ///< ||lambda_t|| below the radius
  Slip,       ///< ||lambda_t|| on the radius
};

/// One contact pair of the result: its discretization's description and what the solve found.
struct PairReport {
  contact::PairInfo info;  ///< surfaces, frame, stability, reach of the master
  Index n_patches = 0;
  Index n_stick = 0, n_slip = 0, n_separated = 0;
  /// The pair's own friction model and law (theory.md §5.7), as ContactReport describes them.
  contact::FrictionModel model = contact::FrictionModel::Tresca;
  std::string friction_law;
  Real normal_force = 0.0;  ///< sum lambda_n |R| [N]
  /// The force of the obstacle (plane or master) on the contact surface [N], and its part
  /// tangential to the patches.
  Vec3 force = Vec3::Zero();
  Vec3 tangential_force = Vec3::Zero();
  /// Max relative tangential displacement [m] at the nodes of the patches in contact; along a
  /// loading path the largest over the steps done (theory.md §2.8).
  Real max_slip = 0.0;
  /// The step of a loading path (1-based) at which max_slip was reached; 0 in a static run.
  int max_slip_step = 0;
  /// Small sliding holds: max_slip is at most kSmallSlidingShare of the master's element size
  /// (the pairing, computed once, stays valid); along a path, at every step.
  bool small_sliding = true;
  /// Against a body: the largest penetration [m] of a master node into the slave surface after
  /// the solve (contact::master_penetration; the constraints keep only the slave out of the
  /// master), and the scale it is compared with: the largest displacement of the two surfaces
  /// along their normals [m] (theory.md §2.8).
  Real master_penetration = 0.0;
  Real normal_displacement = 0.0;
  /// master_penetration is at most kMasterPenetrationShare of normal_displacement: the master's
  /// mesh is not too fine for the slave's (the slave should be the finer surface).
  bool master_kept_out = true;
};

/// The share of a pair's normal displacement up to which the master may penetrate the slave
/// (PairReport::master_penetration): beyond, the master is too fine for the slave's patches to
/// hold it out, and the surfaces should be swapped (theory.md §2.8).
inline constexpr Real kMasterPenetrationShare = 0.1;

/// The share of the master's element size up to which the relative tangential displacement
/// keeps the reference pairing valid (small sliding, theory.md §2.8).
inline constexpr Real kSmallSlidingShare = 0.5;

/// Whether a relative tangential displacement `max_slip` [m] keeps the pair's reference pairing
/// valid: at most kSmallSlidingShare of the master's element size (always against a plane).
bool within_small_sliding(const contact::PairInfo& pair, Real max_slip);

struct ContactReport {
  /// The friction model of every pair; with pairs of different models (mixed_models) Coulomb,
  /// whose certificate then covers the Coulomb pairs (each pair's own in `pairs`).
  contact::FrictionModel model = contact::FrictionModel::Tresca;
  bool mixed_models = false;  ///< the pairs do not all have one model
  std::string boundary;
  /// The law of every pair (FrictionLaw::describe); with laws that differ, each pair's, joined
  /// by "; " and prefixed by the pair's key.
  std::string friction_law;
  dual::DualOperatorKind dual_operator = dual::DualOperatorKind::Auto;  ///< the one used
  Index n_patches = 0;
  Index n_dual = 0;  ///< 3 n_patches (the paper's n_d)
  /// Patches in the last QP (theory.md §2.7): n_patches without a contact search.
  Index n_candidate_patches = 0;
  /// Solves of the contact search: 1 when the first candidates were enough, 1 more for each
  /// growth of the set; 0 without a search.
  int search_rounds = 0;
  Index n_surface_nodes = 0;
  Index n_contact_nodes = 0;         ///< surface nodes whose normal displacement is free
  Real stability_ratio = 0.0;        ///< sigma_min / sigma_max of B (condition (5.1))
  bool stability_estimated = false;  ///< by power/inverse iteration rather than exactly
  /// Multiplier components whose direction Dirichlet conditions fix on the whole patch: they act
  /// on nothing and stay zero (contact::StabilityReport::n_inactive).
  Index n_inactive_multipliers = 0;
  std::string radius_integration;  ///< how the radii were integrated
  Real norm_Q = 0.0;               ///< power-method estimate of ||Q|| [m^3/Pa]
  /// Power-method estimate of ||D Q D|| (theory.md §4.5; = norm_Q without scaling), whose
  /// reciprocal sets the QP's fixed step length [dimensionless with the patch factors].
  Real norm_Q_scaled = 0.0;
  /// How the partition was made stable (ContactDiscretization::partition_note; may be empty).
  std::string partition_note;
  outer::OuterTermination termination = outer::OuterTermination::IterationLimit;
  int outer_iterations = 0;
  long n_mult = 0;                ///< products with Q over all QPs (the paper's n_mult)
  long qp_iterations = 0;         ///< MPGP steps over all QPs
  qp::MpgpSteps qp_steps;         ///< the same by kind
  long n_kinv = 0;                ///< solves with the factor of K, all of them
  int n_objective_increases = 0;  ///< over all QPs (expected 0)
  std::vector<Real> err_history;
  std::vector<IterationReport> history;
  // The paper's measures of the last iterate (theory.md §6.4), with w_n = w.n on the surface:
  /// ||max(0, w_n - gap)|| in L2(surface), the face element's interpolant [m^2] (the penetration;
  /// w_n at zero gap)
  Real wn_pos_l2 = 0.0;
  Real wn_pos_inf = 0.0;    ///< max over surface nodes of max(0, w_n - gap) [m]
  Real max_neg_wn = 0.0;    ///< max of gap - w_n (the largest opening) [m]
  Real max_wt = 0.0;        ///< max ||w_t|| [m]
  Real max_lambda_n = 0.0;  ///< [Pa]
  Real max_lambda_t = 0.0;  ///< max ||lambda_t|| [Pa]
  /// The normal force [N]: sum lambda_n |R_p|, the resultant of the contact pressure over the
  /// patches (theory.md §6.1).
  Real total_normal_force = 0.0;
  /// The part of total_normal_force [N] that acts on free displacement components of the
  /// contact surface: the contact force that the body's loads and reactions balance. The rest
  /// acts on components with a prescribed displacement and goes straight into their supports
  /// (it is among the reactions); equal to total_normal_force where no contact node has a
  /// prescribed component along its patch's normal (theory.md §6.1).
  Real transmitted_normal_force = 0.0;
  /// Of the last QP, with g = Q lambda - h through a fresh solve with K (the certificate).
  qp::KktResiduals kkt;
  Real kkt_bound = 0.0;  ///< kCertificateFactor * qp_rtol: the certificate's bound on kkt.max()
  /// Coulomb only: the natural-map residual of the Coulomb problem at the result
  /// (qp::coulomb_residual, with mu_R from the returned slips) over the patches of the Coulomb
  /// pairs, and its bound.
  Real coulomb_residual = 0.0;
  Real coulomb_bound = 0.0;
  /// The floor [Pa] of the multipliers' scale (PathStep::lambda_scale; 0 in a static run): what
  /// coulomb_residual is relative to besides ||lambda||.
  Real lambda_scale = 0.0;
  /// The pressure [Pa] below which a patch counts as separated besides round-off of the largest
  /// lambda_n (separation_threshold): outer_tol times lambda_scale, the accuracy of a path
  /// step's pressures (theory.md §2.9); 0 in a static run.
  Real pressure_floor = 0.0;
  /// Floating bodies (theory.md §2.10; empty or 0 without): the amplitudes of their free motions
  /// at the result (the columns of Model::floating.R) [m or rad]; the motions no contact force
  /// resists (columns over those motions, qp::SmalseReport::undetermined); the relative residual
  /// qp::equality_residual of G lambda = e at the certificate and its bound; and the outer
  /// steps of SMALSE-M over all QPs.
  VectorXd rigid_amplitudes;
  MatrixXd undetermined_motions;
  Real equality_residual = 0.0;
  Real equality_bound = 0.0;
  long smalse_outer_iterations = 0;
  long coarse_solves = 0;  ///< solves with the coarse problem G G^T over all QPs (SMALSE-M)
  double coarse_s = 0.0;   ///< their wall time and that of its decompositions [s]
  /// Backend "tfeti" (theory.md §8.6): the violation of the gluing and Dirichlet rows by the
  /// result, its root mean square relative to that of the displacement; certified against
  /// kkt_bound. 0 otherwise.
  Real gluing_residual = 0.0;
  /// Against a curved rigid obstacle (theory.md §2.11): the geometric updates made (solves
  /// again at the deformed position) and, at the result, the largest difference between the
  /// linearized and the true gap of a node in contact [m], the largest normal displacement there
  /// [m] and the share of it allowed (contact.geometry_tolerance); -1 updates: no curved obstacle.
  int geometry_updates = -1;
  Real geometry_change = 0.0;
  Real geometry_scale = 0.0;
  Real geometry_tolerance = 0.0;
  /// Rounds of further steps at tighter tolerances that the Coulomb certificate needed.
  int certificate_refinements = 0;
  /// Per outer iteration, the relative change of each block of the state (phi; lambda_n).
  std::vector<std::vector<Real>> block_history;
  std::vector<std::string> state_blocks;           ///< the names of those blocks
  Index n_stick = 0, n_slip = 0, n_separated = 0;  ///< patches in each PatchState
  /// ||Psi(phi) - phi|| / ||phi|| at the returned phi (the last err(k)).
  Real fixed_point_residual = 0.0;
  /// Observed contraction factor of the successive approximations (outer::OuterReport).
  Real contraction_ratio = 0.0;
  std::vector<PairReport> pairs;  ///< per contact pair, in the problem's order
};

/// Fields on the contact surface, per surface node and per patch.
struct ContactFields {
  contact::ContactSurface surface;
  contact::Patches patches;
  contact::Frames patch_frames;   ///< per patch: the frame of its multipliers
  std::vector<Index> patch_pair;  ///< per patch: its pair (ContactReport::pairs)
  VectorXd lambda;                ///< multipliers (lambda_n, lambda_t1, lambda_t2) per patch [Pa]
  VectorXd radius;                ///< slip bounds rho_p used by the last QP [Pa]
  VectorXd phi;                   ///< phi per surface node used for the last radii [m]
  VectorXd gap;                   ///< initial gap per surface node [m] (ContactDiscretization)
  VectorXd wn, wt1, wt2;          ///< components of the displacement w per surface node [m]
  /// The slip the coefficient is evaluated at, per surface node [m]: ||w_t||, along a loading
  /// path the accumulated slip (theory.md §2.9).
  VectorXd slip;
  VectorXd F;                     ///< F(slip) per surface node
  VectorXd slip_bound;            ///< g per surface node [Pa]
  VectorXd coefficient;           ///< per patch: F_R = (1/|R|) int_R F(||w_t||) dS of the result
  std::vector<PatchState> state;  ///< per patch
};

struct ContactOutcome {
  bool converged = false;
  std::string message;
  ContactReport report;
  ContactFields fields;
  VectorXd w;  ///< displacement over the free dofs of the last inner solve [m]
  Vec3 contact_force = Vec3::Zero();  ///< -sum of B^T lambda over free dofs, per direction [N]
  /// The sum over the nodes of the magnitudes of the nodal forces -B^T lambda [N].
  Real contact_force_magnitude = 0.0;
  /// ||K w - f + B^T lambda|| / max(||f||, ||B^T lambda||) (absolute when both are 0)
  Real linear_residual = 0.0;
  std::optional<qp::DualProblem> first_dual;  ///< if RunOptions::keep_first_dual
};

/// A contact search's view of a solve (theory.md §2.7): the discretization of every patch and
/// the patches of the one solved (contact::restrict_to_patches of it).
struct PatchSelection {
  const contact::ContactDiscretization& whole;
  const std::vector<Index>& patches;  ///< increasing indices into whole's patches
  int round = 1;                      ///< the search's solve this is (ContactReport::search_rounds)
};

/// What a step of a loading path brings to the contact solve (theory.md §2.9).
struct PathStep {
  const SlipHistory* history = nullptr;  ///< the slips are measured from the last step
  /// The first multipliers [Pa] (a prediction from the last steps, pressures non-negative): the
  /// first QP starts from them (with solver.warm_start), and for Coulomb the first radii take
  /// their pressures. Null: zero.
  const VectorXd* lambda = nullptr;
  /// The first slips of the outer loop [m] per surface node (a prediction: the last step's
  /// accumulated slip plus its increment); null: the accumulated slip (a zero increment).
  const VectorXd* predicted_slip = nullptr;
  /// ||Q|| and ||D Q D|| of the path's operator, estimated at its first step; 0: estimate them.
  Real norm_Q = 0.0, norm_Q_scaled = 0.0;
  /// The largest ||lambda|| [Pa] of the earlier steps: the floor of the multipliers' norm that
  /// the pressures' change (err(k)) and the Coulomb certificate are relative to, so that a step
  /// unloaded to lambda = 0 is not measured against its own vanishing multipliers (theory.md
  /// §2.9); 0: none.
  Real lambda_scale = 0.0;
};

/// Runs the contact solve for `problem.contact` on the factored model with the contact
/// discretization `disc` and the dual operator `Q` built on them; phases are timed into `times`
/// ("dual", "qp", "recovery", "postprocess"). With a `selection`, `disc` is the part of
/// selection->whole on its patches, and the outcome is that of the whole: the patches left out
/// with zero multipliers, the certificate and the measures over every patch. Non-convergence
/// (including a failed certificate) is returned, not thrown. A `step` of a loading path brings
/// the history the friction acts on (with a selection too: its multipliers are then those of
/// the selected patches, its slips those of every surface node).
ContactOutcome solve_contact(const Problem& problem, const Model& model,
                             const contact::ContactDiscretization& disc,
                             const dual::DualOperator& Q, PhaseTimes& times,
                             const RunOptions& options = {},
                             const PatchSelection* selection = nullptr,
                             const PathStep* step = nullptr);

/// The slip bounds on the discretization: the patches of each pair (disc.pairs, in the order of
/// problem.contact) by the pair's own model and law, which the bounds own (theory.md §5.7).
std::unique_ptr<contact::SlipBounds> make_slip_bounds(const Problem& problem,
                                                      const mesh::TetMesh& mesh,
                                                      const contact::ContactDiscretization& disc);

}  // namespace fricon::driver

FRICON_ENUM_NAMES(fricon::driver::PatchState, "patch state",
                  {driver::PatchState::Separated, "separated"},
                  {driver::PatchState::Stick, "stick"}, {driver::PatchState::Slip, "slip"});
