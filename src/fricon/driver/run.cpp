#include "fricon/driver/run.hpp"

#include <algorithm>
#include <memory>

#include "fricon/core/error.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/fe/stress.hpp"
#include "fricon/parallel/distributed_run.hpp"

namespace fricon::driver {

bool stop_requested(const RunOptions& o) {
  return o.stop_requested && o.stop_requested->load();
}

void phase_start(const RunOptions& o, const std::string& name) {
  if (o.on_phase_start) o.on_phase_start(name);
}

std::function<void()> interrupt_poll(const RunOptions& options) {
  return [&options] {
    if (stop_requested(options)) throw Interrupted("interrupted while forming Q");
  };
}

VectorXd solve_with_operator(const Problem& problem, const contact::ContactDiscretization& disc,
                             const dual::DualOperator& Q, const RunOptions& options, RunResult& r) {
  RunReport& rep = r.report;
  phase_start(options, "outer loop");
  ContactOutcome c = solve_contact(problem, r.model, disc, Q, rep.times, options);
  r.first_dual = std::move(c.first_dual);
  rep.status = c.converged ? Status::Converged : Status::NotConverged;
  rep.message = c.message;
  rep.contact_force = c.contact_force;
  rep.linear_residual = c.linear_residual;
  rep.contact = std::move(c.report);
  r.contact = std::move(c.fields);
  return std::move(c.w);
}

namespace {

// The contact solve on the factored model: the dual operator (phase "dual"), then the outer
// loop. Fills the report's contact part and returns the displacement over the free dofs.
VectorXd solve_with_contact(const Problem& problem, const contact::ContactDiscretization& disc,
                            const RunOptions& options, RunResult& r) {
  const Model& m = r.model;
  phase_start(options, "dual");
  std::unique_ptr<dual::DualOperator> Q;
  {
    ScopedPhase phase(r.report.times, "dual");
    const dual::DualInput input{m.factor,    disc.B, m.f, disc.dofs, interrupt_poll(options),
                                &disc.offset};
    Q = dual::make_dual_operator(problem.solver.dual_operator, input);
  }
  return solve_with_operator(problem, disc, *Q, options, r);
}

// Without contact: one solve with the factor of K.
VectorXd solve_elastic(RunResult& r) {
  ScopedPhase phase(r.report.times, "solve");
  const Model& m = r.model;
  VectorXd u = m.factor.solve(m.f);
  r.report.linear_residual = elastic_residual(m, u);
  return u;
}

// Stresses, and the global equilibrium of applied loads, contact forces and reactions.
void postprocess(const Problem& problem, const VectorXd& u, RunResult& r) {
  RunReport& rep = r.report;
  const Model& m = r.model;
  ScopedPhase phase(rep.times, "postprocess");
  r.displacement = m.dofs.to_nodal(u) + m.prescribed;
  rep.max_displacement = r.displacement.colwise().norm().maxCoeff();
  fe::StressField s = fe::compute_stresses(m.mesh, m.materials, r.displacement);
  r.stress = std::move(s.stress);
  r.von_mises = std::move(s.von_mises);
  rep.applied_force = applied_force_total(problem, m.mesh);
  rep.reaction_force = reaction_total(m, problem, r.displacement);
  // Relative to the largest of the three: a body pressed by a prescribed displacement has no
  // applied load.
  const Real scale = std::max(
      {rep.applied_force.norm(), rep.contact_force.norm(), rep.reaction_force.norm(), 1e-300});
  rep.equilibrium_residual =
      (rep.applied_force + rep.contact_force + rep.reaction_force).norm() / scale;
}

}  // namespace

void report_sizes(const Model& model, RunReport& report) {
  report.n_nodes = model.mesh.n_nodes();
  report.n_tets = model.mesh.n_tets();
  report.n_primal = model.dofs.n_free();
}

Real elastic_residual(const Model& model, const VectorXd& u) {
  return (stiffness_times(model, u) - model.f).norm() / std::max(model.f.norm(), 1e-300);
}

void finish_run(const Problem& problem, const VectorXd& u, const RunOptions& options,
                RunResult& r) {
  if (stop_requested(options) && r.report.status == Status::Converged) {
    r.report.status = Status::NotConverged;
    r.report.message = "interrupted";
  }
  postprocess(problem, u, r);
}

RunResult run(const Problem& problem, const RunOptions& options) {
  if (problem.solver.backend == parallel::Backend::Petsc) {
    // Validated on every rank there; a build without PETSc says here how to get it.
    if (!parallel::petsc_available()) validate(problem);
    return parallel::run_distributed(problem, options);
  }
  const Stopwatch total;
  validate(problem);
  RunResult r;
  RunReport& rep = r.report;

  // @sect: the elastic model and, with contact, its discretization on the contact surface.
  r.model = assemble_model(problem, rep.times, options.on_phase_start);
  std::optional<contact::ContactDiscretization> disc;
  if (problem.contact) {
    phase_start(options, "contact");
    ScopedPhase phase(rep.times, "contact");
    disc = discretize_contact(problem, r.model.mesh, r.model.dofs);
  }

  // @sect: the factorization of K, ordered as the dual operator asks.
  const dual::FactorizationRequest request =
      disc ? dual::factorization_request(problem.solver.dual_operator, disc->dofs)
           : dual::FactorizationRequest{};
  factorize_model(r.model, request, rep.times, options.on_phase_start);
  report_sizes(r.model, rep);
  rep.factor = r.model.factor.info();
  if (stop_requested(options)) throw Interrupted("interrupted before the solve");

  // @sect: the displacement: one solve, or the outer loop of dual QPs.
  const VectorXd u = disc ? solve_with_contact(problem, *disc, options, r) : solve_elastic(r);

  // @sect: fields and the self-check of the result.
  finish_run(problem, u, options, r);
  rep.time_s = total.seconds();
  return r;
}

}  // namespace fricon::driver
