#pragma once
// fricon (the program): what every subcommand shares. Each subcommand lives in its own file
// (solve_command.cpp, check_command.cpp, ...): define_X adds it to the command line and returns
// the function that runs it, which main() calls when the user chose it.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "fricon/core/enum_names.hpp"

namespace fricon::app {

/// The program's exit codes (docs/problem-file.md, "Exit codes"; README): kOutputError when the
/// results could not be written (the folder is not a folder or not writable, the disk is full;
/// fricon::OutputError).
enum ExitCode {
  kConverged = 0,
  kBadInput = 1,
  kNotConverged = 2,
  kInternalError = 3,
  kOutputError = 4
};

/// A subcommand: its parser, and what runs when it was chosen (returns the exit code; errors
/// are exceptions, mapped to exit codes by main()).
struct Command {
  CLI::App* parser = nullptr;
  std::function<int()> run;
};

/// The whole command line, for report.json (results record how they were made).
struct Invocation {
  std::string command_line;
};

Command define_solve(CLI::App& app, const Invocation& invocation);
Command define_check(CLI::App& app);
Command define_plot(CLI::App& app);
Command define_paper(CLI::App& app);
std::vector<Command> define_dual(CLI::App& app);
std::vector<Command> define_mesh(CLI::App& app);
Command define_keys(CLI::App& app);

/// Renders the figures of results folder `dir` into `out` (default DIR/plots) with
/// scripts/plot_results.py under Debian's Python; kConverged, or kBadInput if plotting failed.
int render_plots(const std::string& dir, const std::string& out);

/// The spellings of enum E, for CLI::IsMember.
template <typename E>
std::vector<std::string> enum_names() {
  std::vector<std::string> names;
  for (const auto& entry : EnumNames<E>::table)
    names.emplace_back(entry.second);
  return names;
}

}  // namespace fricon::app
