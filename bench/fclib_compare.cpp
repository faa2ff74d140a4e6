// bench: fricon against Siconos on the friction problems of other codes (FCLIB and Siconos .dat
// files, by default ../shared/data/siconos-fc3d): `fricon dual solve`'s method (successive
// approximations over Tresca QPs by MPGP, driver/local_solve.hpp) and Siconos 4.4's nonsmooth
// Newton method on the Alart-Curnier formulation (NSN_AC), block Gauss-Seidel (NSGS) and the
// proximal point method (PROX), each from r = 0 with Siconos' default options but its tolerance
// (1e-10 on its own error) and 10000 iterations. Every answer is measured by the same yardstick,
// FCLIB's merit (fclib_merit_local); "ok" means merit <= 1e-8. Times are the median of 3 runs
// (one run when it takes more than a second).
//   build/bench/fclib_compare [DIR or FILES...]   (--help: the options)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "Friction_cst.h"
#include "common/bench_args.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/io/fclib_file.hpp"
#include "fricon/io/local_problem_file.hpp"
#include "tests/common/siconos_solve.hpp"

namespace {

using fricon::VectorXd;
namespace fs = std::filesystem;

struct Outcome {
  int iterations = 0;
  double seconds = 0.0, merit = 0.0;
  bool finished = false;
};

constexpr int kRepeats = 3;
constexpr double kRepeatBelow = 1.0;  // [s]
constexpr double kSiconosTolerance = 1e-10;
constexpr int kSiconosIterations = 10000;
constexpr double kSolvedMerit = 1e-8;

// The median of kRepeats runs, or the one run when it took longer than kRepeatBelow.
Outcome median_of(const std::function<Outcome()>& run) {
  std::vector<Outcome> o{run()};
  if (o.front().seconds > kRepeatBelow) return o.front();
  for (int k = 1; k < kRepeats; ++k)
    o.push_back(run());
  std::sort(o.begin(), o.end(),
            [](const Outcome& a, const Outcome& b) { return a.seconds < b.seconds; });
  return o[kRepeats / 2];
}

Outcome fricon_run(const fricon::qp::LocalProblem& p) {
  fricon::driver::LocalSolveOptions o;
  o.merit = [&p](const VectorXd& r, const VectorXd& u) { return fricon::io::fclib_merit(p, r, u); };
  const auto s = fricon::driver::solve_local(p, o);
  return {static_cast<int>(s.qp_iterations), s.seconds, s.merit, s.solved};
}

Outcome siconos_run(const fricon::qp::LocalProblem& p, int solver) {
  const auto s = fricon::test::siconos_solve(fricon::MatrixXd(p.W), p.q, p.mu, solver,
                                             kSiconosTolerance, kSiconosIterations);
  Outcome out;
  out.seconds = s.seconds;
  out.iterations = s.iterations;
  out.finished = s.info == 0;
  const VectorXd u = p.W * s.r + p.q;
  out.merit = fricon::io::fclib_merit(p, s.r, u);
  return out;
}

void row(const std::string& name, fricon::Index m, const char* solver, const Outcome& o,
         double reference_seconds) {
  const bool ok = o.merit <= kSolvedMerit;
  fmt::print("{:<42} {:>5} {:<8} {:>7} {:>10.3f} {:>10.2e} {:>7} {}\n", name, m, solver,
             o.iterations, 1e3 * o.seconds, o.merit,
             reference_seconds > 0 ? fmt::format("{:.2f}", o.seconds / reference_seconds) : "-",
             ok ? "ok" : (o.finished ? "merit not reached" : "not converged"));
  std::fflush(stdout);
}

std::vector<fs::path> problem_files(const std::vector<fs::path>& arguments) {
  std::vector<fs::path> files;
  for (const auto& a : arguments) {
    if (!fs::is_directory(a)) {
      files.push_back(a);
      continue;
    }
    for (const auto& e : fs::directory_iterator(a))
      if (e.path().extension() == ".hdf5" || e.path().extension() == ".dat")
        files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The table: every problem by fricon, then by each Siconos solver.
int compare(const std::vector<std::string>& given) {
  std::vector<fs::path> arguments(given.begin(), given.end());
  if (arguments.empty()) {
    const fs::path shared = fs::path(FRICON_SOURCE_DIR) / ".." / "shared" / "data" / "siconos-fc3d";
    if (!fs::is_directory(shared)) {
      fmt::print("fclib_compare: {} is absent; give problem files or a folder\n", shared.string());
      return 0;
    }
    arguments.push_back(shared);
  }
  const auto files = problem_files(arguments);
  fmt::print(
      "fricon (dual solve) against Siconos 4.4 on the same local problems; merit = FCLIB's "
      "fclib_merit_local of each answer, ok = merit <= 1e-8;\ntime = median of {} runs (one run "
      "above {} s), ratio = "
      "time / fricon's; iterations: fricon's QP iterations over all Tresca steps, Siconos' "
      "own.\n\n",
      kRepeats, kRepeatBelow);
  fmt::print("{:<42} {:>5} {:<8} {:>7} {:>10} {:>10} {:>7} {}\n", "problem", "m", "solver", "iters",
             "time[ms]", "merit", "ratio", "status");
  for (const auto& f : files) {
    const auto p = fricon::io::read_local_problem(f);
    if (!p.is_coulomb()) continue;
    const Outcome ours = median_of([&] { return fricon_run(p); });
    row(f.filename().string(), p.q.size(), "fricon", ours, ours.seconds);
    for (const auto& [name, id] :
         {std::pair{"NSN_AC", SICONOS_FRICTION_3D_NSN_AC},
          std::pair{"NSGS", SICONOS_FRICTION_3D_NSGS}, std::pair{"PROX", SICONOS_FRICTION_3D_PROX}})
      row(f.filename().string(), p.q.size(), name, median_of([&] { return siconos_run(p, id); }),
          ours.seconds);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fricon's `dual solve` against Siconos 4.4 (NSN_AC, NSGS, PROX) on the friction problems "
      "of other codes, all measured by FCLIB's merit.",
      "fclib_compare"};
  std::vector<std::string> given;
  app.add_option("problems", given,
                 "Problem files (.hdf5, .dat) or folders of them (default: "
                 "../shared/data/siconos-fc3d)");
  return fricon::bench::run_main(app, argc, argv, [&] { return compare(given); });
}
