// fricon: the command-line program. Thin on purpose: parse the command line, run the chosen
// subcommand (one file each: solve_command.cpp, check_command.cpp, plot_command.cpp,
// paper_command.cpp, dual_command.cpp, mesh_command.cpp, keys_command.cpp), and map the outcome
// to an exit code: 0 converged, 1 bad input (or an ill-posed problem), 2 not converged,
// 3 internal error, 4 the results could not be written.

#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/parallel/backend.hpp"
#ifdef FRICON_HAVE_PETSC
#include "fricon/parallel/mpi/session.hpp"
#endif

namespace {

using namespace fricon::app;

std::string join_command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i)
    s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

// The command's exit code; exceptions become their codes, with one message.
int run_guarded(const std::vector<Command>& commands, int threads) {
  try {
    fricon::linalg::choose_threads(threads);
    for (const Command& c : commands)
      if (*c.parser) return c.run();
    return kInternalError;
  } catch (const fricon::Interrupted& e) {
    std::cerr << "fricon: " << e.what() << " (no iterate to write yet)\n";
    return kNotConverged;
  } catch (const fricon::OutputError& e) {
    std::cerr << "fricon: error: cannot write the results: " << e.what() << "\n";
    return kOutputError;
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
      "Exit codes: 0 converged, 1 bad input, 2 not converged, 3 internal error, 4 the results\n"
      "could not be written (folder not writable or not a folder, disk full)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("fricon ") + FRICON_VERSION +
                                        " (backends: cholmod" +
                                        (fricon::parallel::petsc_available() ? ", petsc)" : ")"));
  int threads = 0;
  app.add_option("--threads", threads,
                 "Threads of the BLAS (factorization, forming Q). Default: OPENBLAS_NUM_THREADS\n"
                 "if set, else the cores that other runnable processes leave free (1 on a busy\n"
                 "machine, where spinning BLAS threads would be several times slower)")
      ->check(CLI::Range(1, 1024));
  app.fallthrough();
  const Invocation invocation{join_command_line(argc, argv)};
  std::vector<Command> commands{define_solve(app, invocation), define_check(app), define_plot(app),
                                define_paper(app), define_keys(app)};
  for (auto group : {define_dual(app), define_mesh(app)})
    commands.insert(commands.end(), group.begin(), group.end());
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }

  // @sect: the run, and its outcome as an exit code (rank 0's, on every rank of an MPI job).
  const int code = run_guarded(commands, threads);
#ifdef FRICON_HAVE_PETSC
  if (fricon::parallel::initialized()) {
    int agreed = code;
    MPI_Bcast(&agreed, 1, MPI_INT, 0, fricon::parallel::world());
    return agreed;
  }
#endif
  return code;
}
