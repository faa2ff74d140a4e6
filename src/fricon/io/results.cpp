#include "fricon/io/results.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string_view>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/io/atomic_file.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/io/vtu.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::io {

namespace {

nlohmann::json vec3(const Vec3& v) {
  return nlohmann::json::array({v(0), v(1), v(2)});
}

// A rigid obstacle: its kind, its parameters at rest ("point", "normal", "center", "radius",
// ...) and its displacement [m] (the position it is in: the points moved by it).
nlohmann::json obstacle_json(const contact::Obstacle& obstacle, const Vec3& displacement) {
  nlohmann::json j = {{"kind", std::string(obstacle.kind())}};
  for (const contact::ObstacleParameter& p : obstacle.parameters())
    j[p.name] = p.value.size() == 1 ? nlohmann::json(p.value.front()) : nlohmann::json(p.value);
  j["displacement"] = vec3(displacement);
  return j;
}

// The counts of the contact solve: sizes, outer iterations and the QPs' steps and products.
nlohmann::json contact_counts(const driver::ContactReport& c) {
  return {{"n_dual", c.n_dual},
          {"n_candidate_patches", c.n_candidate_patches},
          {"search_rounds", c.search_rounds},
          {"outer_iterations", c.outer_iterations},
          {"n_mult", c.n_mult},
          {"qp_iterations", c.qp_iterations},
          {"qp_steps",
           {{"cg", c.qp_steps.cg},
            {"expansion", c.qp_steps.expansion},
            {"proportioning", c.qp_steps.proportioning}}},
          {"n_kinv", c.n_kinv},
          {"err_history", c.err_history}};
}

// The paper's measures of the last iterate and the contact forces (theory.md §6.4).
nlohmann::json contact_measures(const driver::ContactReport& c) {
  return {{"wn_pos_l2", c.wn_pos_l2},
          {"wn_pos_inf", c.wn_pos_inf},
          {"max_neg_wn", c.max_neg_wn},
          {"max_wt", c.max_wt},
          {"max_lambda_n", c.max_lambda_n},
          {"max_lambda_t", c.max_lambda_t},
          {"total_normal_force", c.total_normal_force},
          {"transmitted_normal_force", c.transmitted_normal_force}};
}

// The certificate: the KKT residuals of the last QP, and where they apply the Coulomb
// residual, the balance of floating bodies and the gluing of Total FETI.
void add_certificates(const driver::ContactReport& c, nlohmann::json& j) {
  j["kkt"] = {{"feasibility", c.kkt.feasibility},
              {"stationarity", c.kkt.stationarity},
              {"complementarity", c.kkt.complementarity},
              {"max", c.kkt.max()},
              {"bound", c.kkt_bound}};
  if (c.model == contact::FrictionModel::Coulomb)
    j["coulomb"] = {{"residual", c.coulomb_residual},
                    {"bound", c.coulomb_bound},
                    {"scale", c.lambda_scale},
                    {"refinements", c.certificate_refinements}};
  if (c.rigid_amplitudes.size() > 0)
    j["balance"] = {{"equality_residual", c.equality_residual},
                    {"bound", c.equality_bound},
                    {"smalse_outer_iterations", c.smalse_outer_iterations}};
  if (c.gluing_residual > 0.0) j["gluing_residual"] = c.gluing_residual;
}

// The outer iterations, one entry each.
nlohmann::json outer_history(const driver::ContactReport& c) {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& it : c.history)
    history.push_back({{"k", it.k},
                       {"err", it.err},
                       {"qp_iterations", it.qp_iterations},
                       {"qp_products", it.qp_products},
                       {"qp_rel_gp", it.qp_rel_gp},
                       {"qp_termination", enum_name(it.qp_termination)},
                       {"n_objective_increases", it.n_objective_increases},
                       {"seconds", it.seconds}});
  return history;
}

// The "contact" section: the discretization, the dual operator and the outer loop's history.
nlohmann::json contact_section(const driver::ContactReport& c) {
  return {{"boundary", c.boundary},
          {"friction_law", c.friction_law},
          {"dual_operator", enum_name(c.dual_operator)},
          {"n_patches", c.n_patches},
          {"n_surface_nodes", c.n_surface_nodes},
          {"n_contact_nodes", c.n_contact_nodes},
          {"stability_ratio", c.stability_ratio},
          {"stability_estimated", c.stability_estimated},
          {"n_inactive_multipliers", c.n_inactive_multipliers},
          {"radius_integration", c.radius_integration},
          {"contraction_ratio", c.contraction_ratio},
          {"norm_Q", c.norm_Q},
          {"norm_Q_scaled", c.norm_Q_scaled},
          {"fixed_point_residual", c.fixed_point_residual},
          {"history", outer_history(c)}};
}

// One contact pair: what touches what, its forces and states; for two bodies the master side.
nlohmann::json pair_json(const driver::PairReport& r) {
  const contact::PairInfo& p = r.info;
  nlohmann::json pair = {
      {"key", p.key},
      {"boundary", p.boundary},
      {"obstacle", !p.master.empty() ? std::string("body")
                   : p.obstacle      ? std::string(p.obstacle->kind())
                                     : std::string("plane")},
      {"model", enum_name(r.model)},
      {"friction_law", r.friction_law},
      {"n_patches", r.n_patches},
      {"patch_states", {{"stick", r.n_stick}, {"slip", r.n_slip}, {"separated", r.n_separated}}},
      {"normal_force", r.normal_force},
      {"force", vec3(r.force)},
      {"tangential_force", vec3(r.tangential_force)},
      {"stability_ratio", p.stability.ratio},
      {"basis", {{"n", vec3(p.n)}, {"t1", vec3(p.t1)}, {"t2", vec3(p.t2)}}},
      {"max_slip", r.max_slip}};
  if (p.obstacle) pair["obstacle_geometry"] = obstacle_json(*p.obstacle, p.obstacle_displacement);
  if (!p.master.empty()) {
    pair["master"] = p.master;
    pair["search_distance"] = p.search_distance;
    pair["master_coverage"] = p.master_coverage;
    pair["master_element_size"] = p.master_element_size;
    pair["small_sliding"] = r.small_sliding;
    pair["max_slip_step"] = r.max_slip_step;
    pair["master_penetration"] = r.master_penetration;
    pair["normal_displacement"] = r.normal_displacement;
    pair["master_kept_out"] = r.master_kept_out;
  }
  return pair;
}

// The contact part of the report: counts, the paper's measures, the certificate, the outer
// history and the pairs.
void add_contact_report(const driver::ContactReport& c, nlohmann::json& j) {
  j.update(contact_counts(c));
  j.update(contact_measures(c));
  add_certificates(c, j);
  j["termination"] = enum_name(c.termination);
  j["n_objective_increases"] = c.n_objective_increases;
  j["model"] = c.mixed_models ? std::string("mixed") : std::string(enum_name(c.model));
  j["patch_states"] = {{"stick", c.n_stick}, {"slip", c.n_slip}, {"separated", c.n_separated}};
  j["state_blocks"] = c.state_blocks;
  j["block_err_history"] = c.block_history;
  j["contact"] = contact_section(c);
  if (!c.partition_note.empty()) j["partition_note"] = c.partition_note;
  if (c.geometry_updates >= 0)
    j["geometry"] = {{"updates", c.geometry_updates},
                     {"change", c.geometry_change},
                     {"normal_displacement", c.geometry_scale},
                     {"tolerance", c.geometry_tolerance}};
  nlohmann::json pairs = nlohmann::json::array();
  for (const driver::PairReport& r : c.pairs)
    pairs.push_back(pair_json(r));
  j["pairs"] = std::move(pairs);
}

// The regions of the body: per region its name, number of tetrahedra and volume [m^3].
void add_regions(const mesh::TetMesh& mesh, nlohmann::json& j) {
  const auto n = static_cast<size_t>(mesh.n_regions());
  std::vector<Index> n_tets(n, 0);
  std::vector<Real> volume(n, 0.0);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const auto r = static_cast<size_t>(mesh.region(t));
    ++n_tets[r];
    volume[r] += mesh::tet_volume(mesh, t);
  }
  nlohmann::json regions = nlohmann::json::array();
  for (size_t r = 0; r < n; ++r)
    regions.push_back({{"name", mesh.region_names.empty() ? "body" : mesh.region_names[r]},
                       {"n_tets", n_tets[r]},
                       {"volume", volume[r]}});
  j["n_regions"] = mesh.n_regions();
  j["regions"] = regions;
}

// The first pair's obstacle: a rigid one (its kind, parameters at rest and displacement; a plane
// without [contact.obstacle] is that of the flat contact surface, through its mean node), or the
// master's tag; and the basis (n, t1, t2) of the (first) contact surface, in which the
// tangential components are given (README, Conventions; each pair's in report.json's pairs).
void add_contact_geometry(const driver::Problem& problem, const mesh::TetMesh& mesh,
                          const driver::RunReport& report, const driver::ContactFields& c,
                          nlohmann::json& j) {
  const auto& s = c.surface;
  j["contact_basis"] = {{"n", vec3(s.n)}, {"t1", vec3(s.t1)}, {"t2", vec3(s.t2)}};
  const auto& first = problem.contact.front().obstacle;
  if (first && first->kind == driver::ObstacleKind::Body) {
    j["obstacle"] = {{"kind", "body"}, {"boundary", first->boundary}};
    return;
  }
  const contact::PairInfo* pair = report.contact && !report.contact->pairs.empty()
                                      ? &report.contact->pairs.front().info
                                      : nullptr;
  if (first && pair && pair->obstacle) {
    j["obstacle"] = obstacle_json(*pair->obstacle, pair->obstacle_displacement);
    j["obstacle"]["given"] = true;
    return;
  }
  Vec3 point = Vec3::Zero();
  for (Index node : s.nodes)
    point += mesh.nodes.col(node);
  point /= static_cast<Real>(std::max<Index>(s.n_nodes(), 1));
  j["obstacle"] = {{"kind", "plane"},
                   {"point", vec3(point)},
                   {"normal", vec3(-s.n)},
                   {"displacement", vec3(Vec3::Zero())},
                   {"given", false}};
}

// A distributed run: its ranks, partition and each rank's work and memory.
void add_parallel_report(const parallel::ParallelReport& p, nlohmann::json& j) {
  nlohmann::json ranks = nlohmann::json::array();
  for (const auto& r : p.ranks)
    ranks.push_back({{"n_tets", r.n_tets},
                     {"n_nodes", r.n_nodes},
                     {"peak_memory_mib", r.peak_memory_mib},
                     {"mumps_memory_mib", r.mumps_memory_mib},
                     {"mumps_estimate_mib", r.mumps_estimate_mib},
                     {"model_memory_mib", r.model_memory_mib}});
  j["parallel"] = {
      {"backend", "petsc"},   {"n_ranks", p.n_ranks},       {"partition", enum_name(p.partition)},
      {"n_schur", p.n_schur}, {"analysis_s", p.analysis_s}, {"factorization_s", p.factorization_s},
      {"ranks", ranks}};
}

// Backend "tfeti": the subdomains, the interface and coarse problem, counts, times and memory.
void add_feti_report(const feti::FetiReport& f, nlohmann::json& j) {
  nlohmann::json ranks = nlohmann::json::array();
  for (const feti::RankShare& r : f.ranks)
    ranks.push_back({{"n_subdomains", r.n_subdomains},
                     {"n_tets", r.n_tets},
                     {"factor_mib", r.factor_mib},
                     {"factorization_cpu_s", r.factorization_cpu_s},
                     {"peak_memory_mib", r.peak_memory_mib},
                     {"model_memory_mib", r.model_memory_mib},
                     {"n_multipliers", r.n_multipliers},
                     {"n_ghosts", r.n_ghosts}});
  j["feti"] = {
      {"backend", "tfeti"},
      {"n_subdomains", f.n_subdomains},
      {"n_split", f.n_split},
      {"partition_note", f.partition_note},
      {"subdomain_nodes", {{"min", f.min_nodes}, {"max", f.max_nodes}, {"mean", f.mean_nodes}}},
      {"softness",
       {{"softest_subdomain", f.softness.softest},
        {"softest_relative", f.softness.softest_relative()},
        {"median_relative", f.softness.median},
        {"ratio", f.softness.ratio},
        {"necked", f.softness.necked},
        {"n_recut", f.n_recut},
        {"recut_rounds", f.recut_rounds},
        {"n_kept_factors", f.n_kept_factors},
        {"seconds", f.softness_s}}},
      {"n_torn", f.n_torn},
      {"n_contact", f.n_contact},
      {"n_gluing", f.n_gluing},
      {"n_dirichlet", f.n_dirichlet},
      {"n_coarse", f.n_coarse},
      {"row_scaling", f.row_scaling},
      {"preconditioner", f.preconditioner},
      {"n_preconditioner", f.n_preconditioner},
      {"preconditioner_s", f.preconditioner_s},
      {"threads", f.threads},
      {"nnz_factors", f.nnz_factors},
      {"factor_mib", f.factor_mib},
      {"partition_s", f.partition_s},
      {"factorization_s", f.factorization_s},
      {"factorization_cpu_s", f.factorization_cpu_s},
      {"operator_s", f.operator_s},
      {"n_products", f.n_products},
      {"products_s", f.products_s},
      {"sums_s", f.sums_s},
      {"n_coarse_solves", f.n_coarse_solves},
      {"coarse_s", f.coarse_s},
      {"qp_iterations", f.qp_iterations},
      {"smalse_outer_iterations", f.smalse_outer_iterations},
      {"gluing_residual", f.gluing_residual},
      {"gluing_bound", f.gluing_bound},
      {"free_displacement_note", f.free_displacement_note},
      {"peak_memory_mib", f.peak_memory_mib},
      {"n_ranks", f.n_ranks},
      {"ranks", ranks}};
}

}  // namespace

namespace {

// A rigid obstacle that moves: a displacement or a path.
bool moving_obstacle(const driver::ContactOptions& c) {
  return c.obstacle && driver::is_rigid(*c.obstacle) &&
         (!c.obstacle->path.empty() || !c.obstacle->displacement.isZero(0.0));
}

// Per pair whose rigid obstacle moves: its displacement at step k [m].
nlohmann::json obstacle_steps(const driver::Problem& problem, int k) {
  nlohmann::json out = nlohmann::json::object();
  for (size_t i = 0; i < problem.contact.size(); ++i)
    if (moving_obstacle(problem.contact[i]))
      out[problem.contact_key(i)] = vec3(
          driver::obstacle_displacement(*problem.contact[i].obstacle, k, problem.loading.steps));
  return out;
}

}  // namespace

nlohmann::json step_json(const driver::Problem& problem, const driver::StepReport& s) {
  const std::vector<driver::PathLoad> loads = driver::path_loads(problem);
  nlohmann::json factors = nlohmann::json::object(), displacement = nlohmann::json::object();
  for (size_t i = 0; i < loads.size() && i < s.factors.size(); ++i) {
    factors[loads[i].key] = s.factors[i];
    if (!loads[i].boundary.empty()) displacement[loads[i].key] = vec3(s.load_displacement[i]);
  }
  return {
      {"step", s.step},
      {"status", enum_name(s.status)},
      {"message", s.message},
      {"factors", factors},
      {"normal_force", s.normal_force},
      {"tangential_force", vec3(s.tangential_force)},
      {"contact_force", vec3(s.contact_force)},
      {"reaction_force", vec3(s.reaction_force)},
      {"applied_force", vec3(s.applied_force)},
      {"load_displacement", displacement},
      {"obstacle_displacement", obstacle_steps(problem, s.step)},
      {"max_slip", s.max_slip},
      {"max_accumulated_slip", s.max_accumulated_slip},
      {"patch_states", {{"stick", s.n_stick}, {"slip", s.n_slip}, {"separated", s.n_separated}}},
      {"outer_iterations", s.outer_iterations},
      {"n_mult", s.n_mult},
      {"kkt", s.kkt},
      {"equilibrium_residual", s.equilibrium_residual},
      {"time_s", s.time_s}};
}

Table steps_table(const driver::Problem& problem, const driver::RunReport& report) {
  const std::vector<driver::PathLoad> loads = driver::path_loads(problem);
  const auto n = static_cast<Index>(report.steps.size());
  Table t;
  const auto column = [&](std::string name, auto value) {
    Table::Column c{std::move(name), VectorXd(n), {}};
    for (Index i = 0; i < n; ++i)
      c.values(i) = static_cast<Real>(value(report.steps[static_cast<size_t>(i)]));
    t.columns.push_back(std::move(c));
  };
  column("step", [](const driver::StepReport& s) { return s.step; });
  for (size_t i = 0; i < loads.size(); ++i)
    column("factor." + loads[i].key, [i](const driver::StepReport& s) { return s.factors[i]; });
  column("normal_force", [](const driver::StepReport& s) { return s.normal_force; });
  const auto vector_columns = [&](const std::string& name, auto field) {
    for (int c = 0; c < 3; ++c)
      column(fmt::format("{}_{}", name, "xyz"[c]),
             [field, c](const driver::StepReport& s) { return field(s)(c); });
  };
  vector_columns("tangential_force",
                 [](const driver::StepReport& s) { return s.tangential_force; });
  vector_columns("reaction", [](const driver::StepReport& s) { return s.reaction_force; });
  for (size_t i = 0; i < loads.size(); ++i)
    if (!loads[i].boundary.empty())
      vector_columns("displacement." + loads[i].key,
                     [i](const driver::StepReport& s) { return s.load_displacement[i]; });
  for (size_t i = 0; i < problem.contact.size(); ++i)
    if (moving_obstacle(problem.contact[i]))
      vector_columns("obstacle." + problem.contact_key(i),
                     [&problem, i](const driver::StepReport& s) {
                       return driver::obstacle_displacement(*problem.contact[i].obstacle, s.step,
                                                            problem.loading.steps);
                     });
  column("max_slip", [](const driver::StepReport& s) { return s.max_slip; });
  column("max_accumulated_slip",
         [](const driver::StepReport& s) { return s.max_accumulated_slip; });
  column("n_stick", [](const driver::StepReport& s) { return s.n_stick; });
  column("n_slip", [](const driver::StepReport& s) { return s.n_slip; });
  column("n_separated", [](const driver::StepReport& s) { return s.n_separated; });
  column("outer_iterations", [](const driver::StepReport& s) { return s.outer_iterations; });
  column("n_mult", [](const driver::StepReport& s) { return s.n_mult; });
  column("equilibrium_residual",
         [](const driver::StepReport& s) { return s.equilibrium_residual; });
  column("time_s", [](const driver::StepReport& s) { return s.time_s; });
  Table::Column status{"status", {}, {}};
  for (const driver::StepReport& s : report.steps)
    status.text.push_back(std::string(enum_name(s.status)));
  t.columns.push_back(std::move(status));
  return t;
}

nlohmann::json report_json(const driver::Problem& problem, const driver::RunResult& result,
                           const RunContext& context) {
  const driver::RunReport& r = result.report;
  nlohmann::json j;
  j["fricon_version"] = FRICON_VERSION;
  j["status"] = enum_name(r.status);
  j["message"] = r.message;
  j["source"] = problem.source;
  j["overrides"] = context.overrides;
  j["command_line"] = context.command_line;
  j["n_nodes"] = r.n_nodes;
  j["n_tets"] = r.n_tets;
  j["nodes_per_tet"] = r.nodes_per_tet;
  j["n_primal"] = r.n_primal;
  j["factor"] = {{"n", r.factor.n},
                 {"nnz_K", r.factor.nnz_K},
                 {"nnz_L", r.factor.nnz_L},
                 {"flops", r.factor.flops},
                 {"ordering", r.factor.ordering},
                 {"supernodal", r.factor.supernodal},
                 {"rcond_estimate", r.factor.rcond},
                 {"blas_threads", r.factor.blas_threads}};
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& [name, e] : r.times.phases)
    timings[name] = e.seconds;
  j["timings"] = timings;
  j["time_s"] = r.time_s;
  j["max_displacement"] = r.max_displacement;
  j["applied_force"] = vec3(r.applied_force);
  j["reaction_force"] = vec3(r.reaction_force);
  j["contact_force"] = vec3(r.contact_force);
  j["warnings"] = r.warnings;
  j["force_scale"] = r.force_scale;
  j["equilibrium_residual"] = r.equilibrium_residual;
  j["linear_residual"] = r.linear_residual;
  j["max_von_mises"] = result.von_mises.size() ? result.von_mises.maxCoeff() : 0.0;
  add_regions(result.model.mesh, j);
  j["bodies"] = nlohmann::json::array();
  for (const driver::BodyReport& b : r.bodies)
    j["bodies"].push_back({{"index", b.index},
                           {"description", b.description},
                           {"floating", !b.free_motions.empty()},
                           {"free_motions", b.free_motions},
                           {"amplitudes", b.amplitudes},
                           {"undetermined", b.undetermined}});
  if (r.contact) add_contact_report(*r.contact, j);
  if (r.parallel) add_parallel_report(*r.parallel, j);
  if (r.feti) add_feti_report(*r.feti, j);
  if (result.contact) add_contact_geometry(problem, result.model.mesh, r, *result.contact, j);
  if (!r.steps.empty()) {
    j["steps"] = nlohmann::json::array();
    for (const driver::StepReport& s : r.steps)
      j["steps"].push_back(step_json(problem, s));
  }
  j["problem"] = to_json(problem);
  return j;
}

namespace {
// Every file a run may write, by its base name and extension.
const std::vector<std::pair<std::string, std::string>> kResultFiles{
    {"solution", ".vtu"},      {"contact", ".vtu"}, {"obstacle", ".vtu"}, {"solution", ".pvd"},
    {"contact_nodes", ".csv"}, {"patches", ".csv"}, {"report", ".json"},  {"steps", ".csv"}};
constexpr const char* kNotConverged = ".not-converged";
}  // namespace

Index Table::rows() const {
  if (columns.empty()) return 0;
  const Column& c = columns.front();
  return c.text.empty() ? c.values.size() : static_cast<Index>(c.text.size());
}

Table contact_node_table(const mesh::TetMesh& mesh, const driver::ContactFields& c) {
  const Index n = c.surface.n_nodes();
  Table table;
  for (const char* name : {"x", "y", "z"})
    table.columns.push_back({name, VectorXd(n), {}});
  for (Index k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d)
      table.columns[static_cast<size_t>(d)].values(k) =
          mesh.nodes(d, c.surface.nodes[static_cast<size_t>(k)]);
  VectorXd phi(n);
  for (Index k = 0; k < n; ++k)
    phi(k) = std::hypot(c.wt1(k), c.wt2(k));
  table.columns.push_back({"gap", c.gap, {}});
  table.columns.push_back({"w_n", c.wn, {}});
  table.columns.push_back({"w_t1", c.wt1, {}});
  table.columns.push_back({"w_t2", c.wt2, {}});
  table.columns.push_back({"phi", phi, {}});
  table.columns.push_back({"F", c.F, {}});
  VectorXd pair(n);
  for (Index k = 0; k < n; ++k)
    pair(k) = static_cast<Real>(c.surface.node_pair[static_cast<size_t>(k)]);
  table.columns.push_back({"pair", pair, {}});
  return table;
}

Table patch_table(const driver::ContactFields& c) {
  const Index n = c.patches.size();
  Table table;
  for (const char* name :
       {"x", "y", "z", "area", "lambda_n", "lambda_t1", "lambda_t2", "radius", "F", "ratio"})
    table.columns.push_back({name, VectorXd(n), {}});
  std::vector<std::string> state;
  for (Index p = 0; p < n; ++p) {
    const Real lt = c.lambda.segment<2>(3 * p + 1).norm();
    // ||lambda_t|| / lambda_n; infinite where Tresca friction acts without contact pressure.
    const Real ratio = c.lambda(3 * p) > 0.0 ? lt / c.lambda(3 * p)
                       : lt > 0.0            ? std::numeric_limits<Real>::infinity()
                                             : 0.0;
    const Real row[] = {c.patches.centroid(0, p), c.patches.centroid(1, p),
                        c.patches.centroid(2, p), c.patches.area(p),
                        c.lambda(3 * p),          c.lambda(3 * p + 1),
                        c.lambda(3 * p + 2),      c.radius(p),
                        c.coefficient(p),         ratio};
    for (size_t j = 0; j < std::size(row); ++j)
      table.columns[j].values(p) = row[j];
    state.emplace_back(enum_name(c.state[static_cast<size_t>(p)]));
  }
  table.columns.push_back({"state", {}, std::move(state)});
  VectorXd pair(n);
  for (Index p = 0; p < n; ++p)
    pair(p) = static_cast<Real>(c.patch_pair[static_cast<size_t>(p)]);
  table.columns.push_back({"pair", pair, {}});
  return table;
}

void write_csv(const std::filesystem::path& path, const Table& table) {
  write_atomically(path, [&](std::ostream& out) {
    for (size_t j = 0; j < table.columns.size(); ++j)
      out << (j ? "," : "") << table.columns[j].name;
    out << '\n';
    for (Index i = 0; i < table.rows(); ++i) {
      for (size_t j = 0; j < table.columns.size(); ++j) {
        const Table::Column& col = table.columns[j];
        out << (j ? "," : "");
        if (col.text.empty())
          out << fmt::format("{}", col.values(i));
        else
          out << col.text[static_cast<size_t>(i)];
      }
      out << '\n';
    }
  });
}

std::filesystem::path result_path(const std::filesystem::path& dir, const std::string& base,
                                  const std::string& extension, bool converged) {
  return dir / (base + (converged ? "" : kNotConverged) + extension);
}

namespace {

// Every node of each tetrahedron, one column per tetrahedron in fricon's order (corners, then the
// edge nodes of a quadratic mesh: TetMesh::tet_node, theory.md §2.12); write_vtu writes them in
// VTK's.
Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> tet_cells(const mesh::TetMesh& mesh) {
  Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic> cells(mesh.nodes_per_tet(), mesh.n_tets());
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a)
      cells(a, t) = mesh.tet_node(t, a);
  return cells;
}

// An integer per tetrahedron, value(t) for t = 0 .. n_tets - 1, as a cell field written as Int32.
template <class Value>
VtuField integer_per_tet(const char* name, Index n_tets, Value value) {
  MatrixXd field(1, n_tets);
  for (Index t = 0; t < n_tets; ++t)
    field(0, t) = static_cast<Real>(value(t));
  return {name, field, VtuType::Int32};
}

// The body: displacement and the stress recovered at the nodes with its von Mises equivalent per
// node (every node, the edge nodes of a quadratic mesh too), stress, von Mises, region index
// (report.json "regions" names them), body and, for backend "tfeti", subdomain per tetrahedron.
VtuGrid body_grid(const driver::RunResult& result) {
  const mesh::TetMesh& mesh = result.model.mesh;
  VtuGrid body;
  body.points = mesh.nodes;
  body.cells = tet_cells(mesh);
  body.point_data.push_back({"displacement", result.displacement});
  if (result.nodal_stress.cols() == mesh.n_nodes()) {  // recovered at the nodes (fe/stress.hpp)
    body.point_data.push_back({"nodal_stress", result.nodal_stress});
    body.point_data.push_back({"nodal_von_mises", result.nodal_von_mises.transpose()});
  }
  body.cell_data.push_back({"stress", result.stress});
  body.cell_data.push_back({"von_mises", result.von_mises.transpose()});
  body.cell_data.push_back(
      integer_per_tet("region", mesh.n_tets(), [&](Index t) { return mesh.region(t); }));
  body.cell_data.push_back(integer_per_tet("body", mesh.n_tets(), [&](Index t) {
    return result.model.bodies.tet_body[static_cast<size_t>(t)];
  }));
  const std::optional<feti::FetiReport>& feti = result.report.feti;
  if (feti && static_cast<Index>(feti->subdomain_of_tet.size()) == mesh.n_tets())
    body.cell_data.push_back(integer_per_tet("subdomain", mesh.n_tets(), [&](Index t) {
      return feti->subdomain_of_tet[static_cast<size_t>(t)];
    }));
  return body;
}

// The rigid obstacles given in the problem as triangles where they are (their pictures moved by
// their displacements), each pictured around its contact surface (its middle, and 1.5 times its
// largest distance from it); the cell field "pair". Nothing without such an obstacle.
std::optional<VtuGrid> obstacle_grid(const mesh::TetMesh& mesh, const driver::ContactFields& c,
                                     const driver::ContactReport* report) {
  constexpr Real kMargin = 1.5;  // the picture's extent over the contact surface's
  if (report == nullptr) return std::nullopt;
  const contact::ContactSurface& s = c.surface;
  VtuGrid grid;
  grid.cells.resize(3, 0);
  std::vector<Real> pair_of_cell;
  for (size_t i = 0; i < report->pairs.size(); ++i) {
    const contact::PairInfo& pair = report->pairs[i].info;
    if (!pair.obstacle) continue;
    std::vector<Index> nodes;
    for (Index k = 0; k < s.n_nodes(); ++k)
      if (static_cast<size_t>(s.node_pair[static_cast<size_t>(k)]) == i)
        nodes.push_back(s.nodes[static_cast<size_t>(k)]);
    Vec3 middle = Vec3::Zero();
    for (Index a : nodes)
      middle += mesh.nodes.col(a);
    middle /= static_cast<Real>(std::max<size_t>(nodes.size(), 1));
    Real extent = 0.0;
    for (Index a : nodes)
      extent = std::max(extent, (mesh.nodes.col(a) - middle).norm());
    const contact::ObstacleSurface picture =
        pair.obstacle->picture(middle - pair.obstacle_displacement, kMargin * extent);
    const Index first = grid.points.cols();
    grid.points.conservativeResize(3, first + picture.points.cols());
    grid.points.rightCols(picture.points.cols()) =
        picture.points.colwise() + pair.obstacle_displacement;
    const Index cells = grid.cells.cols();
    grid.cells.conservativeResize(3, cells + picture.triangles.cols());
    grid.cells.rightCols(picture.triangles.cols()) = picture.triangles.array() + first;
    pair_of_cell.insert(pair_of_cell.end(), static_cast<size_t>(picture.triangles.cols()),
                        static_cast<Real>(i));
  }
  if (pair_of_cell.empty()) return std::nullopt;
  grid.cell_data = {
      {"pair",
       Eigen::Map<const MatrixXd>(pair_of_cell.data(), 1, static_cast<Index>(pair_of_cell.size())),
       VtuType::Int32}};
  return grid;
}

// Per pair against a rigid obstacle given in the problem: its parameters at rest and its
// displacement, named "obstacle<i>.<kind>.<parameter>" (the field data of contact.vtu).
std::vector<VtuField> obstacle_fields(const driver::ContactReport* report) {
  std::vector<VtuField> fields;
  if (report == nullptr) return fields;
  for (size_t i = 0; i < report->pairs.size(); ++i) {
    const contact::PairInfo& pair = report->pairs[i].info;
    if (!pair.obstacle) continue;
    const std::string prefix = fmt::format("obstacle{}.{}.", i, pair.obstacle->kind());
    for (const contact::ObstacleParameter& p : pair.obstacle->parameters())
      fields.push_back({prefix + p.name, Eigen::Map<const VectorXd>(
                                             p.value.data(), static_cast<Index>(p.value.size()))});
    fields.push_back({prefix + "displacement", pair.obstacle_displacement});
  }
  return fields;
}

// The contact surface as triangles (as the surface has them, face_nodes: 3 nodes each, or 6 on a
// quadratic mesh, whose edge nodes are surface nodes too): nodal initial gap, w and slip,
// per-triangle multipliers of its patch; the rigid obstacles as field data.
VtuGrid contact_grid(const mesh::TetMesh& mesh, const driver::ContactFields& c,
                     const driver::ContactReport* report) {
  const auto& s = c.surface;
  VtuGrid surface;
  surface.points.resize(3, s.n_nodes());
  for (Index k = 0; k < s.n_nodes(); ++k)
    surface.points.col(k) = mesh.nodes.col(s.nodes[static_cast<size_t>(k)]);
  surface.cells = s.face_nodes;
  MatrixXd w(3, s.n_nodes()), scalars(6, s.n_nodes());
  const bool has_slip = c.slip.size() == s.n_nodes();
  for (Index k = 0; k < s.n_nodes(); ++k) {
    w.col(k) = c.wn(k) * s.node_frames.n.col(k) + c.wt1(k) * s.node_frames.t1.col(k) +
               c.wt2(k) * s.node_frames.t2.col(k);
    const Real norm_wt = std::hypot(c.wt1(k), c.wt2(k));
    scalars.col(k) << c.wn(k), norm_wt, c.phi(k), c.F(k), c.gap(k), has_slip ? c.slip(k) : norm_wt;
  }
  // "slip": F's argument, ||w_t|| of a static run, the accumulated slip along a loading path.
  surface.point_data = {{"displacement", w},      {"gap", scalars.row(4)},
                        {"w_n", scalars.row(0)},  {"norm_w_t", scalars.row(1)},
                        {"slip", scalars.row(5)}, {"phi", scalars.row(2)},
                        {"F", scalars.row(3)}};
  const Index nf = s.face_nodes.cols();
  MatrixXd lambda_t(3, nf), per_face(7, nf);
  for (Index p = 0; p < c.patches.size(); ++p)
    for (Index k : c.patches.faces[static_cast<size_t>(p)]) {
      lambda_t.col(k) = c.lambda(3 * p + 1) * c.patch_frames.t1.col(p) +
                        c.lambda(3 * p + 2) * c.patch_frames.t2.col(p);
      per_face.col(k) << c.lambda(3 * p), c.lambda.segment<2>(3 * p + 1).norm(), c.radius(p),
          static_cast<Real>(p), c.coefficient(p),
          static_cast<Real>(c.state[static_cast<size_t>(p)]),
          static_cast<Real>(c.patch_pair[static_cast<size_t>(p)]);
    }
  surface.cell_data = {{"lambda_n", per_face.row(0)},      {"lambda_t", lambda_t},
                       {"norm_lambda_t", per_face.row(1)}, {"radius", per_face.row(2)},
                       {"patch", per_face.row(3)},         {"F_patch", per_face.row(4)},
                       {"state", per_face.row(5)},         {"pair", per_face.row(6)}};
  surface.field_data = obstacle_fields(report);
  // Against a rigid obstacle: the signed distance of each node (undeformed) to the obstacle where
  // it is moved; its zero line is the obstacle's outline on the surface (`fricon plot`).
  if (report != nullptr) {
    MatrixXd distance = MatrixXd::Zero(1, s.n_nodes());
    bool any = false;
    for (Index k = 0; k < s.n_nodes(); ++k) {
      const auto pair = static_cast<size_t>(s.node_pair[static_cast<size_t>(k)]);
      if (pair >= report->pairs.size() || !report->pairs[pair].info.obstacle) continue;
      const contact::PairInfo& info = report->pairs[pair].info;
      distance(0, k) =
          info.obstacle->closest(surface.points.col(k) - info.obstacle_displacement).distance;
      any = true;
    }
    if (any) surface.point_data.push_back({"obstacle_distance", distance});
  }
  return surface;
}

}  // namespace

namespace {

// The per-step files of a loading path: STEPS_DIR/solution-0001.vtu, ...
constexpr const char* kStepsDir = "steps";
std::string step_file(const std::string& base, int step, const std::string& extension) {
  return fmt::format("{}/{}-{:04d}{}", kStepsDir, base, step, extension);
}

// Removes `path` if it exists; OutputError if it exists and cannot be removed.
void remove_earlier(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (ec)
    throw OutputError(
        fmt::format("cannot remove {} of an earlier run: {}", path.string(), ec.message()));
}

// Removes the files in `folder` whose names `ours` accepts, and the folder if that empties it
// (files of other names are the user's and stay).
template <typename Ours>
void remove_earlier_files(const std::filesystem::path& folder, Ours ours) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.is_regular_file() && ours(entry.path().filename().string()))
      remove_earlier(entry.path());
  if (std::filesystem::is_empty(folder, ec)) remove_earlier(folder);
}

// Whether `name` is a per-step file of a loading path (step_file), or its temporary file.
// NAME-DDDD[D...].EXT[.tmp], NAME solution, contact, obstacle or patches and EXT vtu or csv.
bool is_step_file(const std::string& name) {
  constexpr std::size_t kMinDigits = 4;  // step_file's width
  std::string_view rest(name);
  const auto take = [&rest](std::string_view prefix) {
    if (rest.substr(0, prefix.size()) != prefix) return false;
    rest.remove_prefix(prefix.size());
    return true;
  };
  if (!take("solution-") && !take("contact-") && !take("obstacle-") && !take("patches-"))
    return false;
  std::size_t digits = 0;
  while (digits < rest.size() && std::isdigit(static_cast<unsigned char>(rest[digits])) != 0)
    ++digits;
  if (digits < kMinDigits) return false;
  rest.remove_prefix(digits);
  if (!take(".vtu") && !take(".csv")) return false;
  return rest.empty() || rest == ".tmp";
}

// Removes the result files of an earlier run (converged or not), and with `steps` its per-step
// files.
void remove_results(const std::filesystem::path& dir, bool steps) {
  for (const auto& [base, ext] : kResultFiles)
    for (bool c : {true, false})
      remove_earlier(result_path(dir, base, ext, c));
  if (steps) remove_earlier_files(dir / kStepsDir, is_step_file);
}

// The figures of `fricon plot` in DIR/plots (scripts/plot_results.py writes only these
// formats).
constexpr const char* kPlotsDir = "plots";
bool is_figure(const std::string& name) {
  const std::string ext = std::filesystem::path(name).extension().string();
  return ext == ".png" || ext == ".pdf" || ext == ".svg";
}

// A probe file of kProbeBytes into `dir`, removed again: fails (OutputError) where the results
// could not be written.
void probe_writable(const std::filesystem::path& dir) {
  const std::filesystem::path probe = dir / ".fricon-write-probe";
  try {
    write_atomically(probe, [](std::ostream& out) {
      const std::string block(kProbeBytes, '\0');
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
    });
  } catch (const OutputError& e) {
    throw OutputError(
        fmt::format("the results folder {} cannot be written: {}", dir.string(), e.what()));
  }
  std::error_code ec;
  std::filesystem::remove(probe, ec);
}

// solution.pvd: the last state (body and contact surface), or along a loading path the time
// series of the steps whose files were written (time = step number).
std::vector<PvdEntry> pvd_entries(const std::filesystem::path& dir,
                                  const std::vector<int>& written_steps,
                                  const std::vector<std::string>& parts) {
  std::vector<PvdEntry> entries;
  for (const int step : written_steps) {
    entries.push_back({static_cast<Real>(step), 0, step_file("solution", step, ".vtu")});
    const std::string surface = step_file("contact", step, ".vtu");
    if (std::filesystem::exists(dir / surface))
      entries.push_back({static_cast<Real>(step), 1, surface});
    const std::string obstacle = step_file("obstacle", step, ".vtu");
    if (std::filesystem::exists(dir / obstacle))
      entries.push_back({static_cast<Real>(step), 2, obstacle});
  }
  if (entries.empty())  // a static run, or a path whose step files were not written
    for (size_t i = 0; i < parts.size(); ++i)
      entries.push_back({0.0, static_cast<int>(i), parts[i]});
  return entries;
}

}  // namespace

void prepare_results(const std::filesystem::path& dir) {
  if (dir.empty()) throw InputError("the results folder is an empty path");
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw OutputError(fmt::format(
        "the results folder {} is not a folder (a file of that name exists)", dir.string()));
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw OutputError(
        fmt::format("cannot create the results folder {}: {}", dir.string(), ec.message()));
  probe_writable(dir);
  remove_results(dir, true);
  remove_earlier_files(dir / kPlotsDir, is_figure);
}

bool step_files_wanted(const driver::OutputOptions& output, int step, int steps) {
  if (step == steps) return true;
  if (!output.step_files.empty())
    return std::find(output.step_files.begin(), output.step_files.end(), step) !=
           output.step_files.end();
  return step % output.step_files_every == 0;
}

std::optional<StepFiles> step_files(const driver::RunResult& result) {
  if (result.report.steps.empty() || result.report.status != driver::RunStatus::Converged)
    return std::nullopt;
  StepFiles files;
  files.step = result.report.steps.back().step;
  files.body = body_grid(result);
  if (result.contact) {
    const driver::ContactReport* report = result.report.contact ? &*result.report.contact : nullptr;
    files.contact = contact_grid(result.model.mesh, *result.contact, report);
    files.obstacle = obstacle_grid(result.model.mesh, *result.contact, report);
    files.patches = patch_table(*result.contact);
  }
  return files;
}

std::vector<std::filesystem::path> write_step_files(const std::filesystem::path& dir,
                                                    const StepFiles& files, VtuEncoding encoding) {
  std::vector<std::filesystem::path> written;
  written.push_back(dir / step_file("solution", files.step, ".vtu"));
  write_vtu(written.back(), files.body, encoding);
  if (files.contact) {
    written.push_back(dir / step_file("contact", files.step, ".vtu"));
    write_vtu(written.back(), *files.contact, encoding);
  }
  if (files.obstacle) {
    written.push_back(dir / step_file("obstacle", files.step, ".vtu"));
    write_vtu(written.back(), *files.obstacle, encoding);
  }
  if (files.patches) {
    written.push_back(dir / step_file("patches", files.step, ".csv"));
    write_csv(written.back(), *files.patches);
  }
  return written;
}

std::vector<std::filesystem::path> write_step(const std::filesystem::path& dir,
                                              const driver::RunResult& result,
                                              VtuEncoding encoding) {
  const std::optional<StepFiles> files = step_files(result);
  return files ? write_step_files(dir, *files, encoding) : std::vector<std::filesystem::path>{};
}

std::vector<std::filesystem::path> write_results(const std::filesystem::path& dir,
                                                 const driver::Problem& problem,
                                                 const driver::RunResult& result,
                                                 const RunContext& context,
                                                 const std::vector<int>& written_steps) {
  const bool converged = result.report.status == driver::RunStatus::Converged;
  // Results of an earlier run in the same folder, converged or not, would contradict this one;
  // so would step files that this run did not write.
  remove_results(dir, written_steps.empty());
  std::vector<std::filesystem::path> written;
  auto path = [&](const std::string& base, const std::string& ext) {
    written.push_back(result_path(dir, base, ext, converged));
    return written.back();
  };
  const VtuEncoding encoding = problem.output.vtu_encoding;
  try {
    std::vector<std::string> parts;
    write_vtu(path("solution", ".vtu"), body_grid(result), encoding);
    parts.push_back(written.back().filename().string());
    if (result.contact) {
      write_csv(path("contact_nodes", ".csv"),
                contact_node_table(result.model.mesh, *result.contact));
      write_csv(path("patches", ".csv"), patch_table(*result.contact));
      const driver::ContactReport* report =
          result.report.contact ? &*result.report.contact : nullptr;
      write_vtu(path("contact", ".vtu"), contact_grid(result.model.mesh, *result.contact, report),
                encoding);
      parts.push_back(written.back().filename().string());
      if (const auto obstacle = obstacle_grid(result.model.mesh, *result.contact, report)) {
        write_vtu(path("obstacle", ".vtu"), *obstacle, encoding);
        parts.push_back(written.back().filename().string());
      }
    }
    if (!result.report.steps.empty())
      write_csv(path("steps", ".csv"), steps_table(problem, result.report));
    write_pvd(path("solution", ".pvd"), pvd_entries(dir, written_steps, parts));
    // Last: a folder with a report is complete.
    const nlohmann::json report = report_json(problem, result, context);
    write_atomically(path("report", ".json"),
                     [&](std::ostream& out) { out << report.dump(2) << '\n'; });
  } catch (const OutputError&) {
    // Nothing of a run that could not be written stays to be mistaken for its results.
    for (const auto& p : written) {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
    throw;
  }
  return written;
}

}  // namespace fricon::io
