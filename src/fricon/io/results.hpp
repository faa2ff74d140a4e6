#pragma once
// io: the results folder of a run (the last stage of the data flow).
//   solution.vtu   the body: displacement per node, stress and von Mises per tetrahedron
//   report.json    sizes, timings, counters, residuals and the effective problem
// Each file is written atomically, report.json last, so a folder with a report.json is complete.
// A run that did not converge writes the same files with ".not-converged" before the extension
// (report.not-converged.json, ...), so nothing of it can be mistaken for a solution; result files
// of an earlier run in the folder are removed first.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fricon/driver/problem.hpp"
#include "fricon/driver/run.hpp"

namespace fricon::io {

/// Context of a run that is not part of the problem: the command line's overrides and the
/// program version, recorded in the report.
struct RunContext {
  std::vector<std::string> overrides;  ///< the --set KEY=VALUE strings, in order
  std::string command_line;
};

/// The report of a run as JSON (the fields of driver::RunReport plus the effective problem).
nlohmann::json report_json(const driver::Problem& problem, const driver::RunResult& result,
                           const RunContext& context);

/// Path of result file `base` + `extension` in `dir`, marked when the run did not converge.
std::filesystem::path result_path(const std::filesystem::path& dir, const std::string& base,
                                  const std::string& extension, bool converged);

/// Writes every result file of the run into `dir` (created if needed); returns the paths written.
std::vector<std::filesystem::path> write_results(const std::filesystem::path& dir,
                                                 const driver::Problem& problem,
                                                 const driver::RunResult& result,
                                                 const RunContext& context);

}  // namespace fricon::io
