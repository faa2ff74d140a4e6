#include "fricon/driver/local_solve.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/friction_cone.hpp"

namespace fricon::driver {

namespace {

// Power iteration for ||W||, as for the dual Hessian of fricon's own problems.
constexpr int kPowerIterations = 200;
constexpr Real kPowerTolerance = 1e-10;
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

// Coulomb by successive approximations on the normal reactions: the radii of step k are
// mu_R r_n^(k-1)(R), the first step the frictionless problem (theory.md §5.6).
class LocalCoulombMap final : public outer::FixedPointMap {
 public:
  LocalCoulombMap(const qp::LocalProblem& p, const qp::Operator& W, const qp::BlockScaling& D,
                  const qp::MpgpOptions& o, LocalSolution& s)
      : p_(p),
        W_(W),
        D_(D),
        o_(o),
        s_(s),
        c_(qp::SeparableConstraints::contact_layout(p.n_contacts())) {}
  std::vector<outer::StateBlock> layout() const override { return {{"r_n", p_.n_contacts()}}; }
  outer::StepResult apply(int k, const VectorXd& r_n, VectorXd& image) override {
    c_.set_disc_radii(p_.mu.cwiseProduct(r_n.cwiseMax(0.0)));
    const qp::MpgpReport q = qp::solve_mpgp_scaled(W_, -p_.q, c_, D_, o_, s_.r);
    s_.qp_iterations += q.iterations;
    s_.n_products += q.n_products;
    image.resize(p_.n_contacts());
    for (Index i = 0; i < p_.n_contacts(); ++i)
      image(i) = s_.r(3 * i);
    if (q.termination == qp::Termination::Converged) return {};
    return {outer::StepStatus::Failed,
            fmt::format("the QP of step {} did not converge: {}", k, q.message)};
  }
  std::string stall_hint() const override {
    return "large coefficients of friction may make the Coulomb problem have several solutions";
  }

 private:
  const qp::LocalProblem& p_;
  const qp::Operator& W_;
  const qp::BlockScaling& D_;
  qp::MpgpOptions o_;
  LocalSolution& s_;
  qp::SeparableConstraints c_;
};

// One Tresca QP with the given thresholds.
void solve_tresca(const qp::LocalProblem& p, const qp::Operator& W, const qp::BlockScaling& D,
                  const qp::MpgpOptions& o, LocalSolution& s) {
  auto c = qp::SeparableConstraints::contact_layout(p.n_contacts());
  c.set_disc_radii(p.threshold);
  const qp::MpgpReport q = qp::solve_mpgp_scaled(W, -p.q, c, D, o, s.r);
  s.qp_iterations += q.iterations;
  s.n_products += q.n_products;
  s.outer_iterations += 1;
  s.termination = q.termination == qp::Termination::Converged ? outer::Termination::Converged
                                                              : outer::Termination::QpFailed;
  if (s.termination != outer::Termination::Converged)
    s.reason = fmt::format("the QP did not converge: {}", q.message);
}

void solve_coulomb(const qp::LocalProblem& p, const qp::Operator& W, const qp::BlockScaling& D,
                   const qp::MpgpOptions& o, Real outer_tol, int outer_max, LocalSolution& s) {
  LocalCoulombMap map(p, W, D, o, s);
  outer::OuterOptions oo;
  oo.tol = outer_tol;
  oo.max_iterations = outer_max;
  VectorXd r_n(p.n_contacts());  // warm start from the reactions s.r holds
  for (Index i = 0; i < p.n_contacts(); ++i)
    r_n(i) = s.r(3 * i);
  const outer::OuterReport rep = outer::iterate(map, r_n, oo);
  s.outer_iterations += rep.iterations;
  s.termination = rep.termination;
  if (!rep.converged()) s.reason = rep.message;
}

// A failed solve on a W that is singular (rigid bodies: W only positive semidefinite) or, by
// rounding in the code that wrote it, indefinite says so: the reactions are then not unique and
// MPGP's rate, which rests on W's smallest eigenvalue, is lost.
void explain_singular(const qp::LocalProblem& p, LocalSolution& s) {
  if (p.q.size() > kDenseEigenLimit) return;
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(p.W), Eigen::EigenvaluesOnly);
  const Real ratio = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  if (ratio < -kSingularRatio) {
    s.reason += fmt::format(
        "; W is not positive semidefinite (lambda_min/lambda_max = {:.1e}): the QP is not "
        "convex, outside what MPGP solves",
        ratio);
  } else if (ratio < kSingularRatio) {
    s.reason += fmt::format(
        "; W is singular (lambda_min/lambda_max = {:.1e}): only positive semidefinite, so the "
        "reactions are not unique and MPGP loses its rate",
        ratio);
  }
}

// One attempt at the given tolerances, from the reactions s.r holds; then the certificate.
void attempt(const qp::LocalProblem& p, const qp::Operator& W, const qp::BlockScaling& D,
             const LocalSolveOptions& options, Real qp_rtol, Real outer_tol, LocalSolution& s) {
  qp::MpgpOptions o;
  o.variant = options.variant;
  o.expansion = options.expansion;
  o.rel_tolerance = qp_rtol;
  o.max_iterations = options.qp_max;
  o.norm_A = s.norm_W_scaled;
  s.reason.clear();
  if (p.is_coulomb()) {
    solve_coulomb(p, W, D, o, outer_tol, options.outer_max, s);
  } else {
    solve_tresca(p, W, D, o, s);
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

LocalSolution solve_local(const qp::LocalProblem& p, const LocalSolveOptions& options) {
  const Stopwatch watch;
  check_problem(p);
  LocalSolution s;
  const qp::Operator W = [&p](const VectorXd& x, VectorXd& y) { y = p.W * x; };
  s.norm_W = qp::estimate_norm(W, p.q.size(), kPowerIterations, kPowerTolerance);
  s.r = VectorXd::Zero(p.q.size());
  if (!(s.norm_W > 0.0)) {
    s.reason = "W is zero";
    return s;
  }
  // @sect: the scaled variables, and ||D W D|| behind MPGP's step length.
  const qp::BlockScaling D =
      options.scaling ? contact_scaling(p.W.diagonal()) : qp::BlockScaling::identity(p.q.size());
  s.norm_W_scaled = options.scaling ? qp::estimate_norm(D.scaled(W), p.q.size(), kPowerIterations,
                                                        kPowerTolerance)
                                    : s.norm_W;
  if (!(s.norm_W_scaled > 0.0)) {
    s.reason = "D W D is zero";
    return s;
  }
  // @sect: solve, and refine while another code's merit is not yet met.
  Real qp_rtol = options.qp_rtol, outer_tol = options.outer_tol;
  attempt(p, W, D, options, qp_rtol, outer_tol, s);
  while (s.termination == outer::Termination::Converged &&
         (s.merit > options.merit_tol || s.residual > options.residual_tol) &&
         s.refinements < options.refinements) {
    qp_rtol *= kRefinementFactor;
    outer_tol *= kRefinementFactor;
    ++s.refinements;
    attempt(p, W, D, options, qp_rtol, outer_tol, s);
  }
  // @sect: the certificate, whatever the iterations said.
  const bool certified = s.residual <= options.residual_tol && s.merit <= options.merit_tol;
  s.solved = s.termination == outer::Termination::Converged && certified;
  if (s.termination == outer::Termination::Converged && !certified) {
    s.termination = outer::Termination::CertificateFailed;
    s.reason = fmt::format(
        "the answer's natural-map residual {:.2e} (tolerance {:.1e}) or merit {:.2e} (tolerance "
        "{:.1e}) is too large after {} refinements",
        s.residual, options.residual_tol, s.merit, options.merit_tol, s.refinements);
  }
  if (!s.solved) explain_singular(p, s);
  s.seconds = watch.seconds();
  return s;
}

}  // namespace fricon::driver
