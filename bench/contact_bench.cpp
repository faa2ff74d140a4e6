// Benchmark of the whole contact solve on the paper's brick against one linear elastic solve of
// the same mesh, measured in the same process: for each n, first assembly + factorization + one
// solve (the floor of any method with a direct factorization), then the full frictional run
// (param = 6e4, the paper's tolerances). Each n runs in its own child process so that the peak
// resident memory belongs to that size.
//   build/bench/contact_bench                  n = 4, 6, ..., 16
//   build/bench/contact_bench 24 32            chosen sizes
//   build/bench/contact_bench --operator implicit 8
//   build/bench/contact_bench --qp-variant paper 16   the paper's MPGP (default: fricon's default)
//   build/bench/contact_bench --repeat 5 16           fastest of 5 (default 3 up to n = 16, else 1)
//   build/bench/contact_bench --model coulomb         Coulomb friction (the paper's coefficient)
//   build/bench/contact_bench --help                  the options (bench/common/bench_args.hpp)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/bench_args.hpp"
#include "common/child_process.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

namespace {

struct Row {
  long n = 0, n_primal = 0, n_dual = 0, outer = 0, qp_its = 0, n_mult = 0, n_kinv = 0;
  double linear = 0, total = 0, factorize = 0, dual = 0, qp = 0, other = 0, peak_mib = 0;
  bool converged = false;
  char mode[16] = {};
  char variant[16] = {};
};

// One linear solve and one full run, alternated `repeat` times; the fastest of each is kept
// (the machine's noise only ever adds time).
// The choices of the command line.
struct Settings {
  fricon::dual::DualOperatorKind mode = fricon::dual::DualOperatorKind::Auto;
  fricon::qp::MpgpVariant variant = fricon::driver::SolverOptions{}.qp.variant;
  fricon::contact::FrictionModel model = fricon::contact::FrictionModel::Tresca;
  int repeat = 0;  // 0: 3 up to n = 16, 1 beyond
};

Row measure(long n, const Settings& s, int repeat) {
  using namespace fricon;
  Row r;
  r.n = n;
  driver::Problem p = driver::paper_problem(n, 6e4);
  p.contact.front().model = s.model;
  p.solver.dual_operator = s.mode;
  p.solver.qp.variant = s.variant;
  for (int k = 0; k < repeat; ++k) {
    {
      Stopwatch watch;
      PhaseTimes times;
      const driver::Model m = driver::build_model(p, times);
      const VectorXd u = m.factor.solve(m.f);
      const double linear = watch.seconds();
      if (!u.allFinite()) std::exit(3);
      if (k == 0 || linear < r.linear) r.linear = linear;
    }
    const driver::RunResult result = driver::run(p);
    const auto& rep = result.report;
    if (k > 0 && rep.time_s >= r.total) continue;
    const auto& c = *rep.contact;
    r.n_primal = rep.n_primal;
    r.n_dual = c.n_dual;
    r.outer = c.outer_iterations;
    r.qp_its = c.qp_iterations;
    r.n_mult = c.n_mult;
    r.n_kinv = c.n_kinv;
    r.total = rep.time_s;
    r.factorize = rep.times.seconds("factorize");
    r.dual = rep.times.seconds("dual");
    r.qp = rep.times.seconds("qp");
    r.other = r.total - r.factorize - r.dual - r.qp;
    r.converged = rep.status == driver::RunStatus::Converged;
    std::snprintf(r.mode, sizeof r.mode, "%s", std::string(enum_name(c.dual_operator)).c_str());
    std::snprintf(r.variant, sizeof r.variant, "%s",
                  std::string(enum_name(p.solver.qp.variant)).c_str());
  }
  r.peak_mib = fricon::bench::peak_mib();
  return r;
}

// The table: one row per n, each measured in a child process.
int scan(std::vector<long> sizes, const Settings& s) {
  if (sizes.empty()) sizes = {4, 6, 8, 10, 12, 14, 16};
  fmt::print(
      "Paper brick, param = 6e4, {} friction: the full frictional run against one linear solve "
      "of the same mesh\n",
      fricon::enum_name(s.model));
  fmt::print(
      "(linear = assembly + factorization + one solve; ratio = total / linear; times in s, the\n"
      "fastest of 3 alternated repetitions up to n = 16, of one beyond, unless --repeat R)\n\n");
  fmt::print(
      "| n | n_p | n_d | operator | QP variant | outer | QP its | n_mult | K^-1 solves | factorize "
      "| dual | qp "
      "| other | total | linear | ratio | peak RSS [MiB] |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int code = 0;
  for (long n : sizes) {
    const auto row = fricon::bench::run_in_child(
        [&] { return measure(n, s, s.repeat > 0 ? s.repeat : (n <= 16 ? 3 : 1)); });
    if (!row) {
      fmt::print("| {} | failed (out of memory or killed) |\n", n);
      code = 3;
      continue;
    }
    const Row& r = *row;
    fmt::print(
        "| {} | {} | {} | {} | {} | {}{} | {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | "
        "{:.3f} | "
        "{:.3f} | {:.2f} | {:.0f} |\n",
        r.n, r.n_primal, r.n_dual, r.mode, r.variant, r.outer,
        r.converged ? "" : " (not converged)", r.qp_its, r.n_mult, r.n_kinv, r.factorize, r.dual,
        r.qp, r.other, r.total, r.linear, r.total / r.linear, r.peak_mib);
    std::fflush(stdout);
    if (!r.converged) code = 2;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fricon;
  CLI::App app{
      "The whole contact solve of the paper's brick against one linear elastic solve of the same "
      "mesh, one child process per n.",
      "contact_bench"};
  std::vector<long> sizes;
  Settings s;
  app.add_option("n", sizes, "Mesh parameters n (default 4, 6, ..., 16)")
      ->check(CLI::Range(1L, 1000L));
  app.add_option("--operator", s.mode, "Dual operator (default auto)")
      ->transform(bench::enum_spelling<dual::DualOperatorKind>());
  app.add_option("--qp-variant", s.variant, "QP variant (default: fricon's default)")
      ->transform(bench::enum_spelling<qp::MpgpVariant>());
  app.add_option("--repeat", s.repeat,
                 "Keep the fastest of R runs (0, the default: 3 up to n = 16, else 1)")
      ->check(CLI::Range(0, 1000));
  app.add_option("--model", s.model, "Friction model (default tresca)")
      ->transform(bench::enum_spelling<contact::FrictionModel>());
  return bench::run_main(app, argc, argv, [&] { return scan(sizes, s); });
}
