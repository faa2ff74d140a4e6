#include "fricon/driver/contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"

namespace fricon::driver {

namespace {
// "auto" forms a dense Q by the forward sweep over the reach of the contact surface (measured the
// fastest on the paper's brick, docs/benchmarks.md) while Q (n_dual^2 doubles) takes no more
// memory than the factor of K already does, or at most this many multipliers (288 MB) on small
// meshes; beyond, Q stays implicit.
constexpr Index kDenseDualLimit = 6000;
}  // namespace

std::string dual_operator_for(const Problem& problem, const linalg::CholeskyFactor& factor,
                              Index n_dual) {
  const std::string& requested = problem.solver.dual_operator;
  if (requested != "auto") {
    if (requested == "schur" && factor.trailing_order().empty())
      throw Error("dual_operator = schur needs K factored with the contact dofs last");
    return requested;
  }
  const double q_entries = static_cast<double>(n_dual) * static_cast<double>(n_dual);
  const double limit = std::max(factor.info().nnz_L, static_cast<double>(kDenseDualLimit) *
                                                         static_cast<double>(kDenseDualLimit));
  return q_entries <= limit ? "forward" : "implicit";
}

std::vector<Index> contact_dofs(const Problem& problem, const Model& m) {
  return m.dofs.free_dofs(
      contact::make_contact_surface(m.mesh, m.dofs, problem.contact->boundary, problem.source)
          .nodes);
}

bool wants_schur(const Problem& problem) {
  return problem.contact && problem.solver.dual_operator == "schur";
}

std::unique_ptr<contact::FrictionLaw> make_friction_law(const FrictionOptions& o) {
  if (o.law == "paper") return contact::paper_law(o.param);
  if (o.law == "constant") return contact::constant_law(o.value);
  if (o.law == "table") return contact::table_law(o.t, o.f);
  throw InputError(fmt::format("contact.friction.law: unknown law '{}'", o.law));
}

namespace {

// Columns per block solve when forming Q densely by solves with K.
constexpr Index kDenseBlock = 64;
// Power iteration for ||Q||: the reference reproduction used 200 iterations (method.md §6.4).
constexpr int kPowerIterations = 200;
constexpr Real kPowerTolerance = 1e-10;

bool stop_requested(const RunOptions& o) {
  return o.stop_requested && o.stop_requested->load();
}

// The dual data of method.md §2.6: Q = B K^-1 B^T (as a product), h = B K^-1 f, u0 = K^-1 f.
// Modes:
//   implicit  each product with Q is one solve with the factor of K (the paper's way);
//   dense     Q formed once by block solves with n_dual right-hand sides;
//   schur     K factored with the contact dofs last, so its trailing block L22 factors the Schur
//             complement S onto them: Q = Y^T Y with Y = L22^-1 Bc^T, and the displacement of the
//             contact dofs is w_c = u0_c - L22^-T Y lambda. The outer loop then never touches
//             the volume; w is recovered once at the end.
struct Dual {
  qp::Operator Q;
  VectorXd h, u0;
  std::shared_ptr<const MatrixXd> Q_dense;  // null in implicit mode; shared with Q's closure
  std::string mode;
  // schur mode:
  MatrixXd L22, Y;
  VectorXd u0_c;
  // schur and forward modes: the contact dofs (in schur mode L22's rows, in pivot order), the
  // only dofs where w is recovered inside the outer loop.
  std::vector<Index> order;
  linalg::CholeskyFactor::Reach reach;  // forward mode: the part of the factor they reach
  bool surface_only() const { return mode == "schur" || mode == "forward"; }
};

Dual make_dual(const Model& m, const SparseMatrix& B, const std::vector<Index>& surface_dof_list,
               const std::string& mode, long& n_kinv, const RunOptions& options) {
  Dual d;
  d.u0 = m.factor.solve(m.f);
  ++n_kinv;
  d.h = B * d.u0;
  d.mode = mode;
  const Index nd = B.rows();
  if (mode == "schur") {
    d.order = m.factor.trailing_order();
    d.L22 = m.factor.trailing_factor();
    const Index nc = static_cast<Index>(d.order.size());
    std::vector<Index> position(static_cast<size_t>(B.cols()), -1);
    for (Index k = 0; k < nc; ++k)
      position[static_cast<size_t>(d.order[static_cast<size_t>(k)])] = k;
    MatrixXd BcT = MatrixXd::Zero(nc, nd);  // Bc^T with rows in pivot order
    for (Index col = 0; col < B.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(B, col); it; ++it) {
        FRICON_CHECK(position[static_cast<size_t>(col)] >= 0,
                     "B touches dof " << col << " outside the contact dofs");
        BcT(position[static_cast<size_t>(col)], it.row()) = it.value();
      }
    d.Y = std::move(BcT);
    linalg::solve_lower(d.L22, d.Y);
    auto Q = std::make_shared<MatrixXd>(MatrixXd::Zero(nd, nd));
    linalg::add_gram_lower(d.Y, *Q);
    *Q = Q->selfadjointView<Eigen::Lower>();
    d.Q_dense = Q;
    d.u0_c.resize(nc);
    for (Index k = 0; k < nc; ++k)
      d.u0_c(k) = d.u0(d.order[static_cast<size_t>(k)]);
  } else if (mode == "forward") {
    // Q = Y^T Y with Y = L^-1 P B^T, on the part of the factor the contact dofs reach, and the
    // outer loop on that part only.
    const SparseMatrix Bt = B.transpose();
    d.Q_dense = std::make_shared<const MatrixXd>(m.factor.inverse_gram(Bt, [&options] {
      if (stop_requested(options)) throw Interrupted("interrupted while forming Q");
    }));
    n_kinv += nd;
    d.order = surface_dof_list;
    d.reach = m.factor.reach(d.order);
  } else if (mode == "dense") {
    const SparseMatrix Bt = B.transpose();
    auto Q = std::make_shared<MatrixXd>(nd, nd);
    for (Index j = 0; j < nd; j += kDenseBlock) {
      const Index nb = std::min(kDenseBlock, nd - j);
      if (stop_requested(options)) throw Interrupted("interrupted while forming Q");
      const MatrixXd X = m.factor.solve(MatrixXd(Bt.middleCols(j, nb)));
      Q->middleCols(j, nb) = B * X;
      n_kinv += nb;
    }
    *Q = 0.5 * (*Q + Q->transpose()).eval();
    d.Q_dense = Q;
  } else {
    // Each product is a solve with K; a stop request ends the power iteration for ||Q|| too.
    d.Q = [&m, &B, &n_kinv, &options](const VectorXd& x, VectorXd& y) {
      if (stop_requested(options)) throw Interrupted("interrupted while applying Q");
      y = B * m.factor.solve(VectorXd(B.transpose() * x));
      ++n_kinv;
    };
  }
  if (d.Q_dense) {
    std::shared_ptr<const MatrixXd> Q = d.Q_dense;
    d.Q = [Q](const VectorXd& x, VectorXd& y) { linalg::symmetric_product(*Q, x, y); };
  }
  return d;
}

// w = K^-1 (f - B^T lambda): in schur and forward modes only on the contact dofs (the rest of w
// is left as it is), otherwise everywhere by one solve.
void recover(const Model& m, const SparseMatrix& B, const Dual& d, const VectorXd& lambda,
             VectorXd& w, long& n_kinv) {
  if (d.mode == "schur") {
    const VectorXd wc =
        d.u0_c - d.L22.transpose().triangularView<Eigen::Upper>().solve(d.Y * lambda);
    if (w.size() != m.dofs.n_free()) w = VectorXd::Zero(m.dofs.n_free());
    for (size_t k = 0; k < d.order.size(); ++k)
      w(d.order[k]) = wc(static_cast<Index>(k));
  } else if (d.mode == "forward") {
    VectorXd x = B.transpose() * lambda;
    m.factor.solve_on_reach(d.reach, x);
    ++n_kinv;
    if (w.size() != m.dofs.n_free()) w = VectorXd::Zero(m.dofs.n_free());
    for (Index dof : d.order)
      w(dof) = d.u0(dof) - x(dof);
  } else {
    w = m.factor.solve(VectorXd(m.f - B.transpose() * lambda));
    ++n_kinv;
  }
}

// Geometric mean of err(k)/err(k-1) over the last (up to three) iterations after the first:
// the observed contraction factor of the successive approximations (0 if not measurable).
Real contraction_ratio(const std::vector<Real>& err) {
  const size_t n = err.size();
  if (n < 3) return 0.0;
  const size_t first = n >= 5 ? n - 4 : 1;  // the ratios of the last (up to) three steps
  if (!(err[first] > 0.0) || !(err.back() > 0.0)) return 0.0;
  return std::pow(err.back() / err[first], 1.0 / static_cast<Real>(n - 1 - first));
}

// Anderson mixing (type II) for the fixed point phi = Psi(phi): from the last iterates x_i and
// their images g_i = Psi(x_i), the next iterate is g_k - sum_i gamma_i (g_i+1 - g_i), with gamma
// minimising the norm of the mixed residual f_k - sum_i gamma_i (f_i+1 - f_i), f = g - x. Slips
// are clipped at 0. With depth 0 or a single pair it is the plain iteration.
class AndersonMixing {
 public:
  explicit AndersonMixing(int depth) : depth_(static_cast<size_t>(depth)) {}
  VectorXd next(const VectorXd& x, const VectorXd& g) {
    const VectorXd f = g - x;
    if (!x_.empty() && x_.back().size() == x.size()) {
      dF_.push_back(f - f_last_);
      dG_.push_back(g - g_last_);
      if (dF_.size() > depth_) {
        dF_.erase(dF_.begin());
        dG_.erase(dG_.begin());
      }
    }
    x_.assign(1, x);
    f_last_ = f;
    g_last_ = g;
    if (dF_.empty()) return g;
    MatrixXd F(f.size(), static_cast<Index>(dF_.size())), G(g.size(), F.cols());
    for (size_t i = 0; i < dF_.size(); ++i) {
      F.col(static_cast<Index>(i)) = dF_[i];
      G.col(static_cast<Index>(i)) = dG_[i];
    }
    const VectorXd gamma = F.colPivHouseholderQr().solve(f);
    return (g - G * gamma).cwiseMax(0.0);
  }

 private:
  size_t depth_;
  std::vector<VectorXd> x_, dF_, dG_;
  VectorXd f_last_, g_last_;
};

// Iterations without a new smallest err(k) after which the outer loop is declared stalled.
constexpr size_t kStallWindow = 4;

// Whether the last kStallWindow values of err(k) are all at or above the smallest before them.
bool stalled(const std::vector<Real>& err) {
  if (err.size() <= kStallWindow + 1) return false;
  const auto split = err.end() - static_cast<std::ptrdiff_t>(kStallWindow);
  return *std::min_element(split, err.end()) >= *std::min_element(err.begin(), split);
}

std::string history_text(const std::vector<Real>& err) {
  std::string s;
  for (Real e : err)
    s += fmt::format(" {:.3e}", e);
  return s;
}

// phi = ||w_t|| per surface node, and the components of w there.
void surface_components(const Model& m, const contact::ContactSurface& s, const VectorXd& w,
                        ContactFields& f) {
  const Index n = s.n_nodes();
  f.wn.resize(n);
  f.wt1.resize(n);
  f.wt2.resize(n);
  for (Index k = 0; k < n; ++k) {
    Vec3 u = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index dof = m.dofs.dof(s.nodes[static_cast<size_t>(k)], c);
      if (dof >= 0) u(c) = w(dof);
    }
    f.wn(k) = u.dot(s.n);
    f.wt1(k) = u.dot(s.t1);
    f.wt2(k) = u.dot(s.t2);
  }
}

VectorXd tangential_slip(const ContactFields& f) {
  return (f.wt1.array().square() + f.wt2.array().square()).sqrt().matrix();
}

}  // namespace

ContactOutcome solve_contact(const Problem& problem, const Model& m, PhaseTimes& times,
                             const RunOptions& options) {
  const ContactOptions& opt = *problem.contact;
  const SolverOptions& so = problem.solver;
  ContactOutcome out;
  ContactReport& rep = out.report;
  ContactFields& fields = out.fields;
  const auto law = make_friction_law(opt.friction);
  rep.boundary = opt.boundary;
  rep.friction_law = law->describe();

  // @sect: contact discretization: surface, patches T_H, B and the stability check (5.1).
  SparseMatrix B;
  {
    ScopedPhase phase(times, "contact");
    fields.surface = contact::make_contact_surface(m.mesh, m.dofs, opt.boundary, problem.source);
    if (opt.patches != "chessboard")
      throw InputError(
          fmt::format("{}: contact.patches: unknown partition '{}'", problem.source, opt.patches));
    fields.patches = contact::chessboard_patches(m.mesh, fields.surface, problem.source);
    B = contact::assemble_b(m.mesh, m.dofs, fields.surface, fields.patches);
    rep.stability_ratio = contact::check_stability(B, problem.source);
    fields.slip_bound = VectorXd::Constant(fields.surface.n_nodes(), opt.slip_bound);
  }
  rep.n_patches = fields.patches.size();
  rep.n_dual = B.rows();
  rep.n_surface_nodes = fields.surface.n_nodes();
  rep.n_contact_nodes = fields.surface.n_contact_nodes();

  // @sect: the dual QP data, fixed for the whole outer loop.
  Dual dual;
  if (options.on_phase_start) options.on_phase_start("dual");
  {
    ScopedPhase phase(times, "dual");
    dual = make_dual(m, B, m.dofs.free_dofs(fields.surface.nodes),
                     dual_operator_for(problem, m.factor, B.rows()), rep.n_kinv, options);
    rep.dual_operator = dual.mode;
    rep.norm_Q = qp::estimate_norm(dual.Q, rep.n_dual, kPowerIterations, kPowerTolerance);
  }

  qp::SeparableConstraints constraints = qp::SeparableConstraints::contact_layout(rep.n_patches);
  qp::MpgpOptions qopt;
  qopt.rel_tolerance = so.qp_rtol;
  qopt.max_iterations = so.qp_max;
  qopt.norm_A = rep.norm_Q;
  qopt.variant = parse_enum<qp::MpgpVariant>(so.qp_variant);
  qopt.monitor = [&options](const qp::MpgpIteration& it) {
    if (stop_requested(options)) return false;
    return options.on_qp_iteration ? options.on_qp_iteration(it) : true;
  };

  // @sect: successive approximations (method.md §3).
  VectorXd phi = VectorXd::Zero(fields.surface.n_nodes());
  AndersonMixing anderson(so.anderson_depth);
  VectorXd lambda = VectorXd::Zero(rep.n_dual);
  VectorXd w;
  qp::MpgpReport last_qp;
  for (int k = 1; k <= so.outer_max; ++k) {
    Stopwatch watch;
    OuterIteration it;
    it.k = k;
    fields.radius =
        contact::patch_radii(m.mesh, fields.surface, fields.patches, *law, phi, fields.slip_bound);
    constraints.set_disc_radii(fields.radius);
    if (k == 1 && options.keep_first_dual) {
      DualSnapshot snap;
      if (dual.Q_dense) {
        snap.Q = *dual.Q_dense;
      } else {
        snap.Q.resize(rep.n_dual, rep.n_dual);
        VectorXd e = VectorXd::Zero(rep.n_dual), y;
        for (Index j = 0; j < rep.n_dual; ++j) {
          e(j) = 1.0;
          dual.Q(e, y);
          snap.Q.col(j) = y;
          e(j) = 0.0;
        }
      }
      snap.h = dual.h;
      snap.radius = fields.radius;
      snap.patch_area = fields.patches.area;
      snap.source = problem.source;
      out.first_dual = std::move(snap);
    }
    if (!so.warm_start) lambda.setZero();
    {
      ScopedPhase phase(times, "qp");
      last_qp = qp::solve_mpgp(dual.Q, dual.h, constraints, qopt, lambda);
    }
    rep.n_mult += last_qp.n_products;
    rep.qp_iterations += last_qp.iterations;
    it.qp_iterations = last_qp.iterations;
    it.qp_products = last_qp.n_products;
    it.qp_rel_gp = last_qp.rel_gp;
    it.qp_termination = std::string(enum_name(last_qp.termination));
    {
      ScopedPhase phase(times, "recovery");
      recover(m, B, dual, lambda, w, rep.n_kinv);
    }
    fields.phi = phi;
    surface_components(m, fields.surface, w, fields);
    const VectorXd phi_new = tangential_slip(fields);
    const Real norm_new = phi_new.norm();
    it.err = norm_new > 0 ? (phi_new - phi).norm() / norm_new : 0.0;
    it.seconds = watch.seconds();
    rep.history.push_back(it);
    rep.err_history.push_back(it.err);
    rep.outer_iterations = k;
    if (options.on_outer_iteration) options.on_outer_iteration(it);
    if (stop_requested(options)) {
      out.message = fmt::format("interrupted during outer iteration {}", k);
      break;
    }
    if (last_qp.termination != qp::Termination::Converged) {
      out.message =
          fmt::format("the dual QP of outer iteration {} did not converge: {}", k, last_qp.message);
      break;
    }
    phi = so.acceleration == "anderson" ? anderson.next(phi, phi_new) : phi_new;
    if (it.err <= so.outer_tol) {
      out.converged = true;
      break;
    }
    // The map Psi contracts when F's Lipschitz constant is small (method.md §1); then err(k)
    // falls at every step. If it has not gone below its best value for kStallWindow iterations
    // (growth, or a cycle between two states), the iteration does not contract: stop and say so.
    rep.contraction_ratio = contraction_ratio(rep.err_history);
    if (stalled(rep.err_history)) {
      out.message = fmt::format(
          "the successive approximations do not contract: err(k) has not gone below its best "
          "value {:.3g} for {} iterations (observed ratio err(k)/err(k-1) = {:.3g}); the "
          "friction law's Lipschitz constant {:.3g} 1/m may be too large for this problem, or "
          "qp_rtol too loose for outer_tol; err(k):{}",
          *std::min_element(rep.err_history.begin(), rep.err_history.end()), kStallWindow,
          rep.contraction_ratio, law->lipschitz(), history_text(rep.err_history));
      break;
    }
  }
  rep.contraction_ratio = contraction_ratio(rep.err_history);
  if (!out.converged && out.message.empty())
    out.message = fmt::format(
        "the successive approximations did not reach err <= {:.1e} in {} iterations (observed "
        "contraction ratio {:.3g}); err(k):{}",
        so.outer_tol, so.outer_max, rep.contraction_ratio, history_text(rep.err_history));
  rep.fixed_point_residual = rep.err_history.empty() ? 0.0 : rep.err_history.back();

  // @sect: the displacement of the whole body, once, and the certificate of the last iterate.
  if (dual.surface_only()) {
    ScopedPhase phase(times, "recovery");
    const VectorXd w_c = w;
    w = m.factor.solve(VectorXd(m.f - B.transpose() * lambda));
    ++rep.n_kinv;
    FRICON_CHECK(
        (w - w_c).cwiseProduct(w_c.cwiseAbs().cwiseSign()).norm() <= 1e-8 * w.norm() + 1e-300,
        "the recovery of the contact displacement on the surface disagrees with the full solve");
  }
  {
    ScopedPhase phase(times, "postprocess");
    // The gradient through K^-1 itself, independent of a dense Q: w = K^-1 (f - B^T lambda) is
    // the full solve above, so Q lambda = B K^-1 B^T lambda = B (u0 - w).
    const VectorXd g = B * (dual.u0 - w) - dual.h;
    const qp::KktScales scales = qp::default_kkt_scales(lambda, dual.h, constraints);
    rep.kkt = qp::kkt_residuals(lambda, g, constraints, scales.x, scales.g);

    const VectorXd wn_pos = fields.wn.cwiseMax(0.0);
    rep.wn_pos_l2 = contact::surface_l2_norm(m.mesh, fields.surface, wn_pos);
    rep.wn_pos_inf = wn_pos.maxCoeff();
    rep.max_neg_wn = (-fields.wn).maxCoeff();
    const VectorXd slip = tangential_slip(fields);
    rep.max_wt = slip.maxCoeff();
    fields.F.resize(slip.size());
    for (Index a = 0; a < slip.size(); ++a)
      fields.F(a) = (*law)(slip(a));
    for (Index p = 0; p < rep.n_patches; ++p) {
      rep.max_lambda_n = std::max(rep.max_lambda_n, lambda(3 * p));
      rep.max_lambda_t = std::max(rep.max_lambda_t, lambda.segment<2>(3 * p + 1).norm());
      rep.total_normal_force += lambda(3 * p) * fields.patches.area(p);
    }
    const fe::NodalField contact_nodal = m.dofs.to_nodal(VectorXd(-(B.transpose() * lambda)));
    out.contact_force = contact_nodal.rowwise().sum();
    out.linear_residual =
        (m.K * w - m.f + B.transpose() * lambda).norm() / std::max(m.f.norm(), 1e-300);
  }
  fields.lambda = lambda;
  out.w = w;
  return out;
}

}  // namespace fricon::driver
