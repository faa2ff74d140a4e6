#include "fricon/feti/softness.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "fricon/core/parallel_for.hpp"

namespace fricon::feti {

namespace {

// The angular step of the start vector's entries sin(k (i + 1)): a fixed vector with a part
// along every eigenvector in practice, the same on every run and process.
constexpr Real kStartStep = 0.7548776662466927;

// lambda_7(K_s) / mean(diag K_s) of subdomain s, from above: power steps with P K_s^+ P, where
// P projects onto the complement of R_s. For x orthogonal to R_s, P K_reg^-1 x is the
// pseudo-inverse's K_s^+ x (theory.md §8.9), so the Rayleigh quotients rise to 1 / lambda_7.
Real relative_softness(const Subdomain& s) {
  const Index n = s.n_dofs();
  if (n <= kSubdomainMotions || s.stiffness_diagonal.size() != n) return 1.0;
  const MatrixXd Q = Eigen::HouseholderQR<MatrixXd>(s.R).householderQ() *
                     MatrixXd::Identity(n, s.R.cols());  // orthonormal columns spanning R_s
  const auto project = [&Q](VectorXd& v) { v.noalias() -= Q * (Q.transpose() * v); };
  VectorXd x(n);
  for (Index i = 0; i < n; ++i)
    x(i) = std::sin(kStartStep * static_cast<Real>(i + 1));
  project(x);
  x.normalize();
  Real compliance = 0.0;  // the largest Rayleigh quotient of P K_s^+ P so far [m/N]
  for (int step = 0; step < kSoftnessSteps; ++step) {
    VectorXd y = s.factor.solve(x);
    project(y);
    compliance = std::max(compliance, x.dot(y));
    const Real norm = y.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    x = y / norm;
  }
  const Real mean_diagonal = s.stiffness_diagonal.mean();
  return compliance > 0.0 && mean_diagonal > 0.0 ? 1.0 / (compliance * mean_diagonal) : 1.0;
}

Real median_of(std::vector<Real> v) {
  if (v.empty()) return 0.0;
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

}  // namespace

Softness subdomain_softness(const std::vector<Subdomain>& subdomains, int threads,
                            const Ranks& ranks) {
  const auto n = static_cast<Index>(subdomains.size());
  // @sect: this process's subdomains, then the sum over the processes (zero elsewhere).
  VectorXd relative = VectorXd::Zero(n);
  const auto [first, last] = ranks.block(n);
  parallel_for(last - first, threads, [&](Index k, int) {
    relative(first + k) = relative_softness(subdomains[static_cast<size_t>(first + k)]);
  });
  ranks.sum(relative);

  // @sect: the softest one against the median, and those past kNeckRatio.
  Softness soft;
  soft.relative.assign(relative.data(), relative.data() + n);
  if (n == 0) return soft;
  soft.median = median_of(soft.relative);
  soft.softest = static_cast<Index>(std::min_element(soft.relative.begin(), soft.relative.end()) -
                                    soft.relative.begin());
  const Real softest = soft.relative[static_cast<size_t>(soft.softest)];
  soft.ratio = softest > 0.0 ? soft.median / softest : 1.0;
  for (Index i = 0; i < n; ++i)
    if (soft.relative[static_cast<size_t>(i)] * kNeckRatio <= soft.median) soft.necked.push_back(i);
  return soft;
}

}  // namespace fricon::feti
