#include "fricon/driver/tfeti_solve.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/parallel_for.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/feti/tfeti.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/qp/smalse.hpp"

namespace fricon::driver {

std::unique_ptr<feti::FetiOperator> make_feti_operator(const Problem& problem, const Model& model,
                                                       const contact::ContactDiscretization* disc,
                                                       const RunOptions& options,
                                                       RunReport& report) {
  ScopedPhase phase(report.times, "factorize");
  feti::FetiOptions o;
  o.subdomains = problem.solver.subdomains.value_or(0);
  o.subdomain_size = problem.solver.subdomain_size;
  o.scaling = problem.solver.tfeti_scaling;
  o.preconditioner = problem.solver.tfeti_preconditioner;
  o.neck_cuts = problem.solver.tfeti_neck_cuts;
  // The subdomains are the parallelism: one BLAS thread inside each of their solves.
  o.threads = loop_threads(linalg::threads());
  linalg::set_threads(1);
  o.key_context = problem.where("solver.subdomains");
  const fe::NodalField applied = applied_forces(problem, model.mesh);
  const SparseMatrix no_rows(0, model.dofs.n_free());
  feti::FetiReport feti_report;
  auto op = feti::make_tfeti(
      model.mesh, model.bodies, model.materials, model.dofs, model.prescribed, applied,
      disc ? disc->B : no_rows, disc ? disc->offset : VectorXd(), o,
      options.feti_ranks ? *options.feti_ranks : feti::this_process(), feti_report);
  report.feti = feti_report;
  return op;
}

void record_feti_counts(const feti::FetiOperator& F, RunReport& report) {
  if (!report.feti) return;
  report.feti->n_contact = F.n_contact();  // the contact search's last candidates
  report.feti->n_products = F.n_products();
  report.feti->products_s = F.products_seconds();
  report.feti->sums_s = F.sums_seconds();
  report.feti->n_preconditioner = F.n_preconditioner();
  report.feti->preconditioner_s = F.preconditioner_seconds();
  feti::record_shares(F, *report.feti);
  if (report.contact) {
    report.feti->qp_iterations = report.contact->qp_iterations;
    report.feti->smalse_outer_iterations = report.contact->smalse_outer_iterations;
    report.feti->n_coarse_solves = report.contact->coarse_solves;
    report.feti->coarse_s = report.contact->coarse_s;
    report.feti->gluing_residual = report.contact->gluing_residual;
    report.feti->gluing_bound = report.contact->kkt_bound;
  }
}

void record_run_peak_memory(const RunOptions& options, RunReport& report) {
  if (!report.feti) return;
  feti::record_peak_memory(options.feti_ranks ? *options.feti_ranks : feti::this_process(),
                           *report.feti);
}

GluingSolve solve_gluing(const feti::FetiOperator& F, const Problem& problem,
                         const RunOptions& options) {
  FRICON_CHECK(F.n_contact() == 0, "solve_gluing: F has " << F.n_contact() << " contact rows");
  qp::SeparableConstraints free;
  free.append_free(F.size());
  qp::MpgpOptions inner = problem.solver.qp;
  inner.rel_tolerance *= dual::kEqualityToleranceShare;
  inner.power_tolerance = dual::kEqualityPowerTolerance;
  inner.monitor = [&options](const qp::MpgpIteration&) { return !options.stop_was_requested(); };
  qp::SmalseOptions outer;
  outer.rho_factor = dual::kEqualityPenaltyFactor;
  outer.projected_norm = true;
  outer.equality_tolerance = inner.rel_tolerance;
  GluingSolve g;
  VectorXd lambda = VectorXd::Zero(F.size()), mu;
  // On the multipliers this process holds, with the share's preconditioner (theory.md §8.8).
  g.qp = dual::solve_shared_smalse(F, free, qp::BlockScaling::identity(F.size()), {F.G(), F.e()},
                                   outer, inner, lambda, mu);
  if (g.qp.termination == qp::QpTermination::UserStopped)
    throw Interrupted("interrupted during the Total FETI solve");
  const VectorXd alpha = -mu;
  g.u = F.displacement(lambda) + F.rigid_displacement(alpha);
  g.gluing_residual = F.gluing_residual(lambda, alpha);
  g.gluing_bound = kCertificateFactor * problem.solver.qp.rel_tolerance;
  return g;
}

VectorXd gluing_free_displacement(const feti::FetiOperator& F, const Problem& problem,
                                  const RunOptions& options, RunReport& report) {
  GluingSolve g = solve_gluing(F, problem, options);
  if (!g.converged() && report.feti && report.feti->free_displacement_note.empty())
    report.feti->free_displacement_note =
        g.qp.termination != qp::QpTermination::Converged
            ? g.qp.message
            : fmt::format("gluing residual {:.3e} above {:.1e}", g.gluing_residual, g.gluing_bound);
  return std::move(g.u);
}

VectorXd solve_elastic_tfeti(const Problem& problem, const RunOptions& options, RunResult& r) {
  RunReport& rep = r.report;
  phase_start(options, "factorize");
  const std::unique_ptr<feti::FetiOperator> F =
      make_feti_operator(problem, r.model, nullptr, options, rep);
  phase_start(options, "solve");
  ScopedPhase phase(rep.times, "solve");
  const GluingSolve g = solve_gluing(*F, problem, options);
  rep.linear_residual = elastic_residual(r.model, g.u);
  feti::FetiReport& fr = *rep.feti;
  record_feti_counts(*F, rep);
  fr.n_coarse_solves = g.qp.n_coarse_solves;
  fr.coarse_s = g.qp.coarse_s;
  fr.qp_iterations = g.qp.iterations;
  fr.smalse_outer_iterations = g.qp.outer_iterations;
  fr.gluing_residual = g.gluing_residual;
  fr.gluing_bound = g.gluing_bound;
  if (g.qp.termination != qp::QpTermination::Converged) {
    rep.status = RunStatus::NotConverged;
    rep.message = fmt::format("the Total FETI QP did not converge: {}", g.qp.message);
  } else if (!g.converged()) {
    rep.status = RunStatus::NotConverged;
    rep.message = fmt::format(
        "the certificate failed: the subdomains' copies of the nodes (and the Dirichlet values) "
        "differ by {:.3e} of the displacement (root mean squares), more than {:.1e}",
        fr.gluing_residual, fr.gluing_bound);
  } else {
    rep.message =
        fmt::format("Total FETI on {} subdomains: {} products with F, gluing residual {:.2e}",
                    fr.n_subdomains, fr.n_products, fr.gluing_residual);
  }
  return g.u;
}

}  // namespace fricon::driver
