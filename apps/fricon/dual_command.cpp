// fricon dual solve FILE: a frictional contact problem of another code in local (dual) form.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/io/fclib_file.hpp"
#include "fricon/io/local_problem_file.hpp"

namespace fricon::app {

namespace {

struct DualSolveOptions {
  std::string file, out;
  double tol = 1e-8;
  std::string variant{enum_name(driver::LocalSolveOptions{}.variant)};
  std::string expansion{enum_name(driver::LocalSolveOptions{}.expansion)};
  std::string active_discs{enum_name(driver::LocalSolveOptions{}.active_discs)};
  bool no_scaling = false;
};

// `fricon dual solve FILE`: a local frictional contact problem of another code (FCLIB, or
// fricon's own dual dump) solved by fricon's QP and outer loop, certified by its natural-map
// residual and FCLIB's merit. Exit 0 solved, 2 not solved (with the reason).
int dual_solve(const DualSolveOptions& o) {
  const qp::LocalProblem p = io::read_local_problem(o.file);
  driver::LocalSolveOptions so;
  so.residual_tol = o.tol;
  so.merit_tol = o.tol;
  so.variant = parse_enum<qp::MpgpVariant>(o.variant);
  so.expansion = parse_enum<qp::MpgpExpansion>(o.expansion);
  so.active_discs = parse_enum<qp::MpgpDiscFace>(o.active_discs);
  so.scaling = !o.no_scaling;
  if (p.is_coulomb())
    so.merit = [&p](const VectorXd& r, const VectorXd& u) { return io::fclib_merit(p, r, u); };
  const driver::LocalSolution s = driver::solve_local(p, so);
  fmt::print("fricon dual solve: {}\n", o.file);
  fmt::print("  problem     {}, {} contacts (m = {}), nnz(W) = {}, ||S|| = {:.3e}\n",
             p.is_coulomb() ? "Coulomb" : "Tresca", p.n_contacts(), p.q.size(), p.W.nonZeros(),
             s.norm_W);
  fmt::print("  W           {}\n", driver::describe_symmetry(s));
  fmt::print("  QP          MPGP {}, expansion {}, active discs {}, {}\n", enum_name(so.variant),
             enum_name(so.expansion), enum_name(so.active_discs),
             so.scaling ? fmt::format("scaled per contact (||D S D|| = {:.3e})", s.norm_W_scaled)
                        : std::string("not scaled"));
  fmt::print("  iterations  {} outer ({}), {} QP iterations, {} products with W\n",
             s.outer_iterations, enum_name(s.termination), s.qp_iterations, s.n_products);
  fmt::print("  residual    natural map {:.2e}", s.residual);
  if (p.is_coulomb()) fmt::print(", FCLIB merit {:.2e}", s.merit);
  fmt::print(" (tolerance {:.1e}; {} refinements)\n", o.tol, s.refinements);
  if (p.reference_r && p.reference_r->norm() > 0)
    fmt::print("  reference   ||r - r_file|| / ||r_file|| = {:.2e}\n",
               (s.r - *p.reference_r).norm() / p.reference_r->norm());
  fmt::print("  time        {:.3f} s\n", s.seconds);
  if (!o.out.empty() && s.solved) io::write_fclib_solution(o.out, p, s.r, s.u);
  if (!s.solved) {
    std::cerr << "fricon: NOT SOLVED: " << s.reason << "\n";
    return kNotConverged;
  }
  fmt::print("  solved\n");
  return kConverged;
}

}  // namespace

std::vector<Command> define_dual(CLI::App& app) {
  auto o = std::make_shared<DualSolveOptions>();
  auto* dual =
      app.add_subcommand("dual", "Frictional contact problems of other codes in local (dual) form");
  dual->require_subcommand(1);
  CLI::App* cmd = dual->add_subcommand(
      "solve",
      "Solve a local problem: an FCLIB file (HDF5: local, or global reduced to local form) or a\n"
      "fricon dual file (docs/dual-format.md). Coulomb by successive approximations over Tresca\n"
      "QPs, Tresca by one QP; prints the iterations, the time, the natural-map residual and\n"
      "FCLIB's merit. Exit 0 solved, 2 not solved (the reason is printed)");
  cmd->add_option("file", o->file, "Problem file")->required();
  cmd->add_option("--out,-o", o->out, "Write the problem and its solution as an FCLIB file");
  cmd->add_option("--tol", o->tol, "Solved when the natural-map residual is below this")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--qp-variant", o->variant, "MPGP variant: bb or paper")
      ->check(CLI::IsMember(enum_names<qp::MpgpVariant>()))
      ->capture_default_str();
  cmd->add_option("--qp-expansion", o->expansion,
                  "MPGP expansion move: fixed, opt or projcg (theory.md §4.2)")
      ->check(CLI::IsMember(enum_names<qp::MpgpExpansion>()))
      ->capture_default_str();
  cmd->add_option("--qp-active-discs", o->active_discs,
                  "MPGP's CG steps and the slipping contacts' discs: turn or hold (theory.md §4.7)")
      ->check(CLI::IsMember(enum_names<qp::MpgpDiscFace>()))
      ->capture_default_str();
  cmd->add_flag("--no-scaling", o->no_scaling,
                "Solve each QP in the given variables instead of scaled per contact");
  return {{cmd, [o] { return dual_solve(*o); }}};
}

}  // namespace fricon::app
