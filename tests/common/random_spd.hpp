#pragma once
// A random symmetric positive definite matrix of a chosen condition number: the QP unit tests'
// problems (tests/unit/qp/qp_test_problems.hpp) and bench/qp_bench.cpp's. Header only, so that the
// benches can use it without the test libraries.
#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "fricon/core/types.hpp"

namespace fricon::test {

/// Q diag(lambda) Q^T times `scale`, with Q orthogonal (the QR factor of a matrix of standard
/// normal entries drawn from `rng`, column by column) and the eigenvalues lambda log-spaced in
/// [1, cond]; n >= 1, cond >= 1.
inline Eigen::MatrixXd random_spd(Index n, double cond, std::mt19937& rng, double scale = 1.0) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd G(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i)
      G(i, j) = N(rng);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
  Eigen::VectorXd lam(n);
  for (Index i = 0; i < n; ++i) {
    lam(i) = n == 1 ? 1.0 : std::pow(cond, static_cast<double>(i) / static_cast<double>(n - 1));
  }
  Eigen::MatrixXd M = scale * Q * lam.asDiagonal() * Q.transpose();
  return 0.5 * (M + M.transpose());
}

}  // namespace fricon::test
