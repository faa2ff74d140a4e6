// fricon solve PROBLEM.toml: read, run, write the results, print the summary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/feti/softness.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/results.hpp"
#include "fricon/solve.hpp"
#include "signals.hpp"
#ifdef FRICON_HAVE_PETSC
#include <fcntl.h>
#include <unistd.h>

#include "fricon/parallel/mpi/session.hpp"
#endif

namespace fricon::app {

namespace {

// Two force figures that agree to this relative accuracy are the same up to round-off.
constexpr double kSameForce = 1e-9;

// One line per pair when there are several or one against a body: its patches and forces (its
// warnings are the report's, print_warnings).
void print_pairs(const driver::ContactReport& c) {
  if (c.pairs.size() == 1 && c.pairs.front().info.master.empty()) return;
  for (const driver::PairReport& p : c.pairs) {
    const std::string against =
        p.info.master.empty() ? std::string("the plane") : fmt::format("'{}'", p.info.master);
    fmt::print(
        "  {:<13} '{}' on {}: {} friction {}, {} patches ({} stick, {} slip, {} separated), "
        "normal force {:.4e} N, tangential force {:.4e} N\n",
        p.info.key, p.info.boundary, against, enum_name(p.model), p.friction_law, p.n_patches,
        p.n_stick, p.n_slip, p.n_separated, p.normal_force, p.tangential_force.norm());
  }
}

// The report's warnings (driver::result_warnings): in the summary, or on stderr (the log).
void print_warnings(const driver::RunReport& r, std::FILE* to, const char* prefix) {
  for (const std::string& w : r.warnings)
    fmt::print(to, "{}{}\n", prefix, w);
}

// The softest subdomain against the median (feti/softness.hpp), and what to do when some are
// joined by necks.
void print_softness(const feti::Softness& s) {
  if (s.softest < 0) return;
  fmt::print(
      "  softness      lambda_7(K_s) / mean diag(K_s): median {:.2e}, softest {:.2e} (subdomain "
      "{}), {:.1f} times below\n",
      s.median, s.softest_relative(), s.softest, s.ratio);
  if (s.necked.empty()) return;
  fmt::print(
      "  warning       {} subdomain(s) at least {:.0f} times softer than the median, parts joined "
      "by a neck (theory.md §8.9): the QPs may take several times their usual products; "
      "solver.tfeti_neck_cuts (default {}) cuts such subdomains again, and another "
      "solver.subdomain_size or solver.subdomains gives another partition\n",
      s.necked.size(), feti::kNeckRatio, feti::kDefaultNeckCuts);
}

void print_summary(const driver::RunResult& result, const std::filesystem::path& dir) {
  const auto& r = result.report;
  fmt::print("fricon {}: {}\n", FRICON_VERSION, enum_name(r.status));
  fmt::print("  mesh          {} nodes, {} {}-node tetrahedra\n", r.n_nodes, r.n_tets,
             r.nodes_per_tet);
  fmt::print("  unknowns      n_primal = {}\n", r.n_primal);
  if (r.feti) {
    const auto& f = *r.feti;
    fmt::print(
        "  subdomains    {} (tfeti, {} threads), {}-{} nodes each (mean {:.0f}); {} gluing, {} "
        "Dirichlet, {} contact multipliers; coarse problem {} rows\n",
        f.n_subdomains, f.threads, f.min_nodes, f.max_nodes, f.mean_nodes, f.n_gluing,
        f.n_dirichlet, f.n_contact, f.n_coarse);
    fmt::print(
        "  factors       nnz = {:.0f} ({:.0f} MiB) in {:.3f} s ({:.3f} s summed over the "
        "subdomains); {} products with F in {:.3f} s; peak memory {:.0f} MiB\n",
        f.nnz_factors, f.factor_mib, f.factorization_s, f.factorization_cpu_s, f.n_products,
        f.products_s, f.peak_memory_mib);
    fmt::print(
        "  coarse        G G^T of {} rows: {} solves in {:.3f} s, its decompositions included\n",
        f.n_coarse, f.n_coarse_solves, f.coarse_s);
    if (f.preconditioner != "none")
      fmt::print("  preconditioner {} in face: {} applications in {:.3f} s\n", f.preconditioner,
                 f.n_preconditioner, f.preconditioner_s);
    if (!f.partition_note.empty()) fmt::print("  partition     {}\n", f.partition_note);
    print_softness(f.softness);
    if (f.n_ranks > 1) {
      fmt::print(
          "  ranks         {} (tfeti), subdomains / multipliers / ghosts / factor MiB / memory "
          "MiB with the model built / peak memory MiB per rank:",
          f.n_ranks);
      for (const feti::RankShare& rank : f.ranks)
        fmt::print(" {}/{}/{}/{:.0f}/{:.0f}/{:.0f}", rank.n_subdomains, rank.n_multipliers,
                   rank.n_ghosts, rank.factor_mib, rank.model_memory_mib, rank.peak_memory_mib);
      fmt::print("\n");
    }
  } else {
    fmt::print("  factor        nnz(L) = {:.0f}, ordering {}\n", r.factor.nnz_L, r.factor.ordering);
  }
  if (r.parallel) {
    fmt::print("  ranks         {} (backend petsc, partition {}), peak memory per rank [MiB]:",
               r.parallel->n_ranks, enum_name(r.parallel->partition));
    for (const auto& rank : r.parallel->ranks)
      fmt::print(" {:.0f}", rank.peak_memory_mib);
    fmt::print("\n");
  }
  if (r.contact) {
    const auto& c = *r.contact;
    if (c.mixed_models)
      fmt::print(
          "  contact       '{}': {} patches, n_dual = {}, {} contact nodes, friction per "
          "pair (below)\n",
          c.boundary, c.n_patches, c.n_dual, c.n_contact_nodes);
    else
      fmt::print(
          "  contact       '{}': {} patches, n_dual = {}, {} contact nodes, {} friction {}\n",
          c.boundary, c.n_patches, c.n_dual, c.n_contact_nodes, enum_name(c.model), c.friction_law);
    for (const driver::PairReport& p : c.pairs)
      if (p.info.obstacle)
        fmt::print("  obstacle      {}{}\n", c.pairs.size() > 1 ? p.info.key + ": " : "",
                   contact::describe(*p.info.obstacle, p.info.obstacle_displacement));
    if (c.search_rounds > 0)
      fmt::print(
          "  search        {} of {} patches in the QP, {} left out (none penetrates), {} {}\n",
          c.n_candidate_patches, c.n_patches, c.n_patches - c.n_candidate_patches, c.search_rounds,
          c.search_rounds == 1 ? "round" : "rounds");
    if (c.geometry_updates >= 0)
      fmt::print(
          "  geometry      {} geometric update(s): the linearized gap is within {:.2e} m of the "
          "true one at the deformed position ({:.2e} of the normal displacement {:.3e} m; "
          "tolerance {:g})\n",
          c.geometry_updates, c.geometry_change,
          c.geometry_scale > 0.0 ? c.geometry_change / c.geometry_scale : 0.0, c.geometry_scale,
          c.geometry_tolerance);
    fmt::print("  outer loop    {} iterations ({}), err(k):", c.outer_iterations,
               enum_name(c.termination));
    for (double e : c.err_history)
      fmt::print(" {:.2e}", e);
    // Under Total FETI the dual operator is F, and a solve is one with every subdomain's factor.
    fmt::print(
        "\n  dual QP       {} MPGP steps ({} CG, {} expansion, {} proportioning), n_mult = {} "
        "products with {} ({}), {} {}\n",
        c.qp_iterations, c.qp_steps.cg, c.qp_steps.expansion, c.qp_steps.proportioning, c.n_mult,
        r.feti ? "F" : "Q", enum_name(c.dual_operator), c.n_kinv,
        r.feti ? "rounds of solves with the subdomains' factors" : "solves with K");
    fmt::print(
        "  KKT           feasibility {:.1e}, stationarity {:.1e}, complementarity {:.1e}: max "
        "{:.1e} {} {:.1e} = 100 qp_rtol, certificate {}\n",
        c.kkt.feasibility, c.kkt.stationarity, c.kkt.complementarity, c.kkt.max(),
        c.kkt.max() <= c.kkt_bound ? "<=" : ">", c.kkt_bound,
        c.kkt.max() <= c.kkt_bound ? "passed" : "FAILED");
    if (r.feti)
      fmt::print(
          "  gluing        the subdomains' copies differ by {:.1e} of the displacement (root "
          "mean squares) {} {:.1e} = 100 qp_rtol, certificate {}\n",
          c.gluing_residual, c.gluing_residual <= c.kkt_bound ? "<=" : ">", c.kkt_bound,
          c.gluing_residual <= c.kkt_bound ? "passed" : "FAILED");
    if (c.model == contact::FrictionModel::Coulomb)
      fmt::print(
          "  Coulomb       natural-map residual{} {:.1e} {} {:.1e} = certificate_tol{}, "
          "certificate {}\n",
          c.mixed_models ? " over the Coulomb pairs" : "", c.coulomb_residual,
          c.coulomb_residual <= c.coulomb_bound ? "<=" : ">", c.coulomb_bound,
          c.certificate_refinements > 0
              ? fmt::format(" after {} round(s) at tighter tolerances", c.certificate_refinements)
              : std::string(),
          c.coulomb_residual <= c.coulomb_bound ? "passed" : "FAILED");
    if (c.rigid_amplitudes.size() > 0)
      fmt::print(
          "  balance       floating bodies: ||G lambda - e|| / ||e|| = {:.1e} {} {:.1e}, "
          "certificate {}; SMALSE-M {} outer steps\n",
          c.equality_residual, c.equality_residual <= c.equality_bound ? "<=" : ">",
          c.equality_bound, c.equality_residual <= c.equality_bound ? "passed" : "FAILED",
          c.smalse_outer_iterations);
    fmt::print("  patches       {} stick, {} slip, {} separated\n", c.n_stick, c.n_slip,
               c.n_separated);
    print_pairs(c);
    if (c.n_objective_increases > 0)
      fmt::print("  monotonicity  {} QP steps increased the objective (expected 0)\n",
                 c.n_objective_increases);
    fmt::print(
        "  ||w_hn^+||    L2 {:.3e} m^2, max {:.3e} m; max(-w_n) {:.3e} m, max ||w_t|| {:.3e} m\n",
        c.wn_pos_l2, c.wn_pos_inf, c.max_neg_wn, c.max_wt);
    fmt::print(
        "  multipliers   max lambda_n {:.4e} Pa, max ||lambda_t|| {:.4e} Pa, normal force {:.4e} "
        "N (sum lambda_n |R|)\n",
        c.max_lambda_n, c.max_lambda_t, c.total_normal_force);
    // The two figures of theory.md §6.1 differ where contact nodes have a prescribed normal
    // component: the pressure there acts on their supports.
    if (std::abs(c.total_normal_force - c.transmitted_normal_force) >
        kSameForce * std::abs(c.total_normal_force))
      fmt::print(
          "  normal force  {:.4e} N on free components (balancing the loads and reactions), "
          "{:.4e} N on prescribed components (taken by their supports)\n",
          c.transmitted_normal_force, c.total_normal_force - c.transmitted_normal_force);
  }
  const bool floats = std::any_of(r.bodies.begin(), r.bodies.end(),
                                  [](const auto& b) { return !b.free_motions.empty(); });
  if (floats || r.bodies.size() > 1)
    for (const driver::BodyReport& body : r.bodies)
      fmt::print("  {:<13} {}\n", body.index == 0 ? "bodies" : "", driver::body_line(body));
  fmt::print("  max |u|       {:.6e} m\n", r.max_displacement);
  fmt::print(
      "  equilibrium   |applied + contact + reactions| / sum of the nodal forces' magnitudes "
      "({:.4e} N) = {:.2e}\n",
      r.force_scale, r.equilibrium_residual);
  fmt::print("  residual      ||K u - f + B^T lambda|| / max(||f||, ||B^T lambda||) = {:.2e}\n",
             r.linear_residual);
  print_warnings(r, stdout, "  WARNING       ");
  fmt::print("  results       {}\n", dir.string());
  // Time per phase, like a miniature PETSc -log_view.
  fmt::print("  time          {:.3f} s in all\n", r.time_s);
  fmt::print("    {:<12} {:>10} {:>7} {:>6}\n", "phase", "seconds", "share", "calls");
  for (const auto& [name, e] : r.times.phases)
    fmt::print("    {:<12} {:>10.4f} {:>6.1f}% {:>6}\n", name, e.seconds,
               r.time_s > 0 ? 100.0 * e.seconds / r.time_s : 0.0, e.calls);
}

enum class Verbosity { Quiet, Normal, Verbose };

struct SolveOptions {
  std::string out;
  bool out_given = false;  ///< --out was given (then an empty path is refused)
  std::vector<std::string> sets;
  std::string dump_dual;
  Verbosity verbosity = Verbosity::Normal;
  bool plot = false;
};

// Progress on stderr: phases as they start, one monitor line per outer iteration and, verbose,
// one line per MPGP step (step letters as in PERMON: c = CG, e = expansion, p = proportioning).
driver::RunOptions progress_options(Verbosity v, const Stopwatch& clock) {
  driver::RunOptions o;
  if (v == Verbosity::Quiet) return o;
  o.on_phase_start = [&clock](const std::string& phase) {
    fmt::print(stderr, "[{:8.3f} s] {} ...\n", clock.seconds(), phase);
  };
  auto header = std::make_shared<bool>(false);
  o.on_outer_iteration = [&clock, header](const driver::IterationReport& it) {
    if (!*header) {
      fmt::print(stderr, "{:>4} {:>11} {:>8} {:>8} {:>11} {:>10}\n", "k", "err(k)", "QP its",
                 "Q mults", "||gP||/||h||", "elapsed");
      *header = true;
    }
    fmt::print(stderr, "{:>4} {:>11.3e} {:>8} {:>8} {:>11.2e} {:>8.3f} s\n", it.k, it.err,
               it.qp_iterations, it.qp_products, it.qp_rel_gp, clock.seconds());
  };
  if (v == Verbosity::Verbose)
    o.on_qp_iteration = [](const qp::MpgpIteration& q) {
      fmt::print(stderr,
                 "      qp {:>6} [{}] ||gP|| {:.3e} ||phi|| {:.3e} ||beta|| {:.3e} alpha {:.3e} q "
                 "{:.6e}\n",
                 q.iteration, q.step, q.norm_gp, q.norm_phi, q.norm_beta, q.alpha, q.objective);
      return true;
    };
  return o;
}

struct SolveCommandLine {
  std::string file;
  SolveOptions solve;
  bool quiet = false, verbose = false;
};

#ifdef FRICON_HAVE_PETSC
// Under mpirun every rank runs this program; only rank 0 prints (progress, summary, errors).
// FRICON_RANK_OUTPUT=all keeps the other ranks' output, for debugging.
void silence_other_ranks() {
  if (parallel::world_rank() == 0) return;
  if (const char* keep = std::getenv("FRICON_RANK_OUTPUT"); keep && std::string(keep) == "all")
    return;
  const int null = open("/dev/null", O_WRONLY);
  if (null < 0) return;
  dup2(null, STDOUT_FILENO);
  dup2(null, STDERR_FILENO);
  close(null);
}
#endif

int mpi_ranks() {
#ifdef FRICON_HAVE_PETSC
  return parallel::initialized() ? parallel::world_size() : 1;
#else
  return 1;
#endif
}

bool is_rank_zero() {
#ifdef FRICON_HAVE_PETSC
  if (parallel::initialized()) return parallel::world_rank() == 0;
#endif
  return true;
}

// The results folder: --out if given (not empty), else the file's output.dir.
std::filesystem::path results_folder(const driver::Problem& problem, const SolveOptions& so) {
  if (!so.out_given) return problem.output.dir;
  if (so.out.empty())
    throw InputError("--out: an empty path; name the results folder (e.g. --out results)");
  return so.out;
}

// The problem, read by every rank of an MPI job (an error on one rank ends them all, the same),
// and its results folder, made ready by rank 0 before anything is solved (io::prepare_results:
// a folder that cannot be written ends the run now, not after the solve).
driver::Problem read_problem_on_every_rank(const std::string& file, const SolveOptions& so,
                                           std::filesystem::path& dir) {
  driver::Problem problem;
  const auto read = [&] {
    problem = io::read_problem(file, so.sets);
    if (mpi_ranks() > 1 && problem.solver.backend == parallel::Backend::Cholmod)
      throw InputError(fmt::format(
          "{}: solver.backend: \"{}\" runs on one process, but mpirun started {} ranks; run "
          "with --set solver.backend=petsc or tfeti (docs/parallel.md)",
          problem.where("solver.backend"), enum_name(problem.solver.backend), mpi_ranks()));
    if (!so.dump_dual.empty() && problem.solver.backend == parallel::Backend::Tfeti)
      throw InputError(fmt::format(
          "--dump-dual: the dual QP of backend \"tfeti\" carries the subdomains' gluing "
          "multipliers; dump the contact QP with --set solver.backend=cholmod ({})",
          problem.where("solver.backend")));
    dir = results_folder(problem, so);
    if (is_rank_zero()) io::prepare_results(dir);
  };
#ifdef FRICON_HAVE_PETSC
  if (parallel::initialized()) {
    parallel::collectively(read);
    return problem;
  }
#endif
  read();
  return problem;
}

// A loading path: the files of the steps that [output] chooses are written as each step ends
// (a stop keeps the steps done; `written` lists them, for solution.pvd), with a line per step.
void follow_path(const driver::Problem& problem, const std::filesystem::path& dir,
                 Verbosity verbosity, driver::RunOptions& options,
                 const std::shared_ptr<std::vector<int>>& written) {
  options.on_step = [dir, verbosity, written, output = problem.output,
                     steps = problem.loading.steps](const driver::RunResult& r) {
    if (!is_rank_zero()) return;  // (backend tfeti on MPI ranks: rank 0 writes)
    const int step = r.report.steps.back().step;
    if (io::step_files_wanted(output, step, steps) &&
        !io::write_step(dir, r, output.vtu_encoding).empty())
      written->push_back(step);
    if (verbosity == Verbosity::Quiet) return;
    const driver::StepReport& s = r.report.steps.back();
    fmt::print(stderr,
               "step {:>4}/{}: normal force {:.4e} N, tangential {:.4e} N, stick/slip/separated "
               "{}/{}/{}, max slip {:.3e} m (accumulated {:.3e}), {} outer its, {} products, "
               "{:.2f} s{}\n",
               s.step, steps, s.normal_force, s.tangential_force.norm(), s.n_stick, s.n_slip,
               s.n_separated, s.max_slip, s.max_accumulated_slip, s.outer_iterations, s.n_mult,
               s.time_s, s.status == driver::RunStatus::Converged ? "" : "  NOT CONVERGED");
  };
}

int solve(const std::string& file, const SolveOptions& so, const std::string& command_line) {
  const Stopwatch clock;
#ifdef FRICON_HAVE_PETSC
  if (parallel::launched_by_mpi()) {
    parallel::initialize();
    silence_other_ranks();
  }
#endif
  std::filesystem::path dir;
  const driver::Problem problem = read_problem_on_every_rank(file, so, dir);
  driver::RunOptions options = progress_options(so.verbosity, clock);
  options.keep_first_dual = !so.dump_dual.empty();
  options.fields = is_rank_zero();  // (the other ranks of backend tfeti write nothing)
  options.stop_requested = &stop_requested;
  // From the outer loop on, a signal stops the run at its next QP step with an iterate to save.
  options.on_phase_start = [progress = options.on_phase_start](const std::string& phase) {
    if (phase == "outer loop" || phase == "follow") has_iterate.store(true);
    if (progress) progress(phase);
  };
  const auto written_steps = std::make_shared<std::vector<int>>();
  if (problem.loading.steps > 1) follow_path(problem, dir, so.verbosity, options, written_steps);
  install_signal_handlers();
  const driver::RunResult result = fricon::solve(problem, options);
  // Rank 0 of a distributed run writes the results (the others have served it, or, with
  // tfeti, hold the same).
  if (!is_rank_zero())
    return result.report.status == driver::RunStatus::Converged ? kConverged : kNotConverged;
  if (!so.dump_dual.empty()) {
    if (!result.first_dual)
      throw InputError(fmt::format("{}: --dump-dual needs a [contact] section", file));
    io::write_dual(so.dump_dual, *result.first_dual);
  }
  io::write_results(dir, problem, result, {so.sets, command_line}, *written_steps);
  if (so.verbosity != Verbosity::Quiet) {
    print_warnings(result.report, stderr, "fricon: warning: ");
    print_summary(result, dir);
  }
  if (so.plot) render_plots(dir.string(), "");
  if (result.report.status != driver::RunStatus::Converged) {
    std::cerr << "fricon: NOT CONVERGED: " << result.report.message << "\n"
              << "fricon: the last iterate is in " << dir.string() << "/*.not-converged.*\n";
    return kNotConverged;
  }
  return kConverged;
}

}  // namespace

Command define_solve(CLI::App& app, const Invocation& invocation) {
  auto o = std::make_shared<SolveCommandLine>();
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Solve the problem of a TOML file and write its results.\n"
      "Progress goes to stderr (phases, one line per outer iteration), the summary to stdout.\n"
      "Results: report.json, solution.vtu, contact.vtu, solution.pvd, contact_nodes.csv,\n"
      "patches.csv in the results folder (see README). The folder is checked (and cleared of an\n"
      "earlier run's results and figures) before the solve: one that cannot be written ends\n"
      "the run with exit code 4.");
  cmd->add_option("problem", o->file, "Problem file (TOML), see docs/problem-file.md")->required();
  CLI::Option* out = cmd->add_option("--out,-o", o->solve.out,
                                     "Results folder, not empty (default: the file's output.dir)");
  cmd->add_option("--set", o->solve.sets,
                  "Override a key of the file: KEY=VALUE with a TOML value, e.g.\n"
                  "--set mesh.cells=[24,8,8] --set contact.friction.param=2e4; repeatable;\n"
                  "recorded in report.json")
      ->allow_extra_args(false);
  cmd->add_option("--dump-dual", o->solve.dump_dual,
                  "Also write the dual QP of the first outer iteration to this file\n"
                  "(format: docs/dual-format.md)");
  cmd->add_flag("--quiet,-q", o->quiet, "Print nothing but errors");
  cmd->add_flag("--plot", o->solve.plot, "Also render the figures (as `fricon plot`)");
  cmd->add_flag("--verbose,-v", o->verbose, "Also print every step of the inner QP solver");
  return {cmd, [o, out, &invocation] {
            o->solve.out_given = out->count() > 0;
            o->solve.verbosity = o->quiet     ? Verbosity::Quiet
                                 : o->verbose ? Verbosity::Verbose
                                              : Verbosity::Normal;
            return solve(o->file, o->solve, invocation.command_line);
          }};
}

}  // namespace fricon::app
