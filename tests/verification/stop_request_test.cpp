// A stop request (Ctrl-C, SIGTERM: RunOptions::stop_requested) against the rule of issue 33,
// item 4: a run whose outer loop converged and whose certificate passed is a converged answer,
// whenever the stop arrives after that; a stop before convergence still stops the run, not
// converged, and a loading path stopped after a converged step keeps that step and ends there.
#include <gtest/gtest.h>

#include <atomic>

#include "common/fixtures.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

constexpr Index kPaperN = 4;          // the paper's smallest brick (theory.md §7.2)
constexpr Real kPaperParam = 6.0e4;   // Table 1's friction parameter [1/m]
constexpr int kElasticPathSteps = 3;  // an elastic path: no outer loop polls the stop

// The paper's brick with a stop requested after outer iteration `stop_at` (0: never).
RunResult brick_stopped_after(int stop_at) {
  std::atomic<bool> stop{false};
  RunOptions options;
  options.stop_requested = &stop;
  options.on_outer_iteration = [&](const IterationReport& it) {
    if (it.k == stop_at) stop = true;
  };
  return run(paper_problem(kPaperN, kPaperParam), options);
}

}  // namespace

TEST(StopRequest, AfterTheLastOuterIterationLeavesTheConvergedAnswerConverged) {
  const RunResult free_run = brick_stopped_after(0);
  ASSERT_EQ(free_run.report.status, RunStatus::Converged);
  const int last = free_run.report.contact->outer_iterations;
  const RunResult r = brick_stopped_after(last);
  EXPECT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  EXPECT_EQ(r.report.contact->termination, outer::OuterTermination::Converged);
  EXPECT_EQ(r.report.contact->outer_iterations, last);
  EXPECT_TRUE(r.report.message.empty()) << r.report.message;
}

TEST(StopRequest, BeforeConvergenceStopsTheRunNotConverged) {
  const RunResult r = brick_stopped_after(1);
  ASSERT_GT(brick_stopped_after(0).report.contact->outer_iterations, 1);
  EXPECT_EQ(r.report.status, RunStatus::NotConverged);
  EXPECT_EQ(r.report.contact->termination, outer::OuterTermination::Interrupted);
}

TEST(StopRequest, DuringALoadingPathKeepsTheConvergedStepAndEndsThePath) {
  Problem p = test::clamped_problem(false);
  p.loading.steps = kElasticPathSteps;
  p.traction.front().path = {1.0, 2.0, 3.0};
  std::atomic<bool> stop{false};
  RunOptions options;
  options.stop_requested = &stop;
  options.on_step = [&](const RunResult&) { stop = true; };
  const RunResult r = run(p, options);
  EXPECT_EQ(r.report.status, RunStatus::NotConverged);
  ASSERT_EQ(r.report.steps.size(), 1U);
  EXPECT_EQ(r.report.steps.front().status, RunStatus::Converged);
  EXPECT_NE(r.report.message.find("interrupted after step 1"), std::string::npos)
      << r.report.message;
}
