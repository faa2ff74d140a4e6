// Benchmark of the elastic core on the paper's brick: time and peak memory of assembly,
// factorization and one solve, for n = 8, 16, 24 (or the n given on the command line).
// Each n runs in its own child process, so that the peak resident memory is that of one size.
//   build/bench/elasticity_bench [n ...]   (--help: the options)
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

namespace {

struct Row {
  long n = 0, n_primal = 0;
  double nnz_L = 0, mesh = 0, assembly = 0, factorize = 0, solve = 0, peak_mib = 0;
};

Row measure(fricon::Index n) {
  using namespace fricon;
  const driver::Problem p = driver::paper_problem(n, 6e4);
  PhaseTimes times;
  const driver::Model m = driver::build_model(p, times);
  Stopwatch watch;
  const VectorXd u = m.factor.solve(m.f);
  Row r;
  r.solve = watch.seconds();
  r.n = n;
  r.n_primal = m.dofs.n_free();
  r.nnz_L = m.factor.info().nnz_L;
  r.mesh = times.seconds("mesh");
  r.assembly = times.seconds("assembly");
  r.factorize = times.seconds("factorize");
  r.peak_mib = fricon::bench::peak_mib();
  if (!u.allFinite()) std::exit(3);
  return r;
}

// The table: one row per n, each measured in a child process.
int scan(std::vector<long> sizes) {
  if (sizes.empty()) sizes = {8, 16, 24};
  fmt::print(
      "Elastic brick (paper's mesh, 3n x n x n cubes): one linear solve, phases in seconds\n\n");
  fmt::print(
      "| n | n_primal | nnz(L) | mesh [s] | assembly [s] | factorize [s] | solve [s] | peak RSS "
      "[MiB] |\n");
  fmt::print("|---|---|---|---|---|---|---|---|\n");
  for (long n : sizes) {
    const auto row = fricon::bench::run_in_child([n] { return measure(n); });
    if (!row) {
      fmt::print("| {} | failed |\n", n);
      return 3;
    }
    const Row& r = *row;
    fmt::print("| {} | {} | {:.3e} | {:.3f} | {:.3f} | {:.3f} | {:.4f} | {:.0f} |\n", r.n,
               r.n_primal, r.nnz_L, r.mesh, r.assembly, r.factorize, r.solve, r.peak_mib);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The elastic core on the paper's brick: assembly, factorization and one solve, one child "
      "process per n.",
      "elasticity_bench"};
  std::vector<long> sizes;
  app.add_option("n", sizes, "Mesh parameters n (default 8, 16, 24)")->check(CLI::Range(1L, 1000L));
  return fricon::bench::run_main(app, argc, argv, [&] { return scan(sizes); });
}
