// Benchmark of a loading path (theory.md §2.9) against one static run of the same problem,
// measured in the same process: the paper's brick (param = 6e4, the paper's tolerances but
// qp_rtol = 1e-7 for both: a step moves the slips by a twentieth of the whole, and at 1e-6 the
// QPs' error stalls the outer loop of a step near outer_tol = 1e-4) solved
// statically with its loads, and as a path of `steps` steps that ends at the same loads: the top's
// pressure ramped up over the first quarter of the steps, then the end face's traction (the
// shear) over the rest. K is factorized and Q formed once for the path; the table gives each
// step's time, outer iterations, products with Q and patch states, and the ratio of the path's
// wall time (and products) to the static run's.
//   build/bench/loading_path_bench                 n = 16, 20 steps, fastest of 3
//   build/bench/loading_path_bench --n 8 --steps 40 --repeat 1
#include <algorithm>
#include <cstdio>
#include <vector>

#include <fmt/format.h>

#include "common/bench_args.hpp"
#include "common/child_process.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

namespace {

using namespace fricon;

constexpr Real kQpTolerance = 1e-7;  // qp_rtol of both runs

// The pressure of the top face z1 up to its value over the first quarter of the steps, then
// the traction of the end face x1 (its shear and pull) up to its value over the rest.
driver::Problem press_then_shear(driver::Problem p, int steps) {
  const int press_steps = std::max(1, steps / 4);
  p.loading.steps = steps;
  for (driver::TractionOptions& t : p.traction) {
    const bool top = t.boundary == "z1";
    for (int k = 1; k <= steps; ++k) {
      const Real press = std::min(1.0, static_cast<Real>(k) / press_steps);
      const Real shear =
          k <= press_steps ? 0.0 : static_cast<Real>(k - press_steps) / (steps - press_steps);
      t.path.push_back(top ? press : shear);
    }
  }
  return p;
}

struct Timed {
  driver::RunResult result;
  double seconds = 0.0;
};

// The fastest of `repeat` runs (the machine's noise only ever adds time).
Timed fastest(const driver::Problem& p, int repeat) {
  Timed best;
  for (int k = 0; k < repeat; ++k) {
    const Stopwatch watch;
    driver::RunResult r = driver::run(p);
    const double s = watch.seconds();
    if (k == 0 || s < best.seconds) best = {std::move(r), s};
  }
  return best;
}

int report(long n, int steps, int repeat, dual::DualOperatorKind op) {
  driver::Problem statics = driver::paper_problem(n, 6e4);
  statics.solver.qp.rel_tolerance = kQpTolerance;
  statics.solver.dual_operator = op;
  statics.solver.qp.variant = driver::SolverOptions{}.qp.variant;  // fricon's default MPGP
  const Timed one = fastest(statics, repeat);
  const Timed path = fastest(press_then_shear(statics, steps), repeat);
  const driver::ContactReport& c = *one.result.report.contact;
  fmt::print(
      "paper brick n = {}: {} free dofs, {} patches; static run vs a {}-step path "
      "(press, then shear) ending at the same loads; fastest of {}\n\n",
      n, one.result.report.n_primal, c.n_patches, steps, repeat);
  fmt::print(
      "| step | time [s] | outer its | n_mult | stick/slip/separated | normal force [N] | "
      "tangential force [N] |\n|---|---|---|---|---|---|---|\n");
  long path_products = 0;
  for (const driver::StepReport& s : path.result.report.steps) {
    path_products += s.n_mult;
    fmt::print("| {} | {:.4f} | {} | {} | {}/{}/{} | {:.4e} | {:.4e} |\n", s.step, s.time_s,
               s.outer_iterations, s.n_mult, s.n_stick, s.n_slip, s.n_separated, s.normal_force,
               s.tangential_force.norm());
  }
  const bool ok = one.result.report.status == driver::RunStatus::Converged &&
                  path.result.report.status == driver::RunStatus::Converged;
  fmt::print(
      "\nstatic run: {:.3f} s, {} outer its, n_mult {}; path: {:.3f} s, n_mult {} (all steps)\n"
      "path / static: wall time {:.2f}, products with Q {:.2f}; factorize {:.3f} s and dual "
      "{:.3f} s once for the path; peak memory {:.0f} MiB; {}\n",
      one.seconds, c.outer_iterations, c.n_mult, path.seconds, path_products,
      path.seconds / one.seconds,
      static_cast<double>(path_products) / static_cast<double>(std::max(c.n_mult, 1L)),
      path.result.report.times.seconds("factorize"), path.result.report.times.seconds("dual"),
      bench::peak_mib(), ok ? "both converged" : "NOT CONVERGED");
  fmt::print("phases of the path [s]:");
  for (const auto& [name, e] : path.result.report.times.phases)
    fmt::print(" {} {:.3f};", name, e.seconds);
  fmt::print("\nphases of the static run [s]:");
  for (const auto& [name, e] : one.result.report.times.phases)
    fmt::print(" {} {:.3f};", name, e.seconds);
  fmt::print("\n");
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fricon;
  CLI::App app{"A loading path of the paper's brick against one static run"};
  long n = 16;
  int steps = 20, repeat = 3;
  dual::DualOperatorKind op = dual::DualOperatorKind::Auto;
  app.add_option("--operator", op, "the dual operator of both runs")
      ->transform(bench::enum_spelling<dual::DualOperatorKind>());
  app.add_option("--n", n, "the paper's n (brick of 3n x n x n cubes)")->check(CLI::Range(2, 64));
  app.add_option("--steps", steps, "steps of the path")->check(CLI::Range(2, 1000));
  app.add_option("--repeat", repeat, "runs of each, the fastest kept")->check(CLI::Range(1, 20));
  return fricon::bench::run_main(app, argc, argv, [&] { return report(n, steps, repeat, op); });
}
