#pragma once
// qp: MPGP, the active-set solver for a strictly convex QP on a separable feasible set,
//
//   minimise q(x) = 1/2 x^T A x - x^T b   subject to x in Omega (see constraints.hpp),
//
// with A symmetric positive definite and given only as a product routine. In fricon A is the dual
// Hessian B K^-1 B^T and b = B K^-1 f; the driver calls this once per Tresca step, warm-started.
//
// Each iteration is one of three steps (docs/theory.md §4.2, [HL09]), chosen from the split of
// the projected gradient g^P into the free gradient phi (free blocks) and the chopped gradient
// beta (active blocks) (§4.1):
//   'c'  conjugate gradient step on the free blocks, if it stays feasible      (1 product)
//   'e'  expansion: go to the boundary along the CG direction, then take a projected
//        free-gradient step of fixed length alpha_bar (MpgpOptions::expansion
//        chooses others: MpgpExpansion below)                                   (2 products)
//   'p'  proportioning, when beta dominates the reduced free gradient: the projected gradient
//        step x := P(x - alpha_bar g)                                           (1 product)
// alpha_bar = step_factor / ||A|| with ||A|| given or estimated by power iteration. With
// step_factor <= 2 no step increases q. Convergence is R-linear in the condition number of A.
// MpgpOptions::preconditioner, when given, preconditions the CG steps in face (§4.2): they move
// along M phi restricted to the free blocks, M an approximation of A^-1.
//
// MpgpOptions::variant selects the algorithm (MpgpVariant below): Paper is the algorithm above,
// BarzilaiBorwein (the default) replaces its fixed-length projected-gradient moves by spectral
// ones (§4.3). Both stop on the same test, ||g^P|| <= max(rel_tolerance ||b||, abs_tolerance)
// (BarzilaiBorwein certifies it with a recomputed gradient), and count every product with A in
// MpgpReport::n_products.

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/dual_space.hpp"
#include "fricon/qp/operator.hpp"

namespace fricon::qp {

enum class QpTermination {
  Converged,         ///< ||g^P|| reached the tolerance
  MaxIterations,     ///< MpgpOptions::max_iterations steps taken without converging
  NumericalFailure,  ///< non-finite values, or A found not positive definite along a direction
  UserStopped,       ///< the monitor returned false
};

/// The algorithm solve_mpgp runs. Both variants keep the iterates feasible, stop on the same test
/// and decrease q monotonically (up to rounding). Measured on the paper's problems
/// (bench/qp_variants_bench.cpp): BarzilaiBorwein needs 5 to 10 times fewer products than Paper.
/// The MPRGP proportioning step along beta, the proportionality test with phi^T phi and the
/// spectral projected gradient method without CG were measured too and gave no gain. The
/// expansion step's move is chosen apart from the variant (MpgpExpansion below).
enum class MpgpVariant {
  /// The algorithm of [HL09] (docs/theory.md §4.2): CG, expansion and proportioning steps with the
  /// fixed length alpha_bar. It reproduces the paper's product counts n_mult (Table 1, `fricon
  /// paper`); the unit test MpgpRegression.CountsAndIteratesArePinned checks its counts and
  /// iterates on fixed problems, so that a change of them shows.
  Paper,
  /// MPGP whose projected-gradient moves (the expansion's free-gradient move and the
  /// proportioning step) are spectral (docs/theory.md §4.3): the trial length is a
  /// Barzilai-Borwein length (adaptive ABBmin rule) of the last step instead of alpha_bar,
  /// followed by the exact line search of q on the segment to the projected trial point (same
  /// product counts as Paper: the product with the move replaces the gradient recomputation).
  /// Where the line search is below the rounding level (near a tight solution) the move is
  /// Paper's fixed-length one. CG steps as in Paper, so it stays as fast as Paper where CG
  /// dominates (few active blocks). Default.
  BarzilaiBorwein,
};

/// How an expansion step continues once it has reached the boundary of Omega along the CG
/// direction -p (docs/theory.md §4.2): PERMON's expansion types and lengths
/// (-qps_mpgp_expansion_type, -qps_mpgp_expansion_length_type; [KHC+20]). Every choice keeps the
/// iterate feasible, restarts CG from the free gradient afterwards and never increases q: a move
/// that would is replaced by a fixed-length one (MpgpReport::n_expansion_fallbacks).
/// Measured (bench/expansion_bench.cpp; products with A to ||g^P|| <= 1e-6 / 1e-8 ||b_R||, each QP
/// scaled per contact as `fricon dual solve` scales it; docs/theory.md §4.2), BarzilaiBorwein with
/// Fixed / Optimal / ProjectedCG: on the frictionless QPs of graded meshes, where expansions are a
/// large share of the steps, the graded wheel (first Coulomb step) needs 70/75, 37/41, 47/51 and
/// the graded Hertz hemisphere 46/56, 52/61, 49/58 (Paper: 103/108, 36/40, 48/51 and 74/84,
/// 51/60, 48/57); on the paper's brick (n = 16, Tresca), where proportioning steps dominate,
/// 307/630, 372/730, 271/470 (Optimal's length is nearly always cut by the projection, so 3
/// products a step). With PERMON's length factor 2 Optimal overshoots and falls back often (Hertz
/// 98/107, wheel 48/53). Over these three QPs ProjectedCG with BarzilaiBorwein needs the fewest
/// products, and is the default of `fricon dual solve` (driver::LocalSolveOptions). In whole runs
/// of `fricon solve`'s successive approximations, warm-started, it is not better: the wheel's six
/// Coulomb steps take 2799, 2710 and 5036 products (the later, frictional QPs are dominated by
/// proportioning steps, and after ProjectedCG's expansions the 4th and 5th QP need 1459 and 1168 of
/// them against 349 and 94), the brick's about as many with Fixed as with ProjectedCG. Fixed
/// stays the default here (and Paper with Fixed is the paper's algorithm).
enum class MpgpExpansion {
  /// The variant's own projected free-gradient move from the boundary point: x := P(x - alpha_bar
  /// phi) and g recomputed (Paper), or the spectral move along phi (BarzilaiBorwein, §4.3).
  /// 2 products per expansion step (A p and the move's). Today's step of both variants; Paper with
  /// Fixed is the algorithm that reproduces the paper's counts.
  Fixed,
  /// PERMON's "opt" length: along the reduced free gradient gr = phitilde_{alpha_bar} at the
  /// boundary point, of length a = expansion_length_factor (gr^T g) / (gr^T A gr) (the exact line
  /// search along -gr times the factor; 1 more product, A gr), then projected onto Omega and g
  /// recomputed (1 more product; saved when x - a gr is feasible, since then g - a A gr is exact).
  /// If the projected point has a larger q than the boundary point, the move is the fixed-length
  /// one x - alpha_bar gr (= P(x - alpha_bar phi)), whose gradient g - alpha_bar A gr needs no
  /// product. 2 or 3 products per expansion step (1 if gr = 0).
  Optimal,
  /// PERMON's "projcg": the whole CG step x := P(x - a_cg p), past the boundary, projected onto
  /// Omega, and g recomputed (1 more product). If that point has a larger q than x before the
  /// step, the step is redone as Fixed from x (1 more product). 2 or 3 products per expansion step.
  ProjectedCG,
};

/// The norm that the relative stopping test ||g^P|| <= rel_tolerance ||r|| refers to
/// (docs/theory.md §4.2).
enum class StopReference {
  /// r = b, the paper's test [HL09, §6].
  Whole,
  /// r = b_R, the part of b that the constraints resist (resisted_part below): b on the discs of
  /// positive radius and on the unconstrained (Free) unknowns, max(b_i, 0) on the bounds. A bound
  /// with b_i <= 0 is satisfied at x = 0 by itself (a patch with a gap the free displacement does
  /// not close), so however large such entries are they do not loosen the test. Where every b_i
  /// of the bounds is positive (the paper's brick) it is the paper's test. Default.
  Resisted,
};

/// b_R of StopReference::Resisted: per block, b itself on a disc of positive radius and on a Free
/// (unconstrained) unknown, 0 on a pinned disc, max(b_i, 0) on a bound. x = 0 solves the QP when
/// b_R = 0.
Eigen::VectorXd resisted_part(const Eigen::VectorXd& b, const SeparableConstraints& c);

}  // namespace fricon::qp

FRICON_ENUM_NAMES(fricon::qp::QpTermination, "termination",
                  {qp::QpTermination::Converged, "converged"},
                  {qp::QpTermination::MaxIterations, "max_iterations"},
                  {qp::QpTermination::NumericalFailure, "numerical_failure"},
                  {qp::QpTermination::UserStopped, "user_stopped"});

FRICON_ENUM_NAMES(fricon::qp::MpgpVariant, "solver.qp_variant", {qp::MpgpVariant::Paper, "paper"},
                  {qp::MpgpVariant::BarzilaiBorwein, "bb"});

FRICON_ENUM_NAMES(fricon::qp::MpgpExpansion, "solver.qp_expansion",
                  {qp::MpgpExpansion::Fixed, "fixed"}, {qp::MpgpExpansion::Optimal, "opt"},
                  {qp::MpgpExpansion::ProjectedCG, "projcg"});

namespace fricon::qp {

/// What MPGP's CG steps may do with an active disc, one whose friction force lies on its circle
/// (docs/theory.md §4.7).
enum class MpgpDiscFace {
  /// The paper's: an active disc is off the face, so only the projected moves (expansion and
  /// proportioning) turn its force along the circle.
  Held,
  /// The CG steps turn it: the face keeps the disc's tangent, the CG curvature adds the
  /// circle's (mu_i / rho_i, mu_i the normal force pushing the disc outward), and the point
  /// returns radially to the circle after each step. A disc whose circle is too tight for that
  /// (mu_i / rho_i > kTurnCurvature / alpha_bar) is held.
  Turned,
};

/// The largest circle curvature mu_i / rho_i of a turned disc, times alpha_bar = 1.95 / ||A||:
/// tighter circles (small radius, large normal force; in Coulomb's small pressures) are held.
/// Measured on the paper's brick under Total FETI (docs/theory.md §4.7): 0.15 and 1 need more
/// products than 0.3; without a limit, a disc of radius near 0 cuts every CG step to nothing.
inline constexpr double kTurnCurvature = 0.3;

}  // namespace fricon::qp

FRICON_ENUM_NAMES(fricon::qp::MpgpDiscFace, "solver.qp_active_discs",
                  {qp::MpgpDiscFace::Held, "hold"}, {qp::MpgpDiscFace::Turned, "turn"});

namespace fricon::qp {

/// One completed iteration (or the starting point, step 's'), as passed to the monitor.
struct MpgpIteration {
  int iteration = 0;     ///< 0 for the starting point, then 1, 2, ...
  char step = 's';       ///< 's' start, 'c' CG, 'e' expansion, 'p' proportioning
  double norm_gp = 0;    ///< ||g^P(x)||_2 after the step
  double norm_phi = 0;   ///< ||phi(x)||_2 after the step
  double norm_beta = 0;  ///< ||beta(x)||_2 after the step
  double alpha = 0;      ///< step length: a_cg ('c'), feasible step a_f ('e'; a_cg for a
                         ///< ProjectedCG expansion), alpha_bar ('p'), or for a spectral move
                         ///< ('p' of BarzilaiBorwein) t times the trial length; 0 for 's'
  double objective = 0;  ///< q(x) after the step
};

struct MpgpOptions {
  /// The algorithm. Default BarzilaiBorwein (the program's default); Paper is the reference.
  MpgpVariant variant = MpgpVariant::BarzilaiBorwein;
  /// The move of an expansion step after it reached the boundary (MpgpExpansion). Default Fixed
  /// (the algorithm as it was; ProjectedCG needs fewer products on single QPs, not in whole runs).
  MpgpExpansion expansion = MpgpExpansion::Fixed;
  /// What the CG steps do with active discs (MpgpDiscFace). Default Held (the paper's MPGP;
  /// `fricon solve` turns them).
  MpgpDiscFace active_discs = MpgpDiscFace::Held;
  /// MpgpExpansion::Optimal: the multiple of the line-search length along the reduced free
  /// gradient (PERMON's alpha_user, whose default is 2). Default 1; range (0, 2] (with <= 2 a
  /// feasible move does not increase q).
  double expansion_length_factor = 1.0;
  /// Stop when ||g^P|| <= rel_tolerance * ||r||_2, r given by `reference`. Default 1e-6
  /// ([HL09]); range >= 0.
  double rel_tolerance = 1e-6;
  /// What the relative test refers to. Default Resisted (the paper's ||b|| where every bound's
  /// b_i is positive).
  StopReference reference = StopReference::Resisted;
  /// ... or when ||g^P|| <= abs_tolerance (same unit as b). Default 0 (off); range >= 0.
  double abs_tolerance = 0.0;
  /// Cap on the number of steps. Default 100000; range >= 0.
  int max_iterations = 100000;
  /// Proportioning constant Gamma. Default 1; range > 0.
  double gamma = 1.0;
  /// alpha_bar = step_factor / ||A||. Default 1.95 (a safety margin below 2 because a power-method
  /// estimate of ||A|| is a lower bound); range (0, 2].
  double step_factor = 1.95;
  /// ||A|| if known (> 0); 0 (default) means: estimate it by power iteration.
  double norm_A = 0.0;
  /// Power iteration cap. Default 100; range >= 1.
  int power_iterations = 100;
  /// Power iteration stops when the estimate changes by <= power_tolerance relative.
  /// Default 1e-8; range > 0.
  double power_tolerance = 1e-8;
  /// Relative tolerance of the active-set tests: a Disc block is active iff
  /// ||x_i|| >= (1 - active_tolerance) rho_i; a Bound block iff x_i <= active_tolerance * s, with
  /// s a fixed scale of x (the largest of ||P(x_init)||_inf, the largest radius and
  /// ||b||_2 / ||A||). Default 1e-12; range [0, 1e-3].
  double active_tolerance = 1e-12;
  /// Optional: a stopping threshold that depends on the iterate (the inner test of SMALSE-M,
  /// qp/smalse.hpp): the test becomes ||g^P|| <= max(the threshold above, adaptive_tolerance(x)).
  std::function<double(const Eigen::VectorXd& x)> adaptive_tolerance;
  /// Optional: M, a symmetric positive definite approximation of A^-1, for preconditioning in face
  /// (docs/theory.md §4.2): the CG steps move along z = M phi restricted to the face of x (the
  /// blocks that are not active) instead of phi, and CG restarts from z; the expansion and
  /// proportioning steps, the proportionality and the stopping tests are those without. One
  /// application per CG step and per restart. Empty (default): none.
  Operator preconditioner;
  /// Optional; called after every iteration and once for the starting point. Return false to
  /// stop (QpTermination::UserStopped).
  std::function<bool(const MpgpIteration&)> monitor;
  /// Store every MpgpIteration (starting point included) in MpgpReport::history. Default false.
  bool record_history = false;
  /// Where the vectors live (qp/dual_space.hpp): x, b, the constraints and the operator's
  /// vectors are this process's part of the whole, and every inner product, norm and maximum is
  /// taken over the processes (each must call the solver with the same options). Null (default):
  /// whole_space(), every unknown here. Must outlive the solve.
  const DualSpace* space = nullptr;

  /// *space, or whole_space() when it is null.
  const DualSpace& vectors() const { return space ? *space : whole_space(); }

  /// Throws fricon::InputError naming the first field out of range, its value and the range.
  void validate() const;
};

/// MPGP's steps by kind (docs/theory.md §4.2), summed over one or more solves.
struct MpgpSteps {
  long cg = 0;             ///< conjugate gradient steps
  long expansion = 0;      ///< expansion steps (a CG step cut at the boundary, then a move)
  long proportioning = 0;  ///< proportioning steps (along the chopped gradient)

  MpgpSteps& operator+=(const MpgpSteps& o) {
    cg += o.cg;
    expansion += o.expansion;
    proportioning += o.proportioning;
    return *this;
  }
};

struct MpgpReport {
  QpTermination termination = QpTermination::NumericalFailure;
  std::string message;                             ///< one sentence: why the solver stopped
  MpgpVariant variant = MpgpVariant::Paper;        ///< the algorithm that ran
  MpgpExpansion expansion = MpgpExpansion::Fixed;  ///< its expansion move
  MpgpDiscFace active_discs = MpgpDiscFace::Held;  ///< what its CG steps did with active discs
  /// Steps taken = n_cg + n_expansion + n_proportioning.
  int iterations = 0;
  int n_cg = 0;
  int n_expansion = 0;
  int n_proportioning = 0;
  /// Spectral moves (BarzilaiBorwein) whose line search was below the rounding level, replaced by
  /// Paper's fixed-length move (no extra product).
  int n_fallbacks = 0;
  /// Gradients recomputed as A x - b (one product each) to certify the stopping test where the
  /// gradient had been updated recursively (BarzilaiBorwein only).
  int n_refreshes = 0;
  /// Products with A made by the expansion steps, A p included: 2 n_expansion with
  /// MpgpExpansion::Fixed; 2 or 3 per step with the others (Optimal: 1 where the free gradient
  /// vanishes at the boundary point, so that there is nothing to move).
  long n_expansion_products = 0;
  /// Expansion moves (Optimal, ProjectedCG) that would have increased q, replaced by the
  /// fixed-length one.
  int n_expansion_fallbacks = 0;
  /// Products with A made by the iteration, the initial gradient included:
  /// 1 + n_cg + n_expansion_products + n_proportioning + n_refreshes (n_refreshes = 0 for Paper;
  /// n_expansion_products = 2 n_expansion for Fixed). Power-method products are not included.
  long n_products = 0;
  long n_power_products = 0;  ///< products spent estimating ||A|| (0 if MpgpOptions::norm_A > 0)
  long n_preconditioner = 0;  ///< applications of MpgpOptions::preconditioner (0 without)
  bool norm_A_estimated = false;  ///< true if norm_A_used comes from the power method
  double norm_A_used = 0.0;       ///< ||A|| behind alpha_bar (given or estimated)
  double alpha_bar_used = 0.0;    ///< step_factor / norm_A_used
  double norm_b = 0.0;            ///< ||b||_2
  /// ||r||_2 of the stopping test (MpgpOptions::reference): ||b||_2 or ||b_R||_2.
  double reference_norm = 0.0;
  double norm_gp = 0.0;    ///< final ||g^P||_2
  double rel_gp = 0.0;     ///< norm_gp / reference_norm (norm_gp itself if the reference is 0)
  double objective = 0.0;  ///< final q(x)
  /// Steps that increased q by more than rounding (expected 0; > 0 hints at a too large
  /// alpha_bar, e.g. an underestimated norm_A).
  int n_objective_increases = 0;
  double seconds = 0.0;                ///< wall time of solve_mpgp [s], power method included
  std::vector<MpgpIteration> history;  ///< filled if MpgpOptions::record_history

  MpgpSteps steps() const { return {n_cg, n_expansion, n_proportioning}; }

  /// One line: termination, iterations, products, relative ||g^P|| (and the variant if not
  /// Paper, the expansion if not Fixed).
  std::string brief() const;
  /// Aligned multi-line block with every counter and norm.
  std::string full() const;
};

/// Solves min q(x) over Omega by MPGP. x: in, the initial guess (projected onto Omega first; it
/// need not be feasible); out, the last iterate (the solution if Converged).
/// Throws fricon::InputError on invalid options or constraints, size mismatches, or non-finite
/// entries in b, x or the radii, and fricon::NumericalError if ||A|| comes out <= 0 or
/// non-finite. Numerical trouble during the iteration is reported as NumericalFailure instead.
/// If b = 0, or b_R = 0 with StopReference::Resisted, the solution is x = 0 (0 lies in Omega); it
/// is returned at once, after the initial gradient, without estimating ||A||.
MpgpReport solve_mpgp(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
                      const MpgpOptions& opt, Eigen::VectorXd& x);

/// Estimate of ||A||_2 for SPD A by power iteration from a fixed (deterministic) start vector:
/// returns ||A v_k|| for the last unit iterate v_k, a lower bound of ||A|| that increases to it.
/// Stops after max_iterations products or when the estimate changes by <= tolerance relative.
/// Adds the number of products to *n_products if given. Returns 0 for n = 0 or A v = 0. n is
/// this process's part of the unknowns in `space` (collective there; 0 alone means none).
double estimate_norm(const Operator& A, Index n, int max_iterations, double tolerance,
                     long* n_products = nullptr, const DualSpace& space = whole_space());

/// The power iteration for the norm of a contact solve's dual Hessian (theory.md §4.2), fricon's
/// problems and FCLIB's alike: at most this many products, to this relative change (the settings
/// of the paper's reproduction).
inline constexpr int kNormPowerIterations = 200;
inline constexpr double kNormPowerTolerance = 1e-10;

}  // namespace fricon::qp
