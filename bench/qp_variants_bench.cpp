// bench: the variants of the inner QP solver (qp::MpgpVariant) on the paper's dual problems.
//
//   minimise 1/2 l^T Q l - l^T h  over  l_n >= 0,  ||l_t|| <= radius  (per patch)
//
// Problems: the paper's brick (param 6e4) for n = 4, 8, 12, 16, built through the library with
// Q = B K^-1 B^T formed densely (bench/common/paper_dual.hpp, shared with siconos_compare), or dual
// files
// (--dump, docs/dual-format.md). ||Q|| is estimated once per problem (200 power iterations, as the
// driver does) and passed to every solve, so no count below includes it.
//
// Table 1, "single QP": the dual problem of the first outer iteration (phi = 0, every radius
// F(0) g = 0.3 * 2e7 Pa), solved from l = 0 to ||g^P|| <= tol ||h|| for each variant and tol:
// iterations, products with Q, time (median of --reps runs) and the largest relative KKT
// residual of the result (fricon::qp::kkt_residuals, default scales, g = Q l - h recomputed).
//
// Table 2, "whole run" (problems built from the mesh only): the successive approximations of
// theory.md §5, run by the driver's own map and outer loop (radii from phi, QP warm-started from
// the previous multipliers at the paper's tolerance 1e-6, w = K^-1 (f - B^T l), phi = ||w_t|| at
// the surface nodes, stop when err(k) <= 1e-4): outer iterations, QP iterations and products over
// the run (the paper's n_mult), QP time over the run (median of --reps runs of the whole loop), the
// KKT residual of the last QP and the relative difference of the final phi from the Paper
// variant's.
//
//   build/bench/qp_variants_bench [--n 4,8,12,16] [--dump FILE ...] [--variants paper,bb]
//                                 [--tol 1e-6,1e-8] [--reps 5] [--no-run]   (--help: the options)

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "common/bench_args.hpp"
#include "common/paper_dual.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/tresca_map.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/mpgp.hpp"

namespace {

using fricon::Index;
using fricon::MatrixXd;
using fricon::VectorXd;
namespace fs = std::filesystem;
namespace qp = fricon::qp;

struct Settings {
  std::vector<qp::MpgpVariant> variants = {qp::MpgpVariant::Paper,
                                           qp::MpgpVariant::BarzilaiBorwein};
  std::vector<double> tols = {1e-6, 1e-8};
  int reps = 5;
  bool run = true;
};

struct Case {
  std::string name;
  MatrixXd Q;
  VectorXd h, radius;
  double norm_Q = 0.0;
  std::unique_ptr<fricon::bench::PaperDual> outer;  // what the outer loop needs; null for files

  qp::Operator A() const { return fricon::bench::dense_operator(Q); }
  qp::SeparableConstraints constraints(const VectorXd& r) const {
    return fricon::bench::disc_constraints(r);
  }
};

void finish_case(Case& k) {
  k.norm_Q = qp::estimate_norm(k.A(), k.h.size(), 200, 1e-10);  // the driver's settings
}

Case paper_case(Index n) {
  Case k;
  k.name = fmt::format("paper-n{}", n);
  k.outer = fricon::bench::paper_dual(n);
  k.Q = *k.outer->Q->dense();
  k.h = k.outer->Q->h();
  k.radius = k.outer->radius;
  finish_case(k);
  return k;
}

Case file_case(const fs::path& p) {
  const auto d = fricon::io::read_dual(p);
  Case k;
  k.name = p.filename().string();
  k.Q = d.Q;
  k.h = d.h;
  k.radius = d.radius;
  finish_case(k);
  return k;
}

using fricon::bench::median;

qp::MpgpOptions options(const Case& k, qp::MpgpVariant v, double tol) {
  qp::MpgpOptions o;
  o.variant = v;
  o.rel_tolerance = tol;
  o.norm_A = k.norm_Q;
  return o;
}

// ------------------------------------------------------------------------------------------
// Table 1: one QP from l = 0.

void single_qp(const Case& k, const Settings& s) {
  const auto c = k.constraints(k.radius);
  const qp::Operator A = k.A();
  for (const double tol : s.tols) {
    double paper_ms = 0.0;
    long paper_products = 0;
    for (const auto v : s.variants) {
      const auto opt = options(k, v, tol);
      std::vector<double> ms;
      qp::MpgpReport rep;
      VectorXd l;
      for (int r = 0; r < s.reps; ++r) {
        l = VectorXd::Zero(k.h.size());
        rep = qp::solve_mpgp(A, k.h, c, opt, l);
        ms.push_back(1e3 * rep.seconds);
      }
      const double t = median(ms);
      if (v == qp::MpgpVariant::Paper) {
        paper_ms = t;
        paper_products = rep.n_products;
      }
      fmt::print("{:<10} {:>5} {:>8.0e} {:<14} {:>7} {:>8} {:>9.2f} {:>9.2e} {:>7} {:>7}  {}\n",
                 k.name, k.h.size(), tol, fricon::enum_name(v), rep.iterations, rep.n_products, t,
                 fricon::bench::kkt_max(k.Q, k.h, c, l),
                 paper_products > 0 ? fmt::format("{:.2f}", static_cast<double>(rep.n_products) /
                                                                static_cast<double>(paper_products))
                                    : "-",
                 paper_ms > 0 ? fmt::format("{:.2f}", t / paper_ms) : "-",
                 fricon::enum_name(rep.termination));
    }
  }
}

// ------------------------------------------------------------------------------------------
// Table 2: the whole outer loop, warm-started.

struct RunResult {
  int outer = 0;
  long iterations = 0, products = 0;
  double qp_ms = 0.0;
  double kkt = 0.0;
  bool converged = false;
  VectorXd phi;
};

// The driver's own map Psi and outer loop (driver/tresca_map.hpp, outer/outer_loop.hpp) with
// the QP variant v; the QP time is the sum of the solver's own timings.
RunResult run_outer(const Case& k, qp::MpgpVariant v) {
  const fricon::bench::PaperDual& o = *k.outer;
  const auto& so = o.problem.solver;
  fricon::PhaseTimes times;
  const auto bounds = fricon::driver::make_slip_bounds(o.problem, o.model.mesh, o.disc);
  const auto unscaled = qp::BlockScaling::identity(o.disc.n_dual());  // the map keeps a reference
  fricon::driver::TrescaMap map(o.model.dofs, o.disc, *o.Q, *bounds, unscaled,
                                options(k, v, so.qp.rel_tolerance), so.warm_start, times);
  RunResult res;
  VectorXd phi = VectorXd::Zero(o.disc.surface.n_nodes());
  const auto rep =
      fricon::outer::iterate(map, phi, so.outer, [&](const fricon::outer::OuterIteration&) {
        res.iterations += map.last_qp().iterations;
        res.products += map.last_qp().n_products;
        res.qp_ms += 1e3 * map.last_qp().seconds;
      });
  res.outer = rep.iterations;
  res.converged = rep.converged();
  res.kkt = fricon::bench::kkt_max(k.Q, k.h, map.constraints(), map.lambda());
  res.phi = phi;
  return res;
}

void whole_run(const Case& k, const Settings& s) {
  RunResult paper;
  for (const auto v : s.variants) {
    RunResult res;
    std::vector<double> ms;
    for (int r = 0; r < s.reps; ++r) {
      res = run_outer(k, v);
      ms.push_back(res.qp_ms);
    }
    res.qp_ms = median(ms);
    if (v == qp::MpgpVariant::Paper) paper = res;
    const double dphi = paper.phi.size() == res.phi.size() && paper.phi.norm() > 0
                            ? (res.phi - paper.phi).norm() / paper.phi.norm()
                            : NAN;
    fmt::print("{:<10} {:<14} {:>5} {:>8} {:>8} {:>9.2f} {:>9.2e} {:>9.1e} {:>7} {:>7}  {}\n",
               k.name, fricon::enum_name(v), res.outer, res.iterations, res.products, res.qp_ms,
               res.kkt, dphi,
               paper.products > 0 ? fmt::format("{:.2f}", static_cast<double>(res.products) /
                                                              static_cast<double>(paper.products))
                                  : "-",
               paper.qp_ms > 0 ? fmt::format("{:.2f}", res.qp_ms / paper.qp_ms) : "-",
               res.converged ? "converged" : "NOT converged");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The variants of MPGP (qp::MpgpVariant) on the dual problems of the paper's brick or of "
      "dual files: one QP, then the whole outer loop.",
      "qp_variants_bench"};
  Settings s;
  std::vector<std::string> dumps;
  std::vector<Index> ns = {4, 8, 12, 16};
  fricon::bench::comma_list(app.add_option("--n", ns, "Mesh parameters n of the paper's brick"))
      ->check(CLI::Range(Index{1}, Index{1000}))
      ->capture_default_str();
  app.add_option("--dump", dumps, "Dual files (docs/dual-format.md) instead of the brick");
  fricon::bench::comma_list(app.add_option("--variants", s.variants, "QP variants (paper,bb)"))
      ->transform(fricon::bench::enum_spelling<qp::MpgpVariant>());
  fricon::bench::comma_list(app.add_option("--tol", s.tols, "QP tolerances"))
      ->capture_default_str();
  app.add_option("--reps", s.reps, "Runs per time (the median is shown)")->capture_default_str();
  app.add_flag_callback(
      "--no-run", [&s] { s.run = false; }, "Skip the whole runs");
  return fricon::bench::run_main(app, argc, argv, [&] {
    s.reps = std::max(1, s.reps);
    if (std::find(s.variants.begin(), s.variants.end(), qp::MpgpVariant::Paper) == s.variants.end())
      s.variants.insert(s.variants.begin(), qp::MpgpVariant::Paper);  // the reference

    std::vector<Case> cases;
    if (!dumps.empty()) {
      for (const auto& p : dumps)
        cases.push_back(file_case(p));
    } else {
      for (const Index n : ns)
        cases.push_back(paper_case(n));
    }

    fmt::print(
        "QP variants (qp::MpgpVariant) on the dual problem of the paper's brick, param 6e4.\n"
        "Single QP: first outer iteration (all radii 6e6 Pa), from l = 0, stop at ||g^P|| <= tol "
        "||h||; time = median of {} runs; kkt = max relative KKT residual of the result;\n"
        "x prod, x time = ratio to the variant paper (the reference; bb is the default of fricon "
        "solve).\n\n",
        s.reps);
    fmt::print("{:<10} {:>5} {:>8} {:<14} {:>7} {:>8} {:>9} {:>9} {:>7} {:>7}  {}\n", "problem",
               "n_d", "tol", "variant", "iters", "products", "time[ms]", "kkt", "x prod", "x time",
               "termination");
    for (const auto& k : cases)
      single_qp(k, s);

    if (s.run && dumps.empty()) {
      fmt::print(
          "\nWhole run: successive approximations as in the driver (warm starts, QP tol 1e-6, "
          "outer tol 1e-4); products = n_mult of the run; QP time = median of {} runs;\n"
          "dphi = ||phi - phi_paper|| / ||phi_paper|| of the final slips.\n\n",
          s.reps);
      fmt::print("{:<10} {:<14} {:>5} {:>8} {:>8} {:>9} {:>9} {:>9} {:>7} {:>7}  {}\n", "problem",
                 "variant", "outer", "qp iters", "n_mult", "QP[ms]", "kkt", "dphi", "x prod",
                 "x time", "status");
      for (const auto& k : cases)
        whole_run(k, s);
    }
    return 0;
  });
}
