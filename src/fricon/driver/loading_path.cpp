// driver: the quasi-static loading path (theory.md §2.9). The model, the contact discretization,
// the factor of K and the dual operator Q are built once; each step then changes only the load
// (f, the prescribed displacements, hence h), the offset of the tangential rows (the last step's
// tangential displacement, so that friction acts on the slip increment), the slips the
// coefficient is evaluated at (the accumulated slip) and the warm start.
#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/driver/run_steps.hpp"

namespace fricon::driver {

namespace {

// What one step leaves for the next (theory.md §2.9).
struct PathState {
  SlipHistory history;
  VectorXd lambda;      // multipliers of the last step [Pa]
  VectorXd tangential;  // per multiplier row: the last step's int_R u_t dS [m^3] (normal rows 0)
  Real norm_Q = 0.0, norm_Q_scaled = 0.0;
};

// The loads of step k: the prescribed displacements and f, into the model; the contact
// discretization moved to them, its tangential rows offset by the last step's displacement.
void apply_step_loads(const Problem& step_problem, const PathState& state, Model& m,
                      contact::ContactDiscretization& disc) {
  m.prescribed = make_prescribed(step_problem, m.mesh);
  m.f = load_vector(step_problem, m, Extent::Whole);
  contact::set_prescribed(disc, m.prescribed);
  disc.offset += state.tangential;
}

// int_R u dS per multiplier row, in the patch frames, of the whole displacement (free dofs w and
// the prescribed values); its tangential rows offset the next step.
VectorXd patch_tangential(const contact::ContactDiscretization& disc, const Model& m,
                          const VectorXd& w) {
  const Eigen::Map<const VectorXd> up(m.prescribed.data(), m.prescribed.size());
  VectorXd d = disc.B * w + disc.prescribed_offset * up;
  for (Index p = 0; p < disc.n_patches(); ++p)
    d(3 * p) = 0.0;
  return d;
}

// The mean displacement of the nodes of each path load's boundary (zero for the volume force).
std::vector<Vec3> load_displacements(const std::vector<PathLoad>& loads, const RunResult& r) {
  std::vector<Vec3> out;
  for (const PathLoad& load : loads) {
    Vec3 mean = Vec3::Zero();
    if (!load.boundary.empty()) {
      const std::vector<Index> nodes = r.model.mesh.nodes_with_tag(load.boundary);
      for (Index a : nodes)
        mean += r.displacement.col(a);
      if (!nodes.empty()) mean /= static_cast<Real>(nodes.size());
    }
    out.push_back(mean);
  }
  return out;
}

StepReport describe_step(int k, const std::vector<PathLoad>& loads, const RunResult& r,
                         double seconds) {
  const RunReport& rep = r.report;
  StepReport s;
  s.step = k;
  for (const PathLoad& load : loads)
    s.factors.push_back((*load.factors)[static_cast<std::size_t>(k - 1)]);
  s.status = rep.status;
  s.message = rep.message;
  s.contact_force = rep.contact_force;
  s.reaction_force = rep.reaction_force;
  s.applied_force = rep.applied_force;
  s.load_displacement = load_displacements(loads, r);
  s.equilibrium_residual = rep.equilibrium_residual;
  s.time_s = seconds;
  if (rep.contact) {
    const ContactReport& c = *rep.contact;
    s.normal_force = c.total_normal_force;
    for (const PairReport& pair : c.pairs)
      s.tangential_force += pair.tangential_force;
    s.max_slip = c.max_wt;
    s.n_stick = c.n_stick;
    s.n_slip = c.n_slip;
    s.n_separated = c.n_separated;
    s.outer_iterations = c.outer_iterations;
    s.n_mult = c.n_mult;
    s.kkt = c.kkt.max();
  }
  if (r.contact && r.contact->slip.size() > 0) s.max_accumulated_slip = r.contact->slip.maxCoeff();
  return s;
}

// The state the step leaves: the tangential displacement and accumulated slip at the surface
// nodes, the multipliers, the tangential patch integrals.
void remember_step(const contact::ContactDiscretization& disc, const RunResult& r,
                   const VectorXd& w, PathState& state) {
  const ContactFields& f = *r.contact;
  state.history.wt1 = f.wt1;
  state.history.wt2 = f.wt2;
  state.history.accumulated = f.slip;
  state.lambda = f.lambda;
  state.tangential = patch_tangential(disc, r.model, w);
  const ContactReport& c = *r.report.contact;
  state.norm_Q = c.norm_Q;
  state.norm_Q_scaled = c.norm_Q_scaled;
}

// Every step's prescribed displacements, before the first solve: two [[dirichlet]] entries that
// disagree on a node at some step are refused now, naming the step.
void check_steps(const Problem& problem, const mesh::TetMesh& mesh) {
  for (int k = 1; k <= problem.loading.steps; ++k)
    try {
      (void)make_prescribed(at_step(problem, k), mesh);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{} (at step {} of the loading path)", e.what(), k));
    }
}

// The step's contact solve on the path's operator, then its fields and self-check.
VectorXd solve_step(const Problem& step_problem, const contact::ContactDiscretization& disc,
                    dual::DualOperator& Q, const PathState& state, const RunOptions& options,
                    RunResult& r) {
  Model& m = r.model;
  Q.set_load(m.f, disc.offset);
  const PathStep step{&state.history, state.lambda.size() > 0 ? &state.lambda : nullptr,
                      state.norm_Q, state.norm_Q_scaled};
  phase_start(options, "outer loop");
  ContactOutcome c =
      solve_contact(step_problem, m, disc, Q, r.report.times, options, nullptr, &step);
  RunReport& rep = r.report;
  rep.status = c.converged ? RunStatus::Converged : RunStatus::NotConverged;
  rep.message = c.message;
  rep.contact_force = c.contact_force;
  rep.linear_residual = c.linear_residual;
  rep.contact = std::move(c.report);
  r.contact = std::move(c.fields);
  return std::move(c.w);
}

// Without contact each step is one solve with the factor.
VectorXd solve_elastic_step(RunResult& r) {
  ScopedPhase phase(r.report.times, "solve");
  const VectorXd u = r.model.factor.solve(r.model.f);
  r.report.linear_residual = elastic_residual(r.model, u);
  return u;
}

}  // namespace

RunResult run_path(const Problem& problem, const RunOptions& options) {
  const Stopwatch total;
  validate(problem);
  if (problem.solver.backend != parallel::Backend::Cholmod)
    throw InputError(fmt::format(
        "{}: solver.backend: a loading path ([loading] steps = {}) runs on one process "
        "(\"cholmod\"), not with backend \"{}\"",
        problem.where("solver.backend"), problem.loading.steps, enum_name(problem.solver.backend)));
  RunResult r;
  RunReport& rep = r.report;
  const std::vector<PathLoad> loads = path_loads(problem);

  // @sect: the model, the contact discretization (every patch: the contact search does not
  // apply to a path), the factor of K and Q, once for the whole path.
  r.model = assemble_model(problem, rep.times, options.on_phase_start);
  check_steps(problem, r.model.mesh);
  std::optional<contact::ContactDiscretization> disc;
  if (!problem.contact.empty()) {
    phase_start(options, "contact");
    ScopedPhase phase(rep.times, "contact");
    disc = discretize_contact(problem, r.model.mesh, r.model.dofs);
  }
  const dual::FactorizationRequest request =
      disc ? dual::factorization_request(problem.solver.dual_operator, disc->dofs)
           : dual::FactorizationRequest{};
  factorize_model(r.model, request, rep.times, options.on_phase_start);
  report_sizes(r.model, rep);
  rep.factor = r.model.factor.info();
  if (options.stop_was_requested()) throw Interrupted("interrupted before the first step");
  std::unique_ptr<dual::DualOperator> Q;
  if (disc) {
    phase_start(options, "dual");
    ScopedPhase phase(rep.times, "dual");
    const dual::DualInput input{r.model.factor,          disc->B,      r.model.f, disc->dofs,
                                interrupt_poll(options), &disc->offset};
    Q = dual::make_dual_operator(problem.solver.dual_operator, input);
  }

  // @sect: the steps, each from the state the last one left; a failed step ends the path.
  PathState state;
  if (disc) state.tangential = VectorXd::Zero(disc->n_dual());
  for (int k = 1; k <= problem.loading.steps; ++k) {
    const Stopwatch step_clock;
    const Problem step_problem = at_step(problem, k);
    {
      ScopedPhase phase(rep.times, "assembly");
      if (disc)
        apply_step_loads(step_problem, state, r.model, *disc);
      else {
        r.model.prescribed = make_prescribed(step_problem, r.model.mesh);
        r.model.f = load_vector(step_problem, r.model, Extent::Whole);
      }
    }
    const VectorXd u =
        disc ? solve_step(step_problem, *disc, *Q, state, options, r) : solve_elastic_step(r);
    finish_run(step_problem, u, options, r);
    const bool failed = rep.status != RunStatus::Converged;
    if (failed)
      rep.message = fmt::format("step {} of {} of the loading path failed: {}", k,
                                problem.loading.steps, rep.message);
    rep.steps.push_back(describe_step(k, loads, r, step_clock.seconds()));
    if (options.on_step) options.on_step(r);
    if (failed) break;
    if (disc) remember_step(*disc, r, u, state);
  }
  rep.time_s = total.seconds();
  return r;
}

}  // namespace fricon::driver
