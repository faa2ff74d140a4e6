#include "fricon/driver/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include <fmt/format.h>

#include "fricon/contact/candidates.hpp"
#include "fricon/contact/dual_scaling.hpp"
#include "fricon/contact/master_penetration.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/floating_bodies.hpp"
#include "fricon/driver/tresca_map.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/qp/friction_cone.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

namespace {

// The recovery on the contact dofs must agree with the full solve to this relative accuracy.
constexpr Real kRecoveryTolerance = 1e-8;
// A patch slips when ||lambda_t|| is this close to its radius (relative); it is separated when
// lambda_n is at most separation_threshold (tresca_map.hpp).
constexpr Real kSlipTolerance = 1e-6;

Index state_size(const TrescaMap& map) {
  Index n = 0;
  for (const auto& block : map.layout())
    n += block.size;
  return n;
}

// The friction of the pairs, for reports: each pair's model and law, and the whole's (theory.md
// §5.7): one model and one law when the pairs share them, else each pair's.
struct PairsFriction {
  std::vector<contact::FrictionModel> model;
  std::vector<std::string> law;
  std::vector<std::string> radius_integration;
};

PairsFriction describe_pairs(const Problem& problem) {
  PairsFriction f;
  for (const ContactOptions& c : problem.contact) {
    const auto law = contact::make_friction_law(c.friction);
    f.model.push_back(c.model);
    f.law.push_back(law->describe());
    f.radius_integration.push_back(contact::radius_integration(*law));
  }
  return f;
}

// One text when every pair has it, else each pair's prefixed by its key.
std::string shared_or_each(const Problem& problem, const std::vector<std::string>& texts) {
  if (std::all_of(texts.begin(), texts.end(), [&](const auto& t) { return t == texts.front(); }))
    return texts.front();
  std::string out;
  for (std::size_t i = 0; i < texts.size(); ++i)
    out += fmt::format("{}{}: {}", i == 0 ? "" : "; ", problem.contact_key(i), texts[i]);
  return out;
}

ContactReport describe(const Problem& problem, const contact::ContactDiscretization& disc,
                       const dual::DualOperator& Q) {
  ContactReport rep;
  const PairsFriction f = describe_pairs(problem);
  const bool any_coulomb =
      std::find(f.model.begin(), f.model.end(), contact::FrictionModel::Coulomb) != f.model.end();
  rep.mixed_models = any_coulomb && std::find(f.model.begin(), f.model.end(),
                                              contact::FrictionModel::Tresca) != f.model.end();
  rep.model = any_coulomb ? contact::FrictionModel::Coulomb : contact::FrictionModel::Tresca;
  rep.boundary = disc.surface.tag;
  rep.friction_law = shared_or_each(problem, f.law);
  rep.dual_operator = Q.kind();
  rep.n_patches = disc.n_patches();
  rep.n_dual = disc.n_dual();
  rep.n_surface_nodes = disc.surface.n_nodes();
  rep.n_contact_nodes = disc.surface.n_contact_nodes();
  rep.stability_ratio = disc.stability.ratio;
  rep.stability_estimated = disc.stability.estimated;
  rep.n_inactive_multipliers = disc.stability.n_inactive;
  rep.radius_integration = shared_or_each(problem, f.radius_integration);
  rep.partition_note = disc.partition_note;
  rep.kkt_bound = kCertificateFactor * problem.solver.qp.rel_tolerance;
  rep.equality_bound = rep.kkt_bound;
  rep.coulomb_bound = problem.solver.certificate_tol;
  return rep;
}

// ||D Q D|| by power iteration (D = I for ||Q||); a stop request ends it (there is no iterate
// to return yet).
Real estimate_norm_Q(const dual::DualOperator& Q, const qp::BlockScaling& D,
                     const RunOptions& options) {
  const qp::Operator product = Q.as_qp_operator();
  const qp::Operator scaled = D.scaled(product);
  const qp::Operator apply = [&scaled, &options](const VectorXd& x, VectorXd& y) {
    if (options.stop_was_requested()) throw Interrupted("interrupted while estimating ||Q||");
    scaled(x, y);
  };
  return qp::estimate_norm(
      apply, Q.size(), qp::kNormPowerIterations,
      Q.n_equality() > 0 ? dual::kEqualityPowerTolerance : qp::kNormPowerTolerance);
}

// The change of variables of the dual QP (theory.md §4.5): per patch the factor of
// contact::patch_scale_factors, on its bound and its disc alike.
qp::BlockScaling dual_scaling(const Problem& problem, const Model& m,
                              const contact::ContactDiscretization& disc,
                              const qp::SeparableConstraints& layout) {
  if (problem.solver.dual_scaling == contact::DualScaling::None)
    return qp::BlockScaling::identity(disc.n_dual());
  const VectorXd d = contact::patch_scale_factors(m.mesh, disc.surface, disc.patches, m.materials);
  VectorXd per_block(2 * d.size());
  for (Index p = 0; p < d.size(); ++p)
    per_block(2 * p) = per_block(2 * p + 1) = d(p);
  return qp::BlockScaling::per_block(layout, per_block);
}

qp::BlockScaling with_equality_multipliers(const qp::BlockScaling& contact,
                                           const dual::DualOperator& Q) {
  if (Q.n_equality() == 0) return contact;
  VectorXd d = VectorXd::Ones(Q.size());
  d.head(contact.size()) = contact.d();
  qp::SeparableConstraints layout;
  layout.append_free(Q.size());
  return qp::BlockScaling::per_block(layout, d);
}

// The QP's options; with equality multipliers, dual::solve_shared_smalse adds the preconditioner.
qp::MpgpOptions qp_options(const SolverOptions& so, Real norm_Q, const RunOptions& options) {
  qp::MpgpOptions o = so.mpgp();
  o.norm_A = norm_Q;
  o.monitor = [&options](const qp::MpgpIteration& it) {
    if (options.stop_was_requested()) return false;
    return options.on_qp_iteration ? options.on_qp_iteration(it) : true;
  };
  return o;
}

// The QP of the first outer iteration (phi = 0), for --dump-dual.
qp::DualProblem first_dual_problem(const Problem& problem,
                                   const contact::ContactDiscretization& disc,
                                   const dual::DualOperator& Q, const TrescaMap& map) {
  if (Q.n_equality() > 0)
    throw InputError(
        "the dual QP of backend \"tfeti\" carries the subdomains' gluing multipliers: dump "
        "the contact QP with solver.backend = \"cholmod\"");
  qp::DualProblem d;
  d.Q = Q.to_dense();
  d.h = Q.h();
  d.radius = map.radii(1, VectorXd::Zero(state_size(map)));
  d.patch_area = disc.patches.area;
  d.source = problem.source;
  return d;
}

// A step of a loading path starts where the last one ended: slips measured from its tangential
// displacement, the accumulated slip as the first phi (the slip increment is zero), and its
// multipliers as the warm start and (Coulomb) the first pressures; the pressures are measured
// against the path's scale, to the accuracy outer_tol times it (theory.md §2.9).
void start_from_last_step(const PathStep& step, const contact::ContactDiscretization& disc,
                          const contact::SlipBounds& bounds, Real outer_tol, TrescaMap& map,
                          VectorXd& state) {
  map.set_history(step.history);
  map.set_pressure_scale(step.lambda_scale, outer_tol * step.lambda_scale);
  if (step.predicted_slip)
    state.head(disc.surface.n_nodes()) = *step.predicted_slip;
  else if (step.history && !step.history->empty())
    state.head(disc.surface.n_nodes()) = step.history->accumulated;
  if (!step.lambda) return;
  map.set_lambda(*step.lambda);
  if (bounds.uses_pressure())
    for (Index p = 0; p < disc.n_patches(); ++p)
      state(disc.surface.n_nodes() + p) = (*step.lambda)(3 * p);
}

// The successive approximations, with the QP counts of every iteration in the report.
// A refinement (refine_coulomb) calls it again: the counts and histories accumulate.
outer::OuterReport successive_approximations(TrescaMap& map, VectorXd& phi,
                                             const outer::OuterOptions& outer_options,
                                             ContactReport& rep, const RunOptions& options) {
  const auto monitor = [&](const outer::OuterIteration& o) {
    const qp::MpgpReport& q = map.last_qp();
    const IterationReport it{.k = o.k,
                             .err = o.err,
                             .qp_iterations = q.iterations,
                             .qp_products = q.n_products,
                             .qp_rel_gp = q.rel_gp,
                             .qp_termination = q.termination,
                             .n_objective_increases = q.n_objective_increases,
                             .seconds = o.seconds};
    rep.n_mult += q.n_products;
    rep.qp_iterations += q.iterations;
    rep.qp_steps += q.steps();
    rep.n_objective_increases += q.n_objective_increases;
    rep.smalse_outer_iterations += map.last_smalse().outer_iterations;
    rep.coarse_solves += map.last_smalse().n_coarse_solves;
    rep.coarse_s += map.last_smalse().coarse_s;
    rep.history.push_back(it);
    if (options.on_outer_iteration) options.on_outer_iteration(it);
  };
  const outer::OuterReport o =
      outer::iterate(map, phi, outer_options, monitor, options.stop_requested);
  rep.termination = o.termination;
  rep.outer_iterations += o.iterations;
  rep.err_history.insert(rep.err_history.end(), o.err_history.begin(), o.err_history.end());
  rep.contraction_ratio = o.contraction_ratio;
  rep.fixed_point_residual = o.fixed_point_residual;
  rep.block_history.insert(rep.block_history.end(), o.block_history.begin(), o.block_history.end());
  rep.state_blocks.clear();
  for (const auto& b : map.layout())
    rep.state_blocks.push_back(b.name);
  return o;
}

// The natural-map residual of the Coulomb problem (qp::coulomb_residual) over the patches of the
// Coulomb pairs (theory.md §5.7): the multipliers lambda [Pa] and the gradient g [m^3] of every
// patch, with the mean coefficient mu_R of each; 0 without Coulomb patches.
Real coulomb_pairs_residual(const contact::SlipBounds& bounds, const VectorXd& lambda,
                            const VectorXd& g, const VectorXd& mu, Real alpha, Real lambda_scale) {
  std::vector<Index> coulomb;
  for (Index p = 0; p < mu.size(); ++p)
    if (bounds.coulomb_patch(p)) coulomb.push_back(p);
  if (static_cast<Index>(coulomb.size()) == mu.size())
    return qp::coulomb_residual(lambda, g, mu, alpha, lambda_scale);
  const auto n = static_cast<Index>(coulomb.size());
  VectorXd l(3 * n), gc(3 * n), m(n);
  for (Index i = 0; i < n; ++i) {
    const Index p = coulomb[static_cast<size_t>(i)];
    l.segment<3>(3 * i) = lambda.segment<3>(3 * p);
    gc.segment<3>(3 * i) = g.segment<3>(3 * p);
    m(i) = mu(p);
  }
  return n == 0 ? 0.0 : qp::coulomb_residual(l, gc, m, alpha, lambda_scale);
}

// That residual on the patches of the QP (those a contact search left out carry no pressure
// and, unpenetrated, no residual), from the current multipliers and slips: g = Q lambda - h, one
// product with Q (with floating bodies the Lagrangian's gradient, - G^T alpha added: theory.md
// §2.10).
Real coulomb_residual_now(const TrescaMap& map, const VectorXd& state, const dual::DualOperator& Q,
                          const contact::SlipBounds& bounds, const ContactReport& rep) {
  VectorXd g;
  Q.apply(map.all_lambda(), g);
  g -= Q.h();
  if (Q.n_motions() > 0) g -= Q.G().transpose() * map.alpha();
  g.conservativeResize(Q.n_contact());
  return coulomb_pairs_residual(bounds, map.lambda(), g, bounds.mean_coefficients(map.slips(state)),
                                1.0 / rep.norm_Q, rep.lambda_scale);
}

// A Coulomb fixed point whose natural-map residual is above solver.certificate_tol takes further
// steps, warm-started, with the QP and outer tolerances a hundredfold tighter each round, as
// `fricon dual solve` refines (theory.md §5.6); the final certificate decides.
outer::OuterReport refine_coulomb(TrescaMap& map, VectorXd& state, const Problem& problem,
                                  const dual::DualOperator& Q, const contact::SlipBounds& bounds,
                                  outer::OuterReport loop, ContactReport& rep,
                                  const RunOptions& options) {
  if (!bounds.uses_pressure()) return loop;
  Real qp_rtol = problem.solver.qp.rel_tolerance;
  outer::OuterOptions outer_options = problem.solver.outer;
  while (loop.converged() && rep.certificate_refinements < kMaxCertificateRefinements &&
         coulomb_residual_now(map, state, Q, bounds, rep) > problem.solver.certificate_tol) {
    qp_rtol *= kCertificateRefinementFactor;
    outer_options.tol *= kCertificateRefinementFactor;
    map.set_qp_tolerance(qp_rtol);
    ++rep.certificate_refinements;
    loop = successive_approximations(map, state, outer_options, rep, options);
  }
  return loop;
}

// The displacement of the whole body from the final multipliers (one solve), checked against
// the recovery on the contact dofs, and the KKT residuals of the final QP with the gradient
// through that solve: Q lambda = B K^-1 B^T lambda = B (u0 - w) (theory.md §5.5).
// The motions N (columns over the free motions) that no contact force resists leave every
// constraint as it is (G_a^T N = 0, theory.md §2.10); the solution is the one with none of them
// in the least-squares sense: w -= R N c, c minimizing ||w - R N c||.
void remove_undetermined_motions(const dual::DualOperator& Q, const SparseMatrix& R,
                                 const MatrixXd& N, VectorXd& w) {
  if (N.cols() == 0 || R.cols() != N.rows()) return;
  const MatrixXd RN = R * N;
  const VectorXd c = (RN.transpose() * RN).ldlt().solve(RN.transpose() * w);
  w -= Q.rigid_displacement(N * c);
}

// The scale of the gradient in the certificate of a QP with equality multipliers (Total FETI,
// theory.md §8.6): the resisted part of its whole scaled data, contact and equality rows, as its
// stopping test had it. The prescribed displacements enter through the Dirichlet rows' data
// there, not through the contact rows' (h_C = B_C K^+ f - c_C), which may be all but zero (a
// body driven by prescribed displacements alone). 0 (the contact rows' own) without them.
Real whole_data_scale(const dual::DualOperator& Q, const TrescaMap& map,
                      const qp::BlockScaling& scaling) {
  if (Q.n_equality() == 0) return 0.0;
  qp::SeparableConstraints layout = qp::SeparableConstraints::contact_layout(Q.n_contact() / 3);
  layout.set_disc_radii(map.radius());
  layout.append_free(Q.n_equality());
  const qp::BlockScaling D = with_equality_multipliers(scaling, Q);
  return qp::resisted_part(D.dual_to_scaled(Q.h()), D.scaled(layout)).norm();
}

VectorXd certify(const contact::ContactDiscretization& disc, const dual::DualOperator& Q,
                 const SparseMatrix& R, const TrescaMap& map, const qp::BlockScaling& scaling,
                 ContactReport& rep, VectorXd& g) {
  VectorXd w = Q.displacement(map.all_lambda());
  if (Q.n_motions() > 0) {
    // The rigid motions that contact fixes (with Total FETI those of every subdomain), and the
    // balance of the floating bodies (of the subdomains).
    w += Q.rigid_displacement(map.alpha());
    rep.equality_residual =
        qp::equality_residual({Q.G(), Q.e()}, map.all_lambda(), map.last_smalse().equality_floor);
    if (Q.n_equality() == 0) {
      rep.rigid_amplitudes = map.alpha();
      rep.undetermined_motions = map.last_smalse().undetermined;
    }
  }
  // Total FETI: the copies of every node agree and the Dirichlet values hold (theory.md §8.6).
  if (Q.n_equality() > 0) rep.gluing_residual = Q.gluing_residual(map.all_lambda(), map.alpha());
  const VectorXd& w_c = map.w();
  const Real tolerance = kRecoveryTolerance * w.lpNorm<Eigen::Infinity>();
  for (Index dof : disc.dofs)
    FRICON_CHECK(std::abs(w(dof) - w_c(dof)) <= tolerance,
                 "the recovery of the contact displacement (dof "
                     << dof << ": " << w_c(dof) << ") disagrees with the full solve (" << w(dof)
                     << ")");
  if (Q.n_motions() > 0) remove_undetermined_motions(Q, R, rep.undetermined_motions, w);
  const VectorXd h = Q.h().head(Q.n_contact());
  g = disc.B * (Q.u0() - w) - h;
  qp::SeparableConstraints contact = qp::SeparableConstraints::contact_layout(disc.n_patches());
  contact.set_disc_radii(map.radius());
  rep.kkt =
      qp::scaled_kkt_residuals(map.lambda(), g, h, contact, scaling, qp::StopReference::Resisted,
                               whole_data_scale(Q, map, scaling));
  return w;
}

// The result on every patch of a contact search (theory.md §2.7): the patches left out with
// zero multipliers and radii, the gradient g = c - B w of the whole QP through the displacement w
// of the whole body, and the certificate over every patch, relative to `data_scale` as certify's
// (whole_data_scale: under Total FETI the data of the equality rows too, theory.md §8.6).
struct WholeResult {
  VectorXd lambda, radius, g;
};

WholeResult cover_left_out(const Problem& problem, const Model& m, const PatchSelection& selection,
                           const dual::DualOperator& Q, const TrescaMap& map, const VectorXd& w,
                           Real data_scale, ContactReport& rep) {
  const contact::ContactDiscretization& whole = selection.whole;
  const Index n = whole.n_patches();
  WholeResult r;
  r.lambda = contact::expand_to_patches(map.lambda(), selection.patches, n, 3);
  r.radius = contact::expand_to_patches(map.radius(), selection.patches, n, 1);
  r.g = whole.offset - whole.B * w;
  const VectorXd h = whole.B * Q.u0() - whole.offset;
  qp::SeparableConstraints c = qp::SeparableConstraints::contact_layout(n);
  c.set_disc_radii(r.radius);
  const qp::BlockScaling D = dual_scaling(problem, m, whole, c);
  rep.kkt =
      qp::scaled_kkt_residuals(r.lambda, r.g, h, c, D, qp::StopReference::Resisted, data_scale);
  rep.n_candidate_patches = rep.n_patches;
  rep.n_patches = n;
  rep.n_dual = whole.n_dual();
  rep.search_rounds = selection.round;
  return r;
}

// The part of sum lambda_n |R| that acts on free components of the contact surface (theory.md
// §6.1): per patch, lambda_n times int_R sum_a psi_a (n_R . n_R restricted to the free
// components of node a) dS, the shape functions integrated by the face element
// (contact/surface_integrals.hpp).
Real transmitted_normal_force(const mesh::TetMesh& mesh, const contact::ContactDiscretization& disc,
                              const VectorXd& lambda) {
  const contact::ContactSurface& s = disc.surface;
  Real force = 0.0;
  for (Index p = 0; p < disc.n_patches(); ++p) {
    const Vec3 n = disc.patch_frames.n.col(p);
    Real free_area = 0.0;  // [m^2]
    for (Index face : disc.patches.faces[static_cast<size_t>(p)]) {
      const VectorXd shape = contact::face_integrals(mesh, s, face).shape;
      for (Index v = 0; v < s.face_nodes.rows(); ++v) {
        const auto& fixed = s.fixed[static_cast<size_t>(s.face_nodes(v, face))];
        for (int c = 0; c < 3; ++c)
          if (!fixed[static_cast<size_t>(c)]) free_area += shape(v) * n(c) * n(c);
      }
    }
    force += lambda(3 * p) * free_area;
  }
  return force;
}

// The paper's measures and the surface fields of the result.
void measure(const Model& m, const contact::ContactDiscretization& disc,
             const contact::SlipBounds& bounds, const VectorXd& lambda, const SlipHistory* history,
             const std::vector<bool>& in_contact, ContactOutcome& out) {
  ContactReport& rep = out.report;
  ContactFields& fields = out.fields;
  const contact::SurfaceDisplacement s = contact::surface_displacement(disc.surface, m.dofs, out.w);
  fields.wn = s.wn;
  fields.wt1 = s.wt1;
  fields.wt2 = s.wt2;
  // Penetration of the obstacle w_n - gap (w_n itself at zero gap, the paper's quantity).
  const VectorXd penetration = s.wn - disc.gap;
  const VectorXd wn_pos = penetration.cwiseMax(0.0);
  rep.wn_pos_l2 = contact::surface_l2_norm(m.mesh, disc.surface, wn_pos);
  rep.wn_pos_inf = wn_pos.maxCoeff();
  rep.max_neg_wn = (-penetration).maxCoeff();
  const VectorXd wt = s.slip();
  rep.max_wt = wt.maxCoeff();
  fields.slip = history ? history->slips(s, in_contact) : wt;
  const VectorXd& slip = fields.slip;
  fields.F = bounds.nodal_coefficients(slip);  // one batch per law: a function law is called once
  for (Index p = 0; p < rep.n_patches; ++p) {
    rep.max_lambda_n = std::max(rep.max_lambda_n, lambda(3 * p));
    rep.max_lambda_t = std::max(rep.max_lambda_t, lambda.segment<2>(3 * p + 1).norm());
    rep.total_normal_force += lambda(3 * p) * disc.patches.area(p);
  }
  rep.transmitted_normal_force = transmitted_normal_force(m.mesh, disc, lambda);
  const VectorXd contact_load = -(disc.B.transpose() * lambda);
  const fe::NodalField contact_nodal = m.dofs.to_nodal(contact_load);
  out.contact_force = contact_nodal.rowwise().sum();
  out.contact_force_magnitude = force_magnitude_sum(contact_nodal);
  // Relative to the larger of the two forces: a step unloaded to nothing has f = 0.
  const Real force_scale = std::max(m.f.norm(), contact_load.norm());
  out.linear_residual = (stiffness_times(m, out.w) - m.f - contact_load).norm() /
                        (force_scale > 0.0 ? force_scale : 1.0);
}

// Per patch: the mean coefficient F_R of the result and whether it sticks, slips or is separated
// (against the radius its last QP had).
void classify_patches(const contact::SlipBounds& bounds, const VectorXd& radius,
                      ContactOutcome& out) {
  ContactFields& f = out.fields;
  ContactReport& rep = out.report;
  f.coefficient = bounds.mean_coefficients(f.slip);
  const Real negligible = separation_threshold(rep.max_lambda_n, rep.pressure_floor);
  f.state.resize(static_cast<size_t>(rep.n_patches));
  for (Index p = 0; p < rep.n_patches; ++p) {
    const Real ln = f.lambda(3 * p), lt = f.lambda.segment<2>(3 * p + 1).norm();
    PatchState state = PatchState::Stick;
    if (ln <= negligible && (lt <= negligible || lt <= kSlipTolerance * radius(p)))
      state = PatchState::Separated;
    else if (radius(p) > 0.0 && lt >= (1.0 - kSlipTolerance) * radius(p))
      state = PatchState::Slip;
    f.state[static_cast<size_t>(p)] = state;
    rep.n_separated += state == PatchState::Separated ? 1 : 0;
    rep.n_stick += state == PatchState::Stick ? 1 : 0;
    rep.n_slip += state == PatchState::Slip ? 1 : 0;
  }
}

// Per pair: its friction, its patches' states and forces, whether the slips kept to small
// sliding, and against a body how far the master penetrates the slave.
void report_pairs(const Problem& problem, const Model& m,
                  const contact::ContactDiscretization& disc, ContactOutcome& out) {
  const ContactFields& f = out.fields;
  std::vector<PairReport>& pairs = out.report.pairs;
  const PairsFriction friction = describe_pairs(problem);
  for (std::size_t i = 0; i < disc.pairs.size(); ++i)
    pairs.push_back(
        {.info = disc.pairs[i], .model = friction.model.at(i), .friction_law = friction.law.at(i)});
  for (Index p = 0; p < disc.n_patches(); ++p) {
    PairReport& r = pairs[static_cast<size_t>(disc.patch_pair[static_cast<size_t>(p)])];
    const Vec3 lambda = f.lambda.segment<3>(3 * p);
    // int_R of the directions of the rows: the force of the multipliers on the body (area times
    // the patch's frame where it has one frame).
    const Mat3& integral = disc.frame_integrals[static_cast<size_t>(p)];
    r.n_patches += 1;
    r.normal_force += disc.patches.area(p) * lambda(0);
    r.force -= integral.transpose() * lambda;
    r.tangential_force -= integral.bottomRows<2>().transpose() * lambda.tail<2>();
    const PatchState state = f.state[static_cast<size_t>(p)];
    r.n_stick += state == PatchState::Stick ? 1 : 0;
    r.n_slip += state == PatchState::Slip ? 1 : 0;
    r.n_separated += state == PatchState::Separated ? 1 : 0;
  }
  // Where the bodies touch: the nodes of the patches not separated (elsewhere the pairing is
  // never used, however far the surfaces move).
  for (Index p = 0; p < disc.n_patches(); ++p) {
    if (f.state[static_cast<size_t>(p)] == PatchState::Separated) continue;
    PairReport& r = pairs[static_cast<size_t>(disc.patch_pair[static_cast<size_t>(p)])];
    for (Index face : disc.patches.faces[static_cast<size_t>(p)])
      for (Index v = 0; v < disc.surface.face_nodes.rows(); ++v) {
        const Index k = disc.surface.face_nodes(v, face);
        r.max_slip = std::max(r.max_slip, std::hypot(f.wt1(k), f.wt2(k)));
      }
  }
  for (PairReport& r : pairs)
    r.small_sliding = within_small_sliding(r.info, r.max_slip);
  const fe::NodalField u = m.dofs.to_nodal(out.w) + m.prescribed;
  for (size_t i = 0; i < pairs.size(); ++i) {
    PairReport& r = pairs[i];
    if (r.info.master.empty()) continue;
    const contact::MasterPenetration p = contact::master_penetration(
        m.mesh, disc.surface, static_cast<Index>(i), r.info.master, r.info.search_distance, u);
    r.master_penetration = p.depth;
    r.normal_displacement = p.normal_displacement;
    r.master_kept_out = p.depth <= kMasterPenetrationShare * p.normal_displacement;
  }
}

// The outcome's status: the loop's termination, unless a converged run fails its certificate
// (the final QP's KKT residuals, and for Coulomb the residual of the Coulomb problem).
void conclude(const outer::OuterReport& loop, ContactOutcome& out) {
  ContactReport& rep = out.report;
  out.converged = loop.converged();
  out.message = loop.message;
  // The first check that fails ends the run's convergence and gives its message.
  const auto check = [&](bool passed, const auto& message) {
    if (!out.converged || passed) return;
    rep.termination = outer::OuterTermination::CertificateFailed;
    out.converged = false;
    out.message = message();
  };
  check(rep.model != contact::FrictionModel::Coulomb || rep.coulomb_residual <= rep.coulomb_bound,
        [&] {
          return fmt::format(
              "the certificate of the Coulomb solution failed: its natural-map residual {:.3e} "
              "exceeds solver.certificate_tol = {:.1e} after {} rounds of further steps at "
              "tighter tolerances",
              rep.coulomb_residual, rep.coulomb_bound, rep.certificate_refinements);
        });
  check(rep.equality_residual <= rep.equality_bound, [&] {
    return fmt::format(
        "the certificate of the final QP failed: the floating bodies' balance G lambda = e has "
        "the relative residual {:.3e}, more than {:.1e}",
        rep.equality_residual, rep.equality_bound);
  });
  check(rep.gluing_residual <= rep.kkt_bound, [&] {
    return fmt::format(
        "the certificate of the final QP failed: the subdomains' copies of the nodes (and the "
        "Dirichlet values) differ by {:.3e} of the displacement (root mean squares), more than "
        "{:.1e}",
        rep.gluing_residual, rep.kkt_bound);
  });
  check(rep.kkt.max() <= rep.kkt_bound, [&] {
    return fmt::format(
        "the certificate of the final QP failed: its largest KKT residual {:.3e} (feasibility "
        "{:.1e}, stationarity {:.1e}, complementarity {:.1e}) exceeds {:g} x qp_rtol = {:.1e}",
        rep.kkt.max(), rep.kkt.feasibility, rep.kkt.stationarity, rep.kkt.complementarity,
        kCertificateFactor, rep.kkt_bound);
  });
}

}  // namespace

bool within_small_sliding(const contact::PairInfo& pair, Real max_slip) {
  return pair.master.empty() || max_slip <= kSmallSlidingShare * pair.master_element_size;
}

std::unique_ptr<contact::SlipBounds> make_slip_bounds(const Problem& problem,
                                                      const mesh::TetMesh& mesh,
                                                      const contact::ContactDiscretization& disc) {
  std::vector<contact::PairFriction> frictions;
  for (const ContactOptions& c : problem.contact)
    frictions.push_back({.model = c.model,
                         .law = contact::make_friction_law(c.friction),
                         .start_slip_bound = c.start_slip_bound});
  return contact::make_pair_bounds(mesh, disc, std::move(frictions));
}

ContactOutcome solve_contact(const Problem& problem, const Model& m,
                             const contact::ContactDiscretization& disc,
                             const dual::DualOperator& Q, PhaseTimes& times,
                             const RunOptions& options, const PatchSelection* selection,
                             const PathStep* step) {
  ContactOutcome out;
  out.report = describe(problem, disc, Q);
  ContactReport& rep = out.report;
  rep.n_candidate_patches = disc.n_patches();

  // @sect: the scaled dual and its norm for the QP's fixed step length (||Q|| itself for the
  // Coulomb residual), then the map Psi on the state.
  const qp::BlockScaling scaling =
      dual_scaling(problem, m, disc, qp::SeparableConstraints::contact_layout(disc.n_patches()));
  // Over every multiplier of Q: the equality multipliers of an operator that has them (Total
  // FETI's, whose rows are scaled already, theory.md §8.5) keep the factor 1.
  const qp::BlockScaling qp_scaling = with_equality_multipliers(scaling, Q);
  if (step && step->norm_Q > 0.0) {
    rep.norm_Q = step->norm_Q;
    rep.norm_Q_scaled = step->norm_Q_scaled;
  } else {
    ScopedPhase phase(times, "dual");
    rep.norm_Q = estimate_norm_Q(Q, qp::BlockScaling::identity(Q.size()), options);
    rep.norm_Q_scaled = problem.solver.dual_scaling == contact::DualScaling::None
                            ? rep.norm_Q
                            : estimate_norm_Q(Q, qp_scaling, options);
  }
  const auto bounds = make_slip_bounds(problem, m.mesh, disc);
  TrescaMap map(m.dofs, disc, Q, *bounds, qp_scaling,
                qp_options(problem.solver, rep.norm_Q_scaled, options), problem.solver.warm_start,
                times);
  if (options.keep_first_dual) out.first_dual = first_dual_problem(problem, disc, Q, map);
  // Every process of a Total FETI run finds the same certificate (the QP's decisions are the
  // same on all): the refusal is an error they agree on, not one process's failure.
  map.set_infeasibility_handler([&](const qp::Infeasibility& certificate) {
    const feti::Ranks& ranks = options.feti_ranks ? *options.feti_ranks : feti::this_process();
    ranks.collectively([&] { refuse_unbalanced_load(problem, m, certificate); });
  });

  // @sect: successive approximations (theory.md §5), from the zero state (phi = 0, and for
  // Coulomb lambda_n = 0: the first step is then the frictionless problem); along a loading path
  // from the state the last step left (theory.md §2.9).
  VectorXd state = VectorXd::Zero(state_size(map));
  if (step) {
    start_from_last_step(*step, disc, *bounds, problem.solver.outer.tol, map, state);
    rep.lambda_scale = step->lambda_scale;
    rep.pressure_floor = step->lambda_scale * problem.solver.outer.tol;
  }
  outer::OuterReport loop =
      successive_approximations(map, state, problem.solver.outer, rep, options);
  loop = refine_coulomb(map, state, problem, Q, *bounds, loop, rep, options);

  // @sect: the displacement of the whole body, once, and the certificate of the last iterate
  // (over every patch, those a contact search left out too).
  VectorXd g;
  {
    ScopedPhase phase(times, "recovery");
    out.w = certify(disc, Q, m.floating.R, map, scaling, rep, g);
  }
  const contact::ContactDiscretization& whole = selection ? selection->whole : disc;
  WholeResult result{map.lambda(), map.radius(), std::move(g)};
  if (selection)
    result = cover_left_out(problem, m, *selection, Q, map, out.w,
                            whole_data_scale(Q, map, scaling), rep);
  {
    ScopedPhase phase(times, "postprocess");
    const auto whole_bounds = selection ? make_slip_bounds(problem, m.mesh, whole) : nullptr;
    const contact::SlipBounds& result_bounds = selection ? *whole_bounds : *bounds;
    out.fields.lambda = result.lambda;
    out.fields.radius = result.radius;
    measure(
        m, whole, result_bounds, result.lambda, step ? step->history : nullptr,
        nodes_in_contact(whole, result.lambda, result_bounds.uses_pressure(), rep.pressure_floor),
        out);
    classify_patches(result_bounds, result.radius, out);
    report_pairs(problem, m, whole, out);
    if (result_bounds.uses_pressure())
      rep.coulomb_residual =
          coulomb_pairs_residual(result_bounds, result.lambda, result.g, out.fields.coefficient,
                                 1.0 / rep.norm_Q, rep.lambda_scale);
  }
  conclude(loop, out);
  rep.n_kinv = Q.n_kinv();
  out.fields.surface = whole.surface;
  out.fields.patches = whole.patches;
  out.fields.patch_frames = whole.patch_frames;
  out.fields.patch_pair = whole.patch_pair;
  out.fields.slip_bound = whole.slip_bound;
  out.fields.gap = whole.gap;
  out.fields.phi = map.slips(state);
  return out;
}

}  // namespace fricon::driver
