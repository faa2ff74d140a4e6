// fricon paper: Tables 1 and 2 of the paper, our numbers beside the published ones.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/solve.hpp"

namespace fricon::app {

namespace {

struct PaperOptions {
  Index max_n = 16;
  std::string table = "both";
  std::string dual_operator = "auto";
  double qp_rtol = 1e-6;
};

// Prints one table of the paper with our values beside theirs ("ours / paper").
// The largest relative deviation from the paper of one column, and the row where it is.
struct Deviation {
  double largest = 0.0;
  std::string where;
  void add(double ours, double theirs, const driver::PaperRow& row) {
    const double d = std::abs(ours - theirs) / std::abs(theirs);
    if (d >= largest) {
      largest = d;
      where = fmt::format("n = {}, param = {:g}", row.n, row.param);
    }
  }
};

// Prints one table of the paper with our values beside theirs ("ours / paper"), and the largest
// deviations of n_mult and ||w_hn^+||_inf.
bool print_paper_table(const std::string& title, const std::vector<driver::PaperRow>& rows,
                       const PaperOptions& o) {
  fmt::print("\n{}\n\n", title);
  fmt::print(
      "| n | param | n_p | n_d | it | n_mult | time [s] | ||w_hn^+||_0 | ||w_hn^+||_inf | "
      "max(-w_n) | max lambda_n | max ||w_t|| | max ||lambda_t|| | KKT max |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool ok = true;
  Deviation n_mult, wn_inf;
  for (const auto& row : rows) {
    if (row.n > o.max_n) continue;
    driver::Problem problem = driver::paper_problem(row.n, row.param);
    problem.solver.dual_operator = parse_enum<dual::DualOperatorKind>(o.dual_operator);
    problem.solver.qp.rel_tolerance = o.qp_rtol;
    const driver::RunResult r = fricon::solve(problem);
    const auto& c = *r.report.contact;
    const bool sizes_equal = r.report.n_primal == row.n_p && c.n_dual == row.n_d;
    const bool converged = r.report.status == driver::RunStatus::Converged;
    ok = ok && sizes_equal && converged;
    n_mult.add(static_cast<double>(c.n_mult), static_cast<double>(row.n_mult), row);
    wn_inf.add(c.wn_pos_inf, row.wn_pos_inf, row);
    fmt::print(
        "| {} | {:g} | {} / {} | {} / {} | {}{} / {} | {} / {} | {:.3f} / {:g} | {:.1e} / {:.1e} | "
        "{:.2e} / {:.1e} | {:.2e} | {:.3e} | {:.3e} | {:.3e} | {:.1e} |\n",
        row.n, row.param, r.report.n_primal, row.n_p, c.n_dual, row.n_d, c.outer_iterations,
        converged ? "" : "(!)", row.it, c.n_mult, row.n_mult, r.report.time_s, row.time_s,
        c.wn_pos_l2, row.wn_pos_l2, c.wn_pos_inf, row.wn_pos_inf, c.max_neg_wn, c.max_lambda_n,
        c.max_wt, c.max_lambda_t, c.kkt.max());
    std::fflush(stdout);
  }
  fmt::print(
      "\nLargest deviations from the paper: n_mult {:.1f} % ({}), ||w_hn^+||_inf {:.1f} % ({}; "
      "the paper prints two digits).\n",
      100 * n_mult.largest, n_mult.where, 100 * wn_inf.largest, wn_inf.where);
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
    ok = print_paper_table("Table 1 (param = 6e4)", driver::paper_table1(), o) && ok;
  if (o.table == "2" || o.table == "both")
    ok = print_paper_table("Table 2 (n = 16)", driver::paper_table2(), o) && ok;
  if (!ok) {
    std::cerr << "fricon paper: a run did not converge or a size differs from the paper\n";
    return kNotConverged;
  }
  return kConverged;
}

}  // namespace

Command define_paper(CLI::App& app) {
  auto o = std::make_shared<PaperOptions>();
  CLI::App* cmd = app.add_subcommand(
      "paper", "Reproduce Tables 1 and 2 of the paper: our numbers beside the published ones");
  cmd->add_option("--max-n", o->max_n, "Largest mesh parameter n to run (4..16)")
      ->check(CLI::Range(4, 16));
  cmd->add_option("--table", o->table, "Which table: 1, 2 or both")
      ->check(CLI::IsMember({"1", "2", "both"}));
  cmd->add_option("--dual-operator", o->dual_operator,
                  "How Q = B K^-1 B^T is applied: implicit (the paper's way), forward, schur, "
                  "auto (docs/theory.md §3.3)")
      ->check(CLI::IsMember(enum_names<dual::DualOperatorKind>()));
  cmd->add_option("--qp-rtol", o->qp_rtol, "QP tolerance (paper: 1e-6)")
      ->check(CLI::PositiveNumber);
  return {cmd, [o] { return paper(*o); }};
}

}  // namespace fricon::app
