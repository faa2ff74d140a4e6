// The global equilibrium of a run (RunReport::equilibrium_residual, theory.md §5.5) against what
// holds exactly: the applied loads, the contact forces and the reactions of a converged run sum
// to zero up to round-off, so relative to a force scale of the problem the residual is at the
// level of round-off, also when the reactions cancel each other:
//   - a bar clamped at x = 0 and pulled at x = 3 by a prescribed displacement (no load, no
//     contact): its two end reactions are equal and opposite, their resultant is round-off, and
//     the residual relative to the nodal forces' magnitudes is round-off too;
//   - the two normal forces (theory.md §6.1): a block pressed on the plane whose side face x = 1
//     has its vertical displacement prescribed (zero, a roller), so that the contact nodes of that
//     edge have a prescribed normal component. The pressure's resultant sum lambda_n |R| exceeds
//     the transmitted normal force by exactly lambda_n times the integrals of the hat functions of
//     those nodes (|T|/3 per vertex of each triangle T), and the transmitted one is the normal
//     component of the contact force that the reactions balance.
#include <gtest/gtest.h>

#include <cmath>

#include "fricon/driver/run.hpp"
#include "fricon/mesh/tet_mesh.hpp"

using namespace fricon;
using namespace fricon::driver;

namespace {

constexpr Real kPull = 1.0e-4;       // the prescribed elongation of the 3 m bar [m]
constexpr Real kRoundoff = 1.0e-10;  // relative
constexpr Real kPressure = 1.0e6;    // on the pressed block's top [Pa]

}  // namespace

TEST(Equilibrium, ABarPulledByAPrescribedDisplacementIsInEquilibrium) {
  Problem p;
  p.mesh.size = {3.0, 1.0, 1.0};
  p.mesh.cells = {6, 2, 2};
  DirichletOptions clamp;
  clamp.boundary = "x0";
  clamp.components = {true, true, true};
  DirichletOptions pull;
  pull.boundary = "x1";
  pull.components = {true, false, false};
  pull.value = Vec3(kPull, 0.0, 0.0);
  p.dirichlet = {clamp, pull};
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  // The reactions of the two ends cancel: the bar is pulled, so each is large.
  const Real resultant = r.report.reaction_force.norm();
  const Real stiffness_force = p.material.young * 1.0 * kPull / 3.0;  // E A (elongation / L) [N]
  EXPECT_LE(resultant, 1e-6 * stiffness_force);
  EXPECT_LE(r.report.equilibrium_residual, kRoundoff);
}

TEST(Equilibrium, TheNormalForceOnPrescribedComponentsGoesToTheirSupports) {
  Problem p;
  p.mesh.size = {1.0, 1.0, 0.5};
  p.mesh.cells = {4, 4, 2};
  // The top held sideways and pressed by a traction; the side x = 1 held along x and
  // vertically (so are the contact nodes of its bottom edge).
  DirichletOptions top;
  top.boundary = "z1";
  top.components = {true, true, false};
  DirichletOptions side;
  side.boundary = "x1";
  side.components = {true, false, true};
  p.dirichlet = {top, side};
  TractionOptions press;
  press.boundary = "z1";
  press.value = Vec3(0.0, 0.0, -kPressure);
  p.traction = {press};
  ContactOptions c;
  c.boundary = "z0";
  c.slip_bound = 0.0;  // frictionless
  p.contact = {c};
  p.solver.qp.rel_tolerance = 1e-12;
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  const ContactReport& rep = *r.report.contact;
  const ContactFields& f = *r.contact;
  // lambda_n times the exact integrals of the hat functions of the nodes with u_z prescribed.
  Real on_supports = 0.0;
  for (Index p_ = 0; p_ < f.patches.size(); ++p_)
    for (Index face : f.patches.faces[static_cast<size_t>(p_)])
      for (int v = 0; v < 3; ++v) {
        const Index k = f.surface.face_nodes(v, face);
        if (f.surface.fixed[static_cast<size_t>(k)][2])
          on_supports += f.lambda(3 * p_) *
                         mesh::face_area(r.model.mesh, f.surface.faces[static_cast<size_t>(face)]) /
                         3.0;
      }
  ASSERT_GT(on_supports, 1e-3 * rep.total_normal_force);  // the edge carries pressure
  EXPECT_NEAR(rep.total_normal_force - rep.transmitted_normal_force, on_supports,
              kRoundoff * rep.total_normal_force);
  // The contact force on the free dofs (the plane's normal is +z) is the transmitted one, and
  // the reactions balance it.
  EXPECT_NEAR(r.report.contact_force.z(), rep.transmitted_normal_force,
              kRoundoff * rep.total_normal_force);
  EXPECT_LE(r.report.equilibrium_residual, kRoundoff);
}
