#include "fricon/driver/local_solve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/friction_cone.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

namespace {

// A refinement divides the QP and outer tolerances by this.
constexpr Real kRefinementFactor = 1e-2;
// A failed solve looks at W's spectrum (dense, up to this size): below kSingularRatio of the
// largest eigenvalue, the smallest counts as zero.
constexpr Index kDenseEigenLimit = 3000;
constexpr Real kSingularRatio = 1e-12;

void check_problem(const qp::LocalProblem& p) {
  const Index m = p.q.size();
  if (m == 0 || m % 3 != 0 || p.W.rows() != m || p.W.cols() != m)
    throw InputError(
        fmt::format("{}: a local problem needs W of m x m and q of m = 3 n_contacts "
                    "entries (W is {} x {}, q has {})",
                    p.source, p.W.rows(), p.W.cols(), m));
  const Index nc = m / 3;
  if (p.is_coulomb() == (p.threshold.size() > 0))
    throw InputError(
        fmt::format("{}: give either coefficients of friction (Coulomb) or "
                    "thresholds (Tresca), one per contact",
                    p.source));
  const VectorXd& per_contact = p.is_coulomb() ? p.mu : p.threshold;
  if (per_contact.size() != nc)
    throw InputError(fmt::format("{}: {} contacts but {} {}", p.source, nc, per_contact.size(),
                                 p.is_coulomb() ? "coefficients of friction" : "thresholds"));
  if (!p.q.allFinite() || !per_contact.allFinite() || (per_contact.array() < 0.0).any())
    throw InputError(
        fmt::format("{}: q, mu and thresholds must be finite, mu and thresholds >= 0", p.source));
}

// The pieces of W the QPs see (theory.md §5.6): S = (W + W^T)/2, their Hessian, and, when W is
// split, A = (W - W^T)/2, whose product with the reactions of the previous step goes into q.
struct Parts {
  SparseMatrix S, A;
  bool split = false;
  qp::Operator S_op() const {
    return [this](const VectorXd& x, VectorXd& y) { y = S * x; };
  }
};

// The successive approximations of theory.md §5.6 as one fixed-point map on the state
// (r_n, A r): r_n for Coulomb, A r when W is split. Step k solves the Tresca QP with Hessian S, the
// radii mu_a r_n,a of the state (Coulomb) or the thresholds (Tresca), and the linear term q + A r
// of the state; image = the state of its answer. From r = 0 the first step is the frictionless
// problem (Coulomb) with q itself. Where S is singular (rigid bodies) r is not unique but S r is
// (the minimisers of a convex QP share it), and so is A r wherever A vanishes on S's null space.
class LocalMap final : public outer::FixedPointMap {
 public:
  LocalMap(const qp::LocalProblem& p, const Parts& parts, const qp::BlockScaling& D,
           const qp::MpgpOptions& o, LocalSolution& s)
      : p_(p),
        parts_(parts),
        S_(parts.S_op()),
        D_(D),
        o_(o),
        s_(s),
        c_(qp::SeparableConstraints::contact_layout(p.n_contacts())) {
    if (!p.is_coulomb()) c_.set_disc_radii(p.threshold);
  }
  Index n_normal() const { return p_.is_coulomb() ? p_.n_contacts() : 0; }
  Index n_shift() const { return parts_.split ? p_.q.size() : 0; }
  std::vector<outer::StateBlock> layout() const override {
    std::vector<outer::StateBlock> blocks;
    if (n_normal() > 0) blocks.push_back({"r_n", n_normal()});
    if (n_shift() > 0) blocks.push_back({"A r", n_shift()});
    return blocks;
  }
  // The state of the reactions s.r holds.
  VectorXd state() const {
    VectorXd x(n_normal() + n_shift());
    for (Index i = 0; i < n_normal(); ++i)
      x(i) = s_.r(3 * i);
    if (n_shift() > 0) x.tail(n_shift()) = parts_.A * s_.r;
    return x;
  }
  outer::MapStep apply(int k, const VectorXd& x, VectorXd& image) override {
    if (n_normal() > 0) c_.set_disc_radii(p_.mu.cwiseProduct(x.head(n_normal()).cwiseMax(0.0)));
    const VectorXd q = n_shift() > 0 ? VectorXd(p_.q + x.tail(n_shift())) : p_.q;
    const qp::MpgpReport rep = qp::solve_mpgp_scaled(S_, -q, c_, D_, o_, s_.r);
    s_.qp_iterations += rep.iterations;
    s_.n_products += rep.n_products;
    image = state();
    if (rep.termination == qp::QpTermination::Converged) return {};
    return {outer::StepStatus::Failed,
            fmt::format("the QP of step {} did not converge: {}", k, rep.message)};
  }
  std::string stall_hint() const override {
    std::string hint;
    if (parts_.split)
      hint = fmt::format(
          "the splitting W = S + A (||A||/||S|| = {:.2e}) contracts only while A is small against "
          "S on the contacts that carry load",
          s_.norm_A / s_.norm_W);
    if (p_.is_coulomb())
      hint += std::string(hint.empty() ? "" : "; ") +
              "large coefficients of friction, or a singular S (rigid bodies), may make the "
              "Coulomb problem have several solutions";
    return hint;
  }

 private:
  const qp::LocalProblem& p_;
  const Parts& parts_;
  qp::Operator S_;
  const qp::BlockScaling& D_;
  qp::MpgpOptions o_;
  LocalSolution& s_;
  qp::SeparableConstraints c_;
};

// One Tresca QP with the given thresholds (W symmetric: no successive approximations needed).
void solve_tresca(const qp::LocalProblem& p, const Parts& parts, const qp::BlockScaling& D,
                  const qp::MpgpOptions& o, LocalSolution& s) {
  auto c = qp::SeparableConstraints::contact_layout(p.n_contacts());
  c.set_disc_radii(p.threshold);
  const qp::MpgpReport q = qp::solve_mpgp_scaled(parts.S_op(), -p.q, c, D, o, s.r);
  s.qp_iterations += q.iterations;
  s.n_products += q.n_products;
  s.outer_iterations += 1;
  s.termination = q.termination == qp::QpTermination::Converged ? outer::OuterTermination::Converged
                                                                : outer::OuterTermination::QpFailed;
  if (s.termination != outer::OuterTermination::Converged)
    s.reason = fmt::format("the QP did not converge: {}", q.message);
}

// The successive approximations (Coulomb, or W split), warm-started from the reactions s.r holds.
void solve_successive(const qp::LocalProblem& p, const Parts& parts, const qp::BlockScaling& D,
                      const qp::MpgpOptions& o, Real outer_tol, int outer_max, LocalSolution& s) {
  LocalMap map(p, parts, D, o, s);
  outer::OuterOptions oo;
  oo.tol = outer_tol;
  oo.max_iterations = outer_max;
  VectorXd x = map.state();
  const outer::OuterReport rep = outer::iterate(map, x, oo);
  s.outer_iterations += rep.iterations;
  s.termination = rep.termination;
  s.contraction = rep.contraction_ratio;
  s.last_changes.clear();
  if (!rep.block_history.empty()) {
    const std::vector<outer::StateBlock> blocks = map.layout();
    for (size_t b = 0; b < blocks.size(); ++b)
      s.last_changes.emplace_back(blocks[b].name, rep.block_history.back()[b]);
  }
  if (rep.converged()) return;
  s.reason = rep.message;
  if (s.last_changes.size() > 1) {
    s.reason += "; last relative change per block:";
    for (const auto& [name, change] : s.last_changes)
      s.reason += fmt::format(" {} {:.2e}", name, change);
  }
}

// A failed solve on a W whose symmetric part S is singular (rigid bodies: only positive
// semidefinite) or, by rounding in the code that wrote it, indefinite says so: the reactions are
// then not unique and MPGP's rate, which rests on S's smallest eigenvalue, is lost. The
// eigenvalues are those of S (the quadratic form r^T W r = r^T S r), never of one triangle of W.
void explain_singular(const qp::LocalProblem& p, const Parts& parts, LocalSolution& s) {
  if (p.q.size() > kDenseEigenLimit) return;
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(parts.S), Eigen::EigenvaluesOnly);
  const VectorXd& lambda = eig.eigenvalues();
  const Real ratio = lambda.minCoeff() / lambda.maxCoeff();
  const auto n_zero = (lambda.array().abs() <= kSingularRatio * lambda.maxCoeff()).count();
  const char* of = parts.split ? "the symmetric part (W + W^T)/2 of W" : "W";
  if (ratio < -kSingularRatio) {
    s.reason += fmt::format(
        "; {} is not positive semidefinite (lambda_min/lambda_max = {:.1e}): the QP is not "
        "convex, outside what MPGP solves",
        of, ratio);
  } else if (ratio <= kSingularRatio) {
    s.reason += fmt::format(
        "; {} is singular ({} of its {} eigenvalues are zero to {:.0e} lambda_max; "
        "lambda_min/lambda_max = {:.1e}): only positive semidefinite, so the reactions are not "
        "unique and MPGP loses its rate",
        of, n_zero, lambda.size(), kSingularRatio, ratio);
  }
}

// One attempt at the given tolerances, from the reactions s.r holds; then the certificate.
void attempt(const qp::LocalProblem& p, const Parts& parts, const qp::BlockScaling& D,
             const LocalSolveOptions& options, Real qp_rtol, Real outer_tol, LocalSolution& s) {
  qp::MpgpOptions o;
  o.variant = options.variant;
  o.expansion = options.expansion;
  o.active_discs = options.active_discs;
  o.rel_tolerance = qp_rtol;
  o.max_iterations = options.qp_max;
  o.norm_A = s.norm_W_scaled;
  s.reason.clear();
  if (p.is_coulomb() || parts.split) {
    solve_successive(p, parts, D, o, outer_tol, options.outer_max, s);
  } else {
    solve_tresca(p, parts, D, o, s);
  }
  s.u = p.W * s.r + p.q;
  const Real alpha = 1.0 / s.norm_W;
  s.residual = p.is_coulomb() ? qp::coulomb_residual(s.r, s.u, p.mu, alpha)
                              : qp::tresca_residual(s.r, s.u, p.threshold, alpha);
  s.merit = options.merit ? options.merit(s.r, s.u) : 0.0;
}

}  // namespace

qp::BlockScaling contact_scaling(const VectorXd& diagonal) {
  if (diagonal.size() % 3 != 0)
    throw InputError(
        fmt::format("contact_scaling: {} diagonal entries are not 3 per contact", diagonal.size()));
  const Index nc = diagonal.size() / 3;
  VectorXd factor(2 * nc);
  for (Index a = 0; a < nc; ++a) {
    const Real mean = diagonal.segment<3>(3 * a).mean();
    const Real d = mean > 0.0 && std::isfinite(mean) ? 1.0 / std::sqrt(mean) : 1.0;
    factor(2 * a) = factor(2 * a + 1) = d;
  }
  return qp::BlockScaling::per_block(qp::SeparableConstraints::contact_layout(nc), factor);
}

Asymmetry measure_asymmetry(const SparseMatrix& W) {
  if (W.rows() != W.cols())
    throw InputError(
        fmt::format("measure_asymmetry: W is {} x {}, not square", W.rows(), W.cols()));
  const SparseMatrix D = W - SparseMatrix(W.transpose());
  Asymmetry a;
  for (Index k = 0; k < D.nonZeros(); ++k)
    a.max_difference = std::max(a.max_difference, std::abs(D.valuePtr()[k]));
  for (Index k = 0; k < W.nonZeros(); ++k)
    a.max_entry = std::max(a.max_entry, std::abs(W.valuePtr()[k]));
  return a;
}

std::string describe_symmetry(const LocalSolution& s) {
  const std::string sizes =
      fmt::format("max|W - W^T| = {:.2e}, max|W| = {:.2e}, relative {:.1e}",
                  s.asymmetry.max_difference, s.asymmetry.max_entry, s.asymmetry.relative());
  if (!s.split) return fmt::format("symmetric ({})", sizes);
  std::string text = fmt::format(
      "NOT symmetric ({}): solved as S + A, S = (W + W^T)/2 the QPs' Hessian, A = (W - W^T)/2 "
      "with A r in q (||A||/||S|| = {:.2e}",
      sizes, s.norm_W > 0.0 ? s.norm_A / s.norm_W : 0.0);
  for (const auto& [name, change] : s.last_changes)
    if (name == "A r") text += fmt::format(", last relative change of A r {:.1e}", change);
  return text + ")";
}

LocalSolution solve_local(const qp::LocalProblem& p, const LocalSolveOptions& options) {
  const Stopwatch watch;
  check_problem(p);
  LocalSolution s;
  // @sect: W = S + A; S is the QPs' Hessian, A r moves into q when W is not symmetric.
  s.asymmetry = measure_asymmetry(p.W);
  Parts parts;
  const SparseMatrix Wt = p.W.transpose();
  parts.S = 0.5 * (p.W + Wt);
  parts.split = s.asymmetry.max_difference > options.symmetry_tol * s.asymmetry.max_entry;
  s.split = parts.split;
  if (parts.split) parts.A = 0.5 * (p.W - Wt);
  const qp::Operator S = parts.S_op();
  s.norm_W = qp::estimate_norm(S, p.q.size(), qp::kNormPowerIterations, qp::kNormPowerTolerance);
  if (parts.split)
    s.norm_A = qp::estimate_norm([&parts](const VectorXd& x, VectorXd& y) { y = parts.A * x; },
                                 p.q.size(), qp::kNormPowerIterations, qp::kNormPowerTolerance);
  s.r = VectorXd::Zero(p.q.size());
  if (!(s.norm_W > 0.0)) {
    s.reason = "the symmetric part of W is zero";
    return s;
  }
  // @sect: the scaled variables, and ||D S D|| behind MPGP's step length.
  const qp::BlockScaling D = options.scaling ? contact_scaling(parts.S.diagonal())
                                             : qp::BlockScaling::identity(p.q.size());
  s.norm_W_scaled = options.scaling
                        ? qp::estimate_norm(D.scaled(S), p.q.size(), qp::kNormPowerIterations,
                                            qp::kNormPowerTolerance)
                        : s.norm_W;
  if (!(s.norm_W_scaled > 0.0)) {
    s.reason = "D W D is zero";
    return s;
  }
  // @sect: solve, and refine while another code's merit is not yet met.
  Real qp_rtol = options.qp_rtol, outer_tol = options.outer_tol;
  attempt(p, parts, D, options, qp_rtol, outer_tol, s);
  while (s.termination == outer::OuterTermination::Converged &&
         (s.merit > options.merit_tol || s.residual > options.residual_tol) &&
         s.refinements < options.refinements) {
    qp_rtol *= kRefinementFactor;
    outer_tol *= kRefinementFactor;
    ++s.refinements;
    attempt(p, parts, D, options, qp_rtol, outer_tol, s);
  }
  // @sect: the certificate, whatever the iterations said.
  const bool certified = s.residual <= options.residual_tol && s.merit <= options.merit_tol;
  s.solved = s.termination == outer::OuterTermination::Converged && certified;
  if (s.termination == outer::OuterTermination::Converged && !certified) {
    s.termination = outer::OuterTermination::CertificateFailed;
    s.reason = fmt::format(
        "the answer's natural-map residual {:.2e} (tolerance {:.1e}) or merit {:.2e} (tolerance "
        "{:.1e}) is too large after {} refinements",
        s.residual, options.residual_tol, s.merit, options.merit_tol, s.refinements);
  }
  if (!s.solved) explain_singular(p, parts, s);
  s.seconds = watch.seconds();
  return s;
}

}  // namespace fricon::driver
