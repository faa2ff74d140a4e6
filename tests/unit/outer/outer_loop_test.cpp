// The outer loop as a unit, on maps whose fixed points and behaviour are known in closed form:
// a linear contraction (its fixed point solves a linear system), a map that collapses to zero,
// a two-cycle, failing and interrupted steps, and a two-block state.
#include "fricon/outer/outer_loop.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fricon/core/error.hpp"
#include "fricon/outer/anderson.hpp"

namespace fricon::outer {
namespace {

// A map given by a function of (k, x), with one block or the blocks given.
class FunctionMap final : public FixedPointMap {
 public:
  using Step = std::function<MapStep(int, const VectorXd&, VectorXd&)>;
  FunctionMap(std::vector<StateBlock> blocks, Step step)
      : blocks_(std::move(blocks)), step_(std::move(step)) {}
  std::vector<StateBlock> layout() const override { return blocks_; }
  MapStep apply(int k, const VectorXd& x, VectorXd& image) override {
    ++calls;
    return step_(k, x, image);
  }
  std::string stall_hint() const override { return "the test's map cycles"; }
  int calls = 0;

 private:
  std::vector<StateBlock> blocks_;
  Step step_;
};

// x -> A x + b with ||A|| < 1: the fixed point solves (I - A) x = b.
struct Affine {
  MatrixXd A;
  VectorXd b;
  FunctionMap map() const {
    return FunctionMap({{"x", b.size()}}, [this](int, const VectorXd& x, VectorXd& image) {
      image = A * x + b;
      return MapStep{};
    });
  }
  VectorXd fixed_point() const {
    return (MatrixXd::Identity(b.size(), b.size()) - A).partialPivLu().solve(b);
  }
};

Affine rotation_contraction(Real rate) {
  // A rotation by 60 degrees scaled by `rate`, in two 2 x 2 blocks: a contraction that is not
  // symmetric (plain iteration converges only linearly, Anderson accelerates it).
  Affine a;
  a.A = MatrixXd::Zero(4, 4);
  const Real c = 0.5, s = 0.8660254037844386;
  a.A.block<2, 2>(0, 0) << c, -s, s, c;
  a.A.block<2, 2>(2, 2) << c, s, -s, c;
  a.A *= rate;
  // The fixed point (1, 2, 3, 4) is positive, as the states the loop iterates are (Anderson's
  // iterates are clipped at 0).
  const VectorXd x_star = (VectorXd(4) << 1.0, 2.0, 3.0, 4.0).finished();
  a.b = x_star - a.A * x_star;
  return a;
}

TEST(OuterLoop, ContractionConvergesToItsFixedPoint) {
  const Affine a = rotation_contraction(0.5);
  FunctionMap map = a.map();
  OuterOptions o;
  o.tol = 1e-10;
  VectorXd x = VectorXd::Zero(4);
  const OuterReport rep = iterate(map, x, o);
  ASSERT_EQ(rep.termination, OuterTermination::Converged) << rep.message;
  EXPECT_TRUE(rep.converged());
  EXPECT_LT((x - a.fixed_point()).norm(), 1e-9 * a.fixed_point().norm());
  EXPECT_EQ(rep.iterations, static_cast<int>(rep.err_history.size()));
  EXPECT_LE(rep.err_history.back(), o.tol);
  EXPECT_EQ(rep.fixed_point_residual, rep.err_history.back());
  // err(k) of an affine map with rate 1/2 falls by about 1/2 per step.
  EXPECT_NEAR(rep.contraction_ratio, 0.5, 0.1);
}

TEST(OuterLoop, AndersonMixingReachesTheSameFixedPointFaster) {
  const Affine a = rotation_contraction(0.9);
  OuterOptions o;
  o.tol = 1e-10;
  o.max_iterations = 500;
  // err(k) = ||Psi(x) - x|| / ||Psi(x)|| is not monotone on a rotating map (||Psi(x)|| swings
  // while the iterates spiral in), so the stall test is widened here.
  o.stall_window = 100;
  FunctionMap plain_map = a.map();
  VectorXd plain = VectorXd::Zero(4);
  const OuterReport p = iterate(plain_map, plain, o);
  o.acceleration = Acceleration::Anderson;
  o.anderson_depth = 3;
  FunctionMap mixed_map = a.map();
  VectorXd mixed = VectorXd::Zero(4);
  const OuterReport m = iterate(mixed_map, mixed, o);
  ASSERT_TRUE(p.converged()) << p.message;
  ASSERT_TRUE(m.converged()) << m.message;
  EXPECT_LT(m.iterations, p.iterations / 2);
  EXPECT_LT((mixed - a.fixed_point()).norm(), 1e-8 * a.fixed_point().norm());
}

TEST(OuterLoop, AnImageThatCollapsesToZeroIsNotConvergence) {
  // Psi(0) = (1, 1, 1); Psi(x) = 0 otherwise. At k = 2 the image is zero while the state is
  // not: err(2) is a change of everything (1), not 0. At k = 3 both are zero: converged.
  FunctionMap map({{"phi", 3}}, [](int k, const VectorXd&, VectorXd& image) {
    image = k == 1 ? VectorXd::Ones(3) : VectorXd::Zero(3);
    return MapStep{};
  });
  VectorXd x = VectorXd::Zero(3);
  const OuterReport rep = iterate(map, x, OuterOptions{});
  ASSERT_EQ(rep.err_history.size(), 3u);
  EXPECT_EQ(rep.err_history[0], 1.0);
  EXPECT_EQ(rep.err_history[1], 1.0);
  EXPECT_EQ(rep.err_history[2], 0.0);
  EXPECT_EQ(rep.termination, OuterTermination::Converged);
}

TEST(OuterLoop, RelativeChangeOfZeroVectors) {
  const VectorXd zero = VectorXd::Zero(2), one = VectorXd::Ones(2);
  EXPECT_EQ(relative_change(zero, zero), 0.0);
  EXPECT_EQ(relative_change(zero, one), 1.0);
  EXPECT_DOUBLE_EQ(relative_change(one, zero), 1.0);
  EXPECT_DOUBLE_EQ(relative_change(2 * one, one), 0.5);
}

TEST(OuterLoop, ABlockWithAScaleConvergesToZero) {
  // A block halved at every step, as the pressures of a step unloaded to nothing decay to the
  // answer 0: relative to itself its change stays 1 (never converged); relative to a scale that
  // does not vanish (StateBlock::scale) it falls below any tolerance.
  EXPECT_DOUBLE_EQ(relative_change(VectorXd::Constant(1, 1e-12), VectorXd::Constant(1, 2e-12)),
                   1.0);
  EXPECT_DOUBLE_EQ(relative_change(VectorXd::Constant(1, 1e-12), VectorXd::Constant(1, 2e-12), 1.0),
                   1e-12);
  EXPECT_DOUBLE_EQ(relative_change(VectorXd::Constant(1, 4.0), VectorXd::Constant(1, 2.0), 1.0),
                   0.5);  // a scale below the norm changes nothing
  FunctionMap map({{"lambda_n", 2, 1.0}}, [](int, const VectorXd& x, VectorXd& image) {
    image = 0.5 * x;
    return MapStep{};
  });
  VectorXd x = VectorXd::Ones(2);
  OuterOptions o;
  o.tol = 1e-6;
  const OuterReport rep = iterate(map, x, o);
  EXPECT_EQ(rep.termination, OuterTermination::Converged) << rep.message;
  EXPECT_LE(x.norm(), 1e-5);
}

TEST(OuterLoop, ATwoCycleStallsWithinTheWindowAndSaysWhy) {
  FunctionMap map({{"phi", 2}}, [](int k, const VectorXd&, VectorXd& image) {
    image = (k % 2 == 0 ? 1.0 : 3.0) * VectorXd::Ones(2);
    return MapStep{};
  });
  OuterOptions o;
  o.max_iterations = 50;
  VectorXd x = VectorXd::Zero(2);
  const OuterReport rep = iterate(map, x, o);
  EXPECT_EQ(rep.termination, OuterTermination::Stalled);
  EXPECT_LE(rep.iterations, o.stall_window + 3);
  EXPECT_NE(rep.message.find("do not contract"), std::string::npos) << rep.message;
  EXPECT_NE(rep.message.find("the test's map cycles"), std::string::npos) << rep.message;
  EXPECT_TRUE(stalled(rep.err_history, static_cast<size_t>(o.stall_window)));
}

TEST(OuterLoop, IterationLimitIsReportedWithTheHistory) {
  const Affine a = rotation_contraction(0.9);
  FunctionMap map = a.map();
  OuterOptions o;
  o.tol = 1e-12;
  o.max_iterations = 3;
  VectorXd x = VectorXd::Zero(4);
  const OuterReport rep = iterate(map, x, o);
  EXPECT_EQ(rep.termination, OuterTermination::IterationLimit);
  EXPECT_EQ(rep.iterations, 3);
  EXPECT_NE(rep.message.find("did not reach"), std::string::npos) << rep.message;
  EXPECT_NE(rep.message.find("err(k):"), std::string::npos);
}

TEST(OuterLoop, AFailedOrInterruptedStepStopsTheLoopWithItsReason) {
  FunctionMap failing({{"phi", 1}}, [](int k, const VectorXd&, VectorXd& image) {
    image = VectorXd::Constant(1, k);
    return k == 2 ? MapStep{StepStatus::Failed, "the QP failed"} : MapStep{};
  });
  VectorXd x = VectorXd::Zero(1);
  OuterReport rep = iterate(failing, x, OuterOptions{});
  EXPECT_EQ(rep.termination, OuterTermination::QpFailed);
  EXPECT_EQ(rep.message, "the QP failed");
  EXPECT_EQ(rep.iterations, 2);
  EXPECT_EQ(x(0), 1.0);  // the state the failed step started from

  FunctionMap stopped({{"phi", 1}}, [](int, const VectorXd&, VectorXd& image) {
    image = VectorXd::Ones(1);
    return MapStep{StepStatus::Interrupted, "stopped"};
  });
  x.setZero();
  rep = iterate(stopped, x, OuterOptions{});
  EXPECT_EQ(rep.termination, OuterTermination::Interrupted);
  EXPECT_EQ(rep.iterations, 1);

  // A stop request ends the loop after the iteration in progress.
  const Affine a = rotation_contraction(0.9);
  FunctionMap map = a.map();
  std::atomic<bool> stop{true};
  x = VectorXd::Zero(4);
  rep = iterate(map, x, OuterOptions{}, {}, &stop);
  EXPECT_EQ(rep.termination, OuterTermination::Interrupted);
  EXPECT_EQ(map.calls, 1);
}

TEST(OuterLoop, AStopRequestedOnceTheIterationConvergedKeepsItConverged) {
  // Issue 33, item 4: the inner solve of the iteration ended normally and err(k) <= tol, so the
  // state is a fixed point to the tolerance; a stop request that comes after it is too late to
  // undo that.
  FunctionMap fixed({{"phi", 1}}, [](int, const VectorXd&, VectorXd& image) {
    image = VectorXd::Ones(1);  // x = 1 is the fixed point: err(1) = 0
    return MapStep{};
  });
  VectorXd x = VectorXd::Ones(1);
  std::atomic<bool> stop{true};
  const OuterReport rep = iterate(fixed, x, OuterOptions{}, {}, &stop);
  EXPECT_EQ(rep.termination, OuterTermination::Converged);
  EXPECT_EQ(rep.iterations, 1);
}

TEST(OuterLoop, ErrIsTheLargestRelativeChangeOfTheBlocks) {
  // Block "phi" settles at once, block "lambda_n" halves its distance to 8 every step: the
  // loop stops on the slower block, and the monitor sees both changes.
  FunctionMap map({{"phi", 2}, {"lambda_n", 1}}, [](int, const VectorXd& x, VectorXd& image) {
    image.resize(3);
    image << 1.0, 1.0, 0.5 * (x(2) + 8.0);
    return MapStep{};
  });
  OuterOptions o;
  o.tol = 1e-6;
  std::vector<OuterIteration> seen;
  VectorXd x = VectorXd::Zero(3);
  const OuterReport rep = iterate(map, x, o, [&](const OuterIteration& it) { seen.push_back(it); });
  ASSERT_TRUE(rep.converged());
  ASSERT_EQ(seen.size(), static_cast<size_t>(rep.iterations));
  for (const auto& it : seen) {
    ASSERT_EQ(it.block_err.size(), 2u);
    EXPECT_EQ(it.err, std::max(it.block_err[0], it.block_err[1]));
  }
  EXPECT_EQ(seen[2].block_err[0], 0.0);
  EXPECT_GT(seen[2].block_err[1], 0.1);
  EXPECT_NEAR(x(2), 8.0, 1e-4);
}

TEST(OuterLoop, RejectsInvalidOptionsAndAStateOfTheWrongSize) {
  const Affine a = rotation_contraction(0.5);
  FunctionMap map = a.map();
  VectorXd x = VectorXd::Zero(4);
  OuterOptions o;
  o.tol = 0.0;
  EXPECT_THROW(iterate(map, x, o), InputError);
  o = {};
  o.anderson_depth = 21;
  EXPECT_THROW(iterate(map, x, o), InputError);
  o = {};
  o.stall_window = 0;
  EXPECT_THROW(iterate(map, x, o), InputError);
  VectorXd wrong = VectorXd::Zero(3);
  EXPECT_THROW(iterate(map, wrong, OuterOptions{}), InputError);
}

TEST(AndersonMixing, DepthZeroIsThePlainIterationAndResultsAreClipped) {
  AndersonMixing plain(0);
  const VectorXd x = VectorXd::Ones(3), g = 2 * VectorXd::Ones(3);
  EXPECT_EQ(plain.next(x, g), g);
  EXPECT_EQ(plain.next(g, 3 * VectorXd::Ones(3)), 3 * VectorXd::Ones(3));
  // On a scalar affine map g = 0.5 x - 1 (fixed point -2), one Anderson step with depth 1 is
  // the secant step, exact for an affine map, but clipped at the lower bound 0.
  AndersonMixing mix(1, 0.0);
  VectorXd x0 = VectorXd::Constant(1, 4.0), g0 = VectorXd::Constant(1, 1.0);
  EXPECT_EQ(mix.next(x0, g0)(0), 1.0);
  const VectorXd x1 = g0, g1 = VectorXd::Constant(1, -0.5);
  EXPECT_EQ(mix.next(x1, g1)(0), 0.0);
  AndersonMixing unclipped(1, -1e300);
  unclipped.next(x0, g0);
  EXPECT_NEAR(unclipped.next(x1, g1)(0), -2.0, 1e-12);
}

}  // namespace
}  // namespace fricon::outer
