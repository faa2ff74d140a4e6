// Benchmarks of the qp module: solve_mpgp on random dense SPD "dual" problems with the contact
// layout (one bound and one disc per patch), at the sizes of the model example's multiplier
// spaces (36, 144, 576, 1296, 2304 unknowns: n = 4, 8, 16, 24, 32), for the default QP variant
// (bb) and the paper's (paper), plus one dense product for reference (a solve costs about
// n_products of them). Products go through BLAS dsymv, as in the driver. ||A|| is computed once
// outside the timed loop, as the driver does.

#include <cstdint>
#include <random>

#include <benchmark/benchmark.h>
#include <Eigen/Dense>

#include "fricon/linalg/blas.hpp"
#include "fricon/qp/mpgp.hpp"
#include "tests/common/random_spd.hpp"

namespace {

using fricon::Index;
using fricon::qp::SeparableConstraints;

struct DualProblem {
  Eigen::MatrixXd Q;
  Eigen::VectorXd h;
  SeparableConstraints c;
  double norm_Q = 0.0;
};

// Q = V diag(lambda) V^T with lambda log-spaced in [1, cond] and a random orthogonal V
// (tests/common/random_spd.hpp, as the QP unit tests); h random; disc radii a random fraction
// (0.2 ... 1.5) of the tangential part of the unconstrained solution, so that roughly half of the
// discs end up active; fixed seed.
DualProblem make_problem(Index n_unknowns, double cond, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.2, 1.5);
  DualProblem p;
  p.Q = fricon::test::random_spd(n_unknowns, cond, rng);
  p.norm_Q = cond;  // the largest eigenvalue
  p.h.resize(n_unknowns);
  for (Index i = 0; i < n_unknowns; ++i)
    p.h(i) = N(rng);
  const Index n_patches = n_unknowns / 3;
  p.c = SeparableConstraints::contact_layout(n_patches);
  const Eigen::VectorXd xu = p.Q.llt().solve(p.h);
  Eigen::VectorXd rho(n_patches);
  for (Index i = 0; i < n_patches; ++i)
    rho(i) = U(rng) * xu.segment<2>(3 * i + 1).norm();
  p.c.set_disc_radii(rho);
  return p;
}

void BM_SolveMpgp(benchmark::State& state) {
  const DualProblem p = make_problem(state.range(0), 100.0, 2009);
  const fricon::qp::Operator A = [&p](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    fricon::linalg::symmetric_product(p.Q, x, y);
  };
  fricon::qp::MpgpOptions opt;  // rel_tolerance 1e-6, as in [HL09]
  opt.norm_A = p.norm_Q;
  opt.variant = static_cast<fricon::qp::MpgpVariant>(state.range(1));
  state.SetLabel(std::string(fricon::enum_name(opt.variant)));
  Eigen::VectorXd x(p.h.size());
  fricon::qp::MpgpReport rep;
  for (auto _ : state) {
    x.setZero();
    rep = fricon::qp::solve_mpgp(A, p.h, p.c, opt, x);
    benchmark::DoNotOptimize(x.data());
  }
  if (rep.termination != fricon::qp::QpTermination::Converged) state.SkipWithError("not converged");
  state.counters["iterations"] = rep.iterations;
  state.counters["n_products"] = static_cast<double>(rep.n_products);
  state.counters["n_expansion"] = rep.n_expansion;
  state.counters["n_proportioning"] = rep.n_proportioning;
}
BENCHMARK(BM_SolveMpgp)
    ->ArgsProduct({{36, 144, 576, 1296, 2304},
                   {static_cast<int64_t>(fricon::qp::MpgpVariant::BarzilaiBorwein),
                    static_cast<int64_t>(fricon::qp::MpgpVariant::Paper)}})
    ->ArgNames({"n_dual", "variant"})
    ->Unit(benchmark::kMicrosecond);

void BM_DenseProduct(benchmark::State& state) {
  const DualProblem p = make_problem(state.range(0), 100.0, 2009);
  Eigen::VectorXd x = p.h, y(p.h.size());
  for (auto _ : state) {
    fricon::linalg::symmetric_product(p.Q, x, y);
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(BM_DenseProduct)
    ->Arg(36)
    ->Arg(144)
    ->Arg(576)
    ->Arg(1296)
    ->Arg(2304)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
