#include "fricon/driver/run.hpp"

#include <algorithm>
#include <memory>

#include <fmt/format.h>
#include "fricon/core/error.hpp"
#include "fricon/driver/candidate_operators.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/driver/tfeti_solve.hpp"
#include "fricon/fe/stress.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::driver {

namespace {
// Mean gaps within this share of the smallest are the same (rounding of a flat face's gaps).
constexpr Real kSameGap = 1e-9;
}  // namespace

void phase_start(const RunOptions& o, const std::string& name) {
  if (o.on_phase_start) o.on_phase_start(name);
}

std::function<void()> interrupt_poll(const RunOptions& options) {
  return [&options] {
    if (options.stop_was_requested()) throw Interrupted("interrupted while forming Q");
  };
}

VectorXd adopt(ContactOutcome&& c, RunResult& r) {
  RunReport& rep = r.report;
  r.first_dual = std::move(c.first_dual);
  rep.status = c.converged ? RunStatus::Converged : RunStatus::NotConverged;
  rep.message = c.message;
  rep.contact_force = c.contact_force;
  rep.contact_force_magnitude = c.contact_force_magnitude;
  rep.linear_residual = c.linear_residual;
  rep.contact = std::move(c.report);
  r.contact = std::move(c.fields);
  return std::move(c.w);
}

VectorXd solve_with_operator(const Problem& problem, const contact::ContactDiscretization& disc,
                             const dual::DualOperator& Q, const RunOptions& options, RunResult& r) {
  phase_start(options, "outer loop");
  return adopt(solve_contact(problem, r.model, disc, Q, r.report.times, options), r);
}

namespace {

// Every radius of the pair is 0 whatever the state: F = 0, or Tresca with g = 0.
bool frictionless(const ContactOptions& c) {
  const bool no_coefficient =
      c.friction.law == contact::FrictionLawKind::Constant && c.friction.value == 0.0;
  const bool no_tresca_bound = c.model == contact::FrictionModel::Tresca && c.slip_bound <= 0.0;
  return no_coefficient || no_tresca_bound;
}

// Every radius of every pair is 0 whatever the state.
bool frictionless(const Problem& problem) {
  return std::all_of(problem.contact.begin(), problem.contact.end(),
                     [](const ContactOptions& c) { return frictionless(c); });
}

}  // namespace

bool search_applies(const Problem& problem, const Model& model) {
  if (problem.solver.contact_search == contact::ContactSearch::Off) return false;
  // Total FETI starts the search from the gluing's displacement, which a floating body lacks,
  // and has no refusal of candidates that cannot balance it (theory.md §8.7): every patch.
  if (problem.solver.backend == parallel::Backend::Tfeti && !model.floating.empty()) return false;
  // A positive Tresca bound g F acts without pressure: every patch of such a pair resists
  // sliding, so none may be left out (theory.md §2.7).
  const bool tresca_with_friction =
      std::any_of(problem.contact.begin(), problem.contact.end(), [](const ContactOptions& c) {
        return c.model == contact::FrictionModel::Tresca && !frictionless(c);
      });
  return !tresca_with_friction;
}

namespace {

// The first candidates of a model with a floating body (theory.md §2.10): the patches whose mean
// gap is the smallest, every one that ties (a flat face on a plane), and those within `margin`
// of the gaps' spread above it. `penetration` is minus the mean gap per patch.
std::vector<Index> closed_gaps(const VectorXd& penetration, Real margin) {
  std::vector<Index> candidates;
  if (penetration.size() == 0) return candidates;
  const Real closest = penetration.maxCoeff();
  const Real spread = closest - penetration.minCoeff();
  const Real threshold = closest - std::max(margin * spread, kSameGap * std::abs(closest));
  for (Index p = 0; p < penetration.size(); ++p)
    if (penetration(p) >= threshold) candidates.push_back(p);
  return candidates;
}

}  // namespace

std::unique_ptr<CandidateOperators> make_candidate_operators(const Problem& problem, const Model& m,
                                                             const RunOptions& options,
                                                             RunReport& report) {
  return problem.solver.backend == parallel::Backend::Tfeti
             ? make_feti_candidates(problem, m, options, report)
             : make_factor_candidates(problem, m, options, report);
}

VectorXd solve_with_search(const Problem& problem, const contact::ContactDiscretization& disc,
                           const RunOptions& options, RunResult& r, CandidateOperators& operators,
                           const std::vector<Index>* first_candidates) {
  const Model& m = r.model;
  // @sect: the free displacement and the first candidates (theory.md §2.7); with a floating
  // body, whose free displacement does not exist, those of the closed gaps (theory.md §2.10).
  std::vector<Index> candidates;
  Real tolerance = 0.0;
  {
    const VectorXd& u0 = operators.free_displacement();
    const VectorXd free_penetration = contact::mean_penetration(
        disc, m.floating.empty() ? u0 : VectorXd(VectorXd::Zero(u0.size())));
    const Real margin = problem.solver.contact_search_margin;
    if (first_candidates)
      candidates = *first_candidates;
    else if (m.floating.empty())
      candidates = contact::initial_candidates(free_penetration, margin);
    else
      candidates = closed_gaps(free_penetration, margin);
    tolerance = problem.solver.qp.rel_tolerance * free_penetration.cwiseAbs().maxCoeff();
  }
  // @sect: solve on the candidates, add the left-out patches that penetrate, again until none
  // does (after kMaxSearchRounds growths, with every patch). The counts of the report are
  // those of every round (and of the solve for u0).
  SearchRounds rounds(operators.take_free_displacement_solves());
  // Without friction every radius is 0 and the tangential multipliers stay 0: their rows of B
  // need not enter Q (a third of the rows to form); a dumped QP keeps them (a Q without zero
  // rows, for other solvers).
  const bool normal_rows = frictionless(problem) && !options.keep_first_dual;
  const contact::PatchRows rows =
      normal_rows ? contact::PatchRows::Normal : contact::PatchRows::All;
  for (int round = 1;; ++round) {
    const contact::ContactDiscretization part =
        contact::restrict_to_patches(disc, candidates, rows);
    const dual::DualOperator& Q = operators.on_candidates(part);
    phase_start(options, "outer loop");
    const PatchSelection selection{disc, candidates, round};
    ContactOutcome c;
    try {
      c = solve_contact(problem, m, part, Q, r.report.times, options, &selection);
    } catch (const UnbalancedLoad&) {
      // Candidates that cannot balance a floating body: again with every patch, which decides.
      if (static_cast<Index>(candidates.size()) == disc.n_patches()) throw;
      candidates = all_patches(disc);
      continue;
    }
    const std::vector<Index> added =
        rounds.patches_to_add(disc, candidates, c, tolerance, round, options);
    if (added.empty()) {
      VectorXd u = rounds.adopt_answer(std::move(c), r);
      operators.record(r.report);
      return u;
    }
    candidates = contact::merge_patches(candidates, added);
  }
}

std::vector<Index> all_patches(const contact::ContactDiscretization& disc) {
  std::vector<Index> all(static_cast<size_t>(disc.n_patches()));
  for (Index p = 0; p < disc.n_patches(); ++p)
    all[static_cast<size_t>(p)] = p;
  return all;
}

std::vector<Index> SearchRounds::patches_to_add(const contact::ContactDiscretization& disc,
                                                const std::vector<Index>& candidates,
                                                const ContactOutcome& c, Real tolerance, int round,
                                                const RunOptions& options) {
  std::vector<Index> added =
      contact::penetrating_patches(contact::mean_penetration(disc, c.w), candidates, tolerance);
  // A round that left out a pressing patch fails its certificate over every patch: that
  // failure is what the growth repairs; any other is the answer.
  const bool grow =
      !added.empty() && !options.stop_was_requested() &&
      (c.converged || c.report.termination == outer::OuterTermination::CertificateFailed);
  if (!grow) return {};
  products_ += c.report.n_mult;
  qp_iterations_ += c.report.qp_iterations;
  steps_ += c.report.qp_steps;
  solves_ += c.report.n_kinv;
  if (round < kMaxSearchRounds) return added;
  // Every left-out patch: the candidates are increasing, the rest is their complement.
  added.clear();
  std::size_t next = 0;
  for (Index p = 0; p < disc.n_patches(); ++p) {
    if (next < candidates.size() && candidates[next] == p)
      ++next;
    else
      added.push_back(p);
  }
  return added;
}

VectorXd SearchRounds::adopt_answer(ContactOutcome&& c, RunResult& r) const {
  c.report.n_mult += products_;
  c.report.qp_iterations += qp_iterations_;
  c.report.qp_steps += steps_;
  c.report.n_kinv += solves_;
  return adopt(std::move(c), r);
}

namespace {

// The contact solve on every patch (no contact search): the dual operator (phase "dual"), then
// the outer loop. Under Total FETI the operator is the kept one of `operators` (made at the first
// call), whose contact rows a geometric update replaces, so that no subdomain is factored again
// (theory.md §8.7); on one factor of K it is formed here. Fills the report's contact part and
// returns the displacement over the free dofs.
VectorXd solve_with_contact(const Problem& problem, const contact::ContactDiscretization& disc,
                            const RunOptions& options, RunResult& r,
                            std::unique_ptr<CandidateOperators>& operators) {
  const Model& m = r.model;
  if (problem.solver.backend == parallel::Backend::Tfeti) {
    if (!operators) operators = make_candidate_operators(problem, m, options, r.report);
    VectorXd u = solve_with_operator(problem, disc, operators->on_candidates(disc), options, r);
    operators->record(r.report);
    return u;
  }
  phase_start(options, "dual");
  std::unique_ptr<dual::DualOperator> Q;
  {
    ScopedPhase phase(r.report.times, "dual");
    dual::DualInput input{m.factor, disc.B, m.f, disc.dofs, interrupt_poll(options), &disc.offset};
    input.R = &m.floating.R;
    Q = dual::make_dual_operator(problem.solver.dual_operator, input);
  }
  return solve_with_operator(problem, disc, *Q, options, r);
}

// With contact: on every patch, or on those of the contact search. The operators (made at the
// first call, kept in `operators`) serve the solves of the geometric updates too: the free
// displacement does not depend on the contact rows, and under Total FETI no subdomain is
// factored again.
VectorXd solve_contact_problem(const Problem& problem, const contact::ContactDiscretization& disc,
                               const RunOptions& options, RunResult& r,
                               std::unique_ptr<CandidateOperators>& operators) {
  if (!search_applies(problem, r.model))
    return solve_with_contact(problem, disc, options, r, operators);
  if (!operators) operators = make_candidate_operators(problem, r.model, options, r.report);
  return solve_with_search(problem, disc, options, r, *operators);
}

// The geometric updates of the pairs against curved rigid obstacles (theory.md §2.11): at most
// the largest contact.geometry_updates, and their smallest tolerance; none without such a pair.
struct GeometryUpdates {
  int max = -1;
  Real tolerance = 1.0;
};

GeometryUpdates geometry_updates(const Problem& problem,
                                 const contact::ContactDiscretization& disc) {
  GeometryUpdates g;
  for (std::size_t i = 0; i < disc.pairs.size(); ++i) {
    const contact::PairInfo& pair = disc.pairs[i];
    if (!pair.obstacle || pair.obstacle->flat()) continue;
    g.max = std::max(g.max, problem.contact[i].geometry_updates);
    g.tolerance = std::min(g.tolerance, problem.contact[i].geometry_tolerance);
  }
  return g;
}

// Per surface node: whether a patch of it is not separated.
std::vector<bool> nodes_in_contact(const contact::ContactDiscretization& disc,
                                   const ContactFields& fields) {
  std::vector<bool> in(static_cast<size_t>(disc.surface.n_nodes()), false);
  for (Index p = 0; p < disc.n_patches(); ++p) {
    if (fields.state[static_cast<size_t>(p)] == PatchState::Separated) continue;
    for (Index face : disc.patches.faces[static_cast<size_t>(p)])
      for (Index v = 0; v < disc.surface.face_nodes.rows(); ++v)
        in[static_cast<size_t>(disc.surface.face_nodes(v, face))] = true;
  }
  return in;
}

}  // namespace

bool measure_linearization(const Problem& problem, const contact::ContactDiscretization& disc,
                           const VectorXd& u, int updates_done, RunResult& r) {
  const GeometryUpdates updates = geometry_updates(problem, disc);
  if (updates.max < 0 || !r.report.contact || !r.contact) return true;
  ContactReport& c = *r.report.contact;
  const fe::NodalField deformation = r.model.dofs.to_nodal(u) + r.model.prescribed;
  const contact::LinearizationError e = contact::linearization_error(
      r.model.mesh, disc, deformation, nodes_in_contact(disc, *r.contact));
  c.geometry_updates = updates_done;
  c.geometry_change = e.change;
  c.geometry_scale = e.scale;
  c.geometry_tolerance = updates.tolerance;
  return e.change <= updates.tolerance * e.scale;
}

VectorXd update_geometry(
    const Problem& problem, const contact::ContactDiscretization& first, VectorXd u,
    const RunOptions& options, RunResult& r,
    const std::function<VectorXd(const contact::ContactDiscretization&)>& solve_again,
    const std::vector<Vec3>* obstacles) {
  const GeometryUpdates updates = geometry_updates(problem, first);
  if (updates.max < 0 || !r.report.contact || !r.contact) return u;
  std::optional<contact::ContactDiscretization> relinearized;
  long products = 0, qp_iterations = 0, solves = 0;
  qp::MpgpSteps steps;
  for (int done = 0;; ++done) {
    const contact::ContactDiscretization& disc = relinearized ? *relinearized : first;
    const bool close = measure_linearization(problem, disc, u, done, r);
    ContactReport& c = *r.report.contact;
    c.n_mult += products;
    c.qp_iterations += qp_iterations;
    c.qp_steps += steps;
    c.n_kinv += solves;
    if (close || done == updates.max || r.report.status != RunStatus::Converged ||
        options.stop_was_requested())
      return u;
    products = c.n_mult;
    qp_iterations = c.qp_iterations;
    steps = c.qp_steps;
    solves = c.n_kinv;
    {
      phase_start(options, "contact");
      ScopedPhase phase(r.report.times, "contact");
      const fe::NodalField deformation = r.model.dofs.to_nodal(u) + r.model.prescribed;
      relinearized =
          discretize_contact(problem, r.model.mesh, r.model.dofs, &deformation, obstacles);
    }
    u = solve_again(*relinearized);
  }
}

namespace {

// Without contact: one solve with the factor of K.
VectorXd solve_elastic(RunResult& r) {
  ScopedPhase phase(r.report.times, "solve");
  const Model& m = r.model;
  VectorXd u = m.factor.solve(m.f);
  r.report.linear_residual = elastic_residual(m, u);
  return u;
}

// Stresses (unless not wanted), and the global equilibrium of applied loads, contact forces and
// reactions.
void postprocess(const Problem& problem, const VectorXd& u, RunResult& r, bool with_stresses) {
  RunReport& rep = r.report;
  const Model& m = r.model;
  ScopedPhase phase(rep.times, "postprocess");
  r.displacement = m.dofs.to_nodal(u) + m.prescribed;
  rep.max_displacement = r.displacement.colwise().norm().maxCoeff();
  if (with_stresses) compute_stresses(r);
  const fe::NodalField applied = applied_forces(problem, m.mesh);
  const fe::NodalField reactions = reaction_forces(m, problem, r.displacement);
  rep.applied_force = applied.rowwise().sum();
  rep.reaction_force = reactions.rowwise().sum();
  // Relative to the nodal forces' magnitudes, which cannot cancel as the resultants do (two
  // reactions of a bar pulled at both ends; the contact forces of two bodies on each other).
  if (!rep.contact) rep.contact_force_magnitude = 0.0;
  rep.force_scale =
      force_magnitude_sum(applied) + rep.contact_force_magnitude + force_magnitude_sum(reactions);
  rep.bodies = describe_bodies(m, u, rep.contact ? rep.contact->undetermined_motions : MatrixXd());
  const Real residual = (rep.applied_force + rep.contact_force + rep.reaction_force).norm();
  rep.equilibrium_residual = rep.force_scale > 0.0 ? residual / rep.force_scale : residual;
}

}  // namespace

std::optional<contact::ContactDiscretization> build_factored_model(const Problem& problem,
                                                                   const RunOptions& options,
                                                                   RunResult& r) {
  RunReport& rep = r.report;
  // Total FETI factors the subdomains instead (driver/tfeti_solve.hpp): no K of the whole.
  const bool tfeti = problem.solver.backend == parallel::Backend::Tfeti;
  r.model = tfeti ? assemble_loads(problem, rep.times, options.on_phase_start)
                  : assemble_model(problem, rep.times, options.on_phase_start);
  std::optional<contact::ContactDiscretization> disc;
  if (problem.contact.empty()) {
    (void)check_model(problem, r.model);
  } else {
    phase_start(options, "contact");
    ScopedPhase phase(rep.times, "contact");
    disc = check_model(problem, r.model);
  }
  report_sizes(r.model, rep);
  if (tfeti) return disc;
  const dual::FactorizationRequest request =
      disc ? dual::factorization_request(problem.solver.dual_operator, disc->dofs)
           : dual::FactorizationRequest{};
  factorize_model(r.model, request, rep.times, options.on_phase_start, &problem);
  rep.factor = r.model.factor.info();
  return disc;
}

void report_sizes(const Model& model, RunReport& report) {
  report.n_nodes = model.mesh.n_nodes();
  report.n_tets = model.mesh.n_tets();
  report.nodes_per_tet = model.mesh.nodes_per_tet();
  report.n_primal = model.dofs.n_free();
}

Real elastic_residual(const Model& model, const VectorXd& u) {
  return (stiffness_times(model, u) - model.f).norm() / std::max(model.f.norm(), 1e-300);
}

void compute_stresses(RunResult& r) {
  fe::StressField s = fe::compute_stresses(r.model.mesh, r.model.materials, r.displacement);
  r.stress = std::move(s.stress);
  r.von_mises = std::move(s.von_mises);
  r.nodal_stress = std::move(s.nodal_stress);
  r.nodal_von_mises = std::move(s.nodal_von_mises);
}

void finish_run(const Problem& problem, const VectorXd& u, RunResult& r, bool with_stresses) {
  postprocess(problem, u, r, with_stresses);
  r.report.warnings = result_warnings(r.report);
}

std::vector<std::string> result_warnings(const RunReport& report) {
  std::vector<std::string> w;
  if (!report.contact) return w;
  const ContactReport& c = *report.contact;
  if (report.feti && !report.feti->free_displacement_note.empty())
    w.push_back(fmt::format(
        "the contact search's free displacement under Total FETI (the gluing alone) did not "
        "converge: {}; it only chooses the first candidates; the search's rounds check every "
        "patch left out with the displacement of their own solves (theory.md §8.7)",
        report.feti->free_displacement_note));
  if (!c.partition_note.empty())
    w.push_back(fmt::format(
        "the contact partition failed condition (5.1) and was coarsened: {}; the patches are "
        "coarser than asked for (theory.md §2.3)",
        c.partition_note));
  const bool off =
      c.geometry_updates >= 0 && c.geometry_change > c.geometry_tolerance * c.geometry_scale;
  if (off && report.parallel)
    w.push_back(fmt::format(
        "the linearized gap against the curved obstacle is off the true gap at the deformed "
        "position by {:.3e} m, more than contact.geometry_tolerance = {:g} of the normal "
        "displacement {:.3e} m: backend \"petsc\" keeps the linearization it starts from (no "
        "geometric updates; backend \"cholmod\" makes them, theory.md §2.11)",
        c.geometry_change, c.geometry_tolerance, c.geometry_scale));
  else if (off && !report.steps.empty())
    w.push_back(fmt::format(
        "along the loading path the linearized gap against the curved obstacle is off the true "
        "gap at the deformed position by up to {:.3e} m, more than contact.geometry_tolerance = "
        "{:g} of the normal displacement {:.3e} m, after {} geometric update(s) of that step: "
        "raise contact.geometry_updates, or take smaller steps (the error grows as s^2/(2R) "
        "with a step's slide s on a radius R, theory.md §2.11)",
        c.geometry_change, c.geometry_tolerance, c.geometry_scale, c.geometry_updates));
  else if (off)
    w.push_back(fmt::format(
        "the linearized gap against the curved obstacle is off the true gap at the deformed "
        "position by {:.3e} m, more than contact.geometry_tolerance = {:g} of the normal "
        "displacement {:.3e} m, after {} geometric update(s) (contact.geometry_updates): raise "
        "geometry_updates (theory.md §2.11)",
        c.geometry_change, c.geometry_tolerance, c.geometry_scale, c.geometry_updates));
  for (const PairReport& p : c.pairs) {
    if (!p.small_sliding)
      w.push_back(fmt::format(
          "{}: the largest relative slip {:.3e} m{} exceeds {} of the master's element size "
          "{:.3e} m: the pairing, computed once in the reference configuration (small sliding), "
          "may no longer hold",
          p.info.key, p.max_slip,
          p.max_slip_step > 0 ? fmt::format(" (at step {})", p.max_slip_step) : std::string(),
          kSmallSlidingShare, p.info.master_element_size));
    if (!p.master_kept_out)
      w.push_back(fmt::format(
          "{}: the master '{}' penetrates the contact surface '{}' by {:.3e} m, {:.2g} of the "
          "surfaces' normal displacement {:.3e} m (more than {}): the slave's patches keep the "
          "master out only in the mean, and a master finer than the slave, or a master edge or "
          "corner pressing into it (a punch's rim), sinks its nodes in; if the master is the "
          "finer surface, make it the slave (contact.boundary) (theory.md §2.8)",
          p.info.key, p.info.master, p.info.boundary, p.master_penetration,
          p.master_penetration / p.normal_displacement, p.normal_displacement,
          kMasterPenetrationShare));
  }
  return w;
}

RunResult run(const Problem& problem, const RunOptions& options) {
  if (problem.loading.steps > 1) return run_path(problem, options);
  const Stopwatch total;
  validate(problem);
  if (problem.solver.backend == parallel::Backend::Petsc)
    throw InputError(fmt::format(
        "{}: solver.backend: driver::run runs on one process (\"cholmod\" or \"tfeti\"); "
        "fricon::solve (fricon/solve.hpp) runs backend \"{}\"",
        problem.where("solver.backend"), enum_name(problem.solver.backend)));
  const linalg::KeepThreads blas_threads;  // Total FETI runs the BLAS on one thread
  RunResult r;
  RunReport& rep = r.report;

  // @sect: the elastic model, with contact its discretization, and the factor of K.
  const std::optional<contact::ContactDiscretization> disc =
      build_factored_model(problem, options, r);
  if (options.stop_was_requested()) throw Interrupted("interrupted before the solve");

  // @sect: the displacement: one solve, or the outer loop of dual QPs.
  const bool tfeti = problem.solver.backend == parallel::Backend::Tfeti;
  std::unique_ptr<CandidateOperators> operators;  // kept for every solve (solve_contact_problem)
  VectorXd u = disc    ? solve_contact_problem(problem, *disc, options, r, operators)
               : tfeti ? solve_elastic_tfeti(problem, options, r)
                       : solve_elastic(r);
  if (disc)
    u = update_geometry(problem, *disc, std::move(u), options, r,
                        [&](const contact::ContactDiscretization& relinearized) {
                          return solve_contact_problem(problem, relinearized, options, r,
                                                       operators);
                        });

  // @sect: fields and the self-check of the result, without the operators (Total FETI's
  // subdomain factors), which the fields do not need: the peak memory is the larger of the two.
  operators.reset();
  finish_run(problem, u, r, options.fields);
  record_run_peak_memory(options, rep);
  rep.time_s = total.seconds();
  return r;
}

}  // namespace fricon::driver
