#pragma once
// driver: one whole run of a problem, in the order of the data flow (theory.md §2-5):
//   validate -> mesh, assembly -> [contact discretization] -> factorization (as the dual operator
//   asks) -> [dual operator -> outer loop of dual QPs -> certificate] -> displacement, stresses
//   and the self-check of the result.
// The run returns everything the output stage writes; it never writes files itself. This is the
// run on one process (CHOLMOD); fricon::solve (solve.hpp) chooses between it and the
// distributed run of parallel/.

#include <optional>
#include <string>
#include <vector>

#include "fricon/core/timer.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/floating_bodies.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/parallel/report.hpp"

namespace fricon::driver {

/// The outcome of a run as the report and the exit code give it.
enum class RunStatus { Converged, NotConverged };

/// One step of a loading path (theory.md §2.9), as steps.csv and report.json "steps" give it.
struct StepReport {
  int step = 0;               ///< 1-based
  std::vector<Real> factors;  ///< the factor of each load with a path (driver::path_loads)
  RunStatus status = RunStatus::Converged;
  std::string message;                   ///< why the step failed (empty when converged)
  Real normal_force = 0.0;               ///< sum over the patches of lambda_n |R| [N]
  Vec3 tangential_force = Vec3::Zero();  ///< friction force of the obstacles on the body [N]
  Vec3 contact_force = Vec3::Zero();     ///< RunReport::contact_force [N]
  Vec3 reaction_force = Vec3::Zero();    ///< RunReport::reaction_force [N]
  Vec3 applied_force = Vec3::Zero();     ///< RunReport::applied_force [N]
  /// Per load with a path: the mean displacement of its boundary's nodes [m] (zero for the
  /// volume force).
  std::vector<Vec3> load_displacement;
  Real max_slip = 0.0;              ///< max ||w_t|| over the surface nodes [m]
  Real max_accumulated_slip = 0.0;  ///< max of the accumulated slip s [m]
  Index n_stick = 0, n_slip = 0, n_separated = 0;
  int outer_iterations = 0;
  long n_mult = 0;                  ///< products with Q in this step
  Real equilibrium_residual = 0.0;  ///< RunReport::equilibrium_residual
  Real kkt = 0.0;                   ///< the largest KKT residual of the step's last QP
  double time_s = 0.0;              ///< wall time of the step [s]
};

/// What a run reports (the JSON report serialises this struct).
struct RunReport {
  RunStatus status = RunStatus::Converged;
  std::string message;
  Index n_nodes = 0, n_tets = 0;
  int nodes_per_tet = 4;              ///< 4 (linear) or 10 (quadratic tetrahedra, theory.md §2.12)
  Index n_primal = 0;                 ///< free displacement dofs (the paper's n_p)
  linalg::CholeskyInfo factor;        ///< size, fill and ordering of the Cholesky factor of K
  PhaseTimes times;                   ///< wall time per phase [s]
  double time_s = 0.0;                ///< total wall time of the run [s]
  Real max_displacement = 0.0;        ///< max over nodes of |u| [m]
  Vec3 applied_force = Vec3::Zero();  ///< sum of applied loads [N]
  Vec3 reaction_force = Vec3::Zero();  ///< sum of reactions at fixed dofs [N]
  Vec3 contact_force =
      Vec3::Zero();  ///< sum of contact forces on the body [N] (zero without contact)
  /// The sum over the nodes of the magnitudes of the contact's nodal forces [N] (zero without
  /// contact).
  Real contact_force_magnitude = 0.0;
  /// The sum over the nodes of the magnitudes of the applied, contact and reaction forces [N]:
  /// the scale of equilibrium_residual. Unlike their resultants it cannot cancel (a bar pulled
  /// by a prescribed displacement has two large reactions whose sum is round-off).
  Real force_scale = 0.0;
  /// |applied + contact + reaction| / force_scale: global equilibrium, round-off if all is well.
  Real equilibrium_residual = 0.0;
  /// ||K u - (f - B^T lambda)|| / max(||f||, ||B^T lambda||) (absolute when both are 0)
  Real linear_residual = 0.0;
  std::optional<ContactReport> contact;  ///< present when the problem has a [contact] section
  std::optional<parallel::ParallelReport> parallel;  ///< present for backend "petsc"
  std::optional<feti::FetiReport> feti;              ///< present for backend "tfeti"
  /// With [loading] steps > 1: every step done (the last may have failed); the other fields
  /// hold the last step's values.
  std::vector<StepReport> steps;
  /// Every connected body of the mesh, with the free motions of floating bodies and, after the
  /// solve, their amplitudes (theory.md §2.10).
  std::vector<BodyReport> bodies;
  /// What the result's status does not say, one sentence each (result_warnings): a partition
  /// coarsened to pass condition (5.1), a pair whose slips left small sliding, a master that
  /// penetrates its slave. The command line prints them in the summary and on stderr.
  std::vector<std::string> warnings;
};

/// The warnings of a report (RunReport::warnings) from its contact part; none without contact.
std::vector<std::string> result_warnings(const RunReport& report);

struct RunResult {
  RunReport report;
  Model model;
  fe::NodalField displacement;  ///< 3 x n_nodes [m], zero at fixed components
  /// Per tetrahedron: stress (Voigt order 11,22,33,23,13,12) [Pa], 6 x n_tets.
  Eigen::Matrix<Real, 6, Eigen::Dynamic> stress;
  VectorXd von_mises;  ///< per tetrahedron [Pa]
  /// Per node: the stress recovered at the nodes (fe::StressField::nodal_stress: the mean of the
  /// elements' stresses there), 6 x n_nodes [Pa], and its von Mises equivalent.
  Eigen::Matrix<Real, 6, Eigen::Dynamic> nodal_stress;
  VectorXd nodal_von_mises;
  std::optional<ContactFields> contact;       ///< fields on the contact surface
  std::optional<qp::DualProblem> first_dual;  ///< if RunOptions::keep_first_dual and contact
};

/// Validates and solves the problem on this process (solver.backend "cholmod"; InputError for
/// another: fricon::solve chooses). Throws InputError/NumericalError for ill-posed input, and
/// Interrupted for a stop requested before any iterate exists; a run whose iterations did not
/// converge (or whose certificate failed) returns with report.status == NotConverged.
/// With [loading] steps > 1 it runs the path (run_path).
RunResult run(const Problem& problem, const RunOptions& options = {});

/// The quasi-static loading path of the problem (theory.md §2.9): the model, the contact
/// discretization, the factor of K and Q once; then per step the loads of the step, the contact
/// solve from the state the last step left, and the result, reported to options.on_step. A step
/// that fails (or is interrupted) ends the path: the result is that step's, not converged, with
/// its message naming the step; report.steps holds every step done. A stop requested once a
/// step is solved (stop_requested, set e.g. while on_step runs) ends the path after that step,
/// not converged ("interrupted after step k of N"): report.steps ends with it.
RunResult run_path(const Problem& problem, const RunOptions& options = {});

}  // namespace fricon::driver

FRICON_ENUM_NAMES(fricon::driver::RunStatus, "status", {driver::RunStatus::Converged, "converged"},
                  {driver::RunStatus::NotConverged, "not_converged"});
