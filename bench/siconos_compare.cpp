// bench: peer comparison (issue 5, "Peer comparison"). The dual QP of one Tresca step,
//
//   minimise 1/2 l^T Q l - l^T h  over  l_n >= 0,  ||l_t|| <= radius  (per patch),
//
// solved by fricon's MPGP and by Siconos 4.4's Tresca solvers, each to the same accuracy measured
// the same way: fricon::qp::kkt_residuals on the returned multipliers (max of the relative
// feasibility, stationarity and complementarity residuals <= --kkt, 1e-8 by default). Every
// solver gets the loosest of its own tolerances (on a grid of half decades) that reaches that
// accuracy; then it is timed (median of --reps runs, each from l = 0).
//
// Problems: the dual problems of the first outer iteration (phi = 0, radius = F(0) g = 6e6 Pa
// everywhere) of the paper's brick for n = 4, 8, 12, 16 (param 6e4), built through the library
// with Q = B K^-1 B^T formed densely (bench/common/paper_dual.hpp); or the files given with --dump
// (docs/dual-format.md).
//
// Siconos (docs/dual-format.md, "Mapping"): FrictionContactProblem with dimension 3, one contact
// per patch, M = W (dense) and q from Q and -h, r = l (normal first), thresholds in the solver
// options' dWork. The problem is scaled first (x = l / L, L = max radius; W = Q / ||Q||,
// q = -h / (L ||Q||), thresholds radius / L), because Siconos' error ||r - P(r - u)|| / ||q|| adds
// r to u and its local solvers use absolute tolerances; the KKT residuals are computed on
// l = L x in SI units. fricon's MPGP runs twice: fricon-bb (the default QP variant of fricon
// solve; every ratio is against it) and fricon-paper (the paper's plain MPGP). Siconos solvers
// (all other options at Siconos' defaults):
//   nsgs-cyl-li50  fc3d_nsgs, options solver_options_create(SICONOS_FRICTION_3D_NSGS): error
//                  evaluation LIGHT_WITH_FULL_FINAL (stops on fc3d_Tresca_compute_error < tol),
//                  no shuffle, no relaxation; dWork = the m thresholds; local solver
//                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinderWithLocalIteration with at
//                  most 50 local iterations and local tolerance 1e-14 (the inner solver of
//                  Siconos' own Tresca fixed point SICONOS_FRICTION_3D_TFP, with its settings)
//   nsgs-cyl-li1   the same with 1 local iteration (one projection step per contact and sweep)
//   cqp-pg-cyl     fc3d_ConvexQP_ProjectedGradient_Cylinder, options
//                  solver_options_create(SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER), dWork = the
//                  thresholds; it runs SICONOS_CONVEXQP_PG with its defaults (line search,
//                  initial rho 1e-3, tau 2/3, mu 0.9, rhomin 1e-9) and only our tol and cap
// The plain local solver SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinder cannot be used with
// NSGS in Siconos 4.4 as Debian builds it (assertions on): fc3d_local_problem_allocate allocates
// the local problem's mu, and fc3d_projectionOnCylinder_initialize then fails its assertion
// `!localproblem->mu' (abort). nsgs-cyl-li1 is the closest working variant.
// A self-check on two tiny problems comes first (one with a patch that lifts off and sticks).
//
//   build/bench/siconos_compare [--dump FILE ...] [--save DIR] [--n 4,8,12,16] [--kkt 1e-8]
//                               [--reps 5] [--nsgs-max 20000] [--pg-max 200000]   (--help)

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

// Siconos numerics (C API).
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NumericsMatrix.h"
#include "NumericsVerbose.h"
#include "SolverOptions.h"
#include "fc3d_Solvers.h"
#include "fc3d_compute_error.h"

#include "common/bench_args.hpp"
#include "common/paper_dual.hpp"
#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/qp/dual_problem.hpp"
#include "fricon/qp/kkt.hpp"
#include "fricon/qp/mpgp.hpp"

namespace {

using fricon::Index;
using fricon::MatrixXd;
using fricon::VectorXd;
namespace fs = std::filesystem;
namespace qp = fricon::qp;

// ------------------------------------------------------------------------------------------
// The problems.

struct Case {
  std::string name;
  fricon::qp::DualProblem d;
  qp::SeparableConstraints c;
  double norm_Q = 0.0;  // power-method estimate, as the driver computes it
  double power_ms = 0.0;

  /// y = Q x (refers to this Case: do not move it while the operator is in use).
  qp::Operator A() const { return fricon::bench::dense_operator(d.Q); }
};

void finish_case(Case& k) {
  const Index m = k.d.radius.size();
  k.c = fricon::bench::disc_constraints(k.d.radius);
  fricon::Stopwatch w;
  k.norm_Q = qp::estimate_norm(k.A(), 3 * m, 200, 1e-10);  // the driver's settings
  k.power_ms = 1e3 * w.seconds();
}

// The dual problem of the first outer iteration of the paper's brick for mesh parameter n.
Case paper_case(Index n) {
  const auto p = fricon::bench::paper_dual(n);
  Case k;
  k.name = fmt::format("paper-n{}", n);
  k.d.source = p->problem.source;
  k.d.radius = p->radius;
  k.d.patch_area = p->disc.patches.area;
  k.d.h = p->Q->h();
  k.d.Q = *p->Q->dense();
  finish_case(k);
  return k;
}

Case file_case(const fs::path& p) {
  Case k;
  k.name = p.filename().string();
  k.d = fricon::io::read_dual(p);
  finish_case(k);
  return k;
}

Case tiny_case(std::string name, MatrixXd Q, VectorXd h, VectorXd radius) {
  Case k;
  k.name = std::move(name);
  k.d.Q = std::move(Q);
  k.d.h = std::move(h);
  k.d.radius = std::move(radius);
  k.d.patch_area = VectorXd::Ones(k.d.radius.size());
  k.d.source = k.name;
  finish_case(k);
  return k;
}

// ------------------------------------------------------------------------------------------
// Siconos: the scaled problem and the three solvers.

class SiconosProblem {
 public:
  explicit SiconosProblem(const Case& k)
      : n_(static_cast<int>(k.d.h.size())), L_(std::max(k.d.radius.maxCoeff(), 0.0)) {
    if (!(L_ > 0.0)) L_ = 1.0;
    const double G = L_ * k.norm_Q;
    M_ = NM_create(NM_DENSE, n_, n_);
    Eigen::Map<MatrixXd>(M_->matrix0, n_, n_) = k.d.Q / k.norm_Q;  // column-major, as NM_DENSE
    q_ = -k.d.h / G;
    s_ = k.d.radius / L_;
    mu_ = VectorXd::Zero(k.d.radius.size());  // not read by the Tresca solvers
    fcp_.dimension = 3;
    fcp_.numberOfContacts = static_cast<int>(k.d.radius.size());
    fcp_.M = M_;
    fcp_.q = q_.data();
    fcp_.mu = mu_.data();
  }
  ~SiconosProblem() { NM_free(M_); }
  SiconosProblem(const SiconosProblem&) = delete;
  SiconosProblem& operator=(const SiconosProblem&) = delete;

  FrictionContactProblem* problem() { return &fcp_; }
  double* thresholds() { return s_.data(); }
  int size() const { return n_; }
  double L() const { return L_; }

  /// Siconos' Tresca error ||x - P_C(x - u)|| / ||q|| (fc3d_Tresca_compute_error) of l = L x.
  double error(const VectorXd& l) {
    VectorXd x = l / L_, u(n_);
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    o->dWork = s_.data();
    double err = 0.0;
    fc3d_Tresca_compute_error(&fcp_, x.data(), u.data(), 0.0, o, q_.norm(), &err);
    o->dWork = nullptr;  // ours
    solver_options_delete(o);
    return err;
  }

 private:
  int n_;
  double L_;
  NumericsMatrix* M_ = nullptr;
  VectorXd q_, s_, mu_;
  FrictionContactProblem fcp_{};
};

struct Outcome {
  bool converged = false;
  int iterations = 0;
  double seconds = 0.0;
  VectorXd l;  // the multipliers [Pa]
};

// The solver's own stopping test at tolerance tol, cap max_iter, from l = 0.
using Solver = std::function<Outcome(double tol)>;

// NSGS with the local solver ProjectionOnCylinderWithLocalIteration, at most local_iter
// projection steps (with its own step-length search) per contact and sweep.
Outcome run_nsgs(SiconosProblem& sp, int local_iter, double tol, int max_iter) {
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  solver_options_update_internal(
      o, 0, SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinderWithLocalIteration);
  o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  o->dparam[SICONOS_DPARAM_TOL] = tol;
  o->internalSolvers[0]->iparam[SICONOS_IPARAM_MAX_ITER] = local_iter;
  o->internalSolvers[0]->dparam[SICONOS_DPARAM_TOL] = 1e-14;
  o->dWork = sp.thresholds();
  o->dWorkSize = static_cast<size_t>(sp.problem()->numberOfContacts);
  std::vector<double> r(static_cast<size_t>(sp.size()), 0.0), u(r.size(), 0.0);
  int info = 1;  // fc3d_nsgs returns at once if info == 0
  fricon::Stopwatch w;
  fc3d_nsgs(sp.problem(), r.data(), u.data(), &info, o);
  Outcome out;
  out.seconds = w.seconds();
  out.converged = info == 0;
  out.iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  out.l = sp.L() * Eigen::Map<VectorXd>(r.data(), sp.size());
  o->dWork = nullptr;  // ours, not Siconos'
  solver_options_delete(o);
  return out;
}

// fc3d_ConvexQP_ProjectedGradient_Cylinder creates its own convex-QP options (the defaults of
// SICONOS_CONVEXQP_PG: line search, rho = -1e-3, tau = 2/3, mu = 0.9, rhomin = 1e-9), copies
// only the tolerance and the cap into them and does not return the number of iterations; with
// count_iterations the call runs with numerics verbose and stdout captured, and the count is
// read from its final "#Iteration" line.
Outcome run_pg(SiconosProblem& sp, double tol, int max_iter, bool count_iterations) {
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER);
  o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  o->dparam[SICONOS_DPARAM_TOL] = tol;
  o->dWork = sp.thresholds();
  o->dWorkSize = static_cast<size_t>(sp.problem()->numberOfContacts);
  std::vector<double> r(static_cast<size_t>(sp.size()), 0.0), u(r.size(), 0.0);
  int info = 1;
  Outcome out;
  if (count_iterations) {
    std::fflush(stdout);
    char path[] = "/tmp/siconos_compare_XXXXXX";
    const int fd = mkstemp(path);
    const int saved = dup(1);
    dup2(fd, 1);
    numerics_set_verbose(1);
    fc3d_ConvexQP_ProjectedGradient_Cylinder(sp.problem(), r.data(), u.data(), &info, o);
    numerics_set_verbose(0);
    std::fflush(stdout);
    dup2(saved, 1);
    close(saved);
    close(fd);
    std::ifstream f(path);
    const std::string key = "Projected Gradient (PG) - #Iteration ";
    for (std::string line; std::getline(f, line);) {
      const auto at = line.find(key);
      if (at != std::string::npos) out.iterations = std::atoi(line.c_str() + at + key.size());
    }
    std::remove(path);
  } else {
    // It prints a warning on every call ("does not support a specific matrix A different from
    // the identity", although A is the identity): to /dev/null, outside the timed region.
    std::fflush(stdout);
    const int null_fd = open("/dev/null", O_WRONLY);
    const int saved = dup(1);
    dup2(null_fd, 1);
    fricon::Stopwatch w;
    fc3d_ConvexQP_ProjectedGradient_Cylinder(sp.problem(), r.data(), u.data(), &info, o);
    out.seconds = w.seconds();
    std::fflush(stdout);
    dup2(saved, 1);
    close(saved);
    close(null_fd);
  }
  out.converged = info == 0;
  out.l = sp.L() * Eigen::Map<VectorXd>(r.data(), sp.size());
  o->dWork = nullptr;
  solver_options_delete(o);
  return out;
}

Outcome run_mpgp(const Case& k, double tol, int max_iter, qp::MpgpVariant variant) {
  qp::MpgpOptions opt;
  opt.variant = variant;
  opt.rel_tolerance = tol;
  opt.max_iterations = max_iter;
  opt.norm_A = k.norm_Q;  // computed once per problem (power_ms), as the driver does
  Outcome out;
  out.l = VectorXd::Zero(k.d.h.size());
  const qp::Operator A = k.A();
  fricon::Stopwatch w;
  const auto rep = qp::solve_mpgp(A, k.d.h, k.c, opt, out.l);
  out.seconds = w.seconds();
  out.converged = rep.termination == qp::QpTermination::Converged;
  out.iterations = rep.iterations;
  return out;
}

// ------------------------------------------------------------------------------------------
// Calibration and timing.

struct Row {
  std::string solver;
  double tol = 0.0;
  bool reached = false;    // KKT target reached
  bool converged = false;  // the solver's own test passed at tol
  int iterations = 0;
  double ms = 0.0;  // median
  double kkt = 0.0;
  double siconos_err = 0.0;
  double diff = 0.0;  // ||l - l_mpgp||_inf / ||l_mpgp||_inf
  VectorXd l;
};

double kkt_max(const Case& k, const VectorXd& l) {
  return qp::kkt_residuals(k.A(), k.d.h, l, k.c).max();
}

// Tolerances on the grid 10^(-j/2); the loosest one whose solution satisfies the KKT target.
Row calibrate(const Case& k, const std::string& name, const Solver& solve, double target) {
  auto tol_of = [](int j) { return std::pow(10.0, -0.5 * j); };
  auto attempt = [&](int j, Row& row) {
    const Outcome o = solve(tol_of(j));
    row.tol = tol_of(j);
    row.converged = o.converged;
    row.iterations = o.iterations;
    row.l = o.l;
    row.kkt = kkt_max(k, o.l);
    row.reached = o.converged && row.kkt <= target;
    return row.reached;
  };
  Row best;
  best.solver = name;
  int j = static_cast<int>(std::lround(-2.0 * std::log10(target)));
  if (attempt(j, best)) {
    Row looser = best;
    while (j > 2 && attempt(j - 1, looser)) {
      best = looser;
      --j;
    }
  } else {
    while (best.converged && j < 30) {  // tighter until reached, the cap hit or 1e-15
      if (attempt(++j, best)) break;
    }
  }
  return best;
}

double median_ms(const std::function<double()>& run_seconds, int reps) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i)
    t.push_back(1e3 * run_seconds());
  return fricon::bench::median(t);
}

struct Settings {
  double kkt = 1e-8;
  int reps = 5;
  int mpgp_max = 100000;
  int nsgs_max = 20000;
  int pg_max = 200000;
};

std::vector<Row> compare(const Case& k, const Settings& s) {
  SiconosProblem sp(k);
  std::vector<Row> rows;

  // fricon's default QP (bb) first: the ratios are against it. Then the paper's plain MPGP.
  for (const auto& [name, variant] : {std::pair{"fricon-bb", qp::MpgpVariant::BarzilaiBorwein},
                                      std::pair{"fricon-paper", qp::MpgpVariant::Paper}}) {
    Row f = calibrate(
        k, name, [&](double tol) { return run_mpgp(k, tol, s.mpgp_max, variant); }, s.kkt);
    f.ms = median_ms([&] { return run_mpgp(k, f.tol, s.mpgp_max, variant).seconds; }, s.reps);
    rows.push_back(f);
  }

  for (const int local_iter : {50, 1}) {
    Row r = calibrate(
        k, fmt::format("nsgs-cyl-li{}", local_iter),
        [&](double tol) { return run_nsgs(sp, local_iter, tol, s.nsgs_max); }, s.kkt);
    r.ms = median_ms([&] { return run_nsgs(sp, local_iter, r.tol, s.nsgs_max).seconds; }, s.reps);
    rows.push_back(r);
  }

  Row pg = calibrate(
      k, "cqp-pg-cyl", [&](double tol) { return run_pg(sp, tol, s.pg_max, true); }, s.kkt);
  pg.ms = median_ms([&] { return run_pg(sp, pg.tol, s.pg_max, false).seconds; }, s.reps);
  rows.push_back(pg);

  const VectorXd& ref = rows.front().l;
  const double ref_inf = std::max(ref.cwiseAbs().maxCoeff(), 1e-300);
  for (Row& r : rows) {
    r.siconos_err = sp.error(r.l);
    r.diff = (r.l - ref).cwiseAbs().maxCoeff() / ref_inf;
  }
  return rows;
}

void print_header() {
  fmt::print("{:<18} {:>6} {:<13} {:>8} {:>7} {:>10} {:>9} {:>9} {:>9} {:>8}  {}\n", "problem",
             "n_dual", "solver", "tol", "iters", "time[ms]", "KKT max", "sic.err", "diff", "ratio",
             "status");
}

void print_rows(const Case& k, const std::vector<Row>& rows) {
  const double t0 = rows.front().ms;
  for (const Row& r : rows) {
    std::string status = r.reached ? "ok" : (r.converged ? "KKT not reached" : "not converged");
    const std::string ms = t0 > 0 ? fmt::format("{:.3f}", r.ms) : "-";
    const std::string ratio = t0 > 0 ? fmt::format("{:.2f}", r.ms / t0) : "-";
    fmt::print("{:<18} {:>6} {:<13} {:>8.1e} {:>7} {:>10} {:>9.1e} {:>9.1e} {:>9.1e} {:>8}  {}\n",
               k.name, k.d.h.size(), r.solver, r.tol, r.iterations, ms, r.kkt, r.siconos_err,
               r.diff, ratio, status);
  }
  std::fflush(stdout);
}

// Two tiny problems with known solutions: a random one (whatever its active set), and one patch
// that lifts off and sticks (Q = I, h = (-1, 0.5, 0), radius 1: l = (0, 0.5, 0), g = (1, 0, 0)).
void self_check(const Settings& s) {
  fmt::print("Self-check (tiny problems; each solver at tolerance 1e-12, no KKT calibration):\n");
  print_header();
  std::vector<Case> cases;
  {
    const Index m = 4, n = 3 * m;
    MatrixXd G = MatrixXd::Zero(n, n);
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j < n; ++j)
        G(i, j) = std::sin(1.0 + 3.0 * static_cast<double>(i) + 7.0 * static_cast<double>(j));
    MatrixXd Q = G * G.transpose() + MatrixXd::Identity(n, n);
    VectorXd h(n);
    for (Index i = 0; i < n; ++i)
      h(i) = std::cos(2.0 * static_cast<double>(i));
    cases.push_back(tiny_case("tiny-random", Q, h, VectorXd::Constant(m, 0.3)));
  }
  cases.push_back(tiny_case("tiny-liftstick", MatrixXd::Identity(3, 3),
                            (VectorXd(3) << -1.0, 0.5, 0.0).finished(), VectorXd::Ones(1)));
  for (const Case& k : cases) {
    SiconosProblem sp(k);
    const double tol = 1e-12;
    std::vector<Row> rows;
    auto add = [&](const char* name, const Outcome& o) {
      Row r;
      r.solver = name;
      r.tol = tol;
      r.converged = o.converged;
      r.iterations = o.iterations;
      r.l = o.l;
      r.kkt = kkt_max(k, o.l);
      r.reached = o.converged && r.kkt <= s.kkt;
      r.siconos_err = sp.error(o.l);
      rows.push_back(r);
    };
    add("fricon-bb", run_mpgp(k, tol, s.mpgp_max, qp::MpgpVariant::BarzilaiBorwein));
    add("fricon-paper", run_mpgp(k, tol, s.mpgp_max, qp::MpgpVariant::Paper));
    add("nsgs-cyl-li50", run_nsgs(sp, 50, tol, s.nsgs_max));
    add("nsgs-cyl-li1", run_nsgs(sp, 1, tol, s.nsgs_max));
    add("cqp-pg-cyl", run_pg(sp, tol, s.pg_max, true));
    const double ref_inf = rows.front().l.cwiseAbs().maxCoeff();
    for (Row& r : rows)
      r.diff = (r.l - rows.front().l).cwiseAbs().maxCoeff() / ref_inf;
    print_rows(k, rows);
    if (k.name == "tiny-liftstick")
      for (const Row& r : rows)
        fmt::print("  {:<12} l = ({:.6g}, {:.6g}, {:.6g})   (exact: (0, 0.5, 0))\n", r.solver,
                   r.l(0), r.l(1), r.l(2));
  }
  fmt::print("\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Peer comparison: the dual QP of one Tresca step by fricon's MPGP and by Siconos' Tresca "
      "solvers, each timed at the loosest tolerance that reaches the same KKT accuracy.",
      "siconos_compare"};
  Settings s;
  std::vector<std::string> dumps;
  std::string save_dir;
  std::vector<Index> ns = {4, 8, 12, 16};
  app.add_option("--dump", dumps, "Dual files (docs/dual-format.md) instead of the brick");
  app.add_option("--save", save_dir, "Write each problem's dual file into this folder");
  fricon::bench::comma_list(app.add_option("--n", ns, "Mesh parameters n of the paper's brick"))
      ->check(CLI::Range(Index{1}, Index{1000}))
      ->capture_default_str();
  app.add_option("--kkt", s.kkt, "The KKT accuracy every solver must reach")->capture_default_str();
  app.add_option("--reps", s.reps, "Runs per time (the median is shown)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--nsgs-max", s.nsgs_max, "Most NSGS sweeps")->capture_default_str();
  app.add_option("--pg-max", s.pg_max, "Most projected-gradient iterations")->capture_default_str();
  return fricon::bench::run_main(app, argc, argv, [&] {
    fmt::print(
        "Peer comparison: fricon MPGP vs Siconos 4.4 Tresca solvers on the same dual QP.\n"
        "Target: KKT max (fricon::qp::kkt_residuals, relative) <= {:.0e}; each solver at the "
        "loosest tolerance of its own test (grid 10^(-j/2)) that reaches it; time = median of "
        "{} runs from l = 0.\n"
        "Caps: MPGP {} iterations, NSGS {} sweeps, PG {} iterations. ratio = time / time(MPGP). "
        "sic.err = Siconos' fc3d_Tresca_compute_error of the scaled problem; diff = "
        "||l - l_mpgp||_inf / ||l_mpgp||_inf.\n\n",
        s.kkt, s.reps, s.mpgp_max, s.nsgs_max, s.pg_max);

    self_check(s);

    fmt::print("Comparison:\n");
    print_header();
    auto run_case = [&](const Case& k) {
      if (!save_dir.empty()) {
        const fs::path p = fs::path(save_dir) / fmt::format("{}.dual", k.name);
        fricon::io::write_dual(p, k.d);
      }
      print_rows(k, compare(k, s));
      fmt::print(
          "{:<18} {:>6} ||Q|| estimate (200 power iterations): {:.1f} ms, not in the "
          "times above\n",
          k.name, k.d.h.size(), k.power_ms);
    };
    if (!dumps.empty()) {
      for (const auto& p : dumps)
        run_case(file_case(p));
    } else {
      for (const Index n : ns)
        run_case(paper_case(n));
    }
    return 0;
  });
}
