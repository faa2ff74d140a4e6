// Verification of the general geometry (theory.md §2.2): a rigid plane of any orientation with a
// gap, meshes from Gmsh files, prescribed displacements. The truths are invariances and exact
// identities, not fricon's own earlier output:
//   - rotating the whole problem (mesh, loads, obstacle) rotates the displacement and leaves the
//     pressures and the friction magnitudes unchanged;
//   - a uniform gap d under a body pressed by a prescribed displacement: moving the body by d
//     more gives the zero-gap answer (the problem only sees the gap minus the imposed approach);
//   - the discrete constraints, checked outside the solver: per patch int_R (w_n - gap) <= 0,
//     lambda_n >= 0 and their product zero.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>

#include "common/fixtures.hpp"
#include "fricon/driver/paper.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/gmsh_file.hpp"

namespace {

using namespace fricon;
using namespace fricon::driver;

constexpr Real kGap = 2e-5;  // [m]

/// The paper's brick (n = 4) over a level plane kGap below it, patches from the mesh entities
/// (the chessboard) so that a rotated copy gets the same partition.
Problem brick_over_plane() {
  Problem p = paper_problem(4, 6e4);
  p.solver.qp.rel_tolerance = 1e-10;
  p.solver.outer.tol = 1e-8;
  p.contact.front().patches = contact::PatchKind::Mesh;
  p.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3(0, 0, -kGap), Vec3(0, 0, 1), ""};
  return p;
}

/// `p` rotated by R: its brick written rotated to a Gmsh file, its loads and obstacle rotated.
Problem rotated(const Problem& p, const Mat3& R, const std::filesystem::path& file) {
  mesh::BrickSpec spec;
  spec.size = Vec3(p.mesh.size[0], p.mesh.size[1], p.mesh.size[2]);
  spec.cells = p.mesh.cells;
  mesh::TetMesh m = mesh::make_brick(spec);
  m.nodes = R * m.nodes;
  mesh::write_gmsh(file, m);
  Problem q = p;
  q.mesh.kind = MeshKind::Gmsh;
  q.mesh.file = file.string();
  for (auto& t : q.traction)
    t.value = R * t.value;
  q.volume_force = R * q.volume_force;
  q.contact.front().obstacle->point = R * q.contact.front().obstacle->point;
  q.contact.front().obstacle->normal = R * q.contact.front().obstacle->normal;
  return q;
}

TEST(Geometry, RotatingTheWholeProblemRotatesTheAnswer) {
  const Problem level = brick_over_plane();
  const Mat3 R = Eigen::AngleAxis<Real>(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const test::TempDir dir;
  const auto file = dir.path() / "rotated-brick.msh";
  const RunResult a = run(level);
  const RunResult b = run(rotated(level, R, file));
  ASSERT_EQ(a.report.status, RunStatus::Converged);
  ASSERT_EQ(b.report.status, RunStatus::Converged);
  EXPECT_EQ(a.report.contact->outer_iterations, b.report.contact->outer_iterations);
  const VectorXd& la = a.contact->lambda;
  const VectorXd& lb = b.contact->lambda;
  ASSERT_EQ(la.size(), lb.size());
  const Real scale = la.cwiseAbs().maxCoeff();
  ASSERT_GT(la.maxCoeff(), 0.0);  // there is contact
  for (Index p = 0; p < la.size() / 3; ++p) {
    EXPECT_NEAR(la(3 * p), lb(3 * p), 1e-7 * scale) << "patch " << p;
    EXPECT_NEAR(la.segment<2>(3 * p + 1).norm(), lb.segment<2>(3 * p + 1).norm(), 1e-7 * scale)
        << "patch " << p;
  }
  const Real u_scale = a.displacement.cwiseAbs().maxCoeff();
  EXPECT_LE((R * a.displacement - b.displacement).cwiseAbs().maxCoeff(), 1e-7 * u_scale);
}

TEST(Geometry, AContactSurfaceInTwoPiecesIsOneProblem) {
  // The brick standing on two feet: the bottom faces under x < 1 and x > 2 are one tag "feet"
  // (two disconnected pieces), partitioned by agglomeration; the middle of the bottom is free.
  Problem p = brick_over_plane();
  mesh::TetMesh m = mesh::make_brick({Vec3(3, 1, 1), {12, 4, 4}});
  const int z0 = m.find_tag("z0");
  m.tag_names.push_back("feet");
  const int feet = static_cast<int>(m.tag_names.size()) - 1;
  for (Index f = 0; f < m.n_faces(); ++f) {
    if (m.face_tag[static_cast<size_t>(f)] != z0) continue;
    const Real x =
        (m.nodes.col(m.faces(0, f)) + m.nodes.col(m.faces(1, f)) + m.nodes.col(m.faces(2, f)))(0) /
        3.0;
    if (x < 1.0 || x > 2.0) m.face_tag[static_cast<size_t>(f)] = feet;
  }
  const test::TempDir dir;
  const auto file = dir.path() / "feet.msh";
  mesh::write_gmsh(file, m);
  p.mesh.kind = MeshKind::Gmsh;
  p.mesh.file = file.string();
  p.contact.front().boundary = "feet";
  p.contact.front().patches = contact::PatchKind::Agglomerate;
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged);
  const ContactFields& c = *r.contact;
  // Patches lie in one piece each, and both pieces carry pressure.
  Real force_left = 0.0, force_right = 0.0;
  for (Index q = 0; q < c.patches.size(); ++q) {
    const Real x = c.patches.centroid(0, q);
    EXPECT_TRUE(x < 1.0 || x > 2.0) << "patch " << q << " at x = " << x;
    (x < 1.0 ? force_left : force_right) += c.lambda(3 * q) * c.patches.area(q);
  }
  EXPECT_GT(force_left, 0.0);
  EXPECT_GT(force_right, 0.0);
  EXPECT_NEAR(force_left + force_right, r.report.contact->total_normal_force,
              1e-12 * (force_left + force_right));
  EXPECT_LT(r.report.equilibrium_residual, 1e-10);
}

TEST(Geometry, TheDiscreteConstraintsHoldWithAGap) {
  const RunResult r = run(brick_over_plane());
  ASSERT_EQ(r.report.status, RunStatus::Converged);
  const ContactFields& c = *r.contact;
  const mesh::TetMesh& mesh = r.model.mesh;
  // Scales of the QP's own tolerance (1e-10 relative): pressures, and displacement times area.
  const Real pressure_scale = c.lambda.cwiseAbs().maxCoeff();
  const Real w_scale = r.displacement.cwiseAbs().maxCoeff();
  for (Index p = 0; p < c.patches.size(); ++p) {
    Real mean_opening = 0.0;  // int_R (gap - w_n) dS, exact for P1
    for (Index k : c.patches.faces[static_cast<size_t>(p)]) {
      const Real third = mesh::face_area(mesh, c.surface.faces[static_cast<size_t>(k)]) / 3.0;
      for (int v = 0; v < 3; ++v)
        mean_opening += third * (kGap - c.wn(c.surface.face_nodes(v, k)));
    }
    const Real lambda_n = c.lambda(3 * p);
    const Real area = c.patches.area(p);
    EXPECT_GE(lambda_n, 0.0);
    EXPECT_GE(mean_opening, -1e-8 * w_scale * area) << "patch " << p;
    EXPECT_LE(std::abs(lambda_n * mean_opening), 1e-8 * pressure_scale * w_scale * area)
        << "patch " << p;
  }
}

TEST(Geometry, AGapIsTakenUpByAPrescribedApproach) {
  // A block standing on its bottom, pressed down by its top: with a gap d and the top moved by
  // -(delta + d) it must give the zero-gap answer for -delta, shifted by -d.
  constexpr Real kDelta = 1e-4, kGapDown = 3e-5;  // [m]
  Problem p;
  p.mesh.size = {1.0, 1.0, 0.5};
  p.mesh.cells = {4, 4, 2};
  p.material.young = 2e11;
  p.material.poisson = 0.3;
  DirichletOptions top;
  top.boundary = "z1";
  top.value = Vec3(0, 0, -kDelta);
  p.dirichlet = {top};
  p.contact.emplace_back();
  p.contact.front().boundary = "z0";
  p.contact.front().slip_bound = 1e7;
  p.contact.front().friction.law = contact::FrictionLawKind::Constant;
  p.contact.front().friction.value = 0.2;
  p.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3::Zero(), Vec3(0, 0, 1), ""};
  p.solver.qp.rel_tolerance = 1e-10;
  p.solver.outer.tol = 1e-8;
  Problem q = p;
  q.contact.front().obstacle->point = Vec3(0, 0, -kGapDown);
  q.dirichlet[0].value = Vec3(0, 0, -kDelta - kGapDown);
  const RunResult a = run(p), b = run(q);
  ASSERT_EQ(a.report.status, RunStatus::Converged);
  ASSERT_EQ(b.report.status, RunStatus::Converged);
  const Real scale = a.contact->lambda.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LE((a.contact->lambda - b.contact->lambda).cwiseAbs().maxCoeff(), 1e-7 * scale);
  fe::NodalField shifted = a.displacement;
  shifted.row(2).array() -= kGapDown;
  EXPECT_LE((shifted - b.displacement).cwiseAbs().maxCoeff(), 1e-7 * kDelta);
  // Pressed by displacement only: the top's reaction balances the contact force.
  EXPECT_LT(a.report.equilibrium_residual, 1e-10);
}

}  // namespace
