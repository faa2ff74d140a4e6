#include "fricon/driver/run.hpp"

#include <cmath>

#include "fricon/fe/p1_element.hpp"

namespace fricon::driver {

std::string to_string(Status s) {
  return s == Status::Converged ? "converged" : "not_converged";
}

namespace {

void compute_stresses(RunResult& r) {
  const auto& mesh = r.model.mesh;
  r.stress.resize(6, mesh.n_tets());
  r.von_mises.resize(mesh.n_tets());
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const fe::P1Gradients g = fe::p1_gradients(fe::tet_vertices(mesh, t));
    Eigen::Matrix<Real, 12, 1> ue;
    for (int a = 0; a < 4; ++a)
      ue.segment<3>(3 * a) = r.displacement.col(mesh.tets(a, t));
    const Eigen::Matrix<Real, 6, 1> s = r.model.material.D * (fe::strain_matrix(g.grad) * ue);
    r.stress.col(t) = s;
    r.von_mises(t) =
        std::sqrt(0.5 * ((s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) +
                         (s(2) - s(0)) * (s(2) - s(0))) +
                  3.0 * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5)));
  }
}

}  // namespace

RunResult run(const Problem& problem, const RunOptions& options) {
  Stopwatch total;
  RunResult r;
  RunReport& rep = r.report;
  // @sect: the elastic model (mesh, assembly, factorization), shared by every later stage.
  r.model = assemble_model(problem, rep.times, options.on_phase_start);
  std::vector<Index> last;
  if (wants_schur(problem)) last = contact_dofs(problem, r.model);
  factorize_model(r.model, rep.times, options.on_phase_start, last);
  const Model& m = r.model;
  rep.n_nodes = m.mesh.n_nodes();
  rep.n_tets = m.mesh.n_tets();
  rep.n_primal = m.dofs.n_free();
  rep.factor = m.factor.info();

  // @sect: the displacement. Without contact, one solve with the factor of K; with contact, the
  // successive approximations of Tresca problems, each solved in its dual form.
  VectorXd u;
  if (problem.contact) {
    ContactOutcome c = solve_contact(problem, m, rep.times, options);
    r.first_dual = std::move(c.first_dual);
    u = std::move(c.w);
    rep.status = c.converged ? Status::Converged : Status::NotConverged;
    rep.message = c.message;
    rep.contact_force = c.contact_force;
    rep.linear_residual = c.linear_residual;
    rep.contact = std::move(c.report);
    r.contact = std::move(c.fields);
  } else {
    ScopedPhase phase(rep.times, "solve");
    u = m.factor.solve(m.f);
    rep.linear_residual = (m.K * u - m.f).norm() / std::max(m.f.norm(), 1e-300);
  }

  if (options.stop_requested && options.stop_requested->load() && rep.status == Status::Converged) {
    rep.status = Status::NotConverged;
    rep.message = "interrupted";
  }

  // @sect: fields and the self-check of the result.
  {
    ScopedPhase phase(rep.times, "postprocess");
    r.displacement = m.dofs.to_nodal(u);
    rep.max_displacement = r.displacement.colwise().norm().maxCoeff();
    compute_stresses(r);
    rep.applied_force = applied_force_total(problem, m.mesh);
    rep.reaction_force = reaction_total(m, problem, r.displacement);
    rep.equilibrium_residual = (rep.applied_force + rep.contact_force + rep.reaction_force).norm() /
                               std::max(rep.applied_force.norm(), 1e-300);
  }
  rep.time_s = total.seconds();
  return r;
}

}  // namespace fricon::driver
