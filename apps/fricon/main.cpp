// fricon: the command-line program. Thin on purpose: parse the command line, read the problem,
// run the library, write the results, print a summary, and map the outcome to an exit code:
//   0 converged, 1 bad input (or an ill-posed problem), 2 not converged, 3 internal error.

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "fricon/core/error.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/fclib_file.hpp"
#include "fricon/io/local_problem_file.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/results.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/gmsh_file.hpp"
#ifdef FRICON_HAVE_PETSC
#include <fcntl.h>

#include "fricon/parallel/mpi/session.hpp"
#endif

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
  fmt::print("fricon {}: {}\n", FRICON_VERSION, fricon::enum_name(r.status));
  fmt::print("  mesh          {} nodes, {} tetrahedra\n", r.n_nodes, r.n_tets);
  fmt::print("  unknowns      n_primal = {}\n", r.n_primal);
  fmt::print("  factor        nnz(L) = {:.0f}, ordering {}\n", r.factor.nnz_L, r.factor.ordering);
  if (r.parallel) {
    fmt::print("  ranks         {} (backend petsc, partition {}), peak memory per rank [MiB]:",
               r.parallel->n_ranks, fricon::enum_name(r.parallel->partition));
    for (const auto& rank : r.parallel->ranks)
      fmt::print(" {:.0f}", rank.peak_memory_mib);
    fmt::print("\n");
  }
  if (r.contact) {
    const auto& c = *r.contact;
    fmt::print("  contact       '{}': {} patches, n_dual = {}, {} contact nodes, {} friction {}\n",
               c.boundary, c.n_patches, c.n_dual, c.n_contact_nodes, fricon::enum_name(c.model),
               c.friction_law);
    if (c.search_rounds > 0)
      fmt::print(
          "  search        {} of {} patches in the QP, {} left out (none penetrates), {} {}\n",
          c.n_candidate_patches, c.n_patches, c.n_patches - c.n_candidate_patches, c.search_rounds,
          c.search_rounds == 1 ? "round" : "rounds");
    fmt::print("  outer loop    {} iterations ({}), err(k):", c.outer_iterations,
               fricon::enum_name(c.termination));
    for (double e : c.err_history)
      fmt::print(" {:.2e}", e);
    fmt::print(
        "\n  dual QP       {} MPGP steps, n_mult = {} products with Q ({}), {} solves with K\n",
        c.qp_iterations, c.n_mult, fricon::enum_name(c.dual_operator), c.n_kinv);
    fmt::print(
        "  KKT           feasibility {:.1e}, stationarity {:.1e}, complementarity {:.1e}: max "
        "{:.1e} {} {:.1e} = 100 qp_rtol, certificate {}\n",
        c.kkt.feasibility, c.kkt.stationarity, c.kkt.complementarity, c.kkt.max(),
        c.kkt.max() <= c.kkt_bound ? "<=" : ">", c.kkt_bound,
        c.kkt.max() <= c.kkt_bound ? "passed" : "FAILED");
    if (c.model == fricon::contact::FrictionModel::Coulomb)
      fmt::print("  Coulomb       natural-map residual {:.1e} {} {:.1e}, certificate {}\n",
                 c.coulomb_residual, c.coulomb_residual <= c.coulomb_bound ? "<=" : ">",
                 c.coulomb_bound, c.coulomb_residual <= c.coulomb_bound ? "passed" : "FAILED");
    fmt::print("  patches       {} stick, {} slip, {} separated\n", c.n_stick, c.n_slip,
               c.n_separated);
    if (c.n_objective_increases > 0)
      fmt::print("  monotonicity  {} QP steps increased the objective (expected 0)\n",
                 c.n_objective_increases);
    fmt::print(
        "  ||w_hn^+||    L2 {:.3e} m^2, max {:.3e} m; max(-w_n) {:.3e} m, max ||w_t|| {:.3e} m\n",
        c.wn_pos_l2, c.wn_pos_inf, c.max_neg_wn, c.max_wt);
    fmt::print(
        "  multipliers   max lambda_n {:.4e} Pa, max ||lambda_t|| {:.4e} Pa, normal force {:.4e} "
        "N\n",
        c.max_lambda_n, c.max_lambda_t, c.total_normal_force);
  }
  fmt::print("  max |u|       {:.6e} m\n", r.max_displacement);
  fmt::print("  equilibrium   |applied + contact + reactions| / largest of the three = {:.2e}\n",
             r.equilibrium_residual);
  fmt::print("  residual      ||K u - f|| / ||f|| = {:.2e}\n", r.linear_residual);
  fmt::print("  results       {}\n", dir.string());
  // Time per phase, like a miniature PETSc -log_view.
  fmt::print("  time          {:.3f} s in all\n", r.time_s);
  fmt::print("    {:<12} {:>10} {:>7} {:>6}\n", "phase", "seconds", "share", "calls");
  for (const auto& [name, e] : r.times.phases)
    fmt::print("    {:<12} {:>10.4f} {:>6.1f}% {:>6}\n", name, e.seconds,
               r.time_s > 0 ? 100.0 * e.seconds / r.time_s : 0.0, e.calls);
}

enum class Verbosity { Quiet, Normal, Verbose };

// Ctrl-C (SIGINT), SIGTERM and SIGUSR1. Once the outer loop has started there is an iterate to
// save: the signal asks the run to stop at its next QP step, and the run writes its last iterate
// as not converged. Before (assembly, factorization, forming Q: long library calls with nothing
// to save) the program ends at once with exit code 2 and no results. A second signal ends it at
// once in any case. Under mpirun (docs/parallel.md) SIGUSR1 is the one to send: mpirun forwards
// it to every rank, while on Ctrl-C it kills the ranks a second after SIGTERM; the ranks other
// than 0 ignore the first signal once they follow rank 0's outer loop, whose solves they serve
// until rank 0 has written its results.
std::atomic<bool> g_stop{false};
std::atomic<bool> g_has_iterate{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
extern "C" void on_signal(int sig) {
  if (!g_has_iterate.load()) {
    // Only async-signal-safe calls here: write(2) and _exit(2).
    constexpr char kMessage[] = "fricon: interrupted (no iterate to write yet)\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    _exit(kNotConverged);
  }
  if (g_stop.exchange(true)) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGUSR1, &action, nullptr);
}

struct SolveOptions {
  std::string out;
  std::vector<std::string> sets;
  std::string dump_dual;
  Verbosity verbosity = Verbosity::Normal;
  bool plot = false;
};

// Progress on stderr: phases as they start, one monitor line per outer iteration and, verbose,
// one line per MPGP step (step letters as in PERMON: c = CG, e = expansion, p = proportioning).
fricon::driver::RunOptions progress_options(Verbosity v, const fricon::Stopwatch& clock) {
  fricon::driver::RunOptions o;
  if (v == Verbosity::Quiet) return o;
  o.on_phase_start = [&clock](const std::string& phase) {
    fmt::print(stderr, "[{:8.3f} s] {} ...\n", clock.seconds(), phase);
  };
  auto header = std::make_shared<bool>(false);
  o.on_outer_iteration = [&clock, header](const fricon::driver::OuterIteration& it) {
    if (!*header) {
      fmt::print(stderr, "{:>4} {:>11} {:>8} {:>8} {:>11} {:>10}\n", "k", "err(k)", "QP its",
                 "Q mults", "||gP||/||h||", "elapsed");
      *header = true;
    }
    fmt::print(stderr, "{:>4} {:>11.3e} {:>8} {:>8} {:>11.2e} {:>8.3f} s\n", it.k, it.err,
               it.qp_iterations, it.qp_products, it.qp_rel_gp, clock.seconds());
  };
  if (v == Verbosity::Verbose)
    o.on_qp_iteration = [](const fricon::qp::MpgpIteration& q) {
      fmt::print(stderr,
                 "      qp {:>6} [{}] ||gP|| {:.3e} ||phi|| {:.3e} ||beta|| {:.3e} alpha {:.3e} q "
                 "{:.6e}\n",
                 q.iteration, q.step, q.norm_gp, q.norm_phi, q.norm_beta, q.alpha, q.objective);
      return true;
    };
  return o;
}

// Renders the figures of a results folder with scripts/plot_results.py under Debian's Python
// (which has matplotlib); returns its exit status. FRICON_SCRIPTS_DIR in the environment
// overrides where the script is looked for.
int plot(const std::string& dir, const std::string& out) {
  const char* env = std::getenv("FRICON_SCRIPTS_DIR");
  const std::filesystem::path script =
      std::filesystem::path(env ? env : FRICON_SCRIPTS_DIR) / "plot_results.py";
  if (!std::filesystem::exists(script))
    throw fricon::Error(fmt::format("plot script {} not found", script.string()));
  std::vector<std::string> args{"/usr/bin/python3", script.string(), dir};
  if (!out.empty()) {
    args.push_back("--out");
    args.push_back(out);
  }
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0)
    throw fricon::Error("cannot run /usr/bin/python3 (install python3-matplotlib: make deps)");
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "fricon: plotting " << dir << " failed\n";
    return kBadInput;
  }
  return kConverged;
}

#ifdef FRICON_HAVE_PETSC
// Under mpirun every rank runs this program; only rank 0 prints (progress, summary, errors).
// FRICON_RANK_OUTPUT=all keeps the other ranks' output, for debugging.
void silence_other_ranks() {
  if (fricon::parallel::world_rank() == 0) return;
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
  return fricon::parallel::initialized() ? fricon::parallel::world_size() : 1;
#else
  return 1;
#endif
}

// The problem, read by every rank of an MPI job (an error on one rank ends them all, the same).
fricon::driver::Problem read_problem_on_every_rank(const std::string& file,
                                                   const std::vector<std::string>& sets) {
  fricon::driver::Problem problem;
  const auto read = [&] {
    problem = fricon::io::read_problem(file, sets);
    if (mpi_ranks() > 1 && problem.solver.backend != fricon::parallel::Backend::Petsc)
      throw fricon::InputError(fmt::format(
          "{}: solver.backend: \"{}\" runs on one process, but mpirun started {} ranks; run "
          "with --set solver.backend=petsc (docs/parallel.md)",
          problem.where("solver.backend"), fricon::enum_name(problem.solver.backend), mpi_ranks()));
  };
#ifdef FRICON_HAVE_PETSC
  if (fricon::parallel::initialized()) {
    fricon::parallel::collectively(read);
    return problem;
  }
#endif
  read();
  return problem;
}

int solve(const std::string& file, const SolveOptions& so, const std::string& command_line) {
  const fricon::Stopwatch clock;
#ifdef FRICON_HAVE_PETSC
  if (fricon::parallel::launched_by_mpi()) {
    fricon::parallel::initialize();
    silence_other_ranks();
  }
#endif
  const fricon::driver::Problem problem = read_problem_on_every_rank(file, so.sets);
  const std::filesystem::path dir =
      std::filesystem::path(so.out.empty() ? problem.output.dir : so.out);
  fricon::driver::RunOptions options = progress_options(so.verbosity, clock);
  options.keep_first_dual = !so.dump_dual.empty();
  options.stop_requested = &g_stop;
  // From the outer loop on, a signal stops the run at its next QP step with an iterate to save.
  options.on_phase_start = [progress = options.on_phase_start](const std::string& phase) {
    if (phase == "outer loop" || phase == "follow") g_has_iterate.store(true);
    if (progress) progress(phase);
  };
  install_signal_handlers();
  const fricon::driver::RunResult result = fricon::driver::run(problem, options);
  // The other ranks of a distributed run have served rank 0, which writes the results.
  if (result.report.parallel && result.report.parallel->rank != 0)
    return result.report.status == fricon::driver::Status::Converged ? kConverged : kNotConverged;
  if (!so.dump_dual.empty()) {
    if (!result.first_dual)
      throw fricon::InputError(fmt::format("{}: --dump-dual needs a [contact] section", file));
    fricon::io::write_dual(so.dump_dual, *result.first_dual);
  }
  fricon::io::write_results(dir, problem, result, {so.sets, command_line});
  if (so.verbosity != Verbosity::Quiet) print_summary(result, dir);
  if (so.plot) plot(dir.string(), "");
  if (result.report.status != fricon::driver::Status::Converged) {
    std::cerr << "fricon: NOT CONVERGED: " << result.report.message << "\n"
              << "fricon: the last iterate is in " << dir.string() << "/*.not-converged.*\n";
    return kNotConverged;
  }
  return kConverged;
}

int check(const std::string& file, const std::vector<std::string>& sets) {
  const fricon::driver::Problem problem = fricon::io::read_problem(file, sets);
  const fricon::mesh::TetMesh mesh = fricon::driver::make_mesh(problem);
  (void)fricon::driver::make_materials(problem, mesh);  // every region has its material
  const fricon::fe::DofMap dofs = fricon::driver::make_dofs(problem, mesh);
  std::optional<fricon::contact::ContactDiscretization> disc;
  if (problem.contact) disc = fricon::driver::discretize_contact(problem, mesh, dofs);
  fmt::print("{}: valid\n", file);
  fmt::print("  mesh       {} nodes, {} tetrahedra, {} regions, {} boundary triangles (tags: {})\n",
             mesh.n_nodes(), mesh.n_tets(), mesh.n_regions(), mesh.n_faces(), mesh.tag_list());
  fmt::print("  unknowns   n_primal = {}\n", dofs.n_free());
  if (disc) {
    fmt::print(
        "  contact    '{}': {} surface nodes ({} contact nodes), {} patches ({}), n_dual = {}, "
        "stability sigma_min/sigma_max(B) = {:.3g}, initial gap {:.3g} to {:.3g} m\n",
        disc->surface.tag, disc->surface.n_nodes(), disc->surface.n_contact_nodes(),
        disc->n_patches(), fricon::enum_name(problem.contact->patches), disc->n_dual(),
        disc->stability.ratio, disc->gap.minCoeff(), disc->gap.maxCoeff());
    if (!disc->partition_note.empty()) fmt::print("  partition  {}\n", disc->partition_note);
    fmt::print("  friction   {}\n",
               fricon::contact::make_friction_law(problem.contact->friction)->describe());
  }
  fmt::print("effective problem:\n{}\n", fricon::io::to_json(problem).dump(2));
  return kConverged;
}

struct PaperOptions {
  fricon::Index max_n = 16;
  std::string table = "both";
  std::string dual_operator = "auto";
  double qp_rtol = 1e-6;
};

// Prints one table of the paper with our values beside theirs ("ours / paper").
// The largest relative deviation from the paper of one column, and the row where it is.
struct Deviation {
  double largest = 0.0;
  std::string where;
  void add(double ours, double theirs, const fricon::driver::PaperRow& row) {
    const double d = std::abs(ours - theirs) / std::abs(theirs);
    if (d >= largest) {
      largest = d;
      where = fmt::format("n = {}, param = {:g}", row.n, row.param);
    }
  }
};

// Prints one table of the paper with our values beside theirs ("ours / paper"), and the largest
// deviations of n_mult and ||w_hn^+||_inf.
bool print_paper_table(const std::string& title, const std::vector<fricon::driver::PaperRow>& rows,
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
    fricon::driver::Problem problem = fricon::driver::paper_problem(row.n, row.param);
    problem.solver.dual_operator =
        fricon::parse_enum<fricon::dual::DualOperatorKind>(o.dual_operator);
    problem.solver.qp.rel_tolerance = o.qp_rtol;
    const fricon::driver::RunResult r = fricon::driver::run(problem);
    const auto& c = *r.report.contact;
    const bool sizes_equal = r.report.n_primal == row.n_p && c.n_dual == row.n_d;
    const bool converged = r.report.status == fricon::driver::Status::Converged;
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
    ok = print_paper_table("Table 1 (param = 6e4)", fricon::driver::paper_table1(), o) && ok;
  if (o.table == "2" || o.table == "both")
    ok = print_paper_table("Table 2 (n = 16)", fricon::driver::paper_table2(), o) && ok;
  if (!ok) {
    std::cerr << "fricon paper: a run did not converge or a size differs from the paper\n";
    return kNotConverged;
  }
  return kConverged;
}

struct DualSolveOptions {
  std::string file, out;
  double tol = 1e-8;
  std::string variant{fricon::enum_name(fricon::driver::LocalSolveOptions{}.variant)};
  std::string expansion{fricon::enum_name(fricon::driver::LocalSolveOptions{}.expansion)};
  bool no_scaling = false;
};

// `fricon dual solve FILE`: a local frictional contact problem of another code (FCLIB, or
// fricon's own dual dump) solved by fricon's QP and outer loop, certified by its natural-map
// residual and FCLIB's merit. Exit 0 solved, 2 not solved (with the reason).
int dual_solve(const DualSolveOptions& o) {
  const fricon::qp::LocalProblem p = fricon::io::read_local_problem(o.file);
  fricon::driver::LocalSolveOptions so;
  so.residual_tol = o.tol;
  so.merit_tol = o.tol;
  so.variant = fricon::parse_enum<fricon::qp::MpgpVariant>(o.variant);
  so.expansion = fricon::parse_enum<fricon::qp::MpgpExpansion>(o.expansion);
  so.scaling = !o.no_scaling;
  if (p.is_coulomb())
    so.merit = [&p](const fricon::VectorXd& r, const fricon::VectorXd& u) {
      return fricon::io::fclib_merit(p, r, u);
    };
  const fricon::driver::LocalSolution s = fricon::driver::solve_local(p, so);
  fmt::print("fricon dual solve: {}\n", o.file);
  fmt::print("  problem     {}, {} contacts (m = {}), nnz(W) = {}, ||S|| = {:.3e}\n",
             p.is_coulomb() ? "Coulomb" : "Tresca", p.n_contacts(), p.q.size(), p.W.nonZeros(),
             s.norm_W);
  fmt::print("  W           {}\n", fricon::driver::describe_symmetry(s));
  fmt::print("  QP          MPGP {}, expansion {}, {}\n", fricon::enum_name(so.variant),
             fricon::enum_name(so.expansion),
             so.scaling ? fmt::format("scaled per contact (||D S D|| = {:.3e})", s.norm_W_scaled)
                        : std::string("not scaled"));
  fmt::print("  iterations  {} outer ({}), {} QP iterations, {} products with W\n",
             s.outer_iterations, fricon::enum_name(s.termination), s.qp_iterations, s.n_products);
  fmt::print("  residual    natural map {:.2e}", s.residual);
  if (p.is_coulomb()) fmt::print(", FCLIB merit {:.2e}", s.merit);
  fmt::print(" (tolerance {:.1e}; {} refinements)\n", o.tol, s.refinements);
  if (p.reference_r && p.reference_r->norm() > 0)
    fmt::print("  reference   ||r - r_file|| / ||r_file|| = {:.2e}\n",
               (s.r - *p.reference_r).norm() / p.reference_r->norm());
  fmt::print("  time        {:.3f} s\n", s.seconds);
  if (!o.out.empty() && s.solved) fricon::io::write_fclib_solution(o.out, p, s.r, s.u);
  if (!s.solved) {
    std::cerr << "fricon: NOT SOLVED: " << s.reason << "\n";
    return kNotConverged;
  }
  fmt::print("  solved\n");
  return kConverged;
}

struct MeshOptions {
  std::vector<double> size{3.0, 1.0, 1.0};
  std::vector<fricon::Index> cells{12, 4, 4};
  std::string out, file;
  int msh_version = fricon::mesh::kMsh41;
  bool binary = false;
  double size_factor = 0.0;  // 0: not given
};

// `fricon mesh brick`: the structured brick of the paper (theory.md §7.2) as a Gmsh file.
int mesh_brick(const MeshOptions& o) {
  const fricon::mesh::BrickSpec spec{fricon::Vec3(o.size[0], o.size[1], o.size[2]),
                                     {o.cells[0], o.cells[1], o.cells[2]}};
  const fricon::mesh::TetMesh mesh = fricon::mesh::make_brick(spec);
  fricon::mesh::write_gmsh(o.out, mesh, o.msh_version, o.binary);
  fmt::print("{}: {} nodes, {} tetrahedra, {} boundary triangles (MSH {} {})\n", o.out,
             mesh.n_nodes(), mesh.n_tets(), mesh.n_faces(),
             o.msh_version == fricon::mesh::kMsh41 ? "4.1" : "2.2", o.binary ? "binary" : "ASCII");
  return kConverged;
}

// `fricon mesh info FILE`: the sizes of a Gmsh mesh as fricon reads it.
int mesh_info(const MeshOptions& o) {
  const fricon::mesh::TetMesh mesh = o.size_factor > 0
                                         ? fricon::mesh::read_gmsh(o.file, o.size_factor)
                                         : fricon::mesh::read_gmsh(o.file);
  fmt::print("{}: {} nodes, {} tetrahedra, {} boundary triangles\n", o.file, mesh.n_nodes(),
             mesh.n_tets(), mesh.n_faces());
  std::vector<fricon::Index> tets_in(static_cast<size_t>(mesh.n_regions()), 0);
  std::vector<double> volume_of(tets_in.size(), 0.0);
  for (fricon::Index t = 0; t < mesh.n_tets(); ++t) {
    ++tets_in[static_cast<size_t>(mesh.region(t))];
    volume_of[static_cast<size_t>(mesh.region(t))] += fricon::mesh::tet_volume(mesh, t);
  }
  fmt::print("  regions\n");
  for (int r = 0; r < mesh.n_regions(); ++r)
    fmt::print("    {:<16} {:>10} tetrahedra, volume {:.6e} m^3\n",
               mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<size_t>(r)],
               tets_in[static_cast<size_t>(r)], volume_of[static_cast<size_t>(r)]);
  fmt::print("  boundary tags\n");
  for (const auto& tag : mesh.tag_names) {
    const std::vector<fricon::Index> faces = mesh.faces_with_tag(tag);
    double area = 0.0;
    std::set<int> entities;
    for (fricon::Index f : faces) {
      area += fricon::mesh::face_area(mesh, f);
      if (!mesh.face_entity.empty()) entities.insert(mesh.face_entity[static_cast<size_t>(f)]);
    }
    fmt::print("    {:<16} {:>10} triangles, area {:.6e} m^2, {} entities\n", tag, faces.size(),
               area, entities.size());
  }
  return kConverged;
}

// Everything the command line sets, and which subcommand it chose.
struct CommandLine {
  int threads = 0;
  std::string file;
  SolveOptions solve;
  bool quiet = false, verbose = false;
  std::string plot_dir, plot_out;
  PaperOptions paper;
  DualSolveOptions dual;
  MeshOptions mesh;
  CLI::App* dual_solve_cmd = nullptr;
  CLI::App* mesh_brick_cmd = nullptr;
  CLI::App* mesh_info_cmd = nullptr;
  CLI::App* solve_cmd = nullptr;
  CLI::App* check_cmd = nullptr;
  CLI::App* plot_cmd = nullptr;
  CLI::App* paper_cmd = nullptr;
};

template <typename E>
std::vector<std::string> enum_names() {
  std::vector<std::string> names;
  for (const auto& entry : fricon::EnumNames<E>::table)
    names.emplace_back(entry.second);
  return names;
}

void define_solve(CLI::App& app, CommandLine& cl) {
  cl.solve_cmd = app.add_subcommand(
      "solve",
      "Solve the problem of a TOML file and write its results.\n"
      "Progress goes to stderr (phases, one line per outer iteration), the summary to stdout.\n"
      "Results: report.json, solution.vtu, contact.vtu, solution.pvd, contact_nodes.csv,\n"
      "patches.csv in the results folder (see README).");
  auto* cmd = cl.solve_cmd;
  cmd->add_option("problem", cl.file, "Problem file (TOML), see docs/problem-file.md")->required();
  cmd->add_option("--out,-o", cl.solve.out, "Results folder (default: the file's output.dir)");
  cmd->add_option("--set", cl.solve.sets,
                  "Override a key of the file: KEY=VALUE with a TOML value, e.g.\n"
                  "--set mesh.cells=[24,8,8] --set contact.friction.param=2e4; repeatable;\n"
                  "recorded in report.json")
      ->allow_extra_args(false);
  cmd->add_option("--dump-dual", cl.solve.dump_dual,
                  "Also write the dual QP of the first outer iteration to this file\n"
                  "(format: docs/dual-format.md)");
  cmd->add_flag("--quiet,-q", cl.quiet, "Print nothing but errors");
  cmd->add_flag("--plot", cl.solve.plot, "Also render the figures (as `fricon plot`)");
  cmd->add_flag("--verbose,-v", cl.verbose, "Also print every step of the inner QP solver");
}

void define_check(CLI::App& app, CommandLine& cl) {
  cl.check_cmd =
      app.add_subcommand("check", "Validate a problem file without solving; print its sizes");
  cl.check_cmd->add_option("problem", cl.file, "Problem file (TOML)")->required();
  cl.check_cmd
      ->add_option("--set", cl.solve.sets, "Override a key of the file: KEY=VALUE, repeatable")
      ->allow_extra_args(false);
}

void define_plot(CLI::App& app, CommandLine& cl) {
  cl.plot_cmd = app.add_subcommand(
      "plot",
      "Render PNG figures of a results folder like the paper's: convergence history, friction\n"
      "law, contact-surface maps of -w_n, lambda_n, ||w_t||, ||lambda_t||, F on the surface,\n"
      "friction circles and arrows, and the deformed body (matplotlib, Debian's python3)");
  cl.plot_cmd->add_option("dir", cl.plot_dir, "Results folder written by `fricon solve`")
      ->required();
  cl.plot_cmd->add_option("--out,-o", cl.plot_out, "Folder for the figures (default: DIR/plots)");
}

void define_paper(CLI::App& app, CommandLine& cl) {
  cl.paper_cmd = app.add_subcommand(
      "paper", "Reproduce Tables 1 and 2 of the paper: our numbers beside the published ones");
  auto* cmd = cl.paper_cmd;
  cmd->add_option("--max-n", cl.paper.max_n, "Largest mesh parameter n to run (4..16)")
      ->check(CLI::Range(4, 16));
  cmd->add_option("--table", cl.paper.table, "Which table: 1, 2 or both")
      ->check(CLI::IsMember({"1", "2", "both"}));
  cmd->add_option("--dual-operator", cl.paper.dual_operator,
                  "How Q = B K^-1 B^T is applied: implicit (the paper's way), forward, schur, "
                  "auto (docs/theory.md §3.3)")
      ->check(CLI::IsMember(enum_names<fricon::dual::DualOperatorKind>()));
  cmd->add_option("--qp-rtol", cl.paper.qp_rtol, "QP tolerance (paper: 1e-6)")
      ->check(CLI::PositiveNumber);
}

void define_dual(CLI::App& app, CommandLine& cl) {
  auto* dual =
      app.add_subcommand("dual", "Frictional contact problems of other codes in local (dual) form");
  dual->require_subcommand(1);
  cl.dual_solve_cmd = dual->add_subcommand(
      "solve",
      "Solve a local problem: an FCLIB file (HDF5: local, or global reduced to local form) or a\n"
      "fricon dual file (docs/dual-format.md). Coulomb by successive approximations over Tresca\n"
      "QPs, Tresca by one QP; prints the iterations, the time, the natural-map residual and\n"
      "FCLIB's merit. Exit 0 solved, 2 not solved (the reason is printed)");
  auto* cmd = cl.dual_solve_cmd;
  cmd->add_option("file", cl.dual.file, "Problem file")->required();
  cmd->add_option("--out,-o", cl.dual.out, "Write the problem and its solution as an FCLIB file");
  cmd->add_option("--tol", cl.dual.tol, "Solved when the natural-map residual is below this")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--qp-variant", cl.dual.variant, "MPGP variant: bb or paper")
      ->check(CLI::IsMember(enum_names<fricon::qp::MpgpVariant>()))
      ->capture_default_str();
  cmd->add_option("--qp-expansion", cl.dual.expansion,
                  "MPGP expansion move: fixed, opt or projcg (theory.md §4.2)")
      ->check(CLI::IsMember(enum_names<fricon::qp::MpgpExpansion>()))
      ->capture_default_str();
  cmd->add_flag("--no-scaling", cl.dual.no_scaling,
                "Solve each QP in the given variables instead of scaled per contact");
}

void define_mesh(CLI::App& app, CommandLine& cl) {
  auto* mesh = app.add_subcommand("mesh", "Meshes as Gmsh files (MSH 2.2 and 4.1, .geo)");
  mesh->require_subcommand(1);
  cl.mesh_brick_cmd = mesh->add_subcommand(
      "brick",
      "Write the structured brick of the paper (5 tetrahedra per cell; boundary tags x0 ... z1,\n"
      "each side's 2 x 2-cell blocks one Gmsh surface) as a Gmsh file");
  auto* brick = cl.mesh_brick_cmd;
  brick->add_option("--size", cl.mesh.size, "Edge lengths [m]: X,Y,Z")
      ->delimiter(',')
      ->expected(3)
      ->check(CLI::PositiveNumber);
  brick->add_option("--cells", cl.mesh.cells, "Cells per direction: NX,NY,NZ")
      ->delimiter(',')
      ->expected(3)
      ->check(CLI::Range(fricon::Index{1}, fricon::Index{100000}));
  brick->add_option("--out,-o", cl.mesh.out, "Output file (.msh)")->required();
  brick->add_option("--msh-version", cl.mesh.msh_version, "MSH format version: 41 or 22")
      ->check(CLI::IsMember({fricon::mesh::kMsh41, fricon::mesh::kMsh22}));
  brick->add_flag("--binary", cl.mesh.binary, "Write a binary MSH file");
  cl.mesh_info_cmd = mesh->add_subcommand(
      "info",
      "Read a Gmsh file (.msh, or .geo meshed on the fly) as fricon does and print its nodes,\n"
      "tetrahedra, regions (tetrahedra, volume) and boundary tags (triangles, area, entities)");
  cl.mesh_info_cmd->add_option("file", cl.mesh.file, "Mesh file (.msh or .geo)")->required();
  cl.mesh_info_cmd
      ->add_option("--size-factor", cl.mesh.size_factor,
                   "Mesh.MeshSizeFactor for a .geo file (smaller: finer)")
      ->check(CLI::PositiveNumber);
}

int dispatch(CommandLine& cl, int argc, char** argv) {
  fricon::linalg::choose_threads(cl.threads);
  cl.solve.verbosity = cl.quiet     ? Verbosity::Quiet
                       : cl.verbose ? Verbosity::Verbose
                                    : Verbosity::Normal;
  if (*cl.solve_cmd) return solve(cl.file, cl.solve, join_command_line(argc, argv));
  if (*cl.check_cmd) return check(cl.file, cl.solve.sets);
  if (*cl.paper_cmd) return paper(cl.paper);
  if (*cl.plot_cmd) return plot(cl.plot_dir, cl.plot_out);
  if (*cl.dual_solve_cmd) return dual_solve(cl.dual);
  if (*cl.mesh_brick_cmd) return mesh_brick(cl.mesh);
  if (*cl.mesh_info_cmd) return mesh_info(cl.mesh);
  return kInternalError;
}

// The command's exit code; exceptions become their codes, with one message.
int run_guarded(CommandLine& cl, int argc, char** argv) {
  try {
    return dispatch(cl, argc, argv);
  } catch (const fricon::Interrupted& e) {
    std::cerr << "fricon: " << e.what() << " (no iterate to write yet)\n";
    return kNotConverged;
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
}

}  // namespace

int main(int argc, char** argv) {
  // @sect: the command line.
  CLI::App app{
      "fricon: 3D contact of elastic bodies with Tresca friction and a solution-dependent "
      "coefficient of friction (P1 finite elements, dual MPGP, successive approximations).\n"
      "Exit codes: 0 converged, 1 bad input, 2 not converged, 3 internal error."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("fricon ") + FRICON_VERSION +
                                        " (backends: cholmod" +
                                        (fricon::parallel::petsc_available() ? ", petsc)" : ")"));
  CommandLine cl;
  app.add_option("--threads", cl.threads,
                 "Threads of the BLAS (factorization, forming Q). Default: OPENBLAS_NUM_THREADS\n"
                 "if set, else the cores that other runnable processes leave free (1 on a busy\n"
                 "machine, where spinning BLAS threads would be several times slower)")
      ->check(CLI::Range(1, 1024));
  app.fallthrough();
  define_solve(app, cl);
  define_check(app, cl);
  define_plot(app, cl);
  define_paper(app, cl);
  define_dual(app, cl);
  define_mesh(app, cl);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }

  // @sect: the run, and its outcome as an exit code (rank 0's, on every rank of an MPI job).
  const int code = run_guarded(cl, argc, argv);
#ifdef FRICON_HAVE_PETSC
  if (fricon::parallel::initialized()) {
    int agreed = code;
    MPI_Bcast(&agreed, 1, MPI_INT, 0, fricon::parallel::world());
    return agreed;
  }
#endif
  return code;
}
