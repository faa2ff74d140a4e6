#pragma once
// Test problems and reference computations for the qp unit tests. Everything here is written
// independently of src/fricon/qp (own projection, own objective, own reference solvers), so the
// tests compare the module against separate truth.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "common/random_spd.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/operator.hpp"

namespace fricon::qp::testing {

/// Dense operator y = M x; counts calls in *calls if given.
inline Operator dense_operator(const Eigen::MatrixXd& M, long* calls = nullptr) {
  return [&M, calls](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    if (calls) ++*calls;
    y.noalias() = M * x;
  };
}

using fricon::test::random_spd;  // tests/common/random_spd.hpp, shared with bench/qp_bench.cpp

inline Eigen::VectorXd random_vector(Index n, std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (Index i = 0; i < n; ++i)
    v(i) = N(rng);
  return v;
}

/// q(x) = x^T M x / 2 - b^T x, evaluated directly.
inline double objective(const Eigen::MatrixXd& M, const Eigen::VectorXd& b,
                        const Eigen::VectorXd& x) {
  return 0.5 * x.dot(M * x) - b.dot(x);
}

/// Own projection onto Omega (not SeparableConstraints::project).
inline Eigen::VectorXd reference_project(const SeparableConstraints& c, Eigen::VectorXd x) {
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Index o = c.blocks[k].offset;
    if (c.blocks[k].kind == BlockKind::Free) continue;  // unconstrained: x_i stays
    if (c.blocks[k].kind == BlockKind::Bound) {
      if (x(o) < 0.0) x(o) = 0.0;
    } else {
      const double r = c.radius(static_cast<Index>(k));
      const Eigen::Vector2d v(x(o), x(o + 1));
      const double nv = v.norm();
      if (nv > r) x.segment<2>(o) = (r / nv) * v;
    }
  }
  return x;
}

/// Reference minimiser of q over Omega: FISTA with gradient-based restart and step 1/lambda_max
/// (lambda_max from an eigen-decomposition), run until the gradient map is below tol * ||b||.
inline Eigen::VectorXd reference_solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& b,
                                       const SeparableConstraints& c, double tol = 1e-13,
                                       int max_iterations = 200000) {
  const double L = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().maxCoeff();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  Eigen::VectorXd y = x;
  double t = 1.0;
  const double target = tol * std::max(b.norm(), 1e-300);
  for (int k = 0; k < max_iterations; ++k) {
    const Eigen::VectorXd xn = reference_project(c, y - (M * y - b) / L);
    if ((y - xn).dot(xn - x) > 0.0) t = 1.0;  // restart when momentum points uphill
    const double tn = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * t * t));
    y = xn + ((t - 1.0) / tn) * (xn - x);
    x = xn;
    t = tn;
    if (k % 20 == 0) {
      const Eigen::VectorXd map = L * (x - reference_project(c, x - (M * x - b) / L));
      if (map.norm() <= target) break;
    }
  }
  return x;
}

/// Exact minimiser of q over {x >= 0} by enumerating all active sets (n <= ~12).
inline Eigen::VectorXd enumerate_bound_solution(const Eigen::MatrixXd& M,
                                                const Eigen::VectorXd& b) {
  const Index n = b.size();
  Eigen::VectorXd best;
  double best_violation = INFINITY;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {  // bit i set: x_i is free
    std::vector<Index> F;
    for (Index i = 0; i < n; ++i)
      if (mask & (1u << i)) F.push_back(i);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    if (!F.empty()) {
      const Index m = static_cast<Index>(F.size());
      Eigen::MatrixXd MFF(m, m);
      Eigen::VectorXd bF(m);
      for (Index i = 0; i < m; ++i) {
        bF(i) = b(F[i]);
        for (Index j = 0; j < m; ++j)
          MFF(i, j) = M(F[i], F[j]);
      }
      const Eigen::VectorXd xF = MFF.llt().solve(bF);
      for (Index i = 0; i < m; ++i)
        x(F[i]) = xF(i);
    }
    const Eigen::VectorXd g = M * x - b;
    double violation = 0.0;  // x >= 0 on F, g >= 0 on the complement
    for (Index i = 0; i < n; ++i) {
      violation = std::max(violation, (mask & (1u << i)) ? -x(i) : -g(i));
    }
    if (violation < best_violation) {
      best_violation = violation;
      best = x;
    }
  }
  return best;
}

/// Solution of min q over the disc ||x|| <= rho for a 2x2 SPD M: x = (M + s I)^-1 b with s >= 0
/// the root of ||(M + s I)^-1 b|| = rho (secular equation, bisection), or M^-1 b if inside.
inline Eigen::Vector2d trust_region_2d(const Eigen::Matrix2d& M, const Eigen::Vector2d& b,
                                       double rho) {
  const Eigen::Vector2d xu = M.llt().solve(b);
  if (xu.norm() <= rho) return xu;
  double lo = 0.0, hi = b.norm() / rho;  // at s = hi: ||(M + sI)^-1 b|| <= ||b|| / s = rho
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    const Eigen::Vector2d xm = (M + mid * Eigen::Matrix2d::Identity()).llt().solve(b);
    (xm.norm() > rho ? lo : hi) = mid;
  }
  return (M + hi * Eigen::Matrix2d::Identity()).llt().solve(b);
}

/// Contact layout with random radii: each disc gets u * ||tangential part of M^-1 b|| with u
/// uniform in [0.2, 1.5] (so about half of the discs end up active), or 0 with probability 0.1.
inline SeparableConstraints random_contact_constraints(const Eigen::MatrixXd& M,
                                                       const Eigen::VectorXd& b,
                                                       std::mt19937& rng) {
  const Index n_patches = b.size() / 3;
  SeparableConstraints c = SeparableConstraints::contact_layout(n_patches);
  const Eigen::VectorXd xu = M.llt().solve(b);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::VectorXd r(n_patches);
  for (Index i = 0; i < n_patches; ++i) {
    const double u = U(rng);
    r(i) = u < 0.1 ? 0.0 : (0.2 + 1.3 * U(rng)) * xu.segment<2>(3 * i + 1).norm();
  }
  c.set_disc_radii(r);
  return c;
}

}  // namespace fricon::qp::testing
