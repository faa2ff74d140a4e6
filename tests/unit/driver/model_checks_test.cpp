// driver: the checks of a problem on its mesh (model.hpp) that issue 33 found wanting: a plane
// normal of extreme magnitude, the steps of a path seen by `fricon check` (check_model), and the
// message when K cannot be factorized although every body is held.

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/problem.hpp"

namespace fricon::driver {
namespace {

using ::testing::HasSubstr;

// The brick pressed onto the plane z = -1e-4 m below its face z0, whose normal is `normal`.
Problem on_plane(const Vec3& normal) {
  Problem p = test::clamped_problem();
  ObstacleOptions plane;
  plane.point = Vec3(0.0, 0.0, -1e-4);
  plane.normal = normal;
  p.contact.front().obstacle = plane;
  return p;
}

contact::ContactDiscretization discretized(const Problem& p) {
  validate(p);
  const mesh::TetMesh mesh = make_mesh(p);
  return discretize_contact(p, mesh, make_dofs(p, mesh));
}

// Issue 33, item 18: a normal is a direction, whatever its magnitude; [0, 0, 1e308] squared
// overflows (its normalization gave the zero vector, and the error blamed the geometry), and
// [0, 0, 1e-200] squared underflows to zero.
TEST(PlaneNormal, AnExtremeMagnitudeIsTheSameDirection) {
  const contact::ContactDiscretization unit = discretized(on_plane(Vec3(0.0, 0.0, 1.0)));
  ASSERT_NEAR(unit.gap.minCoeff(), 1e-4, 1e-12);  // the plane 1e-4 m below the face
  for (const Real magnitude : {1e308, 1e-200}) {
    const contact::ContactDiscretization d = discretized(on_plane(Vec3(0.0, 0.0, magnitude)));
    EXPECT_EQ(d.gap, unit.gap) << magnitude;
    EXPECT_TRUE(d.B.isApprox(unit.B)) << magnitude;
  }
}

// Issue 33, item 13: check_model (what `fricon check` runs) finds two [[dirichlet]] entries that
// agree at step 1 of a path and disagree at step 2 (tests/bad_input/129 for solve).
TEST(CheckModel, RefusesEntriesThatDisagreeAtAStepOfThePath) {
  Problem p = test::clamped_problem(false);
  p.dirichlet.front().value = Vec3(0.0, 0.0, -1e-4);
  p.dirichlet.front().path = {1.0, 1.0};
  DirichletOptions z0;
  z0.boundary = "z0";
  z0.components = {false, false, true};
  z0.value = Vec3(0.0, 0.0, -1e-4);
  z0.path = {1.0, 0.5};
  p.dirichlet.push_back(z0);
  p.traction.clear();
  p.loading.steps = 2;
  validate(p);
  PhaseTimes times;
  const Model model = assemble_loads(p, times);  // step 1's values agree
  const std::string message = test::input_error_of([&] { (void)check_model(p, model); });
  EXPECT_THAT(message, HasSubstr("dirichlet[1].value"));
  EXPECT_THAT(message, HasSubstr("(at step 2 of the loading path)"));
}

// Issue 33, item 22: two clamped bodies whose moduli differ by 1e12: the conditions hold every
// body, so the failure is the conditioning, and the message says so (not "is the body clamped?").
TEST(FactorizeModel, AModulusContrastIsNamedAsTheCause) {
  Problem p = test::clamped_problem(false);
  p.mesh.cells = {6, 2, 2};
  p.material.young = 2e11;
  p.material.poisson = 0.3;
  PhaseTimes times;
  Model model = assemble_model(p, times);
  // The brick as two regions, "stiff" (x < 1.5 m, clamped at x0) and "soft", 1e12 times softer.
  model.materials.push_back(fe::isotropic(0.2, 0.3));
  model.mesh.region_names = {"stiff", "soft"};
  model.mesh.tet_region.assign(static_cast<std::size_t>(model.mesh.n_tets()), 0);
  for (Index t = 0; t < model.mesh.n_tets(); ++t)
    if (model.mesh.nodes.col(model.mesh.tets(0, t)).x() > 1.5)
      model.mesh.tet_region[static_cast<std::size_t>(t)] = 1;
  model.K = fe::assemble_stiffness(model.mesh, model.materials, model.dofs);
  try {
    factorize_model(model, {}, times, {}, &p);
    FAIL() << "K with a contrast of 1e12 was factorized";
  } catch (const NumericalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("hold every body"));
    EXPECT_THAT(e.what(), HasSubstr("1.0e+12 times as stiff"));
    EXPECT_THAT(e.what(), HasSubstr("ill-conditioned"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("clamped")));
  }
}

}  // namespace
}  // namespace fricon::driver
