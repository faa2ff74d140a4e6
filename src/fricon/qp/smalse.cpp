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
  o.variant = inner.variant;
  o.rel_tolerance = kPhaseOneTolerance;
  o.reference = StopReference::Whole;
  o.norm_A = 1.0 + kPhaseOneRegularization;
  o.max_iterations = inner.max_iterations;
  const MpgpReport r = solve_mpgp(GtG, rows.G().transpose() * rows.solve(e), c, o, x1);
  if (r.termination != QpTermination::Converged) return {};
  return e - rows.G() * x1;
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
  return Infeasibility{d, d.dot(e), d.dot(rows.G() * x1)};
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
// alone, e.g. a push against mu N); else `found` as it is.
Infeasibility along_one_row(const SparseMatrix& Ga, const Eigen::VectorXd& e,
                            const SeparableConstraints& c, Infeasibility found) {
  const SparseMatrix Gt = Ga.transpose();
  double best = 0.0;
  for (Index j = 0; j < Ga.rows(); ++j) {
    if (e(j) == 0.0) continue;
    const double sign = e(j) > 0.0 ? 1.0 : -1.0;
    const double applied = std::abs(e(j));
    const double carried = support(sign * Eigen::VectorXd(Gt.col(j)), c);
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

double equality_residual(const EqualityConstraint& eq, const Eigen::VectorXd& x) {
  const Eigen::VectorXd Gx = eq.G * x;
  // The magnitudes of the terms of G x, which cancel where the equality holds: a load-free
  // equality (e = 0, a body driven by prescribed displacements) is measured against them.
  const Eigen::VectorXd magnitudes = eq.G.cwiseAbs() * x.cwiseAbs();
  const double scale = std::max(eq.e.norm(), magnitudes.norm());
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

  // @sect: the rows of G over the multipliers free to move and their coarse problem S = G G^T;
  // a row direction on none of them must carry no load.
  const CoarseSpace rows(active_columns(eq.G, c));
  const SparseMatrix& Ga = rows.G();
  const Eigen::MatrixXd& null = rows.null();
  rep.undetermined = null;
  const auto finish = [&] {
    rep.n_coarse_solves = rows.n_solves();
    rep.seconds = watch.seconds();
  };
  if (!opt.drop_unresisted_load)
    if (auto certificate = unresisted_load(rows, eq.e, opt.equality_tolerance)) {
      rep.infeasible = true;
      rep.infeasibility = std::move(*certificate);
      rep.termination = QpTermination::NumericalFailure;
      rep.message =
          "the equality constraint cannot be met: a load acts on a motion no multiplier "
          "resists";
      finish();
      return rep;
    }
  // The equality as it is solved: without the dropped load, if it is dropped.
  const Eigen::VectorXd e =
      opt.drop_unresisted_load ? Eigen::VectorXd(eq.e - null * (null.transpose() * eq.e)) : eq.e;
  const EqualityConstraint kept{Ga, e};
  // With the rows made orthonormal, Gh = W^T G_a and eh = W^T e for some W with W W^T = S^+;
  // every quantity below is written through G_a and S^+ (mu = W mu_h, the null directions of
  // the rows keeping no multiplier: least norm).
  mu -= null * (null.transpose() * mu);
  const auto residual2 = [&](const Eigen::VectorXd& v) {  // ||Gh v - eh||^2
    return std::max(rows.norm2(Ga * v - e), 0.0);
  };
  const double eh2 = std::max(rows.norm2(e), 0.0);  // ||eh||^2

  // @sect: the penalty, the inner precision and the augmented Hessian A + rho Gh^T Gh.
  Eigen::VectorXd Pv;
  const Operator PAP = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    Pv = v;
    rows.project(Pv);
    A(Pv, y);
    rows.project(y);
  };
  double norm_A = 0.0;
  if (opt.projector && opt.projected_norm && rows.rank() > 0) {
    long products = 0;
    norm_A = opt.norm_projected > 0.0
                 ? opt.norm_projected
                 : estimate_norm(PAP, n, inner.power_iterations, inner.power_tolerance, &products);
    rep.n_products += products;
    rep.norm_projected = norm_A;
  } else {
    norm_A = inner.norm_A > 0.0
                 ? inner.norm_A
                 : estimate_norm(A, n, inner.power_iterations, inner.power_tolerance);
  }
  if (!(norm_A > 0.0) || !std::isfinite(norm_A))
    throw NumericalError(fmt::format("solve_smalse: ||A|| = {}", norm_A));
  rep.rho = opt.rho_factor * norm_A;
  const double rho = rep.rho;
  // On the affine set G_a x = e, with P = I - G_a^T S^+ G_a and x_e = G_a^T S^+ e, P x = x - x_e
  // and
  //   q(x) = 1/2 x^T (P A P) x - x^T P (b - A x_e) + const,
  // so the QP may take the projected Hessian P A P (TFETI's natural coarse space, theory.md
  // §4.6, §8.3): the part of A along the rows, which the generalized inverse leaves arbitrary,
  // drops out, and P A P + rho (I - P) has the norm of A for rho = ||A||. The discs stay centred
  // (x itself is not shifted). The multiplier of the original problem is then
  // mu - S^+ G_a (A x - b) at the solution.
  const Operator A_aug = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    const Eigen::VectorXd along_rows = rows.onto_rows(v);
    if (opt.projector) {
      Pv = v - along_rows;
      A(Pv, y);
      rows.project(y);
    } else {
      A(v, y);
    }
    y.noalias() += rho * along_rows;
  };
  // A cold start begins at the least-norm solution of the equality, x_e, projected onto Omega
  // (feasible for a load that pressure alone balances).
  const Eigen::VectorXd x_e = Ga.transpose() * rows.solve(e);
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
    rows.project(b_base);
    ++rep.n_products;
    // The warm start's multiplier in the projected problem.
    if (!cold) {
      A(x, Ax);
      mu += rows.solve(Ga * (Ax - b));
      ++rep.n_products;
    }
  }
  // The gradient test is relative to the data of the problem: b_R and the load rho e, and the
  // projected linear term's b_base_R (the rounding level of its gradient). With the projector
  // b's part along the rows of G is left out: it depends on which generalized inverse made A and
  // b (the subdomains' rigid motions in Total FETI's b = B K^+ f - c, theory.md §8.3), not on the
  // problem, and can exceed the rest by orders of magnitude.
  const double reference =
      std::max(resisted_part(opt.projector ? b_base : b, c).norm(), rho * std::sqrt(eh2));
  const double eta = opt.eta_factor * reference;
  double M = opt.M_factor * norm_A;
  MpgpOptions io = inner;
  io.rel_tolerance = 0.0;
  // ||Gh^T Gh|| = 1; with the projector the two terms act on orthogonal subspaces.
  io.norm_A = opt.projector ? std::max(norm_A, rho) : norm_A + rho;
  // Preconditioning in face: with the projector the Hessian is P A P + rho Q on complementary
  // subspaces, so M approximating A^-1 gives P M P + Q / rho (theory.md §4.6).
  Eigen::VectorXd Pm;
  if (inner.preconditioner && opt.projector)
    io.preconditioner = [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) {
      const Eigen::VectorXd along_rows = rows.onto_rows(v);
      Pm = v - along_rows;
      inner.preconditioner(Pm, z);
      rows.project(z);
      z.noalias() += (1.0 / rho) * along_rows;
    };
  io.adaptive_tolerance = [&](const Eigen::VectorXd& v) {
    return std::min(M * std::sqrt(residual2(v)), eta);
  };

  // @sect: the outer steps.
  double L_prev = 0.0, residual_prev = std::numeric_limits<double>::infinity();
  int stagnant = 0;
  for (int k = 0; k < opt.max_outer; ++k) {
    rep.outer_iterations = k + 1;
    const Eigen::VectorXd b_aug = b_base - Ga.transpose() * mu + rho * x_e;
    rep.reference_norm = std::max(reference, resisted_part(b_base, c).norm());
    const double eps_g = std::max(inner.rel_tolerance * rep.reference_norm, inner.abs_tolerance);
    io.abs_tolerance = eps_g;
    const MpgpReport r = solve_mpgp(A_aug, b_aug, c, io, x);
    accumulate(r, rep);
    rep.norm_gp = r.norm_gp;
    rep.equality_residual = equality_residual(kept, x);
    if (r.termination != QpTermination::Converged) {
      rep.termination = r.termination;
      rep.message = fmt::format("inner solve {}: {}", k + 1, r.message);
      break;
    }
    const Eigen::VectorXd res = Ga * x - e;
    const Eigen::VectorXd S_res = rows.solve(res);
    const double res2 = std::max(res.dot(S_res), 0.0);  // ||Gh x - eh||^2
    if (r.norm_gp <= eps_g && rep.equality_residual <= opt.equality_tolerance) {
      rep.termination = QpTermination::Converged;
      rep.message = fmt::format(
          "||g^P|| = {:.3e} <= {:.3e} and ||G x - e|| relative {:.3e} <= {:.1e} after {} outer "
          "steps",
          r.norm_gp, eps_g, rep.equality_residual, opt.equality_tolerance, k + 1);
      break;
    }
    // Once the residual has stopped decreasing: is the equality feasible at all (phase one)?
    const double res_norm = std::sqrt(res2);
    stagnant = res_norm > kStagnation * residual_prev ? stagnant + 1 : 0;
    residual_prev = res_norm;
    if (stagnant >= kStagnantSteps) {
      stagnant = 0;
      if (auto certificate = phase_one_certificate(
              rows, e, c, inner, x, std::max(kInfeasibleShare, opt.equality_tolerance))) {
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
    const double L = r.objective - mu.dot(e) + 0.5 * rho * eh2 + rho * res2;  // L(x_k, mu_k+1)
    mu += rho * S_res;
    if (k > 0 && L < L_prev + 0.5 * rho * res2) M /= opt.beta;
    L_prev = L;
    if (k + 1 == opt.max_outer) {
      rep.termination = QpTermination::MaxIterations;
      rep.message =
          fmt::format("reached max_outer = {} with ||G x - e|| / ||e|| = {:.3e} (target {:.1e})",
                      opt.max_outer, rep.equality_residual, opt.equality_tolerance);
    }
  }
  if (opt.projector && rows.rank() > 0) {
    Eigen::VectorXd Ax(n);
    A(x, Ax);
    ++rep.n_products;
    mu -= rows.solve(Ga * (Ax - b));
  }
  finish();
  return rep;
}

}  // namespace fricon::qp
