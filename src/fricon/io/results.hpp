#pragma once
// io: the results folder of a run (the last stage of the data flow).
//   solution.vtu   the body: displacement per node, stress and von Mises per tetrahedron
//   report.json    sizes, timings, counters, residuals and the effective problem
// Each file is written atomically, report.json last, so a folder with a report.json is complete.
// A run that did not converge writes the same files with ".not-converged" before the extension
// (report.not-converged.json, ...), so nothing of it can be mistaken for a solution; result files
// of an earlier run in the folder are removed first (prepare_results, before the run). A file or
// folder that cannot be written is a fricon::OutputError (exit code 4 of the program).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fricon/driver/problem.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/vtu.hpp"

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

/// Makes `dir` ready for a run's results, before the run: creates it if needed, checks that it
/// is a folder that a file can be written into (a probe file of kProbeBytes, removed again), and
/// removes the results of an earlier run (converged or not), its per-step files
/// (steps/solution-NNNN.vtu, ...) and the figures of `fricon plot` (the .png, .pdf and .svg
/// files of DIR/plots), each folder too when that empties it; other files stay. Throws InputError
/// for an empty path, OutputError when `dir` is not a folder, cannot be created or written, or
/// an earlier result cannot be removed (so nothing of an earlier run stays beside a failure).
void prepare_results(const std::filesystem::path& dir);

/// The bytes prepare_results writes to find a folder that cannot take a file (read-only, full).
inline constexpr std::size_t kProbeBytes = 64 * 1024;

/// Whether the files of step `step` (1-based) of a loading path of `steps` steps are written:
/// the steps of [output] step_files if given, else every step_files_every-th (k, 2k, ...);
/// the last step always.
bool step_files_wanted(const driver::OutputOptions& output, int step, int steps);

/// The per-step files of one step of a loading path, as data (so that a caller may keep them
/// and write them later: Python's Result.write): steps/solution-NNNN.vtu (body),
/// steps/contact-NNNN.vtu and steps/patches-NNNN.csv (with contact).
struct StepFiles {
  int step = 0;  ///< 1-based
  VtuGrid body;
  std::optional<VtuGrid> contact;
  std::optional<VtuGrid> obstacle;  ///< the rigid obstacles where they are (obstacle.vtu)
  std::optional<Table> patches;
};

/// The step files of the last step of `result` (result.report.steps.back()); nothing when the
/// run has no steps or that step did not converge.
std::optional<StepFiles> step_files(const driver::RunResult& result);

/// Writes `files` into `dir` (each atomically), the .vtu files in `encoding` ([output]
/// vtu_encoding); returns the paths written.
std::vector<std::filesystem::path> write_step_files(const std::filesystem::path& dir,
                                                    const StepFiles& files, VtuEncoding encoding);

/// write_step_files of step_files(result): the files of a loading path's last step, if it
/// converged; returns the paths written (none otherwise).
std::vector<std::filesystem::path> write_step(const std::filesystem::path& dir,
                                              const driver::RunResult& result,
                                              VtuEncoding encoding);

/// Writes every result file of the run into `dir` (created if needed), the .vtu files in
/// problem.output.vtu_encoding; returns the paths written.
/// Result files of an earlier run are removed first. Along a loading path also steps.csv (every
/// step), and solution.pvd is the time series of `written_steps`, the steps whose files this
/// run wrote into `dir` (write_step_files, increasing); without them the step files in steps/
/// are an earlier run's and are removed, and solution.pvd holds the last state. If a file cannot be
/// written, the files written so far are removed and OutputError is thrown.
std::vector<std::filesystem::path> write_results(const std::filesystem::path& dir,
                                                 const driver::Problem& problem,
                                                 const driver::RunResult& result,
                                                 const RunContext& context,
                                                 const std::vector<int>& written_steps = {});

}  // namespace fricon::io
