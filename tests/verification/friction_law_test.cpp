// The paper's brick with the paper's law given as a formula (law "expression") and as code
// (law "function"): the radii are then integrated by adaptive quadrature instead of exactly
// (theory.md §2.6), and the solution must be the same as with law "paper".
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

// The paper's law (theory.md §7, param = 6e4 1/m) as a muparser formula, and its kinks [m].
constexpr const char* kPaperExpression = "max(0.2, min(0.3, 0.3 - 0.05*6e4*(t - 1e-5)))";
const std::vector<Real> kPaperKinks = {1e-5, 1e-5 + 2.0 / 6e4};

Problem tight_paper_problem() {
  Problem p = paper_problem(4, 6e4);
  p.solver.qp.rel_tolerance = 1e-11;
  return p;
}

Real relative_difference(const VectorXd& a, const VectorXd& b) {
  return (a - b).norm() / b.norm();
}

void expect_same_solution(const RunResult& r, const RunResult& ref) {
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& c = *r.report.contact;
  const ContactReport& c_ref = *ref.report.contact;
  EXPECT_EQ(c.outer_iterations, c_ref.outer_iterations);
  ASSERT_EQ(c.err_history.size(), c_ref.err_history.size());
  for (size_t k = 1; k < c.err_history.size(); ++k)
    EXPECT_NEAR(c.err_history[k], c_ref.err_history[k], 1e-6 * c_ref.err_history[k]) << k;
  EXPECT_LT(relative_difference(r.contact->radius, ref.contact->radius), 1e-8);
  EXPECT_LT(relative_difference(r.contact->lambda, ref.contact->lambda), 1e-8);
  EXPECT_LT(relative_difference(r.contact->phi, ref.contact->phi), 1e-8);
}

}  // namespace

TEST(FrictionLawKinds, PaperLawAsAnExpressionGivesThePaperSolution) {
  const RunResult ref = run(tight_paper_problem());
  ASSERT_EQ(ref.report.status, RunStatus::Converged) << ref.report.message;
  EXPECT_EQ(ref.report.contact->radius_integration, contact::kRadiusIntegration);

  Problem p = tight_paper_problem();
  p.contact.front().friction.law = contact::FrictionLawKind::Expression;
  p.contact.front().friction.expression = kPaperExpression;
  p.contact.front().friction.kinks = kPaperKinks;
  const RunResult r = run(p);
  expect_same_solution(r, ref);
  EXPECT_EQ(r.report.contact->friction_law,
            std::string("expression(\"") + kPaperExpression + "\")");
  EXPECT_EQ(r.report.contact->radius_integration,
            "adaptive Gauss-Kronrod (7-15) on the level-line reduction, rtol 1e-10, split at "
            "kinks (2 given)");
}

TEST(FrictionLawKinds, PaperLawAsAFunctionGivesThePaperSolutionInFewCalls) {
  const RunResult ref = run(tight_paper_problem());
  const auto paper = contact::paper_law(6e4);
  int calls = 0;
  Problem p = tight_paper_problem();
  p.contact.front().friction.law = contact::FrictionLawKind::Function;
  p.contact.front().friction.kinks = kPaperKinks;
  p.contact.front().friction.function_name = "paper_copy";
  p.contact.front().friction.function = [&](std::span<const Real> t, std::span<Real> out) {
    ++calls;
    for (size_t i = 0; i < t.size(); ++i)
      out[i] = (*paper)(t[i]);
  };
  const RunResult r = run(p);
  expect_same_solution(r, ref);
  EXPECT_EQ(r.report.contact->friction_law, "function(paper_copy)");
  // One call per radii computation (kinks given: no bisection, one computation per outer
  // iteration) and one for the coefficients at the nodes.
  EXPECT_LE(calls, r.report.contact->outer_iterations + 2);
  EXPECT_GT(calls, 0);
}
