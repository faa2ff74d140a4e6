#include "fricon/qp/mpgp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/timer.hpp"

namespace fricon::qp {

// ---------------------------------------------------------------------------------------------
// Enum <-> string

std::string to_string(Termination t) {
  switch (t) {
    case Termination::Converged:
      return "converged";
    case Termination::MaxIterations:
      return "max_iterations";
    case Termination::NumericalFailure:
      return "numerical_failure";
    case Termination::UserStopped:
      return "user_stopped";
  }
  return "unknown";
}

std::string to_string(ProportioningStep s) {
  switch (s) {
    case ProportioningStep::ProjectedGradient:
      return "projected_gradient";
    case ProportioningStep::ChoppedGradientCG:
      return "chopped_gradient_cg";
  }
  return "unknown";
}

std::string to_string(ProportioningTest t) {
  switch (t) {
    case ProportioningTest::ReducedFree:
      return "reduced_free";
    case ProportioningTest::Free:
      return "free";
  }
  return "unknown";
}

std::string to_string(MpgpVariant v) {
  switch (v) {
    case MpgpVariant::Paper:
      return "paper";
    case MpgpVariant::BarzilaiBorwein:
      return "bb";
    case MpgpVariant::SpectralProjectedGradient:
      return "spg";
  }
  return "unknown";
}

MpgpVariant mpgp_variant_from_string(std::string_view s) {
  for (auto v :
       {MpgpVariant::Paper, MpgpVariant::BarzilaiBorwein, MpgpVariant::SpectralProjectedGradient}) {
    if (s == to_string(v)) return v;
  }
  throw InputError(fmt::format("qp variant = \"{}\" is not one of \"paper\", \"bb\", \"spg\"", s));
}

ProportioningStep proportioning_step_from_string(std::string_view s) {
  for (auto v : {ProportioningStep::ProjectedGradient, ProportioningStep::ChoppedGradientCG}) {
    if (s == to_string(v)) return v;
  }
  throw InputError(fmt::format(
      "proportioning = \"{}\" is not one of \"projected_gradient\", \"chopped_gradient_cg\"", s));
}

ProportioningTest proportioning_test_from_string(std::string_view s) {
  for (auto v : {ProportioningTest::ReducedFree, ProportioningTest::Free}) {
    if (s == to_string(v)) return v;
  }
  throw InputError(
      fmt::format("proportioning_test = \"{}\" is not one of \"reduced_free\", \"free\"", s));
}

// ---------------------------------------------------------------------------------------------
// Options and report

namespace {

template <typename T>
void require(bool ok, const char* field, T value, const char* range) {
  if (!ok) {
    throw InputError(
        fmt::format("MpgpOptions::{} = {} is out of range: expected {}", field, value, range));
  }
}

}  // namespace

void MpgpOptions::validate() const {
  require(std::isfinite(rel_tolerance) && rel_tolerance >= 0.0, "rel_tolerance", rel_tolerance,
          ">= 0");
  require(std::isfinite(abs_tolerance) && abs_tolerance >= 0.0, "abs_tolerance", abs_tolerance,
          ">= 0");
  require(max_iterations >= 0, "max_iterations", max_iterations, ">= 0");
  require(std::isfinite(gamma) && gamma > 0.0, "gamma", gamma, "> 0");
  require(std::isfinite(step_factor) && step_factor > 0.0 && step_factor <= 2.0, "step_factor",
          step_factor, "in (0, 2]");
  require(std::isfinite(norm_A) && norm_A >= 0.0, "norm_A", norm_A,
          ">= 0 (0 = estimate by power iteration)");
  require(power_iterations >= 1, "power_iterations", power_iterations, ">= 1");
  require(std::isfinite(power_tolerance) && power_tolerance > 0.0, "power_tolerance",
          power_tolerance, "> 0");
  require(std::isfinite(active_tolerance) && active_tolerance >= 0.0 && active_tolerance <= 1e-3,
          "active_tolerance", active_tolerance, "in [0, 1e-3]");
  require(proportioning == ProportioningStep::ProjectedGradient ||
              proportioning == ProportioningStep::ChoppedGradientCG,
          "proportioning", static_cast<int>(proportioning), "a ProportioningStep enumerator");
  require(proportioning_test == ProportioningTest::ReducedFree ||
              proportioning_test == ProportioningTest::Free,
          "proportioning_test", static_cast<int>(proportioning_test),
          "a ProportioningTest enumerator");
  require(variant == MpgpVariant::Paper || variant == MpgpVariant::BarzilaiBorwein ||
              variant == MpgpVariant::SpectralProjectedGradient,
          "variant", static_cast<int>(variant), "an MpgpVariant enumerator");
}

std::string MpgpReport::brief() const {
  if (variant == MpgpVariant::Paper) {
    return fmt::format(
        "MPGP {}: {} it ({} cg, {} exp, {} prop), {} products (+{} power), |gP|/|b| = {:.3e}",
        to_string(termination), iterations, n_cg, n_expansion, n_proportioning, n_products,
        n_power_products, rel_gp);
  }
  if (variant == MpgpVariant::SpectralProjectedGradient) {
    return fmt::format(
        "MPGP[spg] {}: {} it, {} products (+{} power, {} refresh), |gP|/|b| = {:.3e}",
        to_string(termination), iterations, n_products, n_power_products, n_refreshes, rel_gp);
  }
  return fmt::format(
      "MPGP[{}] {}: {} it ({} cg, {} exp, {} prop; {} fallback, {} refresh), {} products (+{} "
      "power), |gP|/|b| = {:.3e}",
      to_string(variant), to_string(termination), iterations, n_cg, n_expansion, n_proportioning,
      n_fallbacks, n_refreshes, n_products, n_power_products, rel_gp);
}

std::string MpgpReport::full() const {
  std::string s;
  auto line = [&s](std::string_view key, const std::string& value) {
    s += fmt::format("  {:<22} {}\n", key, value);
  };
  s += "MPGP report\n";
  line("termination", to_string(termination));
  line("message", message);
  line("variant", to_string(variant));
  line("iterations", std::to_string(iterations));
  line("n_cg", std::to_string(n_cg));
  line("n_expansion", std::to_string(n_expansion));
  line("n_proportioning", std::to_string(n_proportioning));
  line("n_gradient", std::to_string(n_gradient));
  line("n_fallbacks", std::to_string(n_fallbacks));
  line("n_refreshes", std::to_string(n_refreshes));
  line("n_products", std::to_string(n_products));
  line("n_power_products", std::to_string(n_power_products));
  line("norm_A_used",
       fmt::format("{:.6e} ({})", norm_A_used, norm_A_estimated ? "power iteration" : "given"));
  line("alpha_bar_used", fmt::format("{:.6e}", alpha_bar_used));
  line("norm_b", fmt::format("{:.6e}", norm_b));
  line("norm_gp", fmt::format("{:.6e}", norm_gp));
  line("rel_gp", fmt::format("{:.6e}", rel_gp));
  line("objective", fmt::format("{:.15e}", objective));
  line("n_objective_increases", std::to_string(n_objective_increases));
  line("seconds", fmt::format("{:.6f}", seconds));
  return s;
}

// ---------------------------------------------------------------------------------------------
// Power method

double estimate_norm(const Operator& A, Index n, int max_iterations, double tolerance,
                     long* n_products) {
  FRICON_CHECK(n >= 0, "n = " << n);
  if (n == 0 || max_iterations <= 0) return 0.0;
  Eigen::VectorXd v(n);
  Eigen::VectorXd w(n);
  // Deterministic, non-symmetric start vector with entries in [0.5, 1.5) (a 64-bit mix of i), so
  // that it is unlikely to be orthogonal to the dominant eigenvector of a structured A.
  for (Index i = 0; i < n; ++i) {
    std::uint64_t z = static_cast<std::uint64_t>(i + 1) * 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    v(i) = 0.5 + static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  v.normalize();
  double est = 0.0;
  for (int k = 1; k <= max_iterations; ++k) {
    A(v, w);
    if (n_products) ++*n_products;
    FRICON_CHECK(w.size() == n,
                 "operator returned a vector of size " << w.size() << ", expected " << n);
    const double nw = w.norm();
    if (!std::isfinite(nw)) {
      throw NumericalError(
          fmt::format("power iteration: ||A v|| = {} at step {} (n = {})", nw, k, n));
    }
    if (nw == 0.0) return 0.0;
    const double prev = est;
    est = nw;  // ||A v|| with ||v|| = 1: a lower bound of ||A||, nondecreasing for SPD A
    v = w / nw;
    if (k > 1 && std::abs(est - prev) <= tolerance * est) break;
  }
  return est;
}

// ---------------------------------------------------------------------------------------------
// MPGP

namespace {

/// Scalars of the gradient split at one point (method.md 4.1).
struct Split {
  double gp2 = 0.0;           ///< ||g^P||^2
  double phi2 = 0.0;          ///< ||phi||^2
  double beta2 = 0.0;         ///< ||beta||^2
  double phit_phi = 0.0;      ///< phitilde_{alpha_bar}^T phi
  bool beta_on_disc = false;  ///< beta has a nonzero Disc component
};

/// Block-wise kernels of MPGP for fixed constraints and tolerances.
class Kernels {
 public:
  Kernels(const SeparableConstraints& c, double tol_bound, double tol_disc, double alpha_bar)
      : c_(c), tol_bound_(tol_bound), tol_disc_(tol_disc), alpha_bar_(alpha_bar) {}

  /// Fills phi (free gradient) and beta (chopped gradient) for g at x and returns the norms.
  /// Active: Bound x_i <= tol_bound; Disc ||x_i|| >= (1 - tol_disc) rho_i (always for rho_i = 0,
  /// whose gradient parts are all 0).
  Split split(const Eigen::VectorXd& x, const Eigen::VectorXd& g, Eigen::VectorXd& phi,
              Eigen::VectorXd& beta) const {
    Split s;
    const double abar = alpha_bar_;
    for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
      const Index o = c_.blocks[k].offset;
      if (c_.blocks[k].kind == BlockKind::Bound) {
        const double xi = x(o);
        const double gi = g(o);
        if (xi <= tol_bound_) {
          const double bi = std::min(gi, 0.0);
          phi(o) = 0.0;
          beta(o) = bi;
          s.gp2 += bi * bi;
          s.beta2 += bi * bi;
        } else {
          phi(o) = gi;
          beta(o) = 0.0;
          s.gp2 += gi * gi;
          s.phi2 += gi * gi;
          // (x - max(x - abar g, 0)) / abar
          const double ti = gi > 0.0 ? std::min(gi, xi / abar) : gi;
          s.phit_phi += ti * gi;
        }
        continue;
      }
      const double rho = c_.radius(static_cast<Index>(k));
      const double x1 = x(o), x2 = x(o + 1);
      const double g1 = g(o), g2 = g(o + 1);
      const double nx = detail::norm2(x1, x2);
      if (rho == 0.0) {  // pinned block
        phi(o) = phi(o + 1) = beta(o) = beta(o + 1) = 0.0;
      } else if (nx >= (1.0 - tol_disc_) * rho) {  // active: nx > 0 here
        const double e1 = x1 / nx, e2 = x2 / nx;   // outward normal
        const double gn = std::min(e1 * g1 + e2 * g2, 0.0);
        const double b1 = g1 - gn * e1, b2 = g2 - gn * e2;
        phi(o) = phi(o + 1) = 0.0;
        beta(o) = b1;
        beta(o + 1) = b2;
        const double bb = b1 * b1 + b2 * b2;
        s.gp2 += bb;
        s.beta2 += bb;
        if (bb > 0.0) s.beta_on_disc = true;
      } else {
        phi(o) = g1;
        phi(o + 1) = g2;
        beta(o) = beta(o + 1) = 0.0;
        const double gg = g1 * g1 + g2 * g2;
        s.gp2 += gg;
        s.phi2 += gg;
        // (x - P_disc(x - abar g)) / abar
        const double y1 = x1 - abar * g1, y2 = x2 - abar * g2;
        const double ny = detail::norm2(y1, y2);
        if (ny <= rho) {
          s.phit_phi += gg;
        } else {
          const double t1 = (x1 - rho * y1 / ny) / abar;
          const double t2 = (x2 - rho * y2 / ny) / abar;
          s.phit_phi += t1 * g1 + t2 * g2;
        }
      }
    }
    return s;
  }

  /// Sum over the blocks of ||g_i|| ||x_i||: the scale of the rounding error of g^T d for a
  /// projected direction d (each d_i is exact only to about eps ||x_i||).
  double rounding_scale(const Eigen::VectorXd& x, const Eigen::VectorXd& g) const {
    double sum = 0.0;
    for (const Block& blk : c_.blocks) {
      const Index o = blk.offset;
      if (blk.kind == BlockKind::Bound) {
        sum += std::abs(g(o) * x(o));
      } else {
        sum += detail::norm2(g(o), g(o + 1)) * detail::norm2(x(o), x(o + 1));
      }
    }
    return sum;
  }

  /// Largest t >= 0 with x - t p in Omega (+inf if no block restricts); x must be feasible up to
  /// rounding.
  double max_feasible_step(const Eigen::VectorXd& x, const Eigen::VectorXd& p) const {
    double a = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < c_.blocks.size(); ++k) {
      const Index o = c_.blocks[k].offset;
      if (c_.blocks[k].kind == BlockKind::Bound) {
        if (p(o) > 0.0) a = std::min(a, std::max(x(o), 0.0) / p(o));
        continue;
      }
      const double p1 = p(o), p2 = p(o + 1);
      const double pp = p1 * p1 + p2 * p2;
      if (pp == 0.0) continue;
      const double rho = c_.radius(static_cast<Index>(k));
      const double x1 = x(o), x2 = x(o + 1);
      const double nx = detail::norm2(x1, x2);
      const double xp = x1 * p1 + x2 * p2;
      // Root t >= 0 of ||x - t p||^2 = rho^2: pp t^2 - 2 xp t - slack = 0, with slack =
      // rho^2 - ||x||^2 clipped at 0 (x may sit outside by rounding). The two algebraically equal
      // forms avoid cancellation for either sign of xp.
      const double slack = std::max((rho - nx) * (rho + nx), 0.0);
      const double sq = std::sqrt(xp * xp + pp * slack);
      const double t = xp >= 0.0 ? (xp + sq) / pp : (sq > xp ? slack / (sq - xp) : 0.0);
      a = std::min(a, t);
    }
    return a;
  }

 private:
  const SeparableConstraints& c_;
  double tol_bound_;
  double tol_disc_;
  double alpha_bar_;
};

/// Safety factor on the rounding level eps ||g|| ||x|| below which g^T d is trusted (see
/// spectral_move in solve_mpgp). Measured: 1 to 64 give about the same counts.
constexpr double kRoundingFactor = 4.0;

/// The adaptive Barzilai-Borwein length "ABBmin" (Frassoldati, Zanghirati and Zanni, 2008) of
/// the spectral moves: after a step s with y = A s, the long length a1 = s^T s / s^T y and the
/// short one a2 = s^T y / y^T y (a2 <= a1, both in [1/||A||, 1/lambda_min]); the next length is
/// the smallest a2 of the last kMemory steps when a2 / a1 < kTau (the step was dominated by large
/// eigenvalues), else a1. Clamped to [lo, hi]. kTau = 0.2 gave the fewest products on the
/// paper's problems among 0.1, 0.2, 0.3 and 0.5 (bench/qp_variants_bench.cpp); the memory 2 ... 5
/// hardly matters.
class SpectralLength {
 public:
  SpectralLength(double initial, double lo, double hi) : length_(initial), lo_(lo), hi_(hi) {}

  double length() const { return length_; }

  /// The last step through s^T s, s^T A s and (A s)^T (A s); a common positive factor cancels,
  /// so a direction d and its multiple t d give the same lengths. A step without positive
  /// curvature (or non-finite values) keeps the current length.
  void update(double ss, double sy, double yy) {
    if (!(ss > 0.0 && sy > 0.0 && yy > 0.0) || !std::isfinite(ss + sy + yy)) return;
    const double a1 = ss / sy;
    const double a2 = sy / yy;
    short_[count_ % kMemory] = a2;
    ++count_;
    double a = a1;
    if (a2 < kTau * a1) {
      a = a2;
      for (int k = 0; k < std::min(count_, kMemory); ++k)
        a = std::min(a, short_[static_cast<std::size_t>(k)]);
    }
    if (std::isfinite(a)) length_ = std::clamp(a, lo_, hi_);
  }

 private:
  static constexpr int kMemory = 3;
  static constexpr double kTau = 0.2;
  double length_;
  double lo_, hi_;
  std::array<double, kMemory> short_{};
  int count_ = 0;
};

}  // namespace

MpgpReport solve_mpgp(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
                      const MpgpOptions& opt, Eigen::VectorXd& x) {
  const Stopwatch watch;
  opt.validate();
  c.validate();
  if (!A) throw InputError("solve_mpgp: the operator A is empty");
  const Index n = c.size();
  if (b.size() != n || x.size() != n) {
    throw InputError(fmt::format(
        "solve_mpgp: the constraints cover {} unknowns but b has {} and x has {} entries", n,
        b.size(), x.size()));
  }
  if (!b.allFinite()) throw InputError("solve_mpgp: b has non-finite entries");
  if (!x.allFinite()) throw InputError("solve_mpgp: the initial guess x has non-finite entries");

  const MpgpVariant variant = opt.variant;
  MpgpReport rep;
  rep.variant = variant;
  rep.norm_b = b.norm();

  // Work vectors, allocated once: g = A x - b, p = search direction (also the projected-gradient
  // direction d of the spectral moves), Ap = A p (also A beta, A phi), phi = free gradient,
  // beta = chopped gradient.
  Eigen::VectorXd g(n), p(n), Ap(n), phi(n), beta(n);
  auto mult = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    A(in, out);
    ++rep.n_products;
    FRICON_CHECK(out.size() == n,
                 "operator returned a vector of size " << out.size() << ", expected " << n);
  };
  auto steps = [&rep]() {
    return rep.n_cg + rep.n_expansion + rep.n_proportioning + rep.n_gradient;
  };
  // Completes the report; called exactly once, by a return statement.
  auto finish = [&](Termination t, std::string message) -> MpgpReport {
    rep.termination = t;
    rep.message = std::move(message);
    rep.iterations = steps();
    rep.seconds = watch.seconds();
    return std::move(rep);
  };

  // b = 0: q(x) = x^T A x / 2 >= 0 = q(0) and 0 is feasible, so x = 0.
  if (rep.norm_b == 0.0) {
    x.setZero();
    mult(x, g);
    g -= b;
    rep.norm_gp = g.norm();  // every block is at an interior point or a pinned disc: g^P = g
    rep.rel_gp = rep.norm_gp;
    rep.objective = 0.0;
    if (rep.norm_gp == 0.0) {
      return finish(Termination::Converged, "b = 0: the solution is x = 0");
    }
    return finish(Termination::NumericalFailure,
                  fmt::format("b = 0 but A 0 has norm {}: A is not linear", rep.norm_gp));
  }

  // ||A|| and the fixed step length.
  if (opt.norm_A > 0.0) {
    rep.norm_A_used = opt.norm_A;
  } else {
    rep.norm_A_estimated = true;
    rep.norm_A_used =
        estimate_norm(A, n, opt.power_iterations, opt.power_tolerance, &rep.n_power_products);
  }
  if (!(rep.norm_A_used > 0.0) || !std::isfinite(rep.norm_A_used)) {
    throw NumericalError(
        fmt::format("solve_mpgp: ||A|| = {} ({}); A must be symmetric positive definite (n = {})",
                    rep.norm_A_used, rep.norm_A_estimated ? "power iteration" : "given", n));
  }
  const double abar = opt.step_factor / rep.norm_A_used;
  rep.alpha_bar_used = abar;

  // Line 1: start from the projection of the initial guess.
  c.project(x);
  const double x_scale =
      std::max({x.lpNorm<Eigen::Infinity>(), c.max_radius(), rep.norm_b / rep.norm_A_used});
  const Kernels kern(c, opt.active_tolerance * x_scale, opt.active_tolerance, abar);
  const double threshold = std::max(opt.rel_tolerance * rep.norm_b, opt.abs_tolerance);
  const double gamma2 = opt.gamma * opt.gamma;
  const bool reduced_test = opt.proportioning_test == ProportioningTest::ReducedFree;
  const bool chopped_cg = opt.proportioning == ProportioningStep::ChoppedGradientCG;
  // Trial lengths of the spectral moves (BarzilaiBorwein, SpectralProjectedGradient), starting
  // from alpha_bar. Every such length lies in [1/||A||, 1/lambda_min(A)]; the clamp only guards
  // against rounding.
  SpectralLength spectral(abar, 1e-3 / rep.norm_A_used, 1e12 / rep.norm_A_used);
  // True while g has been updated recursively (g -= a A p) since the last product A x; a variant
  // other than Paper then recomputes g before it accepts the stopping test.
  bool recursive = false;

  mult(x, g);
  g -= b;
  Split s = kern.split(x, g, phi, beta);
  p = phi;

  auto objective = [&]() { return 0.5 * (x.dot(g) - x.dot(b)); };  // q = x^T (g - b) / 2
  auto norm_gp = [&]() { return std::sqrt(s.gp2); };

  MpgpIteration it;
  it.iteration = 0;
  it.step = 's';
  it.norm_gp = norm_gp();
  it.norm_phi = std::sqrt(s.phi2);
  it.norm_beta = std::sqrt(s.beta2);
  it.objective = objective();
  double q_prev = it.objective;
  if (opt.record_history) rep.history.push_back(it);
  bool stopped = opt.monitor && !opt.monitor(it);

  auto set_final = [&]() {
    rep.norm_gp = norm_gp();
    rep.rel_gp = rep.norm_gp / rep.norm_b;
    rep.objective = objective();
  };
  // Rounding allowance of a comparison of objective values.
  auto q_tolerance = [&](double q_a, double q_b) {
    return 1e-12 * std::max({std::abs(q_a), std::abs(q_b), rep.norm_b * x_scale});
  };
  // Line 3 and the other stopping tests; returns the final report if the solver stops.
  auto stop_test = [&]() -> std::optional<MpgpReport> {
    if (recursive && std::isfinite(s.gp2) && norm_gp() <= threshold) {
      mult(x, g);  // certify the test with the exact gradient
      g -= b;
      s = kern.split(x, g, phi, beta);
      p = phi;  // restart the CG direction (the free set is the same, phi has changed)
      q_prev = objective();
      ++rep.n_refreshes;
      recursive = false;
    }
    if (!std::isfinite(s.gp2) || !std::isfinite(q_prev)) {
      set_final();
      return finish(Termination::NumericalFailure,
                    fmt::format("non-finite gradient or objective after {} iterations", steps()));
    }
    const int done = steps();
    if (norm_gp() <= threshold) {
      set_final();
      return finish(Termination::Converged,
                    fmt::format("||g^P|| = {:.3e} <= {:.3e} after {} iterations", rep.norm_gp,
                                threshold, done));
    }
    if (stopped) {
      set_final();
      return finish(Termination::UserStopped,
                    fmt::format("stopped by the monitor after {} iterations", done));
    }
    if (done >= opt.max_iterations) {
      set_final();
      return finish(Termination::MaxIterations,
                    fmt::format("reached max_iterations = {} with ||g^P|| / ||b|| = {:.3e} "
                                "(target {:.3e})",
                                opt.max_iterations, rep.rel_gp, threshold / rep.norm_b));
    }
    return std::nullopt;
  };
  // After a step: the monitor record, the monotonicity count, history and monitor.
  auto step_done = [&]() {
    it.iteration = steps();
    it.norm_gp = norm_gp();
    it.norm_phi = std::sqrt(s.phi2);
    it.norm_beta = std::sqrt(s.beta2);
    it.objective = objective();
    // With alpha_bar <= 2/||A|| no step increases q; count increases beyond rounding.
    if (it.objective > q_prev + q_tolerance(q_prev, it.objective)) ++rep.n_objective_increases;
    q_prev = it.objective;
    if (opt.record_history) rep.history.push_back(it);
    if (opt.monitor && !opt.monitor(it)) stopped = true;
  };
  // The spectral move from x along the projected direction d = P(x - a v) - x, a the current
  // spectral length, v = g or phi (v is the gradient restricted to the blocks d may move, so
  // g^T d = v^T d <= -||d||^2 / a < 0 for d != 0): x := x + t d with t = min(1, -g^T d / d^T A d),
  // the exact minimiser of q on the segment [x, x + d] (which lies in Omega); 1 product.
  // Each block of d carries a rounding error of order eps ||x_i|| (a projection puts a point on a
  // circle only to rounding) and g is large on active blocks (the normal forces), so g^T d can be
  // trusted only below -eps sum_i ||g_i|| ||x_i|| (times a safety factor). Near the solution it no
  // longer is; then the move is Paper's fixed-length one, x := P(x - alpha_bar v), monotone without
  // a line search, with g recomputed (also 1 product; counted in n_fallbacks). Returns the length
  // of the move along -v (t a or alpha_bar), or a negative value if A is found not positive
  // definite along d.
  auto spectral_move = [&](const Eigen::VectorXd& v) -> double {
    const double a = spectral.length();
    p = x - a * v;
    c.project(p);
    p -= x;
    const double gd = g.dot(p);
    if (!(gd <
          -kRoundingFactor * std::numeric_limits<double>::epsilon() * kern.rounding_scale(x, g))) {
      x.noalias() -= abar * v;
      c.project(x);
      mult(x, g);
      g -= b;
      recursive = false;
      ++rep.n_fallbacks;
      return abar;
    }
    mult(p, Ap);
    const double dAd = p.dot(Ap);
    if (!(dAd > 0.0) || !std::isfinite(dAd)) return -1.0;
    const double t = std::min(1.0, -gd / dAd);
    x.noalias() += t * p;
    g.noalias() += t * Ap;
    c.project(x);  // only removes rounding-level infeasibility (x + t d is a convex combination)
    recursive = true;
    spectral.update(p.squaredNorm(), dAd, Ap.squaredNorm());
    return t * a;
  };

  if (variant == MpgpVariant::SpectralProjectedGradient) {
    while (true) {
      if (auto r = stop_test()) return std::move(*r);
      const double a = spectral_move(g);
      ++rep.n_gradient;
      if (a < 0.0) {
        set_final();
        return finish(Termination::NumericalFailure,
                      "spectral projected gradient step: A is not positive definite along the "
                      "projected gradient direction");
      }
      s = kern.split(x, g, phi, beta);
      it.step = 'g';
      it.alpha = a;
      step_done();
    }
  }

  const bool bb = variant == MpgpVariant::BarzilaiBorwein;
  while (true) {
    if (auto r = stop_test()) return std::move(*r);

    // Line 4: proportionality test.
    const double rhs = gamma2 * (reduced_test ? s.phit_phi : s.phi2);
    if (s.beta2 <= rhs) {
      // Lines 5-12.
      mult(p, Ap);
      const double pAp = p.dot(Ap);
      const double a_cg = g.dot(p) / pAp;
      if (!(pAp > 0.0) || !std::isfinite(pAp) || !(a_cg > 0.0) || !std::isfinite(a_cg)) {
        ++rep.n_cg;  // the product was spent on this (failed) step
        set_final();
        return finish(Termination::NumericalFailure,
                      fmt::format("CG step: p^T A p = {:.3e}, step {:.3e}; A is not positive "
                                  "definite along p, or the direction is not a descent direction",
                                  pAp, a_cg));
      }
      const double a_f = kern.max_feasible_step(x, p);
      if (a_cg <= a_f) {
        // Lines 7-8: CG step inside the feasible set.
        if (bb) spectral.update(p.squaredNorm(), pAp, Ap.squaredNorm());
        x.noalias() -= a_cg * p;
        g.noalias() -= a_cg * Ap;
        c.project(x);  // only removes rounding-level infeasibility when a_cg ~ a_f
        s = kern.split(x, g, phi, beta);
        const double beta_cg = phi.dot(Ap) / pAp;
        p = phi - beta_cg * p;
        ++rep.n_cg;
        it.step = 'c';
        it.alpha = a_cg;
        recursive = variant != MpgpVariant::Paper;
      } else {
        // Lines 10-12: to the boundary, then a projected free-gradient move.
        x.noalias() -= a_f * p;
        g.noalias() -= a_f * Ap;
        kern.split(x, g, phi, beta);
        if (bb) {
          if (spectral_move(phi) < 0.0) {
            ++rep.n_expansion;
            set_final();
            return finish(Termination::NumericalFailure,
                          "expansion step: A is not positive definite along the projected "
                          "free-gradient direction");
          }
        } else {
          x.noalias() -= abar * phi;
          c.project(x);
          mult(x, g);
          g -= b;
          recursive = false;
        }
        s = kern.split(x, g, phi, beta);
        p = phi;
        ++rep.n_expansion;
        it.step = 'e';
        it.alpha = a_f;
      }
    } else {
      // Line 14: proportioning.
      if (chopped_cg && !s.beta_on_disc) {
        // 14(a): exact minimisation along -beta (beta <= 0 on bounds, so x stays feasible).
        mult(beta, Ap);
        const double bAb = beta.dot(Ap);
        const double a = s.beta2 / bAb;  // g^T beta = ||beta||^2
        if (!(bAb > 0.0) || !std::isfinite(a)) {
          ++rep.n_proportioning;
          set_final();
          return finish(Termination::NumericalFailure,
                        fmt::format("proportioning step: beta^T A beta = {:.3e}; A is not "
                                    "positive definite along beta",
                                    bAb));
        }
        if (bb) spectral.update(s.beta2, bAb, Ap.squaredNorm());
        x.noalias() -= a * beta;
        g.noalias() -= a * Ap;
        c.project(x);
        it.alpha = a;
        recursive = variant != MpgpVariant::Paper;
      } else if (bb) {
        // 14(b) with the spectral length and the exact line search.
        const double a = spectral_move(g);
        if (a < 0.0) {
          ++rep.n_proportioning;
          set_final();
          return finish(Termination::NumericalFailure,
                        "proportioning step: A is not positive definite along the projected "
                        "gradient direction");
        }
        it.alpha = a;
      } else {
        // 14(b): projected gradient step of fixed length.
        x.noalias() -= abar * g;
        c.project(x);
        mult(x, g);
        g -= b;
        it.alpha = abar;
        recursive = false;
      }
      s = kern.split(x, g, phi, beta);
      p = phi;  // line 15
      ++rep.n_proportioning;
      it.step = 'p';
    }
    step_done();
  }
}

}  // namespace fricon::qp
