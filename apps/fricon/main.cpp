// fricon: the command-line program. Thin on purpose: parse the command line, read the problem,
// run the library, write the results, print a summary, and map the outcome to an exit code:
//   0 converged, 1 bad input (or an ill-posed problem), 2 not converged, 3 internal error.

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "fricon/core/error.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/results.hpp"

namespace {

enum ExitCode { kConverged = 0, kBadInput = 1, kNotConverged = 2, kInternalError = 3 };

std::string join_command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i)
    s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

void print_summary(const fricon::driver::RunResult& result, const std::filesystem::path& dir) {
  const auto& r = result.report;
  fmt::print("fricon {}: {}\n", FRICON_VERSION, fricon::driver::to_string(r.status));
  fmt::print("  mesh          {} nodes, {} tetrahedra\n", r.n_nodes, r.n_tets);
  fmt::print("  unknowns      n_primal = {}\n", r.n_primal);
  fmt::print("  factor        nnz(L) = {:.0f}, ordering {}\n", r.factor.nnz_L, r.factor.ordering);
  if (r.contact) {
    const auto& c = *r.contact;
    fmt::print("  contact       '{}': {} patches, n_dual = {}, {} contact nodes, friction {}\n",
               c.boundary, c.n_patches, c.n_dual, c.n_contact_nodes, c.friction_law);
    fmt::print("  outer loop    {} iterations, err(k):", c.outer_iterations);
    for (double e : c.err_history)
      fmt::print(" {:.2e}", e);
    fmt::print(
        "\n  dual QP       {} MPGP steps, n_mult = {} products with Q ({}), {} solves with K\n",
        c.qp_iterations, c.n_mult, c.dual_operator, c.n_kinv);
    fmt::print("  KKT           feasibility {:.1e}, stationarity {:.1e}, complementarity {:.1e}\n",
               c.kkt.feasibility, c.kkt.stationarity, c.kkt.complementarity);
    fmt::print(
        "  ||w_hn^+||    L2 {:.3e} m^2, max {:.3e} m; max(-w_n) {:.3e} m, max ||w_t|| {:.3e} m\n",
        c.wn_pos_l2, c.wn_pos_inf, c.max_neg_wn, c.max_wt);
    fmt::print(
        "  multipliers   max lambda_n {:.4e} Pa, max ||lambda_t|| {:.4e} Pa, normal force {:.4e} "
        "N\n",
        c.max_lambda_n, c.max_lambda_t, c.total_normal_force);
  }
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

struct PaperOptions {
  fricon::Index max_n = 16;
  std::string table = "both";
  std::string dual_operator = "auto";
  double qp_rtol = 1e-6;
};

// Prints one table of the paper with our values beside theirs ("ours / paper").
bool print_paper_table(const std::string& title, const std::vector<fricon::driver::PaperRow>& rows,
                       const PaperOptions& o) {
  fmt::print("\n{}\n\n", title);
  fmt::print(
      "| n | param | n_p | n_d | it | n_mult | time [s] | ||w_hn^+||_0 | ||w_hn^+||_inf | "
      "max(-w_n) | max lambda_n | max ||w_t|| | max ||lambda_t|| | KKT max |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool ok = true;
  for (const auto& row : rows) {
    if (row.n > o.max_n) continue;
    fricon::driver::Problem problem = fricon::driver::paper_problem(row.n, row.param);
    problem.solver.dual_operator = o.dual_operator;
    problem.solver.qp_rtol = o.qp_rtol;
    const fricon::driver::RunResult r = fricon::driver::run(problem);
    const auto& c = *r.report.contact;
    const bool sizes_equal = r.report.n_primal == row.n_p && c.n_dual == row.n_d;
    const bool converged = r.report.status == fricon::driver::Status::Converged;
    ok = ok && sizes_equal && converged;
    fmt::print(
        "| {} | {:g} | {} / {} | {} / {} | {}{} / {} | {} / {} | {:.3f} / {:g} | {:.1e} / {:.1e} | "
        "{:.2e} / {:.1e} | {:.2e} | {:.3e} | {:.3e} | {:.3e} | {:.1e} |\n",
        row.n, row.param, r.report.n_primal, row.n_p, c.n_dual, row.n_d, c.outer_iterations,
        converged ? "" : "(!)", row.it, c.n_mult, row.n_mult, r.report.time_s, row.time_s,
        c.wn_pos_l2, row.wn_pos_l2, c.wn_pos_inf, row.wn_pos_inf, c.max_neg_wn, c.max_lambda_n,
        c.max_wt, c.max_lambda_t, c.kkt.max());
    std::fflush(stdout);
  }
  return ok;
}

int paper(const PaperOptions& o) {
  fmt::print("fricon {}: the model example of Haslinger & Ligursky (2009), Tables 1 and 2.\n",
             FRICON_VERSION);
  fmt::print(
      "Each cell: ours / paper. Paper times are from 2007 hardware. Dual operator: {}, qp_rtol = "
      "{:g}.\n",
      o.dual_operator, o.qp_rtol);
  bool ok = true;
  if (o.table == "1" || o.table == "both")
    ok = print_paper_table("Table 1 (param = 6e4)", fricon::driver::paper_table1(), o) && ok;
  if (o.table == "2" || o.table == "both")
    ok = print_paper_table("Table 2 (n = 16)", fricon::driver::paper_table2(), o) && ok;
  if (!ok) {
    std::cerr << "fricon paper: a run did not converge or a size differs from the paper\n";
    return kNotConverged;
  }
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
  auto* solve_cmd =
      app.add_subcommand("solve", "Solve the problem of a TOML file and write results");
  solve_cmd->add_option("problem", file, "Problem file (TOML), see docs/problem-file.md")
      ->required();
  solve_cmd->add_option("--out,-o", out, "Results folder (default: the file's output.dir)");
  solve_cmd
      ->add_option("--set", sets, "Override a key of the file: KEY=VALUE (TOML value), repeatable")
      ->allow_extra_args(false);

  auto* check_cmd =
      app.add_subcommand("check", "Validate a problem file without solving; print its sizes");
  check_cmd->add_option("problem", file, "Problem file (TOML)")->required();
  check_cmd->add_option("--set", sets, "Override a key of the file: KEY=VALUE, repeatable")
      ->allow_extra_args(false);

  PaperOptions paper_opt;
  auto* paper_cmd = app.add_subcommand(
      "paper", "Reproduce Tables 1 and 2 of the paper: our numbers beside the published ones");
  paper_cmd->add_option("--max-n", paper_opt.max_n, "Largest mesh parameter n to run (4..16)")
      ->check(CLI::Range(4, 16));
  paper_cmd->add_option("--table", paper_opt.table, "Which table: 1, 2 or both")
      ->check(CLI::IsMember({"1", "2", "both"}));
  paper_cmd
      ->add_option("--dual-operator", paper_opt.dual_operator,
                   "How Q = B K^-1 B^T is applied: implicit (the paper's way), dense, auto")
      ->check(CLI::IsMember({"auto", "implicit", "dense"}));
  paper_cmd->add_option("--qp-rtol", paper_opt.qp_rtol, "QP tolerance (paper: 1e-6)")
      ->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }

  try {
    if (*solve_cmd) return solve(file, out, sets, join_command_line(argc, argv));
    if (*check_cmd) return check(file, sets);
    if (*paper_cmd) return paper(paper_opt);
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
