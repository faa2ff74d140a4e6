#include "fricon/qp/smalse.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/qp/coarse_space.hpp"

namespace fricon::qp {

namespace {

// The phase-one problem is solved when the residual ||G x - e|| has decreased by less than this
// factor in kStagnantSteps consecutive outer steps (a feasible equality is met at a linear rate).
constexpr double kStagnation = 0.9;
constexpr int kStagnantSteps = 2;
// Phase one: min 1/2 ||G x - e||^2 + delta/2 ||x||^2 over Omega (G with orthonormal rows), delta
// this small against ||G^T G|| = 1 (it only makes the Hessian definite) ...
constexpr double kPhaseOneRegularization = 1e-12;
// ... to this relative gradient; the equality is infeasible when the shortest residual exceeds
// this share of ||e|| (and the asked equality tolerance).
constexpr double kPhaseOneTolerance = 1e-10;
constexpr double kInfeasibleShare = 1e-6;
// b's resisted part is taken for rounding below this share of ||b|| (dimensionless; 64 machine
// epsilons), and x = 0 is then the solution when e = 0.
constexpr double kVanishingData = 64.0 * std::numeric_limits<double>::epsilon();
// A row's load must exceed what Omega gives along it by this share of the load to certify.
constexpr double kRowExcess = 1e-9;

// G with the columns of the discs pinned to zero (radius 0) cleared: those multipliers stay 0.
SparseMatrix active_columns(const SparseMatrix& G, const SeparableConstraints& c) {
  Eigen::VectorXd keep = Eigen::VectorXd::Ones(c.size());
  bool any_pinned = false;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Block& block = c.blocks[k];
    if (block.kind == BlockKind::Disc && c.radius(static_cast<Index>(k)) == 0.0) {
      keep.segment<2>(block.offset).setZero();
      any_pinned = true;
    }
  }
  if (!any_pinned) return G;
  SparseMatrix Ga = G * keep.asDiagonal();
  Ga.prune(0.0);
  return Ga;
}

// Phase one (theory.md §4.6): the point x1 of Omega whose image G x1 is nearest to e in the
// metric of the orthonormal rows (r^T S^+ r); its residual r = e - G x1 certifies infeasibility
// when it is not small: for every x in Omega, d^T G x <= d^T G x1 < d^T e with d = S^+ r. Costs
// products with G and coarse solves only. Returns r (empty if the phase-one solve failed).
Eigen::VectorXd phase_one(const CoarseSpace& rows, const Eigen::VectorXd& e,
                          const SeparableConstraints& c, const MpgpOptions& inner,
                          Eigen::VectorXd& x1) {
  const Operator GtG = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    y = rows.onto_rows(v) + kPhaseOneRegularization * v;
  };
  MpgpOptions o;
  o.space = inner.space;
  o.variant = inner.variant;
  o.rel_tolerance = kPhaseOneTolerance;
  o.reference = StopReference::Whole;
  o.norm_A = 1.0 + kPhaseOneRegularization;
  o.max_iterations = inner.max_iterations;
  const MpgpReport r = solve_mpgp(GtG, rows.transpose_times(rows.solve(e)), c, o, x1);
  if (r.termination != QpTermination::Converged) return {};
  return e - rows.times(x1);
}

// A load along a row direction that acts on no free multiplier (rows.null()): the first such
// direction, signed so that the load along it is positive, as a certificate; none if every such
// load is below `tolerance` ||e||.
std::optional<Infeasibility> unresisted_load(const CoarseSpace& rows, const Eigen::VectorXd& e,
                                             double tolerance) {
  const Eigen::MatrixXd& null = rows.null();
  for (Index j = 0; j < null.cols(); ++j) {
    const double load = null.col(j).dot(e);
    if (std::abs(load) > tolerance * e.norm())
      return Infeasibility{load > 0 ? Eigen::VectorXd(null.col(j)) : Eigen::VectorXd(-null.col(j)),
                           std::abs(load), 0.0};
  }
  return std::nullopt;
}

// The certificate of phase one when its shortest residual exceeds `tolerance` times the length
// of e (both in the metric of the orthonormal rows), as a direction d of the rows of G.
std::optional<Infeasibility> phase_one_certificate(const CoarseSpace& rows,
                                                   const Eigen::VectorXd& e,
                                                   const SeparableConstraints& c,
                                                   const MpgpOptions& inner, Eigen::VectorXd x1,
                                                   double tolerance) {
  const Eigen::VectorXd r = phase_one(rows, e, c, inner, x1);
  if (r.size() == 0) return std::nullopt;
  const Eigen::VectorXd d = rows.solve(r);
  const double length = std::sqrt(std::max(r.dot(d), 0.0));
  if (!(length > tolerance * std::sqrt(std::max(rows.norm2(e), 0.0)))) return std::nullopt;
  // d^T e - d^T G x1 = r^T S^+ r > 0, and d^T G x1 is the most Omega gives along d.
  return Infeasibility{d, d.dot(e), d.dot(rows.times(x1))};
}

// sup { g^T x : x in Omega }: per disc its radius times ||g_i||, per bound 0 when g_i <= 0,
// infinity when g_i > 0 (a bound's multiplier grows without limit), and infinity for a free
// unknown with g_i != 0.
double support(const Eigen::VectorXd& g, const SeparableConstraints& c) {
  double s = 0.0;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Block& block = c.blocks[k];
    if (block.kind == BlockKind::Disc)
      s += c.radius(static_cast<Index>(k)) * g.segment<2>(block.offset).norm();
    else if (block.kind == BlockKind::Bound ? g(block.offset) > 0.0 : g(block.offset) != 0.0)
      return std::numeric_limits<double>::infinity();
  }
  return s;
}

// A certificate along one row of G (one of the motions as they are numbered) rather than the
// phase one's direction, whose metric is that of the orthonormal rows: the row whose load most
// exceeds what Omega gives along it, if one does (then the figures are those of that motion
// alone, e.g. a push against mu N); else `found` as it is. What Omega gives along a row is a sum
// over the unknowns: over the processes of `space` (collective).
Infeasibility along_one_row(const SparseMatrix& Ga, const Eigen::VectorXd& e,
                            const SeparableConstraints& c, Infeasibility found,
                            const DualSpace& space = whole_space()) {
  const SparseMatrix Gt = Ga.transpose();
  Eigen::VectorXd carried_by_row = Eigen::VectorXd::Zero(Ga.rows());
  for (Index j = 0; j < Ga.rows(); ++j)
    if (e(j) != 0.0)
      carried_by_row(j) = support((e(j) > 0.0 ? 1.0 : -1.0) * Eigen::VectorXd(Gt.col(j)), c);
  space.sum(carried_by_row);
  double best = 0.0;
  for (Index j = 0; j < Ga.rows(); ++j) {
    if (e(j) == 0.0) continue;
    const double sign = e(j) > 0.0 ? 1.0 : -1.0;
    const double applied = std::abs(e(j));
    const double carried = carried_by_row(j);
    const double excess = (applied - carried) / applied;
    if (excess > kRowExcess && excess > best) {
      best = excess;
      found = {sign * Eigen::VectorXd::Unit(Ga.rows(), j), applied, carried};
    }
  }
  return found;
}

void accumulate(const MpgpReport& inner, SmalseReport& rep) {
  rep.iterations += inner.iterations;
  rep.steps += inner.steps();
  rep.n_products += inner.n_products;
  rep.n_preconditioner += inner.n_preconditioner;
  rep.last_inner = inner;
}

}  // namespace

std::optional<Infeasibility> balance_certificate(const EqualityConstraint& eq,
                                                 const SeparableConstraints& c, double tolerance) {
  FRICON_CHECK(eq.G.cols() == c.size() && eq.e.size() == eq.G.rows(),
               "balance_certificate: G is " << eq.G.rows() << " x " << eq.G.cols() << " for "
                                            << c.size() << " unknowns");
  const CoarseSpace rows(active_columns(eq.G, c));
  if (auto certificate = unresisted_load(rows, eq.e, tolerance)) return certificate;
  const auto certificate =
      phase_one_certificate(rows, eq.e, c, MpgpOptions{}, Eigen::VectorXd::Zero(c.size()),
                            std::max(kInfeasibleShare, tolerance));
  if (!certificate) return std::nullopt;
  return along_one_row(rows.G(), eq.e, c, *certificate);
}

double equality_residual(const EqualityConstraint& eq, const Eigen::VectorXd& x, double floor,
                         const DualSpace& space) {
  Eigen::VectorXd Gx = eq.G * x;
  // The magnitudes of the terms of G x, which cancel where the equality holds: a load-free
  // equality (e = 0, a body driven by prescribed displacements) is measured against them.
  Eigen::VectorXd magnitudes = eq.G.cwiseAbs() * x.cwiseAbs();
  space.sum(Gx);
  space.sum(magnitudes);
  const double scale = std::max({eq.e.norm(), magnitudes.norm(), floor});
  return scale > 0.0 ? (Gx - eq.e).norm() / scale : 0.0;
}

void SmalseOptions::validate() const {
  require("SmalseOptions::rho_factor", rho_factor, positive());
  require("SmalseOptions::M_factor", M_factor, positive());
  require("SmalseOptions::beta", beta, open_interval(1.0, std::numeric_limits<double>::infinity()));
  require("SmalseOptions::eta_factor", eta_factor, positive());
  require("SmalseOptions::equality_tolerance", equality_tolerance, positive());
  require("SmalseOptions::max_outer", max_outer, integer_at_least(1));
}

namespace {

// One SMALSE-M solve (theory.md §4.6), as named steps: the rows of G over the multipliers free
// to move and their coarse problem S = G G^T (constructor); the check that every load along them
// is resisted; the penalty and the augmented Hessian; the start and the linear term; then the
// outer steps, each an MPGP solve of the augmented Lagrangian and the update of mu and M.
// With the rows made orthonormal, Gh = W^T G_a and eh = W^T e for some W with W W^T = S^+;
// every quantity is written through G_a and S^+ (mu = W mu_h, the null directions of the rows
// keeping no multiplier: least norm). The operators built here refer to the object: it stays
// where it is made.
class SmalseM {
 public:
  SmalseM(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
          const EqualityConstraint& eq, const SmalseOptions& opt, const MpgpOptions& inner,
          SmalseReport& rep)
      : A_(A),
        b_(b),
        c_(c),
        eq_(eq),
        opt_(opt),
        inner_(inner),
        space_(inner.vectors()),
        rep_(rep),
        rows_(active_columns(eq.G, c), space_),
        Ga_(rows_.G()),
        e_(kept_load()),
        kept_{Ga_, e_},
        eh2_(std::max(rows_.norm2(e_), 0.0)) {
    rep_.undetermined = rows_.null();
  }

  // A load along a row direction on no free multiplier, unless dropped, makes the equality
  // infeasible: false, with the certificate in the report.
  bool load_is_resisted() {
    if (opt_.drop_unresisted_load) return true;
    auto certificate = unresisted_load(rows_, eq_.e, opt_.equality_tolerance);
    if (!certificate) return true;
    rep_.infeasible = true;
    rep_.infeasibility = std::move(*certificate);
    rep_.termination = QpTermination::NumericalFailure;
    rep_.message =
        "the equality constraint cannot be met: a load acts on a motion no multiplier resists";
    return false;
  }

  void solve(Eigen::VectorXd& x, Eigen::VectorXd& mu) {
    if (data_vanish()) return accept_zero(x, mu);
    mu -= rows_.null() * (rows_.null().transpose() * mu);
    choose_penalty();
    const Operator A_aug = augmented_hessian();
    start(x, mu);
    set_inner_options();
    for (int k = 0; k < opt_.max_outer; ++k)
      if (outer_step(k, A_aug, x, mu)) break;
    if (opt_.projector && rows_.rank() > 0) recover_multiplier(x, mu);
  }

  long n_coarse_solves() const { return rows_.n_solves(); }
  double coarse_seconds() const { return rows_.seconds(); }

 private:
  // No load on the equality (e = 0) and none of b that the constraints resist (b_R = 0 to
  // rounding, e.g. gaps alone, a body driven by prescribed displacements that are zero): x = 0
  // with mu = 0 meets the KKT conditions exactly (theory.md §4.6). The iteration is not run: with
  // the projector, P b carries the gaps into the free multipliers, and an iterate that only
  // approaches 0 would be measured against itself.
  bool data_vanish() const {
    if (!e_.isZero(0.0)) return false;
    return space_.norm(resisted_part(b_, c_)) <= kVanishingData * space_.norm(b_);
  }

  void accept_zero(Eigen::VectorXd& x, Eigen::VectorXd& mu) {
    x.setZero();
    mu.setZero();
    rep_.termination = QpTermination::Converged;
    rep_.message = "x = 0: the data load no constraint (e = 0 and b_R = 0)";
  }

  // The equality as it is solved: without the load on motions no multiplier resists, if that
  // load is dropped.
  Eigen::VectorXd kept_load() const {
    if (!opt_.drop_unresisted_load) return eq_.e;
    const Eigen::MatrixXd& null = rows_.null();
    return eq_.e - null * (null.transpose() * eq_.e);
  }

  // ||Gh v - eh||^2
  double residual2(const Eigen::VectorXd& v) const {
    return std::max(rows_.norm2(rows_.times(v) - e_), 0.0);
  }

  // rho = rho_factor ||A||, with ||P A P|| in place of ||A|| where the options ask for it.
  void choose_penalty() {
    if (opt_.projector && opt_.projected_norm && rows_.rank() > 0) {
      const Operator PAP = [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
        Pv_ = v;
        rows_.project(Pv_);
        A_(Pv_, y);
        rows_.project(y);
      };
      long products = 0;
      norm_A_ = opt_.norm_projected > 0.0
                    ? opt_.norm_projected
                    : estimate_norm(PAP, c_.size(), inner_.power_iterations, inner_.power_tolerance,
                                    &products, space_);
      rep_.n_products += products;
      rep_.norm_projected = norm_A_;
    } else {
      norm_A_ = inner_.norm_A > 0.0 ? inner_.norm_A
                                    : estimate_norm(A_, c_.size(), inner_.power_iterations,
                                                    inner_.power_tolerance, nullptr, space_);
    }
    if (!(norm_A_ > 0.0) || !std::isfinite(norm_A_))
      throw NumericalError(fmt::format("solve_smalse: ||A|| = {}", norm_A_));
    rep_.rho = opt_.rho_factor * norm_A_;
    rho_ = rep_.rho;
  }

  // A + rho Gh^T Gh, or with the projector P A P + rho Gh^T Gh. On the affine set G_a x = e,
  // with P = I - G_a^T S^+ G_a and x_e = G_a^T S^+ e, P x = x - x_e and
  //   q(x) = 1/2 x^T (P A P) x - x^T P (b - A x_e) + const,
  // so the QP may take the projected Hessian P A P (TFETI's natural coarse space, theory.md
  // §4.6, §8.3): the part of A along the rows, which the generalized inverse leaves arbitrary,
  // drops out, and P A P + rho (I - P) has the norm of A for rho = ||A||. The discs stay centred
  // (x itself is not shifted). The multiplier of the original problem is then
  // mu - S^+ G_a (A x - b) at the solution (recover_multiplier).
  Operator augmented_hessian() {
    return [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
      const Eigen::VectorXd along_rows = rows_.onto_rows(v);
      if (opt_.projector) {
        Pv_ = v - along_rows;
        A_(Pv_, y);
        rows_.project(y);
      } else {
        A_(v, y);
      }
      y.noalias() += rho_ * along_rows;
    };
  }

  // A cold start (x = 0) begins at the least-norm solution of the equality, x_e, projected onto
  // Omega (feasible for a load that pressure alone balances). With the projector the linear term
  // is P (b - A x_e), and a warm start's mu is moved to the projected problem's.
  void start(Eigen::VectorXd& x, Eigen::VectorXd& mu) {
    x_e_ = rows_.transpose_times(rows_.solve(e_));
    const bool cold = space_.max_abs(x) == 0.0;
    if (cold) {
      x = x_e_;
      c_.project(x);
    }
    b_base_ = b_;
    if (!opt_.projector) {
      data_norm_ = space_.norm(resisted_part(b_, c_));
      return;
    }
    Eigen::VectorXd Ax(c_.size());
    A_(x_e_, Ax);
    b_base_ -= Ax;
    data_norm_ = projected_resisted_norm(b_base_);
    rows_.project(b_base_);
    ++rep_.n_products;
    if (!cold) {
      A_(x, Ax);
      mu += rows_.solve(rows_.times(Ax - b_));
      ++rep_.n_products;
    }
  }

  // The size of the projected data d = b - A x_e that the constraints resist: d's resisted part
  // (the gaps of separated patches, which x = 0 satisfies by itself, left out), then projected,
  // then its resisted part again. Projecting d first would spread those gaps over the free
  // multipliers (every row of G is a subdomain's rigid motion, which meets both), and on a mesh
  // with far patches they exceeded the rest by orders of magnitude (theory.md §4.6).
  double projected_resisted_norm(const Eigen::VectorXd& d) const {
    Eigen::VectorXd kept = resisted_part(d, c_);
    rows_.project(kept);
    return space_.norm(resisted_part(kept, c_));
  }

  // The inner MPGP's options: its norm, the preconditioner in face and the adaptive precision
  // min(M ||Gh x - eh||, eta). The gradient test is relative to the data of the problem: the
  // larger of the load rho e and b_R, with the projector the projected linear term's resisted
  // part (projected_resisted_norm). With the projector b's part along the rows of G is left out: it
  // depends on which generalized inverse made A and b (the subdomains' rigid motions in Total
  // FETI's b = B K^+ f - c, theory.md §8.3), not on the problem, and can exceed the rest by orders
  // of magnitude.
  void set_inner_options() {
    reference_ = std::max(data_norm_, rho_ * std::sqrt(eh2_));
    rep_.reference_norm = reference_;
    rep_.equality_floor = equality_floor();
    const double eta = opt_.eta_factor * reference_;
    M_ = opt_.M_factor * norm_A_;
    io_ = inner_;
    io_.rel_tolerance = 0.0;
    // ||Gh^T Gh|| = 1; with the projector the two terms act on orthogonal subspaces.
    io_.norm_A = opt_.projector ? std::max(norm_A_, rho_) : norm_A_ + rho_;
    // Preconditioning in face: with the projector the Hessian is P A P + rho Q on complementary
    // subspaces, so M approximating A^-1 gives P M P + Q / rho (theory.md §4.6).
    if (inner_.preconditioner && opt_.projector)
      io_.preconditioner = [this](const Eigen::VectorXd& v, Eigen::VectorXd& z) {
        const Eigen::VectorXd along_rows = rows_.onto_rows(v);
        Pm_ = v - along_rows;
        inner_.preconditioner(Pm_, z);
        rows_.project(z);
        z.noalias() += (1.0 / rho_) * along_rows;
      };
    io_.adaptive_tolerance = [this, eta](const Eigen::VectorXd& v) {
      return std::min(M_ * std::sqrt(residual2(v)), eta);
    };
  }

  // Outer step k: minimize the augmented Lagrangian at mu, then stop (converged, failed, the
  // equality found infeasible, the steps used up) or update mu and M. Returns true to stop.
  bool outer_step(int k, const Operator& A_aug, Eigen::VectorXd& x, Eigen::VectorXd& mu) {
    rep_.outer_iterations = k + 1;
    const Eigen::VectorXd b_aug = b_base_ - rows_.transpose_times(mu) + rho_ * x_e_;
    const double eps_g = std::max(inner_.rel_tolerance * rep_.reference_norm, inner_.abs_tolerance);
    io_.abs_tolerance = std::min(eps_g, equality_floor_);
    const MpgpReport r = solve_mpgp(A_aug, b_aug, c_, io_, x);
    accumulate(r, rep_);
    rep_.norm_gp = r.norm_gp;
    rep_.equality_residual = equality_residual(kept_, x, rep_.equality_floor, space_);
    if (r.termination != QpTermination::Converged) {
      rep_.termination = r.termination;
      rep_.message = fmt::format("inner solve {}: {}", k + 1, r.message);
      return true;
    }
    const Eigen::VectorXd res = rows_.times(x) - e_;
    const Eigen::VectorXd S_res = rows_.solve(res);
    const double res2 = std::max(res.dot(S_res), 0.0);  // ||Gh x - eh||^2
    if (r.norm_gp <= eps_g && rep_.equality_residual <= opt_.equality_tolerance) {
      rep_.termination = QpTermination::Converged;
      rep_.message = fmt::format(
          "||g^P|| = {:.3e} <= {:.3e} and ||G x - e|| relative {:.3e} <= {:.1e} after {} outer "
          "steps",
          r.norm_gp, eps_g, rep_.equality_residual, opt_.equality_tolerance, k + 1);
      return true;
    }
    if (found_infeasible(std::sqrt(res2), x)) return true;
    tighten_for_equality(res2);
    update_multiplier(k, r.objective, S_res, res2, mu);
    if (k + 1 < opt_.max_outer) return false;
    rep_.termination = QpTermination::MaxIterations;
    rep_.message =
        fmt::format("reached max_outer = {} with ||G x - e|| / ||e|| = {:.3e} (target {:.1e})",
                    opt_.max_outer, rep_.equality_residual, opt_.equality_tolerance);
    return true;
  }

  // Once the residual has stopped decreasing: is the equality feasible at all (phase one)? True,
  // with the certificate in the report, when it is not.
  bool found_infeasible(double res_norm, const Eigen::VectorXd& x) {
    stagnant_ = res_norm > kStagnation * residual_prev_ ? stagnant_ + 1 : 0;
    residual_prev_ = res_norm;
    if (stagnant_ < kStagnantSteps) return false;
    stagnant_ = 0;
    auto certificate = phase_one_certificate(rows_, e_, c_, inner_, x,
                                             std::max(kInfeasibleShare, opt_.equality_tolerance));
    if (!certificate) return false;
    rep_.infeasible = true;
    rep_.infeasibility = along_one_row(Ga_, eq_.e, c_, std::move(*certificate), space_);
    rep_.termination = QpTermination::NumericalFailure;
    rep_.message = fmt::format(
        "the equality constraint cannot be met in Omega: along the certificate direction the "
        "load is {:.4g} but Omega gives at most {:.4g}",
        rep_.infeasibility.applied, rep_.infeasibility.carried);
    return true;
  }

  // The magnitudes of G x's terms for x of the size the gradient test resolves, r / ||A|| spread
  // evenly over the n unknowns: || |G_a| 1 || r / (||A|| sqrt(n)). r is the smaller of the two
  // sizes of the data: b's resisted part before the projection (without the gaps of separated
  // patches, which the projector spreads over the free multipliers) and after it (without the
  // rigid parts that a generalized inverse leaves in b).
  double equality_floor() const {
    const auto n = static_cast<double>(space_.size(c_.size()));
    const double r = std::min(reference_, space_.norm(resisted_part(b_, c_)));
    Eigen::VectorXd spread = Ga_.cwiseAbs() * Eigen::VectorXd::Ones(c_.size());
    space_.sum(spread);
    return spread.norm() * r / (norm_A_ * std::sqrt(n));
  }

  // The residual along the rows moves the augmented gradient by about rho ||Gh x - eh||, so an
  // inner solve that stops at a gradient of eps_g leaves the residual at about eps_g / rho,
  // whatever mu does; M shrinks and the outer steps stall. Where that residual is above the
  // equality's tolerance (e.g. a load-free equality, e = 0, measured against the magnitudes of
  // G x's terms), the later inner solves stop only at the gradient that the tolerance asks for:
  // rho ||Gh x - eh|| scaled by the tolerance over the residual (theory.md §4.6).
  void tighten_for_equality(double res2) {
    if (rep_.equality_residual <= opt_.equality_tolerance) return;
    const double needed = rho_ * std::sqrt(res2) * opt_.equality_tolerance / rep_.equality_residual;
    equality_floor_ = std::min(equality_floor_, needed);
  }

  // mu += rho S^+ (G_a x - e), then the semi-monotonic update of M: divided by beta when
  // L(x_k, mu_k+1) did not increase by rho/2 ||Gh x - eh||^2.
  void update_multiplier(int k, double objective, const Eigen::VectorXd& S_res, double res2,
                         Eigen::VectorXd& mu) {
    const double L = objective - mu.dot(e_) + 0.5 * rho_ * eh2_ + rho_ * res2;
    mu += rho_ * S_res;
    if (k > 0 && L < L_prev_ + 0.5 * rho_ * res2) M_ /= opt_.beta;
    L_prev_ = L;
  }

  // The multiplier of the original problem from the projected one's: mu - S^+ G_a (A x - b).
  void recover_multiplier(const Eigen::VectorXd& x, Eigen::VectorXd& mu) {
    Eigen::VectorXd Ax(c_.size());
    A_(x, Ax);
    ++rep_.n_products;
    mu -= rows_.solve(rows_.times(Ax - b_));
  }

  const Operator& A_;
  const Eigen::VectorXd& b_;
  const SeparableConstraints& c_;
  const EqualityConstraint& eq_;
  const SmalseOptions& opt_;
  const MpgpOptions& inner_;
  const DualSpace& space_;  ///< where x, b and the columns of G live (inner.space)
  SmalseReport& rep_;
  const CoarseSpace rows_;
  const SparseMatrix& Ga_;
  const Eigen::VectorXd e_;        ///< e as solved (kept_load)
  const EqualityConstraint kept_;  ///< G_a x = e_
  const double eh2_;               ///< ||eh||^2
  double norm_A_ = 0.0, rho_ = 0.0;
  Eigen::VectorXd x_e_, b_base_;
  double reference_ = 0.0;  ///< the reference of the gradient test
  double data_norm_ = 0.0;  ///< the resisted data's size (projected_resisted_norm)
  double M_ = 0.0;          ///< the ratio of the inner precision to ||Gh x - eh||
  MpgpOptions io_;          ///< the inner solves' options
  double L_prev_ = 0.0, residual_prev_ = std::numeric_limits<double>::infinity();
  int stagnant_ = 0;
  /// The inner solves' precision that the equality asks for (tighten_for_equality).
  double equality_floor_ = std::numeric_limits<double>::infinity();
  Eigen::VectorXd Pv_, Pm_;  ///< work vectors of the operators
};

void check_sizes(const Eigen::VectorXd& b, const SeparableConstraints& c,
                 const EqualityConstraint& eq, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& mu) {
  const Index n = c.size(), m = eq.G.rows();
  if (eq.G.cols() != n || eq.e.size() != m || b.size() != n || x.size() != n ||
      (mu.size() != 0 && mu.size() != m))
    throw InputError(fmt::format(
        "solve_smalse: G is {} x {}, e has {}, b {}, x {}, mu {} entries for {} unknowns", m,
        eq.G.cols(), eq.e.size(), b.size(), x.size(), mu.size(), n));
}

}  // namespace

SmalseReport solve_smalse(const Operator& A, const Eigen::VectorXd& b,
                          const SeparableConstraints& c, const EqualityConstraint& eq,
                          const SmalseOptions& opt, const MpgpOptions& inner, Eigen::VectorXd& x,
                          Eigen::VectorXd& mu) {
  const Stopwatch watch;
  opt.validate();
  check_sizes(b, c, eq, x, mu);
  if (mu.size() == 0) mu = Eigen::VectorXd::Zero(eq.G.rows());
  SmalseReport rep;
  SmalseM smalse(A, b, c, eq, opt, inner, rep);
  if (smalse.load_is_resisted()) smalse.solve(x, mu);
  rep.n_coarse_solves = smalse.n_coarse_solves();
  rep.coarse_s = smalse.coarse_seconds();
  rep.seconds = watch.seconds();
  return rep;
}

}  // namespace fricon::qp
