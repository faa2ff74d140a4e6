// The friction laws given by a formula ("expression") or by code ("function"), and the radii of
// laws that are not piecewise linear: adaptive Gauss-Kronrod on the level-line reduction
// (theory.md §2.6). The truths are the exact radii of the piecewise-linear path and closed-form
// integrals.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <random>

#include "common/fixtures.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/core/error.hpp"

using namespace fricon;
using namespace fricon::contact;
using ::testing::HasSubstr;

namespace {

// The paper's law (theory.md §7) written as a formula, and its kinks [m].
constexpr const char* kPaperExpression = "max(0.2, min(0.3, 0.3 - 0.05*6e4*(t - 1e-5)))";
const std::vector<Real> kPaperKinks = {1e-5, 1e-5 + 2.0 / 6e4};

// A smooth law: 0.1 + 0.4 exp(-t / c), c [m].
constexpr const char* kSmoothExpression = "0.1 + 0.4*exp(-t/5e-5)";
constexpr Real kSmoothDecay = 5e-5;

FrictionLawSpec expression_spec(const std::string& expression, std::vector<Real> kinks = {},
                                Real rtol = kDefaultQuadratureRtol) {
  FrictionLawSpec s;
  s.law = FrictionLawKind::Expression;
  s.expression = expression;
  s.kinks = std::move(kinks);
  s.quadrature_rtol = rtol;
  return s;
}

Real max_relative_difference(const VectorXd& a, const VectorXd& b) {
  return ((a - b).array().abs() / b.array().abs()).maxCoeff();
}

// Random nodal slips in [0, phi_max] [m] and slip bounds in [1e7, 3e7] Pa.
void random_fields(const test::ClampedBrick& b, Real phi_max, VectorXd& phi, VectorXd& g) {
  std::mt19937 gen(12345);
  std::uniform_real_distribution<Real> u(0.0, 1.0);
  phi.resize(b.surface.n_nodes());
  g.resize(b.surface.n_nodes());
  for (Index k = 0; k < phi.size(); ++k) {
    phi(k) = phi_max * u(gen);
    g(k) = 1e7 + 2e7 * u(gen);
  }
}

}  // namespace

TEST(ExpressionLaw, ValuesDescriptionAndQuadratureKeys) {
  const auto F = make_friction_law(expression_spec(kSmoothExpression, {1e-4}, 1e-8));
  EXPECT_NEAR((*F)(0.0), 0.5, 1e-15);
  EXPECT_NEAR((*F)(1e-4), 0.1 + 0.4 * std::exp(-2.0), 1e-15);
  EXPECT_FALSE(F->piecewise_linear());
  EXPECT_EQ(F->quadrature_rtol(), 1e-8);
  EXPECT_EQ(F->kinks(), std::vector<Real>{1e-4});
  EXPECT_TRUE(std::isnan(F->lipschitz()));
  EXPECT_EQ(F->describe(), "expression(\"0.1 + 0.4*exp(-t/5e-5)\")");
  const std::vector<Real> t = {0.0, 5e-5, 1.0};
  std::vector<Real> out(3);
  F->evaluate(t, out);
  for (size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(out[i], 0.1 + 0.4 * std::exp(-t[i] / kSmoothDecay), 1e-15);
  // The paper's formula gives the paper's values.
  const auto E = make_friction_law(expression_spec(kPaperExpression, kPaperKinks));
  const auto P = paper_law(6e4);
  for (Real s : {0.0, 1e-5, 2e-5, 3e-5, 4e-5, 1e-3})
    EXPECT_NEAR((*E)(s), (*P)(s), 1e-15) << s;
  EXPECT_THAT(radius_integration(*E), HasSubstr("adaptive Gauss-Kronrod (7-15)"));
  EXPECT_THAT(radius_integration(*E), HasSubstr("rtol 1e-10"));
  EXPECT_EQ(radius_integration(*P), kRadiusIntegration);
}

TEST(ExpressionLaw, RejectsBadExpressionsAndQuadratureKeys) {
  EXPECT_THAT(check_friction_expression("0.1 + * t")->what, "syntax error");
  EXPECT_EQ(check_friction_expression("0.1 + * t")->position, 6);
  EXPECT_EQ(check_friction_expression("0.1 + x")->what, "unknown name \"x\"");
  EXPECT_FALSE(check_friction_expression("0.3*(t < 1e-5) + 0.2").has_value());
  try {
    (void)make_friction_law(expression_spec("0.1 + * t"));
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("contact.friction.expression: syntax error at column 7 of "
                                    "\"0.1 + * t\": Unexpected operator"));
  }
  EXPECT_THROW(make_friction_law(expression_spec("0.1", {2e-5, 1e-5})), InputError);
  EXPECT_THROW(make_friction_law(expression_spec("0.1", {-1e-5})), InputError);
  EXPECT_THROW(make_friction_law(expression_spec("0.1", {}, 1.0)), InputError);
  EXPECT_THROW(make_friction_law(expression_spec("0.1", {}, 0.0)), InputError);
}

TEST(ExpressionLaw, NegativeOrNanValuesAreRejectedWithTheSlip) {
  const auto F = make_friction_law(expression_spec("t > 1e-5 ? -0.3 : 0.3"));
  EXPECT_NEAR((*F)(0.0), 0.3, 0.0);
  try {
    (void)(*F)(1.2e-5);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "contact.friction.expression: F(t = 1.2e-05 m) = -0.3: a coefficient of friction "
                 "must be finite and >= 0");
  }
  // In the radii, where the slips reach the negative part.
  const test::ClampedBrick b = test::paper_brick(2);
  VectorXd phi, g;
  random_fields(b, 4e-5, phi, g);
  EXPECT_THROW(patch_radii(b.mesh, b.surface, b.patches, *F, phi, g), InputError);
  const auto N = make_friction_law(expression_spec("sqrt(0.01 - t)"));  // nan beyond t = 0.01
  EXPECT_THROW((*N)(0.02), InputError);
}

TEST(ExpressionLaw, PaperFormulaWithItsKinksGivesTheExactRadii) {
  const test::ClampedBrick b = test::paper_brick(4);
  const auto exact = paper_law(6e4);
  const auto E = make_friction_law(expression_spec(kPaperExpression, kPaperKinks));
  VectorXd phi, g;
  random_fields(b, 8e-5, phi, g);  // across both kinks
  const VectorXd rho_exact = patch_radii(b.mesh, b.surface, b.patches, *exact, phi, g);
  const VectorXd rho = patch_radii(b.mesh, b.surface, b.patches, *E, phi, g);
  EXPECT_LT(max_relative_difference(rho, rho_exact), 1e-8);
  // Without its kinks the quadrature has to find them by bisection. It gets close, but not to
  // its tolerance: a kink between an interval's end and its outermost node is invisible to both
  // rules (|K15 - G7| ~ 0), which is why kinks are to be listed (docs/problem-file.md).
  const auto U = make_friction_law(expression_spec(kPaperExpression, {}, 1e-9));
  const VectorXd rho_u = patch_radii(b.mesh, b.surface, b.patches, *U, phi, g);
  EXPECT_LT(max_relative_difference(rho_u, rho_exact), 1e-5);
  // Constant slips: F(phi) g on every patch.
  const VectorXd flat = VectorXd::Constant(phi.size(), 2e-5);
  const VectorXd ones = VectorXd::Ones(phi.size());
  const VectorXd rho_flat = patch_radii(b.mesh, b.surface, b.patches, *E, flat, ones);
  EXPECT_LT((rho_flat.array() - (*exact)(2e-5)).abs().maxCoeff(), 1e-14);
}

TEST(Radii, SmoothLawConvergesToTheClosedFormAsTheToleranceTightens) {
  // F = a + b exp(-t/c) and g = G constant. On a triangle T (area A) with vertex slips phi_i,
  // by the Hermite-Genocchi formula int_T exp(-phi_h/c) dS = 2A e[a_0, a_1, a_2], the second
  // divided difference of exp at a_i = -phi_i/c, i.e. 2A sum_i e^{a_i} / prod_{j != i} (a_i - a_j):
  // a closed form that does not use the level-line reduction. The slips are phi = c S v(i, j) at
  // the grid node (i, j), v = (37 i + 11 j) mod 64: within every triangle the a_i are at least
  // 11 S apart (no cancellation), and a triangle spans up to ~60 S decay lengths of F, far more
  // than one Gauss-Kronrod interval resolves.
  const Index n = 4;
  const test::ClampedBrick b = test::paper_brick(n);
  const Real a = 0.1, bb = 0.4, G = 2e7, c = kSmoothDecay, S = 2.0, h = 1.0 / static_cast<Real>(n);
  const Index ns = b.surface.n_nodes();
  VectorXd phi(ns);
  for (Index k = 0; k < ns; ++k) {
    const Vec3 x = b.mesh.nodes.col(b.surface.nodes[static_cast<size_t>(k)]);
    const auto i = static_cast<long>(std::lround(x(0) / h)),
               j = static_cast<long>(std::lround(x(1) / h));
    phi(k) = c * S * static_cast<Real>((37 * i + 11 * j) % 64);
  }
  const VectorXd g = VectorXd::Constant(ns, G);
  VectorXd exact = VectorXd::Zero(b.patches.size());
  for (Index p = 0; p < b.patches.size(); ++p) {
    for (Index f : b.patches.faces[static_cast<size_t>(p)]) {
      std::array<Vec3, 3> x;
      std::array<Real, 3> e{};
      for (int v = 0; v < 3; ++v) {
        const Index k = b.surface.face_nodes(v, f);
        x[v] = b.mesh.nodes.col(b.surface.nodes[static_cast<size_t>(k)]);
        e[v] = -phi(k) / c;
      }
      const Real A = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
      Real dd = 0.0;
      for (int i = 0; i < 3; ++i)
        dd += std::exp(e[i]) / ((e[i] - e[(i + 1) % 3]) * (e[i] - e[(i + 2) % 3]));
      exact(p) += G * (a * A + bb * 2.0 * A * dd);
    }
    exact(p) /= b.patches.area(p);
  }
  Real previous_error = INFINITY;
  long previous_points = 0, first_points = 0;
  for (Real rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    long points = 0;
    FrictionLawSpec spec;
    spec.law = FrictionLawKind::Function;
    spec.quadrature_rtol = rtol;
    spec.function = [&](std::span<const Real> t, std::span<Real> out) {
      points += static_cast<long>(t.size());
      for (size_t i = 0; i < t.size(); ++i)
        out[i] = a + bb * std::exp(-t[i] / c);
    };
    const auto F = make_friction_law(spec);
    const VectorXd rho = patch_radii(b.mesh, b.surface, b.patches, *F, phi, g);
    const Real error = max_relative_difference(rho, exact);
    std::cout << "rtol " << rtol << ": error " << error << ", " << points << " points\n";
    EXPECT_LT(error, rtol) << "rtol " << rtol;
    EXPECT_LE(error, previous_error * 1.01 + 1e-15) << "rtol " << rtol;
    EXPECT_GE(points, previous_points) << "rtol " << rtol;
    if (rtol == 1e-4) first_points = points;
    previous_error = error;
    previous_points = points;
  }
  // The refinement is real: 1e-10 needs more nodes than 1e-4.
  EXPECT_GT(previous_points, first_points);
  // The same through the expression law.
  const auto E = make_friction_law(expression_spec(kSmoothExpression, {}, 1e-10));
  EXPECT_LT(max_relative_difference(patch_radii(b.mesh, b.surface, b.patches, *E, phi, g), exact),
            1e-10);
}

TEST(FunctionLaw, IsCalledInFewBatchesAndItsValuesAreChecked) {
  const test::ClampedBrick b = test::paper_brick(4);
  VectorXd phi, g;
  random_fields(b, 3e-4, phi, g);
  int calls = 0;
  size_t largest_batch = 0;
  FrictionLawSpec spec;
  spec.law = FrictionLawKind::Function;
  spec.function_name = "my_law";
  spec.function = [&](std::span<const Real> t, std::span<Real> out) {
    ++calls;
    largest_batch = std::max(largest_batch, t.size());
    for (size_t i = 0; i < t.size(); ++i)
      out[i] = 0.1 + 0.4 * std::exp(-t[i] / kSmoothDecay);
  };
  const auto F = make_friction_law(spec);
  EXPECT_EQ(F->describe(), "function(my_law)");
  EXPECT_FALSE(F->piecewise_linear());
  const VectorXd rho = patch_radii(b.mesh, b.surface, b.patches, *F, phi, g);
  EXPECT_GE(calls, 1);
  EXPECT_LE(calls, 12);  // a few rounds of bisection, each one call
  const auto n_faces = b.surface.faces.size();
  EXPECT_GE(largest_batch, 15 * n_faces);  // the first round has every triangle's nodes
  const auto E = make_friction_law(expression_spec(kSmoothExpression));
  EXPECT_LT(max_relative_difference(rho, patch_radii(b.mesh, b.surface, b.patches, *E, phi, g)),
            1e-9);
  calls = 0;
  EXPECT_NEAR((*F)(0.0), 0.5, 1e-15);
  EXPECT_EQ(calls, 1);

  // Negative and NaN values, and values the function does not set.
  auto failing = [&](Real value, size_t skip) {
    FrictionLawSpec s = spec;
    s.function = [value, skip](std::span<const Real> t, std::span<Real> out) {
      for (size_t i = 0; i + skip < t.size(); ++i)
        out[i] = t[i] > 1e-5 ? value : 0.3;
    };
    return make_friction_law(s);
  };
  try {
    (void)(*failing(-0.3, 0))(1.2e-5);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "contact.friction: the function law's F(t = 1.2e-05 m) = -0.3: a coefficient of "
                 "friction must be finite and >= 0");
  }
  try {
    (void)(*failing(NAN, 0))(1.2e-5);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the function law's F(t = 1.2e-05 m) = nan: a coefficient"));
  }
  EXPECT_THROW(patch_radii(b.mesh, b.surface, b.patches, *failing(-0.3, 0), phi, g), InputError);
  EXPECT_THROW(patch_radii(b.mesh, b.surface, b.patches, *failing(0.3, 1), phi, g), InputError);
  FrictionLawSpec empty = spec;
  empty.function = nullptr;
  EXPECT_THROW(make_friction_law(empty), InputError);
}

TEST(Radii, AJumpNotListedInKinksIsFoundByBisection) {
  // A jump of F that kinks does not list: its interval is bisected until the patch's error is
  // within the tolerance. With the jump given as a kink, every piece is integrated exactly.
  const test::ClampedBrick b = test::paper_brick(2);
  VectorXd phi, g;
  random_fields(b, 3e-5, phi, g);
  const std::string step = "t < 1.23456e-5 ? 0.3 : 0.1";
  const auto K = make_friction_law(expression_spec(step, {1.23456e-5}));
  const VectorXd rho_exact = patch_radii(b.mesh, b.surface, b.patches, *K, phi, g);
  const auto U = make_friction_law(expression_spec(step, {}, 1e-10));
  EXPECT_LT(
      max_relative_difference(patch_radii(b.mesh, b.surface, b.patches, *U, phi, g), rho_exact),
      1e-9);
}

TEST(Radii, ALawThatOscillatesTooFastIsANumericalError) {
  const test::ClampedBrick b = test::paper_brick(2);
  VectorXd phi, g;
  random_fields(b, 3e-5, phi, g);
  const auto F = make_friction_law(expression_spec("0.2 + 0.1*sin(1e10*t)"));
  try {
    (void)patch_radii(b.mesh, b.surface, b.patches, *F, phi, g);
    ADD_FAILURE() << "no exception";
  } catch (const NumericalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("did not reach quadrature_rtol = 1e-10"));
  }
}
