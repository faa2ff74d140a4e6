// driver: the quasi-static loading path (theory.md §2.9). The model, the contact discretization,
// the factor of K and the dual operator Q are built once; each step then changes only the load
// (f, the prescribed displacements, hence h), the offset of the tangential rows (the last step's
// tangential displacement, so that friction acts on the slip increment), the slips the
// coefficient is evaluated at (the accumulated slip) and the warm start.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/driver/run_steps.hpp"
#include "fricon/driver/tfeti_solve.hpp"
#include "fricon/feti/feti_operator.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::driver {

namespace {

// Outer iterations a step typically takes, for the dual operator's choice of how to recover the
// slips (two at least: one that moves, one that confirms; 4.7 on the brick path of
// docs/benchmarks.md).
constexpr long kOuterIterationsPerStep = 4;

// What one step leaves for the next (theory.md §2.9).
struct PathState {
  SlipHistory history;
  VectorXd lambda;       // the next step's first multipliers, extrapolated [Pa]
  VectorXd last_lambda;  // multipliers of the last step [Pa]
  VectorXd tangential;   // per multiplier row: the last step's int_R u_t dS [m^3] (normal rows 0)
  VectorXd predicted;    // the accumulated slip plus the last step's increment [m]
  // The last step's displacement over the free dofs, prescribed values and obstacle positions
  // (a geometric update forms `tangential` again in its new frames).
  VectorXd last_w;
  fe::NodalField last_prescribed;
  std::vector<Vec3> last_obstacles;
  Real norm_Q = 0.0, norm_Q_scaled = 0.0;
  Real lambda_scale = 0.0;  // the largest ||lambda|| of the steps so far [Pa] (PathStep)
  // Per pair: the largest relative slip of the steps so far [m], and its step.
  std::vector<Real> worst_slip;
  std::vector<int> worst_slip_step;
};

// The load of the path as a sum (the loads are linear in their values): f = f_rest + sum_i
// a_i f_i for the factors a_i of the loads with a path, and u0 = K^-1 f likewise, so that a
// step costs no solve for u0 (one per load with a path, and one for the rest, once).
struct LoadBasis {
  std::vector<VectorXd> f, u0;  // [0]: the loads without a path; [1 + i]: load i alone
};

// The prescribed displacements of a part of the loads: each component takes the value of the
// entry that sets it in the whole problem (`owner`, make_prescribed), so that where entries
// overlap (and agree at every step, check_steps) the parts sum to the step's values instead of
// counting the value once per entry.
fe::NodalField owned_prescribed(const Problem& part, const std::vector<int>& owner, Index n_nodes) {
  fe::NodalField u = fe::NodalField::Zero(3, n_nodes);
  for (Index a = 0; a < n_nodes; ++a)
    for (int c = 0; c < 3; ++c) {
      const int e = owner[static_cast<std::size_t>(3 * a + c)];
      if (e >= 0) u(c, a) = part.dirichlet[static_cast<std::size_t>(e)].value(c);
    }
  return u;
}

// How a path's u0 = K^-1 f is solved: with the factor of K; under Total FETI with the contact
// search by the gluing alone (its free displacement, theory.md §8.7, on the path's operator with
// its contact rows removed); or not at all (Total FETI without the search: the operator computes
// its own from the nodal loads).
enum class FreeBy { Factor, Gluing, Nothing };

struct FreeSolver {
  FreeBy by = FreeBy::Factor;
  feti::FetiOperator* feti = nullptr;  ///< FreeBy::Gluing: the path's operator
  const RunOptions* options = nullptr;
  RunReport* report = nullptr;  ///< FreeBy::Gluing: where a solve that did not converge says so
};

// The free displacement of load `part` (its f, and the model's prescribed values of it).
VectorXd free_displacement(const Problem& part, const Model& m, const VectorXd& f,
                           const FreeSolver& solver) {
  switch (solver.by) {
    case FreeBy::Factor:
      return m.factor.solve(f);
    case FreeBy::Nothing:
      return {};
    case FreeBy::Gluing:
      break;
  }
  const fe::NodalField applied = applied_forces(part, m.mesh);
  solver.feti->set_load(f, VectorXd(), nullptr, dual::NodalLoad{&applied, &m.prescribed});
  return gluing_free_displacement(*solver.feti, part, *solver.options, *solver.report);
}

LoadBasis load_basis(const Problem& problem, Model& m, const FreeSolver& solver) {
  const std::size_t n = path_loads(problem).size();
  std::vector<int> owner;
  (void)make_prescribed(problem, m.mesh, &owner);
  if (solver.by == FreeBy::Gluing)
    solver.feti->set_contact_rows(SparseMatrix(0, m.dofs.n_free()), VectorXd());
  LoadBasis basis;
  for (std::size_t i = 0; i <= n; ++i) {
    std::vector<Real> alone(n, 0.0);
    if (i > 0) alone[i - 1] = 1.0;
    const Problem part = scaled_loads(problem, alone, i == 0 ? 1.0 : 0.0);
    m.prescribed = owned_prescribed(part, owner, m.mesh.n_nodes());
    basis.f.push_back(load_vector(part, m, Extent::Whole));
    basis.u0.push_back(free_displacement(part, m, basis.f.back(), solver));
  }
  return basis;
}

// The translation of each pair's rigid obstacle at step k (zero against a body) [m].
std::vector<Vec3> obstacle_displacements(const Problem& problem, int k) {
  std::vector<Vec3> d;
  for (const ContactOptions& c : problem.contact)
    d.push_back(c.obstacle && is_rigid(*c.obstacle)
                    ? obstacle_displacement(*c.obstacle, k, problem.loading.steps)
                    : Vec3(Vec3::Zero()));
  return d;
}

// The loads of step k (factors `a`): the prescribed displacements, f and u0, into the model and
// `u0`; the contact discretization moved to them, its tangential rows offset by the last step's
// displacement.
void apply_step_loads(const Problem& step_problem, int k, const std::vector<Real>& a,
                      const LoadBasis& basis, const PathState& state, Model& m, VectorXd& u0,
                      contact::ContactDiscretization* disc) {
  m.prescribed = make_prescribed(step_problem, m.mesh);
  m.f = basis.f[0];
  u0 = basis.u0[0];
  for (std::size_t i = 0; i < a.size(); ++i) {
    m.f += a[i] * basis.f[i + 1];
    if (u0.size() > 0) u0 += a[i] * basis.u0[i + 1];
  }
  if (!disc) return;
  const std::vector<Vec3> obstacles = obstacle_displacements(step_problem, k);
  contact::set_prescribed(*disc, m.prescribed, &obstacles);
  disc->offset += state.tangential;
}

// int_R (u - u_o) . d dS per multiplier row of the whole displacement (free dofs w and the
// prescribed values) relative to the obstacle's; its tangential rows offset the next step.
VectorXd patch_tangential(const contact::ContactDiscretization& disc, const Model& m,
                          const VectorXd& w) {
  VectorXd d = contact::patch_integrals(disc, w, m.prescribed);
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
  s.factors = step_factors(loads, k);
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
  // The next step's first slips: the same increment again (s + (s - s_before)).
  state.predicted =
      state.history.empty() ? f.slip : VectorXd(2.0 * f.slip - state.history.accumulated);
  state.history.wt1 = f.wt1;
  state.history.wt2 = f.wt2;
  state.history.accumulated = f.slip;
  // The next step's first multipliers: the same change again, the pressures kept non-negative
  // (the QP projects its start onto its constraints; a Coulomb state takes the pressures as they
  // are).
  state.lambda =
      state.last_lambda.size() > 0 ? VectorXd(2.0 * f.lambda - state.last_lambda) : f.lambda;
  for (Index p = 0; p < disc.n_patches(); ++p)
    state.lambda(3 * p) = std::max(state.lambda(3 * p), 0.0);
  state.last_lambda = f.lambda;
  state.lambda_scale = std::max(state.lambda_scale, f.lambda.norm());
  state.tangential = patch_tangential(disc, r.model, w);
  state.last_w = w;
  state.last_prescribed = r.model.prescribed;
  state.last_obstacles.clear();
  for (const contact::PairInfo& pair : disc.pairs)
    state.last_obstacles.push_back(pair.obstacle_displacement);
  const ContactReport& c = *r.report.contact;
  state.norm_Q = c.norm_Q;
  state.norm_Q_scaled = c.norm_Q_scaled;
}

// Small sliding along the path (theory.md §2.8): the reference pairing must hold at every step,
// so each pair reports the largest relative slip of the steps done (k the last), and its step.
void keep_worst_sliding(int k, PathState& state, ContactReport& c) {
  state.worst_slip.resize(c.pairs.size(), 0.0);
  state.worst_slip_step.resize(c.pairs.size(), 0);
  for (std::size_t i = 0; i < c.pairs.size(); ++i) {
    PairReport& pair = c.pairs[i];
    if (state.worst_slip_step[i] == 0 || pair.max_slip > state.worst_slip[i]) {
      state.worst_slip[i] = pair.max_slip;
      state.worst_slip_step[i] = k;
    }
    pair.max_slip = state.worst_slip[i];
    pair.max_slip_step = state.worst_slip_step[i];
    pair.small_sliding = within_small_sliding(pair.info, pair.max_slip);
  }
}

// The path's dual operator for the discretization `disc` (phase "dual"): on the factor of K,
// or, with backend "tfeti", Total FETI's on its subdomains (`feti` then points to it), factored
// once for the path: a geometric update replaces its contact rows (renew_path_operator).
std::unique_ptr<dual::DualOperator> make_path_operator(const Problem& problem,
                                                       const contact::ContactDiscretization& disc,
                                                       int steps_left, const RunOptions& options,
                                                       RunResult& r, feti::FetiOperator*& feti) {
  if (problem.solver.backend == parallel::Backend::Tfeti) {
    phase_start(options, "factorize");
    std::unique_ptr<feti::FetiOperator> F =
        make_feti_operator(problem, r.model, &disc, options, r.report);
    feti = F.get();
    return F;
  }
  phase_start(options, "dual");
  ScopedPhase phase(r.report.times, "dual");
  dual::DualInput input{r.model.factor,          disc.B,      r.model.f, disc.dofs,
                        interrupt_poll(options), &disc.offset};
  input.expected_recoveries = kOuterIterationsPerStep * steps_left;
  input.R = &r.model.floating.R;
  return dual::make_dual_operator(problem.solver.dual_operator, input);
}

// The path's operator after a geometric update made `disc`: under Total FETI the same one with
// `disc`'s contact rows (no subdomain is factored again, theory.md §8.7), else a new one.
void renew_path_operator(const Problem& problem, const contact::ContactDiscretization& disc,
                         int steps_left, const RunOptions& options, RunResult& r,
                         std::unique_ptr<dual::DualOperator>& Q, feti::FetiOperator*& feti) {
  if (feti) {
    phase_start(options, "dual");
    ScopedPhase phase(r.report.times, "dual");
    feti->set_contact_rows(disc.B, disc.offset);
    return;
  }
  Q = make_path_operator(problem, disc, steps_left, options, r, feti);
}

// The step's load into Q with the contact rows' `offset`: f and u0 over the free dofs and, for an
// operator on the subdomains (`nodal`), the applied forces and prescribed displacements at the
// nodes.
void set_step_load(const Problem& step_problem, const Model& m, const VectorXd& offset,
                   const VectorXd& u0, bool nodal, dual::DualOperator& Q) {
  const fe::NodalField applied = nodal ? applied_forces(step_problem, m.mesh) : fe::NodalField();
  Q.set_load(m.f, offset, &u0,
             nodal ? dual::NodalLoad{&applied, &m.prescribed} : dual::NodalLoad{});
}

// The step's contact solve on the path's operator, then its fields and self-check.
VectorXd solve_step(const Problem& step_problem, const contact::ContactDiscretization& disc,
                    dual::DualOperator& Q, const VectorXd& u0, const PathState& state, bool nodal,
                    const RunOptions& options, RunResult& r) {
  Model& m = r.model;
  set_step_load(step_problem, m, disc.offset, u0, nodal, Q);
  const PathStep step{&state.history,
                      state.lambda.size() > 0 ? &state.lambda : nullptr,
                      state.predicted.size() > 0 ? &state.predicted : nullptr,
                      state.norm_Q,
                      state.norm_Q_scaled,
                      state.lambda_scale};
  phase_start(options, "outer loop");
  return adopt(solve_contact(step_problem, m, disc, Q, r.report.times, options, nullptr, &step), r);
}

// A geometric update of the step (theory.md §2.11): `relinearized` (made at the step's loads)
// becomes the path's discretization, with the last step's tangential displacement relative to
// the obstacles in its new frames as the tangential offset.
void relinearize_step(const contact::ContactDiscretization& relinearized, PathState& state,
                      const Model& m, contact::ContactDiscretization& disc) {
  // The step's state (multipliers, candidates) is per patch: the partition must not change.
  FRICON_CHECK(relinearized.n_patches() == disc.n_patches(),
               "relinearize_step: " << relinearized.n_patches() << " patches instead of "
                                    << disc.n_patches());
  disc = relinearized;
  if (state.last_w.size() > 0) {
    state.tangential =
        contact::patch_integrals(disc, state.last_w, state.last_prescribed, state.last_obstacles);
    for (Index p = 0; p < disc.n_patches(); ++p)
      state.tangential(3 * p) = 0.0;
  } else {
    state.tangential = VectorXd::Zero(disc.n_dual());
  }
  contact::set_prescribed(disc, m.prescribed);
  disc.offset += state.tangential;
}

// The contact search along a path (theory.md §2.9): the candidates, carried from step to step
// and only grown, the part of the discretization on them and its dual operator, rebuilt when
// they grow (under Total FETI the path's one operator, `feti`, whose contact rows are replaced,
// theory.md §8.7); ||Q|| and ||D Q D|| of that operator once estimated (0: not yet).
struct PathSearch {
  std::vector<Index> candidates;
  std::unique_ptr<contact::ContactDiscretization> part;
  std::unique_ptr<dual::DualOperator> Q;
  feti::FetiOperator* feti = nullptr;
  Real norm_Q = 0.0, norm_Q_scaled = 0.0;

  // The operator on the part (after prepare_part).
  dual::DualOperator& op() const { return feti ? *feti : *Q; }
  // Drops the part and its operator (the candidates grew, or the discretization changed).
  void drop_part() {
    Q.reset();
    part.reset();
    norm_Q = norm_Q_scaled = 0.0;
  }
};

// Adds `more` (increasing) to the candidates; a set that grows drops its operator.
void grow_candidates(const std::vector<Index>& more, PathSearch& search) {
  std::vector<Index> added;
  std::set_difference(more.begin(), more.end(), search.candidates.begin(), search.candidates.end(),
                      std::back_inserter(added));
  if (added.empty()) return;
  search.candidates = contact::merge_patches(search.candidates, added);
  search.drop_part();
}

// The part on the candidates at this step's loads: built with its operator when the set grew,
// else only its surface (the step's prescribed displacements) and offset (the step's loads and
// the last step's tangential displacement) taken again from the whole; Q keeps its B.
void prepare_part(const Problem& problem, const contact::ContactDiscretization& disc,
                  const Model& m, const RunOptions& options, int steps_left, PathSearch& search) {
  contact::ContactDiscretization fresh = contact::restrict_to_patches(disc, search.candidates);
  if (search.part) {
    search.part->surface = std::move(fresh.surface);
    search.part->offset = std::move(fresh.offset);
    return;
  }
  search.part = std::make_unique<contact::ContactDiscretization>(std::move(fresh));
  const contact::ContactDiscretization& part = *search.part;
  if (search.feti) {
    search.feti->set_contact_rows(part.B, part.offset);
    return;
  }
  dual::DualInput input{m.factor, part.B, m.f, part.dofs, interrupt_poll(options), &part.offset};
  input.expected_recoveries = kOuterIterationsPerStep * steps_left;
  input.R = &m.floating.R;
  search.Q = dual::make_dual_operator(problem.solver.dual_operator, input);
}

// The multipliers of every patch (3 per patch) on the candidates only.
VectorXd restrict_multipliers(const VectorXd& lambda, const std::vector<Index>& candidates) {
  VectorXd out(3 * static_cast<Index>(candidates.size()));
  for (std::size_t i = 0; i < candidates.size(); ++i)
    out.segment<3>(3 * static_cast<Index>(i)) = lambda.segment<3>(3 * candidates[i]);
  return out;
}

// The step's contact solve with the contact search (theory.md §2.7, §2.9): the candidates of
// the last steps and those the step's free displacement u0 penetrates, then, as a static run,
// one more solve of the step with every left-out patch that penetrates added, until none does
// (after kMaxSearchRounds growths, every patch). The counts are those of every round.
VectorXd solve_step_with_search(const Problem& step_problem,
                                const contact::ContactDiscretization& disc, const VectorXd& u0,
                                const PathState& state, int steps_left, PathSearch& search,
                                const RunOptions& options, RunResult& r) {
  Model& m = r.model;
  const VectorXd free_penetration = contact::mean_penetration(disc, u0);
  grow_candidates(
      contact::initial_candidates(free_penetration, step_problem.solver.contact_search_margin),
      search);
  const Real tolerance =
      step_problem.solver.qp.rel_tolerance * free_penetration.cwiseAbs().maxCoeff();
  SearchRounds rounds;
  for (int round = 1;; ++round) {
    {
      phase_start(options, "dual");
      ScopedPhase phase(r.report.times, "dual");
      prepare_part(step_problem, disc, m, options, steps_left, search);
    }
    set_step_load(step_problem, m, search.part->offset, u0, search.feti != nullptr, search.op());
    const VectorXd lambda = state.lambda.size() > 0
                                ? restrict_multipliers(state.lambda, search.candidates)
                                : VectorXd();
    const PathStep step{&state.history,
                        lambda.size() > 0 ? &lambda : nullptr,
                        state.predicted.size() > 0 ? &state.predicted : nullptr,
                        search.norm_Q,
                        search.norm_Q_scaled,
                        state.lambda_scale};
    const PatchSelection selection{disc, search.candidates, round};
    phase_start(options, "outer loop");
    ContactOutcome c = solve_contact(step_problem, m, *search.part, search.op(), r.report.times,
                                     options, &selection, &step);
    search.norm_Q = c.report.norm_Q;
    search.norm_Q_scaled = c.report.norm_Q_scaled;
    const std::vector<Index> added =
        rounds.patches_to_add(disc, search.candidates, c, tolerance, round, options);
    if (added.empty()) return rounds.adopt_answer(std::move(c), r);
    grow_candidates(added, search);
  }
}

// Without contact a step's displacement is u0.
VectorXd solve_elastic_step(const VectorXd& u0, RunResult& r) {
  r.report.linear_residual = elastic_residual(r.model, u0);
  return u0;
}

// The step whose linearized gap was farthest from the true one, relative to its normal
// displacement: the path's report gives that step's figures.
struct WorstLinearization {
  Real ratio = 0.0, change = 0.0, scale = 0.0;
  int updates = 0;

  // Takes a converged step's figures if they are the worst so far; the report then shows the
  // worst of the path.
  void keep(ContactReport& c) {
    if (c.geometry_updates < 0) return;
    const Real step_ratio = c.geometry_scale > 0.0 ? c.geometry_change / c.geometry_scale : 0.0;
    if (step_ratio >= ratio)
      *this = {step_ratio, c.geometry_change, c.geometry_scale, c.geometry_updates};
    c.geometry_change = change;
    c.geometry_scale = scale;
    c.geometry_updates = updates;
  }
};

void refuse_petsc(const Problem& problem) {
  if (problem.solver.backend == parallel::Backend::Petsc)
    throw InputError(fmt::format(
        "{}: solver.backend: a loading path ([loading] steps = {}) does not run with backend "
        "\"petsc\"; use \"cholmod\" or \"tfeti\"",
        problem.where("solver.backend"), problem.loading.steps));
}

// One loading path (theory.md §2.9) as named steps: the model, the contact discretization, the
// factor of K and Q once for the whole path (constructor; with the contact search Q is that of
// the candidates, formed again when they grow), then each step from the state the last one
// left: its loads, its solve, its geometric updates against curved obstacles, its report. A
// failed step ends the path.
class PathRun {
 public:
  PathRun(const Problem& problem, const RunOptions& options)
      : problem_(problem),
        options_(options),
        tfeti_(problem.solver.backend == parallel::Backend::Tfeti),
        loads_(path_loads(problem)) {
    disc_ = build_factored_model(problem_, options_, r_);
    if (options_.stop_was_requested()) throw Interrupted("interrupted before the first step");
    // A floating body has no free displacement to start each step's search from (theory.md
    // §2.10).
    search_ = disc_ && search_applies(problem_, r_.model) && r_.model.floating.empty();
    // Under Total FETI one operator for the whole path, whose contact rows the search replaces.
    if (disc_ && (!search_ || tfeti_))
      Q_ = make_path_operator(problem_, *disc_, problem_.loading.steps, options_, r_, feti_);
    if (search_) path_search_.feti = feti_;
    {
      ScopedPhase phase(r_.report.times, "solve");
      // Under Total FETI the search's free displacements are the gluing's (one solve per load).
      basis_ = load_basis(problem_, r_.model, free_solver());
    }
    if (disc_) state_.tangential = VectorXd::Zero(disc_->n_dual());
  }

  RunResult run() {
    for (int k = 1; k <= problem_.loading.steps; ++k)
      if (run_step(k)) break;
    if (feti_) record_feti_counts(*feti_, r_.report);
    if (options_.fields && r_.stress.cols() != r_.model.mesh.n_tets())
      compute_stresses(r_);  // a failed step's
    return std::move(r_);
  }

 private:
  // Step k; true when the path ends there (the step failed or a stop was requested).
  bool run_step(int k) {
    const Stopwatch step_clock;
    const std::vector<Real> factors = step_factors(loads_, k);
    const Problem step_problem = scaled_loads(problem_, factors, 1.0);  // at_step(problem, k)
    {
      ScopedPhase phase(r_.report.times, "assembly");
      apply_step_loads(step_problem, k, factors, basis_, state_, r_.model, u0_,
                       disc_ ? &*disc_ : nullptr);
    }
    const int steps_left = problem_.loading.steps - k + 1;
    VectorXd u = solve(step_problem, steps_left);
    if (disc_) u = update_geometry_of_step(step_problem, k, steps_left, std::move(u));
    return end_step(k, step_problem, u, step_clock.seconds());
  }

  // How the load basis's free displacements are solved (FreeBy): only the search needs them
  // under Total FETI.
  FreeSolver free_solver() {
    if (!tfeti_) return {FreeBy::Factor};
    if (!search_) return {FreeBy::Nothing};
    return {FreeBy::Gluing, feti_, &options_, &r_.report};
  }

  // The step's solve: elastic (on subdomains with backend "tfeti"), with the contact search, or
  // with the path's Q.
  VectorXd solve(const Problem& step_problem, int steps_left) {
    if (!disc_)
      return tfeti_ ? solve_elastic_tfeti(step_problem, options_, r_) : solve_elastic_step(u0_, r_);
    if (search_)
      return solve_step_with_search(step_problem, *disc_, u0_, state_, steps_left, path_search_,
                                    options_, r_);
    return solve_step(step_problem, *disc_, *Q_, u0_, state_, tfeti_, options_, r_);
  }

  // The step's geometric updates against curved obstacles (theory.md §2.11): each new
  // linearization renews Q (its contact rows) and solves the step again; the last stays for the
  // next steps.
  VectorXd update_geometry_of_step(const Problem& step_problem, int k, int steps_left, VectorXd u) {
    const std::vector<Vec3> obstacles = obstacle_displacements(step_problem, k);
    return update_geometry(
        step_problem, *disc_, std::move(u), options_, r_,
        [&](const contact::ContactDiscretization& relinearized) {
          relinearize_step(relinearized, state_, r_.model, *disc_);
          if (search_) {
            path_search_.drop_part();
          } else {
            renew_path_operator(problem_, *disc_, steps_left, options_, r_, Q_, feti_);
          }
          return solve(step_problem, steps_left);
        },
        &obstacles);
  }

  // The step's report and the state for the next step; true when the path ends here.
  bool end_step(int k, const Problem& step_problem, const VectorXd& u, Real seconds) {
    RunReport& rep = r_.report;
    if (rep.contact) keep_worst_sliding(k, state_, *rep.contact);
    if (disc_ && rep.contact && rep.status == RunStatus::Converged) worst_.keep(*rep.contact);
    // The stresses of a step only for whom watches the steps, and for the result.
    const bool last = k == problem_.loading.steps;
    finish_run(step_problem, u, r_, (options_.on_step || last) && options_.fields);
    const bool failed = rep.status != RunStatus::Converged;
    if (failed)
      rep.message = fmt::format("step {} of {} of the loading path failed: {}", k,
                                problem_.loading.steps, rep.message);
    rep.steps.push_back(describe_step(k, loads_, r_, seconds));
    if (options_.on_step) options_.on_step(r_);
    if (failed) return true;
    // A stop requested during a converged step (or by on_step itself) keeps that step and ends
    // the path there: the result holds the steps that on_step saw, and is not complete.
    if (!last && options_.stop_was_requested()) {
      rep.status = RunStatus::NotConverged;
      rep.message = fmt::format("interrupted after step {} of {} of the loading path", k,
                                problem_.loading.steps);
      return true;
    }
    if (disc_) remember_step(*disc_, r_, u, state_);
    return false;
  }

  const Problem& problem_;
  const RunOptions& options_;
  const bool tfeti_;
  const linalg::KeepThreads blas_threads_;  // Total FETI runs the BLAS on one thread
  const std::vector<PathLoad> loads_;
  RunResult r_;
  std::optional<contact::ContactDiscretization> disc_;
  bool search_ = false;
  std::unique_ptr<dual::DualOperator> Q_;
  feti::FetiOperator* feti_ = nullptr;  // Q_, with backend "tfeti"
  PathSearch path_search_;
  LoadBasis basis_;
  PathState state_;
  VectorXd u0_;
  WorstLinearization worst_;
};

}  // namespace

RunResult run_path(const Problem& problem, const RunOptions& options) {
  const Stopwatch total;
  validate(problem);
  refuse_petsc(problem);
  RunResult r = PathRun(problem, options).run();
  record_run_peak_memory(options, r.report);
  r.report.time_s = total.seconds();
  return r;
}

}  // namespace fricon::driver
