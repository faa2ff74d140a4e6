// Verification of the contact search (theory.md §2.7): leaving patches out of the dual QP must
// not change the answer. Each case is solved with the search and with every patch
// (contact_search = "off"), and the two results are compared patch by patch; the search's
// certificate covers every patch, so a left-out patch that should press shows there.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "fricon/contact/candidates.hpp"
#include "fricon/driver/candidate_operators.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/driver/run_steps.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

// The paper's brick (n = 4) over a plane tilted about the y axis, falling away towards the loaded
// free end (2 mm over the brick's 3 m), so that the free displacement closes only part of the
// gap, and of that part only two patches end up pressing; Coulomb friction 0.3.
Problem tilted_coulomb_brick() {
  Problem p = paper_problem(4, 6e4);
  p.contact.front().model = contact::FrictionModel::Coulomb;
  p.contact.front().friction.law = contact::FrictionLawKind::Constant;
  p.contact.front().friction.value = 0.3;
  // z = -1e-5 - 2e-3 x [m] (nearly).
  p.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3(0.0, 0.0, -1.0e-5), Vec3(2.0e-3, 0.0, 1.0), ""};
  p.solver.qp.rel_tolerance = 1e-10;
  p.solver.outer.tol = 1e-8;
  return p;
}

Problem without_search(Problem p) {
  p.solver.contact_search = contact::ContactSearch::Off;
  return p;
}

// The largest difference of the multipliers of two runs, relative to the largest lambda_n.
Real max_difference(const RunResult& a, const RunResult& b) {
  const VectorXd& la = a.contact->lambda;
  const VectorXd& lb = b.contact->lambda;
  EXPECT_EQ(la.size(), lb.size());
  return (la - lb).lpNorm<Eigen::Infinity>() / std::max(lb.maxCoeff(), 1e-300);
}

// The run's steps up to the outer loop (as driver::run does), then the search from the given
// first candidates.
RunResult run_search_from(const Problem& problem, const std::vector<Index>& first) {
  RunResult r;
  r.model = assemble_model(problem, r.report.times);
  const contact::ContactDiscretization disc =
      discretize_contact(problem, r.model.mesh, r.model.dofs);
  factorize_model(r.model, dual::factorization_request(problem.solver.dual_operator, disc.dofs),
                  r.report.times);
  const RunOptions options;
  const std::unique_ptr<CandidateOperators> operators =
      make_candidate_operators(problem, r.model, options, r.report);
  const VectorXd u = solve_with_search(problem, disc, options, r, *operators, &first);
  finish_run(problem, u, r);
  return r;
}

}  // namespace

TEST(ContactSearch, LeavesOutTheFarPatchesAndGivesTheAnswerOfEveryPatch) {
  const Problem p = tilted_coulomb_brick();
  const RunResult all = run(without_search(p));
  const RunResult searched = run(p);
  ASSERT_EQ(all.report.status, RunStatus::Converged) << all.report.message;
  ASSERT_EQ(searched.report.status, RunStatus::Converged) << searched.report.message;
  const ContactReport& c = *searched.report.contact;
  // Some patches touch, some are left out, and the search needed no growth here.
  EXPECT_LT(c.n_candidate_patches, c.n_patches);
  EXPECT_GT(c.n_candidate_patches, 0);
  EXPECT_EQ(c.search_rounds, 1);
  EXPECT_GT(c.n_separated, 0);
  EXPECT_EQ(all.report.contact->search_rounds, 0);
  EXPECT_EQ(all.report.contact->n_candidate_patches, all.report.contact->n_patches);
  EXPECT_LE(max_difference(searched, all), 1e-7);
  // The certificate covers every patch: the report's sizes are the whole problem's.
  EXPECT_EQ(c.n_dual, 3 * c.n_patches);
  EXPECT_EQ(searched.contact->lambda.size(), c.n_dual);
  EXPECT_LE(c.kkt.max(), c.kkt_bound);
}

TEST(ContactSearch, AFirstSetTooSmallGrowsUntilNoPatchLeftOutPenetrates) {
  const Problem p = tilted_coulomb_brick();
  const RunResult all = run(without_search(p));
  ASSERT_EQ(all.report.status, RunStatus::Converged) << all.report.message;
  // Only the last patch to start with: the others that press must be found by the check.
  const Index n_patches = all.report.contact->n_patches;
  const RunResult grown = run_search_from(p, {n_patches - 1});
  ASSERT_EQ(grown.report.status, RunStatus::Converged) << grown.report.message;
  const ContactReport& c = *grown.report.contact;
  EXPECT_GE(c.search_rounds, 2);
  EXPECT_LE(max_difference(grown, all), 1e-7);
  // Every patch that presses in the whole answer is among the final candidates.
  Index pressing = 0;
  for (Index q = 0; q < n_patches; ++q)
    pressing += all.contact->lambda(3 * q) > 0.0 ? 1 : 0;
  EXPECT_GE(c.n_candidate_patches, pressing);
  EXPECT_LE(c.kkt.max(), c.kkt_bound);
}

TEST(ContactSearch, TrescaWithAPositiveBoundUsesEveryPatch) {
  // The Tresca bound g F acts without pressure: no patch can be left out.
  Problem p = paper_problem(4, 6e4);
  p.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3(0.0, 0.0, -1.0e-5), Vec3(1.0e-4, 0.0, 1.0), ""};
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  EXPECT_EQ(r.report.contact->search_rounds, 0);
  EXPECT_EQ(r.report.contact->n_candidate_patches, r.report.contact->n_patches);
}

TEST(ContactCandidates, FirstCandidatesAreThoseWithinTheMarginOfTheDeepestPenetration) {
  const VectorXd a = (VectorXd(5) << -3.0, 1.0, -0.5, 2.0, -2.5).finished();
  EXPECT_EQ(contact::initial_candidates(a, 0.0), (std::vector<Index>{1, 3}));
  EXPECT_EQ(contact::initial_candidates(a, 0.25), (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(contact::initial_candidates(a, 1.0), (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(contact::initial_candidates(a, 1.5), (std::vector<Index>{0, 1, 2, 3, 4}));
  // Nothing penetrates: the deepest patch alone.
  EXPECT_EQ(contact::initial_candidates(-a.cwiseAbs(), 1.0), (std::vector<Index>{2}));
  const std::vector<Index> left = contact::penetrating_patches(a, {1, 3}, 0.0);
  EXPECT_TRUE(left.empty());
  const VectorXd later = (VectorXd(5) << 1e-3, 1.0, -0.5, 2.0, 1e-9).finished();
  EXPECT_EQ(contact::penetrating_patches(later, {1, 3}, 1e-6), (std::vector<Index>{0}));
  EXPECT_EQ(contact::merge_patches({1, 3}, {0, 4}), (std::vector<Index>{0, 1, 3, 4}));
}
