#include "fricon/io/results.hpp"

#include <fmt/format.h>

#include "fricon/io/atomic_file.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/vtu.hpp"

namespace fricon::io {

namespace {
nlohmann::json vec3(const Vec3& v) { return nlohmann::json::array({v(0), v(1), v(2)}); }
}  // namespace

nlohmann::json report_json(const driver::Problem& problem, const driver::RunResult& result,
                           const RunContext& context) {
  const driver::RunReport& r = result.report;
  nlohmann::json j;
  j["fricon_version"] = FRICON_VERSION;
  j["status"] = driver::to_string(r.status);
  j["message"] = r.message;
  j["source"] = problem.source;
  j["overrides"] = context.overrides;
  j["command_line"] = context.command_line;
  j["n_nodes"] = r.n_nodes;
  j["n_tets"] = r.n_tets;
  j["n_primal"] = r.n_primal;
  j["factor"] = {{"n", r.factor.n},
                 {"nnz_K", r.factor.nnz_K},
                 {"nnz_L", r.factor.nnz_L},
                 {"flops", r.factor.flops},
                 {"ordering", r.factor.ordering},
                 {"supernodal", r.factor.supernodal},
                 {"rcond_estimate", r.factor.rcond}};
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& [name, e] : r.times.phases) timings[name] = e.seconds;
  j["timings"] = timings;
  j["time_s"] = r.time_s;
  j["max_displacement"] = r.max_displacement;
  j["applied_force"] = vec3(r.applied_force);
  j["reaction_force"] = vec3(r.reaction_force);
  j["contact_force"] = vec3(r.contact_force);
  j["equilibrium_residual"] = r.equilibrium_residual;
  j["linear_residual"] = r.linear_residual;
  j["max_von_mises"] = result.von_mises.size() ? result.von_mises.maxCoeff() : 0.0;
  j["problem"] = to_json(problem);
  return j;
}

std::vector<std::filesystem::path> write_results(const std::filesystem::path& dir,
                                                 const driver::Problem& problem,
                                                 const driver::RunResult& result,
                                                 const RunContext& context) {
  std::vector<std::filesystem::path> written;
  const auto& mesh = result.model.mesh;

  VtuGrid body;
  body.points = mesh.nodes;
  body.cells = mesh.tets;
  body.point_data.push_back({"displacement", result.displacement});
  body.cell_data.push_back({"stress", result.stress});
  body.cell_data.push_back({"von_mises", result.von_mises.transpose()});
  write_vtu(dir / "solution.vtu", body);
  written.push_back(dir / "solution.vtu");

  write_pvd(dir / "solution.pvd", {"solution.vtu"});
  written.push_back(dir / "solution.pvd");

  const nlohmann::json report = report_json(problem, result, context);
  write_atomically(dir / "report.json", [&](std::ostream& out) { out << report.dump(2) << '\n'; });
  written.push_back(dir / "report.json");
  return written;
}

}  // namespace fricon::io
