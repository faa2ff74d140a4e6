// bench: the expansion moves of the inner QP solver (qp::MpgpExpansion) with each variant
// (qp::MpgpVariant) on dual problems,
//
//   minimise 1/2 l^T Q l - l^T h  over  l_n >= 0,  ||l_t|| <= radius  (per patch),
//
// solved in the variables scaled per contact as `fricon dual solve` solves them
// (driver::contact_scaling: d = 1 / sqrt(mean of the diagonal of the patch's 3 x 3 block of Q);
// --scaling area for the factors of `fricon solve`, d proportional to area^(-3/4) on a surface of
// one material, contact/dual_scaling.hpp; --scaling none for l itself). ||D Q D|| is estimated
// once per problem (200 power iterations, as the driver does) and passed to every solve, so no
// count below includes it.
//
// Problems: the paper's brick (param 6e4) for n = 4, 8, 12, 16 (bench/common/paper_dual.hpp, Q
// formed densely), and the dual files given as arguments (docs/dual-format.md; e.g. the graded
// Hertz and wheel meshes' QPs written by `fricon solve --dump-dual`).
//
// Table 1, "single QP": each problem's QP (for the brick its first outer iteration, all radii
// 6e6 Pa), from l = 0 to ||D g^P|| <= tol ||D h_R|| for every variant x expansion and tol:
// iterations (cg / exp / prop), products with Q (of them in expansion steps), expansion moves that
// fell back to the fixed length, time (median of --reps runs), the largest relative KKT residual
// (qp::kkt_residuals, default scales, g = Q l - h recomputed) and ||l - l_ref|| / ||l_ref||
// against the first combination's solution at the same tol.
//
// Table 2, "whole run" (the brick, and the problem files given with --run; --no-run to skip):
// the successive approximations of theory.md §5 by the driver's own map and outer loop, scaled
// as the driver scales (solver.dual_scaling; the brick's patches get equal factors), QP
// warm-started, the problem's tolerances (the brick's: QP 1e-6, outer 1e-4): outer iterations, QP
// iterations and products over the run (the paper's n_mult), QP time (median of --reps runs).
//
//   build/bench/expansion_bench [FILE.dual ...] [--n 4,8,12,16] [--variants paper,bb]
//                               [--expansions fixed,opt,projcg] [--factor 1] [--tol 1e-6,1e-8]
//                               [--reps 3] [--no-run] [--run PROBLEM.toml ...] [--verbose]
//                               [--scaling diagonal|area|none]   (--help: the options)

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "common/bench_args.hpp"
#include "common/paper_dual.hpp"
#include "fricon/contact/dual_scaling.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/driver/tresca_map.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/scaling.hpp"

namespace {

using fricon::Index;
using fricon::MatrixXd;
using fricon::VectorXd;
namespace fs = std::filesystem;
namespace qp = fricon::qp;

struct Combination {
  qp::MpgpVariant variant;
  qp::MpgpExpansion expansion;
  std::string name() const {
    return fmt::format("{}/{}", fricon::enum_name(variant), fricon::enum_name(expansion));
  }
};

/// The change of variables of the QPs.
enum class Scaling {
  Diagonal,  ///< `fricon dual solve`'s: from the diagonal of Q
  Area,      ///< `fricon solve`'s (solver.dual_scaling = "patch") on one material: area^(-3/4)
  None,
};

struct Settings {
  std::vector<qp::MpgpVariant> variants = {qp::MpgpVariant::Paper,
                                           qp::MpgpVariant::BarzilaiBorwein};
  std::vector<qp::MpgpExpansion> expansions = {qp::MpgpExpansion::Fixed, qp::MpgpExpansion::Optimal,
                                               qp::MpgpExpansion::ProjectedCG};
  double factor = 1.0;  // MpgpOptions::expansion_length_factor
  std::vector<double> tols = {1e-6, 1e-8};
  int reps = 3;
  bool run = true;
  bool verbose = false;  // print every QP of the whole runs
  Scaling scaling = Scaling::Diagonal;

  std::vector<Combination> combinations() const {
    std::vector<Combination> out;
    for (const auto v : variants)
      for (const auto e : expansions)
        out.push_back({v, e});
    return out;
  }
};

struct Case {
  std::string name;
  MatrixXd Q;
  VectorXd h, radius, area;
  std::unique_ptr<qp::BlockScaling> D;
  double norm_DQD = 0.0;
  std::unique_ptr<fricon::bench::PaperDual> outer;  // what the outer loop needs; null for files
  std::unique_ptr<qp::BlockScaling> D_run;          // the driver's scaling of the outer loop
  double norm_run = 0.0;                            // ||D_run Q D_run||

  qp::Operator A() const { return fricon::bench::dense_operator(Q); }
  qp::SeparableConstraints constraints(const VectorXd& r) const {
    return fricon::bench::disc_constraints(r);
  }
};

qp::BlockScaling area_scaling(const VectorXd& area) {
  VectorXd factor(2 * area.size());
  for (Index p = 0; p < area.size(); ++p)
    factor(2 * p) = factor(2 * p + 1) = std::pow(area(p), -0.75);
  return qp::BlockScaling::per_block(qp::SeparableConstraints::contact_layout(area.size()), factor);
}

void finish_case(Case& k, const Settings& s) {
  switch (s.scaling) {
    case Scaling::Diagonal:
      k.D = std::make_unique<qp::BlockScaling>(fricon::driver::contact_scaling(k.Q.diagonal()));
      break;
    case Scaling::Area:
      k.D = std::make_unique<qp::BlockScaling>(area_scaling(k.area));
      break;
    case Scaling::None:
      k.D = std::make_unique<qp::BlockScaling>(qp::BlockScaling::identity(k.h.size()));
      break;
  }
  k.norm_DQD = qp::estimate_norm(k.D->scaled(k.A()), k.h.size(), 200, 1e-10);
}

Case paper_case(Index n, const Settings& s) {
  Case k;
  k.name = fmt::format("paper-n{}", n);
  k.outer = fricon::bench::paper_dual(n);
  k.Q = *k.outer->Q->dense();
  k.h = k.outer->Q->h();
  k.radius = k.outer->radius;
  k.area.resize(k.radius.size());
  for (Index p = 0; p < k.area.size(); ++p)
    k.area(p) = k.outer->disc.patches.area(p);
  finish_case(k, s);
  return k;
}

Case file_case(const fs::path& p, const Settings& s) {
  const auto d = fricon::io::read_dual(p);
  Case k;
  k.name = p.stem().string();
  k.Q = d.Q;
  k.h = d.h;
  k.radius = d.radius;
  k.area = d.patch_area;
  finish_case(k, s);
  return k;
}

using fricon::bench::median;

qp::MpgpOptions options(double norm, const Settings& s, Combination m, double tol) {
  qp::MpgpOptions o;
  o.variant = m.variant;
  o.expansion = m.expansion;
  o.expansion_length_factor = s.factor;
  o.rel_tolerance = tol;
  o.norm_A = norm;
  return o;
}

// ------------------------------------------------------------------------------------------
// Table 1: one QP from l = 0.

void single_qp(const Case& k, const Settings& s) {
  const auto c = k.constraints(k.radius);
  const qp::Operator A = k.A();
  for (const double tol : s.tols) {
    VectorXd l_ref;
    for (const Combination m : s.combinations()) {
      const auto opt = options(k.norm_DQD, s, m, tol);
      std::vector<double> ms;
      qp::MpgpReport rep;
      VectorXd l;
      for (int r = 0; r < s.reps; ++r) {
        l = VectorXd::Zero(k.h.size());
        rep = qp::solve_mpgp_scaled(A, k.h, c, *k.D, opt, l);
        ms.push_back(1e3 * rep.seconds);
      }
      if (l_ref.size() == 0) l_ref = l;
      const double dl = l_ref.norm() > 0 ? (l - l_ref).norm() / l_ref.norm() : (l - l_ref).norm();
      fmt::print(
          "{:<10} {:>5} {:>6.0e} {:<14} {:>6} {:>16} {:>8} {:>6} {:>5} {:>9.2f} {:>9.2e} {:>8.1e}  "
          "{}\n",
          k.name, k.h.size(), tol, m.name(), rep.iterations,
          fmt::format("{}/{}/{}", rep.n_cg, rep.n_expansion, rep.n_proportioning), rep.n_products,
          rep.n_expansion_products, rep.n_expansion_fallbacks, median(ms),
          fricon::bench::kkt_max(k.Q, k.h, c, l), dl, fricon::enum_name(rep.termination));
    }
  }
}

// ------------------------------------------------------------------------------------------
// Table 2: the whole outer loop, warm-started, scaled as the driver scales (solver.dual_scaling:
// contact::patch_scale_factors, or none).

void prepare_run(Case& k) {
  const fricon::bench::PaperDual& o = *k.outer;
  const Index m = o.disc.n_patches();
  if (o.problem.solver.dual_scaling == fricon::contact::DualScaling::None) {
    k.D_run = std::make_unique<qp::BlockScaling>(qp::BlockScaling::identity(3 * m));
  } else {
    const VectorXd d = fricon::contact::patch_scale_factors(o.model.mesh, o.disc.surface,
                                                            o.disc.patches, o.model.materials);
    VectorXd per_block(2 * m);
    for (Index p = 0; p < m; ++p)
      per_block(2 * p) = per_block(2 * p + 1) = d(p);
    k.D_run = std::make_unique<qp::BlockScaling>(
        qp::BlockScaling::per_block(qp::SeparableConstraints::contact_layout(m), per_block));
  }
  k.norm_run = qp::estimate_norm(k.D_run->scaled(o.Q->as_qp_operator()), 3 * m, 200, 1e-10);
}

Case run_case(const fs::path& p) {
  Case k;
  k.name = p.stem().string();
  k.outer = fricon::bench::problem_dual(fricon::io::read_problem(p.string()));
  prepare_run(k);
  return k;
}

struct RunResult {
  int outer = 0;
  long iterations = 0, products = 0;
  double qp_ms = 0.0;
  bool converged = false;
};

RunResult run_outer(const Case& k, const Settings& s, Combination m) {
  const fricon::bench::PaperDual& o = *k.outer;
  const auto& so = o.problem.solver;
  fricon::PhaseTimes times;
  const auto bounds = fricon::driver::make_slip_bounds(o.problem, o.model.mesh, o.disc);
  fricon::driver::TrescaMap map(o.model.dofs, o.disc, *o.Q, *bounds, *k.D_run,
                                options(k.norm_run, s, m, so.qp.rel_tolerance), so.warm_start,
                                times);
  RunResult res;
  Index n_state = 0;  // phi, and lambda_n for Coulomb
  for (const auto& block : map.layout())
    n_state += block.size;
  VectorXd state = VectorXd::Zero(n_state);
  const auto rep =
      fricon::outer::iterate(map, state, so.outer, [&](const fricon::outer::OuterIteration&) {
        res.iterations += map.last_qp().iterations;
        res.products += map.last_qp().n_products;
        res.qp_ms += 1e3 * map.last_qp().seconds;
        if (s.verbose) fmt::print("  {}\n", map.last_qp().brief());
      });
  res.outer = rep.iterations;
  res.converged = rep.converged();
  return res;
}

void whole_run(const Case& k, const Settings& s) {
  for (const Combination m : s.combinations()) {
    RunResult res;
    std::vector<double> ms;
    for (int r = 0; r < s.reps; ++r) {
      res = run_outer(k, s, m);
      ms.push_back(res.qp_ms);
    }
    fmt::print("{:<10} {:<14} {:>5} {:>8} {:>8} {:>9.2f}  {}\n", k.name, m.name(), res.outer,
               res.iterations, res.products, median(ms),
               res.converged ? "converged" : "NOT converged");
  }
}

}  // namespace

FRICON_ENUM_NAMES(Scaling, "--scaling", {Scaling::Diagonal, "diagonal"}, {Scaling::Area, "area"},
                  {Scaling::None, "none"});

int main(int argc, char** argv) {
  CLI::App app{
      "The expansion moves of MPGP (qp::MpgpExpansion) with each variant (qp::MpgpVariant) on "
      "the paper's brick and on dual files: one QP, then the whole outer loop.",
      "expansion_bench"};
  Settings s;
  std::vector<std::string> dumps, runs;
  std::vector<Index> ns = {4, 8, 12, 16};
  app.add_option("files", dumps, "Dual files (docs/dual-format.md) to solve as single QPs");
  fricon::bench::comma_list(app.add_option("--n", ns, "Mesh parameters n of the paper's brick"))
      ->check(CLI::Range(Index{1}, Index{1000}))
      ->capture_default_str();
  fricon::bench::comma_list(app.add_option("--variants", s.variants, "QP variants (paper,bb)"))
      ->transform(fricon::bench::enum_spelling<qp::MpgpVariant>());
  fricon::bench::comma_list(
      app.add_option("--expansions", s.expansions, "Expansion moves (fixed,opt,projcg)"))
      ->transform(fricon::bench::enum_spelling<qp::MpgpExpansion>());
  app.add_option("--factor", s.factor, "MpgpOptions::expansion_length_factor")
      ->capture_default_str();
  fricon::bench::comma_list(app.add_option("--tol", s.tols, "QP tolerances"))
      ->capture_default_str();
  app.add_option("--reps", s.reps, "Runs per time (the median is shown)")->capture_default_str();
  app.add_flag_callback(
      "--no-run", [&s] { s.run = false; }, "Skip the whole runs");
  app.add_option("--run", runs, "Problem files (TOML) to run whole, besides the brick");
  app.add_flag("--verbose", s.verbose, "Print every QP of the whole runs");
  app.add_option("--scaling", s.scaling, "The change of variables (default diagonal)")
      ->transform(fricon::bench::enum_spelling<Scaling>());
  return fricon::bench::run_main(app, argc, argv, [&] {
    s.reps = std::max(1, s.reps);
    fmt::print(
        "MPGP expansion moves (qp::MpgpExpansion) x variants (qp::MpgpVariant), {}; expansion "
        "length factor {}.\n"
        "Single QP from l = 0, stop at ||g^P|| <= tol ||h_R|| (of the scaled QP); steps = "
        "cg/exp/prop; exp prod = products in expansion steps; fb = expansion fallbacks;\n"
        "time = median of {} runs; kkt = max relative KKT residual of l; dl = ||l - l_first|| / "
        "||l_first|| against the first combination at the same tol.\n\n",
        s.scaling == Scaling::Diagonal ? "scaled per contact (D = diag(1/sqrt(mean diag Q_aa)))"
        : s.scaling == Scaling::Area   ? "scaled per patch by area^(-3/4) (fricon solve's)"
                                       : "not scaled",
        s.factor, s.reps);
    fmt::print("{:<10} {:>5} {:>6} {:<14} {:>6} {:>16} {:>8} {:>6} {:>5} {:>9} {:>9} {:>8}  {}\n",
               "problem", "n_d", "tol", "variant/exp", "iters", "steps", "products", "exp pr", "fb",
               "time[ms]", "kkt", "dl", "termination");
    std::vector<Case> cases;
    for (const Index n : ns) {
      cases.push_back(paper_case(n, s));
      prepare_run(cases.back());
      single_qp(cases.back(), s);
    }
    for (const auto& p : dumps) {
      const Case k = file_case(p, s);
      single_qp(k, s);
    }

    for (const auto& p : runs)
      cases.push_back(run_case(p));
    if (s.run && !cases.empty()) {
      fmt::print(
          "\nWhole run: successive approximations as in the driver (warm starts, the problem's QP "
          "and outer tolerances: for the brick 1e-6 and 1e-4; scaled as solver.dual_scaling "
          "says); products = n_mult of the run; QP time = median of {} runs.\n\n",
          s.reps);
      fmt::print("{:<10} {:<14} {:>5} {:>8} {:>8} {:>9}  {}\n", "problem", "variant/exp", "outer",
                 "qp iters", "n_mult", "QP[ms]", "status");
      for (const auto& k : cases)
        whole_run(k, s);
    }
    return 0;
  });
}
