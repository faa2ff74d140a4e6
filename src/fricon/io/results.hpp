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

/// A table of the results (a CSV file, a dict of numpy arrays in Python): named columns of equal
/// length, each numeric (values) or text (text).
struct Table {
  struct Column {
    std::string name;
    VectorXd values;                ///< a numeric column
    std::vector<std::string> text;  ///< a text column (values empty)
  };
  std::vector<Column> columns;
  Index rows() const;
};

/// contact_nodes.csv: per surface node x, y, z [m], gap [m], w_n, w_t1, w_t2 [m] (components of
/// the displacement in the obstacle's basis), phi = ||w_t|| [m] and F(phi).
Table contact_node_table(const mesh::TetMesh& mesh, const driver::ContactFields& fields);

/// patches.csv: per patch its centroid x, y, z [m], area [m^2], lambda_n, lambda_t1, lambda_t2
/// [Pa], radius [Pa], F (the patch's mean coefficient), ratio ||lambda_t|| / lambda_n and state.
Table patch_table(const driver::ContactFields& fields);

/// Writes `table` as CSV (a header of column names, numbers in shortest round-trip form),
/// atomically.
void write_csv(const std::filesystem::path& path, const Table& table);

/// Path of result file `base` + `extension` in `dir`, marked when the run did not converge.
std::filesystem::path result_path(const std::filesystem::path& dir, const std::string& base,
                                  const std::string& extension, bool converged);

/// steps.csv of a loading path: per step its number, the factor of each load with a path
/// (factor.KEY), normal_force [N], tangential_force_x/y/z [N] (of the obstacles on the contact
/// surface), reaction_x/y/z [N], the mean displacement of each path load's boundary
/// (displacement.KEY_x/y/z [m]), max_slip and max_accumulated_slip [m], the patch counts
/// n_stick, n_slip, n_separated, outer_iterations, n_mult, equilibrium_residual, time_s [s] and
/// status.
Table steps_table(const driver::Problem& problem, const driver::RunReport& report);

/// One step of a loading path as report.json's "steps" holds it (and Python's step callback).
nlohmann::json step_json(const driver::Problem& problem, const driver::StepReport& step);

/// Removes the result files of an earlier run from `dir`, the per-step files of a loading path
/// too (before a path writes its first step).
void clear_results(const std::filesystem::path& dir);

/// The files of the last step of a loading path (result.report.steps.back()), if it converged:
/// steps/solution-NNNN.vtu, steps/contact-NNNN.vtu and steps/patches-NNNN.csv in `dir`, each
/// atomically; returns the paths written.
std::vector<std::filesystem::path> write_step(const std::filesystem::path& dir,
                                              const driver::RunResult& result);

/// Writes every result file of the run into `dir` (created if needed); returns the paths written.
/// Along a loading path also steps.csv, and solution.pvd is the time series of the step files
/// (write_step) found in `dir`.
std::vector<std::filesystem::path> write_results(const std::filesystem::path& dir,
                                                 const driver::Problem& problem,
                                                 const driver::RunResult& result,
                                                 const RunContext& context);

}  // namespace fricon::io
