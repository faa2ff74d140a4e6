#include "fricon/qp/smalse.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/timer.hpp"

namespace fricon::qp {

namespace {

// A row direction of G whose squared length is below this share of the largest acts on no
// multiplier that is free to move (theory.md §4.6).
constexpr double kRankTolerance = 1e-12;
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
// A row's load must exceed what Omega gives along it by this share of the load to certify.
constexpr double kRowExcess = 1e-9;

// G with the columns of the discs pinned to zero (radius 0) cleared: those multipliers stay 0.
Eigen::MatrixXd active_columns(const Eigen::MatrixXd& G, const SeparableConstraints& c) {
  Eigen::MatrixXd Ga = G;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Block& block = c.blocks[k];
    if (block.kind == BlockKind::Disc && c.radius(static_cast<Index>(k)) == 0.0)
      Ga.middleCols(block.offset, 2).setZero();
  }
  return Ga;
}

// The rows of G made orthonormal: W (m x r) with W^T G_a G_a^T W = I over the range of G_a G_a^T,
// and the rest of the row space (m x (m - r)), orthonormal, on which G_a vanishes.
struct Whitening {
  Eigen::MatrixXd W, null;
};

Whitening whiten(const Eigen::MatrixXd& Ga) {
  const Eigen::MatrixXd S = Ga * Ga.transpose();
  Whitening w;
  if (S.rows() == 0) return w;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const double largest = std::max(eig.eigenvalues().maxCoeff(), 0.0);
  std::vector<Index> range, null;
  for (Index i = 0; i < S.rows(); ++i)
    (largest > 0.0 && eig.eigenvalues()(i) > kRankTolerance * largest ? range : null).push_back(i);
  w.W.resize(S.rows(), static_cast<Index>(range.size()));
  w.null.resize(S.rows(), static_cast<Index>(null.size()));
  for (std::size_t j = 0; j < range.size(); ++j)
    w.W.col(static_cast<Index>(j)) =
        eig.eigenvectors().col(range[j]) / std::sqrt(eig.eigenvalues()(range[j]));
  for (std::size_t j = 0; j < null.size(); ++j)
    w.null.col(static_cast<Index>(j)) = eig.eigenvectors().col(null[j]);
  return w;
}

double relative_equality_residual(const EqualityConstraint& eq, const Eigen::VectorXd& x) {
  const Eigen::VectorXd Gx = eq.G * x;
  const double scale = std::max(eq.e.norm(), Gx.norm());
  return scale > 0.0 ? (Gx - eq.e).norm() / scale : 0.0;
}

// Phase one (theory.md §4.6): the point x1 of Omega whose image G x1 is nearest to e, for the
// orthonormal G and e of the solver; its residual d = e - G x1 certifies infeasibility when it is
// not small: for every x in Omega, d^T G x <= d^T G x1 < d^T e. Costs products with G only.
// Returns d (empty if the phase-one solve failed).
Eigen::VectorXd phase_one(const Eigen::MatrixXd& Gh, const Eigen::VectorXd& eh,
                          const SeparableConstraints& c, const MpgpOptions& inner,
                          Eigen::VectorXd& x1) {
  const Operator GtG = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    y = Gh.transpose() * (Gh * v) + kPhaseOneRegularization * v;
  };
  MpgpOptions o;
  o.variant = inner.variant;
  o.rel_tolerance = kPhaseOneTolerance;
  o.reference = StopReference::Whole;
  o.norm_A = 1.0 + kPhaseOneRegularization;
  o.max_iterations = inner.max_iterations;
  const MpgpReport r = solve_mpgp(GtG, Gh.transpose() * eh, c, o, x1);
  if (r.termination != QpTermination::Converged) return {};
  return eh - Gh * x1;
}

// A load along a row direction that acts on no free multiplier (w.null): the first such
// direction, signed so that the load along it is positive, as a certificate; none if every such
// load is below `tolerance` ||e||.
std::optional<Infeasibility> unresisted_load(const Whitening& w, const Eigen::VectorXd& e,
                                             double tolerance) {
  for (Index j = 0; j < w.null.cols(); ++j) {
    const double load = w.null.col(j).dot(e);
    if (std::abs(load) > tolerance * e.norm())
      return Infeasibility{
          load > 0 ? Eigen::VectorXd(w.null.col(j)) : Eigen::VectorXd(-w.null.col(j)),
          std::abs(load), 0.0};
  }
  return std::nullopt;
}

// The certificate of phase one when its shortest residual exceeds `tolerance` ||eh||, mapped back
// to the rows of G by W.
std::optional<Infeasibility> phase_one_certificate(const Whitening& w, const Eigen::MatrixXd& Gh,
                                                   const Eigen::VectorXd& eh,
                                                   const SeparableConstraints& c,
                                                   const MpgpOptions& inner, Eigen::VectorXd x1,
                                                   double tolerance) {
  const Eigen::VectorXd d = phase_one(Gh, eh, c, inner, x1);
  if (d.size() == 0 || !(d.norm() > tolerance * eh.norm())) return std::nullopt;
  // d^T e - d^T G x1 = ||d||^2 > 0, and d^T G x1 is the most Omega gives along d.
  return Infeasibility{w.W * d, d.dot(eh), d.dot(Gh * x1)};
}

// sup { g^T x : x in Omega }: per disc its radius times ||g_i||, per bound 0 when g_i <= 0,
// infinity when g_i > 0 (a bound's multiplier grows without limit).
double support(const Eigen::VectorXd& g, const SeparableConstraints& c) {
  double s = 0.0;
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Block& block = c.blocks[k];
    if (block.kind == BlockKind::Disc)
      s += c.radius(static_cast<Index>(k)) * g.segment<2>(block.offset).norm();
    else if (g(block.offset) > 0.0)
      return std::numeric_limits<double>::infinity();
  }
  return s;
}

// A certificate along one row of G (one of the motions as they are numbered) rather than the
// phase one's direction, whose metric is that of the orthonormal rows: the row whose load most
// exceeds what Omega gives along it, if one does (then the figures are those of that motion
// alone, e.g. a push against mu N); else `found` as it is.
Infeasibility along_one_row(const Eigen::MatrixXd& Ga, const Eigen::VectorXd& e,
                            const SeparableConstraints& c, Infeasibility found) {
  double best = 0.0;
  for (Index j = 0; j < Ga.rows(); ++j) {
    if (e(j) == 0.0) continue;
    const double sign = e(j) > 0.0 ? 1.0 : -1.0;
    const double applied = std::abs(e(j));
    const double carried = support(sign * Ga.row(j).transpose(), c);
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
  rep.n_products += inner.n_products;
  rep.last_inner = inner;
}

}  // namespace

std::optional<Infeasibility> balance_certificate(const EqualityConstraint& eq,
                                                 const SeparableConstraints& c, double tolerance) {
  FRICON_CHECK(eq.G.cols() == c.size() && eq.e.size() == eq.G.rows(),
               "balance_certificate: G is " << eq.G.rows() << " x " << eq.G.cols() << " for "
                                            << c.size() << " unknowns");
  const Eigen::MatrixXd Ga = active_columns(eq.G, c);
  const Whitening w = whiten(Ga);
  if (auto certificate = unresisted_load(w, eq.e, tolerance)) return certificate;
  const Eigen::MatrixXd Gh = w.W.transpose() * Ga;
  const Eigen::VectorXd eh = w.W.transpose() * eq.e;
  const auto certificate =
      phase_one_certificate(w, Gh, eh, c, MpgpOptions{}, Eigen::VectorXd::Zero(c.size()),
                            std::max(kInfeasibleShare, tolerance));
  if (!certificate) return std::nullopt;
  return along_one_row(Ga, eq.e, c, *certificate);
}

void SmalseOptions::validate() const {
  require("SmalseOptions::rho_factor", rho_factor, positive());
  require("SmalseOptions::M_factor", M_factor, positive());
  require("SmalseOptions::beta", beta, open_interval(1.0, std::numeric_limits<double>::infinity()));
  require("SmalseOptions::eta_factor", eta_factor, positive());
  require("SmalseOptions::equality_tolerance", equality_tolerance, positive());
  require("SmalseOptions::max_outer", max_outer, integer_at_least(1));
}

SmalseReport solve_smalse(const Operator& A, const Eigen::VectorXd& b,
                          const SeparableConstraints& c, const EqualityConstraint& eq,
                          const SmalseOptions& opt, const MpgpOptions& inner, Eigen::VectorXd& x,
                          Eigen::VectorXd& mu) {
  const Stopwatch watch;
  opt.validate();
  const Index n = c.size(), m = eq.G.rows();
  if (eq.G.cols() != n || eq.e.size() != m || b.size() != n || x.size() != n ||
      (mu.size() != 0 && mu.size() != m))
    throw InputError(fmt::format(
        "solve_smalse: G is {} x {}, e has {}, b {}, x {}, mu {} entries for {} unknowns", m,
        eq.G.cols(), eq.e.size(), b.size(), x.size(), mu.size(), n));
  if (mu.size() == 0) mu = Eigen::VectorXd::Zero(m);
  SmalseReport rep;

  // @sect: the rows of G over the multipliers free to move, made orthonormal; a row direction on
  // none of them must carry no load.
  const Eigen::MatrixXd Ga = active_columns(eq.G, c);
  const Whitening w = whiten(Ga);
  rep.undetermined = w.null;
  if (!opt.drop_unresisted_load)
    if (auto certificate = unresisted_load(w, eq.e, opt.equality_tolerance)) {
      rep.infeasible = true;
      rep.infeasibility = std::move(*certificate);
      rep.termination = QpTermination::NumericalFailure;
      rep.message =
          "the equality constraint cannot be met: a load acts on a motion no multiplier "
          "resists";
      rep.seconds = watch.seconds();
      return rep;
    }
  // The equality as it is solved: without the dropped load, if it is dropped.
  const EqualityConstraint kept{
      Ga, opt.drop_unresisted_load ? Eigen::VectorXd(eq.e - w.null * (w.null.transpose() * eq.e))
                                   : eq.e};
  const Eigen::MatrixXd Gh = w.W.transpose() * Ga;  // r x n, orthonormal rows
  const Eigen::VectorXd eh = w.W.transpose() * eq.e;
  // mu = W mu_h (the null directions keep no multiplier: least norm).
  Eigen::VectorXd mu_h = w.W.rows() > 0
                             ? Eigen::VectorXd(w.W.completeOrthogonalDecomposition().solve(mu))
                             : Eigen::VectorXd();

  // @sect: the penalty, the inner precision and the augmented Hessian A + rho Gh^T Gh.
  const double norm_A = inner.norm_A > 0.0
                            ? inner.norm_A
                            : estimate_norm(A, n, inner.power_iterations, inner.power_tolerance);
  if (!(norm_A > 0.0) || !std::isfinite(norm_A))
    throw NumericalError(fmt::format("solve_smalse: ||A|| = {}", norm_A));
  rep.rho = opt.rho_factor * norm_A;
  const double rho = rep.rho;
  // On the affine set Gh x = eh, with P = I - Gh^T Gh and x_e = Gh^T eh, P x = x - x_e and
  //   q(x) = 1/2 x^T (P A P) x - x^T P (b - A x_e) + const,
  // so the QP may take the projected Hessian P A P (TFETI's natural coarse space, theory.md
  // §4.6): the part of A along the rows, which the generalized inverse leaves arbitrary, drops
  // out, and P A P + rho Gh^T Gh has the norm of A for rho = ||A||. The discs stay centred (x
  // itself is not shifted). The multiplier of the original problem is then
  // mu_h - Gh (A x - b) at the solution.
  const auto project = [&](Eigen::VectorXd& v) { v.noalias() -= Gh.transpose() * (Gh * v); };
  Eigen::VectorXd Pv;
  const Operator A_aug = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    if (opt.projector) {
      Pv = v;
      project(Pv);
      A(Pv, y);
      project(y);
    } else {
      A(v, y);
    }
    y.noalias() += rho * (Gh.transpose() * (Gh * v));
  };
  // A cold start begins at the least-norm solution of the equality, x_e, projected onto Omega
  // (feasible for a load that pressure alone balances).
  const Eigen::VectorXd x_e = Gh.transpose() * eh;
  const bool cold = x.isZero(0.0);
  if (cold) {
    x = x_e;
    c.project(x);
  }
  Eigen::VectorXd b_base = b;
  if (opt.projector) {
    Eigen::VectorXd Ax(n);
    A(x_e, Ax);
    b_base -= Ax;
    project(b_base);
    ++rep.n_products;
    // The warm start's multiplier in the projected problem.
    if (!cold) {
      A(x, Ax);
      mu_h += Gh * (Ax - b);
      ++rep.n_products;
    }
  }
  // The gradient test is relative to the data of the problem (b_R and the load rho e) or, when
  // larger, to the projected linear term's (b_base_R below: the rounding level of its gradient).
  const double reference = std::max(resisted_part(b, c).norm(), rho * eh.norm());
  const double eta = opt.eta_factor * reference;
  double M = opt.M_factor * norm_A;
  MpgpOptions io = inner;
  io.rel_tolerance = 0.0;
  // ||Gh^T Gh|| = 1; with the projector the two terms act on orthogonal subspaces.
  io.norm_A = opt.projector ? std::max(norm_A, rho) : norm_A + rho;
  io.adaptive_tolerance = [&](const Eigen::VectorXd& v) {
    return std::min(M * (Gh * v - eh).norm(), eta);
  };

  // @sect: the outer steps.
  double L_prev = 0.0, residual_prev = std::numeric_limits<double>::infinity();
  int stagnant = 0;
  for (int k = 0; k < opt.max_outer; ++k) {
    rep.outer_iterations = k + 1;
    const Eigen::VectorXd b_aug = b_base - Gh.transpose() * mu_h + rho * (Gh.transpose() * eh);
    rep.reference_norm = std::max(reference, resisted_part(b_base, c).norm());
    const double eps_g = std::max(inner.rel_tolerance * rep.reference_norm, inner.abs_tolerance);
    io.abs_tolerance = eps_g;
    const MpgpReport r = solve_mpgp(A_aug, b_aug, c, io, x);
    accumulate(r, rep);
    rep.norm_gp = r.norm_gp;
    rep.equality_residual = relative_equality_residual(kept, x);
    if (r.termination != QpTermination::Converged) {
      rep.termination = r.termination;
      rep.message = fmt::format("inner solve {}: {}", k + 1, r.message);
      break;
    }
    const Eigen::VectorXd res = Gh * x - eh;
    if (r.norm_gp <= eps_g && rep.equality_residual <= opt.equality_tolerance) {
      rep.termination = QpTermination::Converged;
      rep.message = fmt::format(
          "||g^P|| = {:.3e} <= {:.3e} and ||G x - e|| / ||e|| = {:.3e} <= {:.1e} after {} outer "
          "steps",
          r.norm_gp, eps_g, rep.equality_residual, opt.equality_tolerance, k + 1);
      break;
    }
    // Once the residual has stopped decreasing: is the equality feasible at all (phase one)?
    stagnant = res.norm() > kStagnation * residual_prev ? stagnant + 1 : 0;
    residual_prev = res.norm();
    if (stagnant >= kStagnantSteps) {
      stagnant = 0;
      if (auto certificate = phase_one_certificate(
              w, Gh, eh, c, inner, x, std::max(kInfeasibleShare, opt.equality_tolerance))) {
        rep.infeasible = true;
        rep.infeasibility = along_one_row(Ga, eq.e, c, std::move(*certificate));
        rep.termination = QpTermination::NumericalFailure;
        rep.message = fmt::format(
            "the equality constraint cannot be met in Omega: along the certificate direction the "
            "load is {:.4g} but Omega gives at most {:.4g}",
            rep.infeasibility.applied, rep.infeasibility.carried);
        break;
      }
    }
    // Lagrange multipliers, then the semi-monotonic update of M.
    const double L = r.objective - mu_h.dot(eh) + 0.5 * rho * eh.squaredNorm() +
                     rho * res.squaredNorm();  // L(x_k, mu_{k+1}, rho)
    mu_h += rho * res;
    if (k > 0 && L < L_prev + 0.5 * rho * res.squaredNorm()) M /= opt.beta;
    L_prev = L;
    if (k + 1 == opt.max_outer) {
      rep.termination = QpTermination::MaxIterations;
      rep.message =
          fmt::format("reached max_outer = {} with ||G x - e|| / ||e|| = {:.3e} (target {:.1e})",
                      opt.max_outer, rep.equality_residual, opt.equality_tolerance);
    }
  }
  if (opt.projector && w.W.cols() > 0) {
    Eigen::VectorXd Ax(n);
    A(x, Ax);
    ++rep.n_products;
    mu_h -= Gh * (Ax - b);
  }
  mu = w.W.cols() > 0 ? Eigen::VectorXd(w.W * mu_h) : Eigen::VectorXd::Zero(m);
  rep.seconds = watch.seconds();
  return rep;
}

}  // namespace fricon::qp
