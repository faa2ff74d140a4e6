// Verification of the scaled dual (theory.md §4.5): the patch factors follow the half-space
// formula, and solving in scaled variables changes the iteration, not the answer. The graded-mesh
// counterpart (the Hertz example with and without scaling) is in
// tests/regression/check_geometry.py.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fricon/contact/dual_scaling.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

Problem with_scaling(Problem p, contact::DualScaling scaling) {
  p.solver.dual_scaling = scaling;
  return p;
}

}  // namespace

TEST(DualScaling, PatchFactorsAreTheHalfSpaceFormulaOfAreaAndModulus) {
  const Problem p = paper_problem(4, 6e4);
  PhaseTimes times;
  const Model m = assemble_model(p, times);
  const contact::ContactDiscretization disc = discretize_contact(p, m.mesh, m.dofs);
  const VectorXd d = contact::patch_scale_factors(m.mesh, disc.surface, disc.patches, m.materials);
  const Real E = p.material.young, nu = p.material.poisson;
  const Real M = E / (1.0 - nu * nu);
  EXPECT_NEAR(contact::indentation_modulus(m.materials.front()), M, 1e-12 * M);
  ASSERT_EQ(d.size(), disc.n_patches());
  for (Index q = 0; q < d.size(); ++q) {
    const Real A = disc.patches.area(q);
    const Real expected =
        std::sqrt(3.0 * std::pow(std::numbers::pi, 1.5) * M / 16.0) * std::pow(A, -0.75);
    EXPECT_NEAR(d(q), expected, 1e-12 * expected) << "patch " << q;
  }
}

TEST(DualScaling, ScaledAndUnscaledSolvesGiveTheSameMultipliersOnThePaperBrick) {
  Problem p = paper_problem(4, 6e4);
  p.solver.qp.rel_tolerance = 1e-10;
  const RunResult scaled = run(with_scaling(p, contact::DualScaling::Patch));
  const RunResult plain = run(with_scaling(p, contact::DualScaling::None));
  ASSERT_EQ(scaled.report.status, RunStatus::Converged) << scaled.report.message;
  ASSERT_EQ(plain.report.status, RunStatus::Converged) << plain.report.message;
  const VectorXd& a = scaled.contact->lambda;
  const VectorXd& b = plain.contact->lambda;
  EXPECT_LE((a - b).lpNorm<Eigen::Infinity>(), 1e-7 * b.lpNorm<Eigen::Infinity>());
}

TEST(DualScaling, OnTheUniformBrickThePaperCountsMoveByRoundingOnly) {
  // Equal patches get equal factors: the scaled QP is the unscaled one times a constant, so the
  // paper variant takes the same steps up to rounding (theory.md §4.5).
  Problem p = paper_problem(6, 6e4);
  p.solver.qp.variant = qp::MpgpVariant::Paper;
  const RunResult scaled = run(with_scaling(p, contact::DualScaling::Patch));
  const RunResult plain = run(with_scaling(p, contact::DualScaling::None));
  ASSERT_EQ(scaled.report.status, RunStatus::Converged) << scaled.report.message;
  ASSERT_EQ(plain.report.status, RunStatus::Converged) << plain.report.message;
  const auto& s = *scaled.report.contact;
  const auto& u = *plain.report.contact;
  EXPECT_EQ(s.outer_iterations, u.outer_iterations);
  EXPECT_NEAR(static_cast<double>(s.n_mult), static_cast<double>(u.n_mult), 0.01 * u.n_mult);
}
