// fricon plot DIR: the figures of a results folder (scripts/plot_results.py, matplotlib).
#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/core/error.hpp"

namespace fricon::app {

// Renders the figures of a results folder with scripts/plot_results.py under Debian's Python
// (which has matplotlib); returns its exit status. FRICON_SCRIPTS_DIR in the environment
// overrides where the script is looked for.
int render_plots(const std::string& dir, const std::string& out) {
  const char* env = std::getenv("FRICON_SCRIPTS_DIR");
  const std::filesystem::path script =
      std::filesystem::path(env ? env : FRICON_SCRIPTS_DIR) / "plot_results.py";
  if (!std::filesystem::exists(script))
    throw Error(fmt::format("plot script {} not found", script.string()));
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
    throw Error("cannot run /usr/bin/python3 (install python3-matplotlib: make deps)");
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "fricon: plotting " << dir << " failed\n";
    return kBadInput;
  }
  return kConverged;
}

Command define_plot(CLI::App& app) {
  struct Options {
    std::string dir, out;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Render PNG figures of a results folder like the paper's: convergence history, friction\n"
      "law, contact-surface maps of -w_n, lambda_n, ||w_t||, ||lambda_t||, F on the surface,\n"
      "friction circles and arrows, and the deformed body; for a loading path ([loading]\n"
      "steps > 1: steps.csv) also the force-displacement history (force_displacement.png) and\n"
      "the stick/slip map of the patches per step (stick_slip_steps.png) (matplotlib, Debian's\n"
      "python3). The figures of an earlier run in the folder are removed first.");
  cmd->add_option("dir", o->dir,
                  "Results folder written by `fricon solve`; of a run that did not converge\n"
                  "(report.not-converged.json), its last iterate is drawn, the figures named\n"
                  "*.not-converged.png")
      ->required();
  CLI::Option* out =
      cmd->add_option("--out,-o", o->out, "Folder for the figures, not empty (default: DIR/plots)");
  return {cmd, [o, out] {
            if (o->dir.empty()) throw InputError("dir: an empty path; name the results folder");
            if (out->count() > 0 && o->out.empty())
              throw InputError("--out: an empty path; name the folder for the figures");
            return render_plots(o->dir, o->out);
          }};
}

}  // namespace fricon::app
