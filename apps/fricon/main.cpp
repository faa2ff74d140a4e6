// fricon: the command-line program. Thin on purpose: parse the command line, read the problem,
// run the library, write the results, print a summary, and map the outcome to an exit code:
//   0 converged, 1 bad input (or an ill-posed problem), 2 not converged, 3 internal error.

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/results.hpp"

namespace {

enum ExitCode { kConverged = 0, kBadInput = 1, kNotConverged = 2, kInternalError = 3 };

std::string join_command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

void print_summary(const fricon::driver::RunResult& result, const std::filesystem::path& dir) {
  const auto& r = result.report;
  fmt::print("fricon {}: {}\n", FRICON_VERSION, fricon::driver::to_string(r.status));
  fmt::print("  mesh          {} nodes, {} tetrahedra\n", r.n_nodes, r.n_tets);
  fmt::print("  unknowns      n_primal = {}\n", r.n_primal);
  fmt::print("  factor        nnz(L) = {:.0f}, ordering {}\n", r.factor.nnz_L, r.factor.ordering);
  fmt::print("  max |u|       {:.6e} m\n", r.max_displacement);
  fmt::print("  equilibrium   |applied + contact + reactions| / |applied| = {:.2e}\n",
             r.equilibrium_residual);
  fmt::print("  residual      ||K u - f|| / ||f|| = {:.2e}\n", r.linear_residual);
  fmt::print("  time          {:.3f} s (", r.time_s);
  bool first = true;
  for (const auto& [name, e] : r.times.phases) {
    fmt::print("{}{} {:.3f}", first ? "" : ", ", name, e.seconds);
    first = false;
  }
  fmt::print(")\n  results       {}\n", dir.string());
}

int solve(const std::string& file, const std::string& out, const std::vector<std::string>& sets,
          const std::string& command_line) {
  const fricon::driver::Problem problem = fricon::io::read_problem(file, sets);
  const std::filesystem::path dir = std::filesystem::path(out.empty() ? problem.output.dir : out);
  const fricon::driver::RunResult result = fricon::driver::run(problem);
  fricon::io::write_results(dir, problem, result, {sets, command_line});
  print_summary(result, dir);
  if (result.report.status != fricon::driver::Status::Converged) {
    std::cerr << "fricon: NOT CONVERGED: " << result.report.message << "\n";
    return kNotConverged;
  }
  return kConverged;
}

int check(const std::string& file, const std::vector<std::string>& sets) {
  const fricon::driver::Problem problem = fricon::io::read_problem(file, sets);
  fricon::PhaseTimes times;
  const fricon::mesh::TetMesh mesh = fricon::driver::make_mesh(problem);
  fmt::print("{}: valid\n", file);
  fmt::print("  mesh   {} nodes, {} tetrahedra, {} boundary triangles (tags: {})\n", mesh.n_nodes(),
             mesh.n_tets(), mesh.n_faces(), mesh.tag_list());
  fmt::print("{}\n", fricon::io::to_json(problem).dump(2));
  return kConverged;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fricon: 3D contact of elastic bodies with Tresca friction and a solution-dependent "
      "coefficient of friction (P1 finite elements, dual MPGP, successive approximations).\n"
      "Exit codes: 0 converged, 1 bad input, 2 not converged, 3 internal error."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("fricon ") + FRICON_VERSION);

  std::string file, out;
  std::vector<std::string> sets;
  auto* solve_cmd = app.add_subcommand("solve", "Solve the problem of a TOML file and write results");
  solve_cmd->add_option("problem", file, "Problem file (TOML), see docs/problem-file.md")->required();
  solve_cmd->add_option("--out,-o", out, "Results folder (default: the file's output.dir)");
  solve_cmd->add_option("--set", sets, "Override a key of the file: KEY=VALUE (TOML value), repeatable")
      ->allow_extra_args(false);

  auto* check_cmd = app.add_subcommand("check", "Validate a problem file without solving; print its sizes");
  check_cmd->add_option("problem", file, "Problem file (TOML)")->required();
  check_cmd->add_option("--set", sets, "Override a key of the file: KEY=VALUE, repeatable")
      ->allow_extra_args(false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }

  try {
    if (*solve_cmd) return solve(file, out, sets, join_command_line(argc, argv));
    if (*check_cmd) return check(file, sets);
  } catch (const fricon::InputError& e) {
    std::cerr << "fricon: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const fricon::NumericalError& e) {
    std::cerr << "fricon: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "fricon: internal error: " << e.what() << "\n";
    return kInternalError;
  }
  return kInternalError;
}
