// The final Coulomb problem of a fricon run, as an FCLIB local problem (W = Q, q = -h, mu per
// patch, contacts ordered (n, t1, t2); theory.md §5.6), solved by another code: Siconos' nonsmooth
// Newton method on the Alart-Curnier formulation (NSN_AC) and its block Gauss-Seidel (NSGS). Both
// must find fricon's multipliers to 1e-6 relative, on the paper's brick with F = 0.3 and with the
// paper's F(||u_t||) frozen at fricon's solution. Built only where Siconos is installed.
#include <gtest/gtest.h>

#include "common/siconos_solve.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"

using namespace fricon;

namespace {

struct Coulomb {
  MatrixXd W;
  VectorXd q, mu, lambda;  // lambda: fricon's answer [Pa]
};

// fricon's Coulomb solution of the paper's brick (n = 4), tight, and its final local problem.
Coulomb fricon_coulomb(contact::FrictionLawKind law) {
  driver::Problem p = driver::paper_problem(4, 6e4);
  p.contact.front().model = contact::FrictionModel::Coulomb;
  p.contact.front().friction.law = law;
  p.contact.front().friction.value = 0.3;
  p.solver.qp.rel_tolerance = 1e-12;
  p.solver.outer.tol = 1e-11;
  driver::RunOptions o;
  o.keep_first_dual = true;  // Q and h are those of every outer iteration
  const driver::RunResult r = driver::run(p, o);
  EXPECT_EQ(r.report.status, driver::RunStatus::Converged) << r.report.message;
  return {r.first_dual->Q, -r.first_dual->h, r.contact->coefficient, r.contact->lambda};
}

// Siconos' answer, on the problem scaled to unit ||W|| and unit multipliers (the cone and the
// solution do not change under the scaling; it only brings Siconos' absolute tolerances to a
// meaningful size).
VectorXd siconos_solve(const Coulomb& c, int solver) {
  const double norm_W = c.W.norm(), L = c.lambda.cwiseAbs().maxCoeff();
  const test::SiconosSolution s =
      test::siconos_solve(c.W / norm_W, c.q / (norm_W * L), c.mu, solver, 1e-13, 100000);
  EXPECT_EQ(s.info, 0) << "Siconos solver " << solver << " did not converge";
  return L * s.r;
}

void expect_same_multipliers(contact::FrictionLawKind law) {
  const Coulomb c = fricon_coulomb(law);
  for (const int solver : {SICONOS_FRICTION_3D_NSN_AC, SICONOS_FRICTION_3D_NSGS}) {
    const VectorXd l = siconos_solve(c, solver);
    EXPECT_LT((l - c.lambda).norm(), 1e-6 * c.lambda.norm())
        << "Siconos solver " << solver << ", law " << enum_name(law);
  }
}

}  // namespace

TEST(CoulombAgainstSiconos, ConstantCoefficient) {
  expect_same_multipliers(contact::FrictionLawKind::Constant);
}

TEST(CoulombAgainstSiconos, ThePapersCoefficientFrozenAtTheSolution) {
  expect_same_multipliers(contact::FrictionLawKind::Paper);
}
