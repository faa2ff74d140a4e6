// The contact discretization: sizes of the paper, B's exact integrals, the stability check,
// friction laws and the exact integration of the radii.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/contact/b_matrix.hpp"
#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/contact/radii.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::contact;

using test::paper_brick;
using Brick = test::ClampedBrick;  // the paper's brick clamped at x0, contact on z0, with its B

TEST(ContactSurface, PaperSizesAndBasis) {
  // Table 1: n_d = 36, 81, 144 for n = 4, 6, 8; 3n(n+1) contact nodes (theory.md §2.2).
  for (Index n : {4, 6, 8}) {
    const Brick b = paper_brick(n);
    EXPECT_EQ(b.B.rows(), 9 * n * n / 4);
    EXPECT_EQ(b.surface.n_contact_nodes(), 3 * n * (n + 1));
    EXPECT_NEAR((b.surface.n - Vec3(0, 0, -1)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((b.surface.t1 - Vec3(1, 0, 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((b.surface.t2 - Vec3(0, 1, 0)).norm(), 0.0, 1e-15);
    for (Index p = 0; p < b.patches.size(); ++p) {
      EXPECT_EQ(b.patches.faces[static_cast<size_t>(p)].size(), 8u);
      EXPECT_NEAR(b.patches.area(p), 4.0 / static_cast<Real>(n * n), 1e-15);
    }
  }
}

TEST(ContactSurface, PatchesAreCentredOnOddNodes) {
  const Brick b = paper_brick(4);
  const Real h = 0.25;
  for (Index p = 0; p < b.patches.size(); ++p) {
    const Real i = b.patches.centroid(0, p) / h, j = b.patches.centroid(1, p) / h;
    EXPECT_NEAR(std::fmod(i, 2.0), 1.0, 1e-12);
    EXPECT_NEAR(std::fmod(j, 2.0), 1.0, 1e-12);
  }
}

TEST(ContactSurface, BIntegratesTracesExactly) {
  // (B v)_{n,p} = int_{R_p} v.n: for v = (0, 0, 1) (not on fixed nodes) the normal rows give
  // -|R_p| on patches away from x = 0; for the linear field v = (x, 0, 0) the t1 rows give the
  // first moment int_{R_p} x dS = |R_p| x_centroid.
  const Brick b = paper_brick(4);
  fe::NodalField up(3, b.mesh.n_nodes()), lin(3, b.mesh.n_nodes());
  for (Index a = 0; a < b.mesh.n_nodes(); ++a) {
    up.col(a) = Vec3(0, 0, 1);
    lin.col(a) = Vec3(b.mesh.nodes(0, a), 0, 0);
  }
  const VectorXd Bu = b.B * b.dofs.from_nodal(up);
  const VectorXd Bl = b.B * b.dofs.from_nodal(lin);
  for (Index p = 0; p < b.patches.size(); ++p) {
    EXPECT_NEAR(Bl(3 * p + 1), b.patches.area(p) * b.patches.centroid(0, p), 1e-15);
    EXPECT_NEAR(Bl(3 * p), 0.0, 1e-15);
    EXPECT_NEAR(Bl(3 * p + 2), 0.0, 1e-15);
    if (b.patches.centroid(0, p) > 0.5) {
      EXPECT_NEAR(Bu(3 * p), -b.patches.area(p), 1e-15);
    }
  }
  // Node weights of an interior patch: centre 4h^2/3, the 8 others h^2/3 (theory.md §2.4).
  const Real h2 = 0.0625;
  std::vector<Real> weights;
  const SparseMatrix Bt = b.B.transpose();
  for (SparseMatrix::InnerIterator it(Bt, 3 * 5); it; ++it)
    weights.push_back(-it.value());
  std::sort(weights.begin(), weights.end());
  ASSERT_EQ(weights.size(), 9u);
  for (int k = 0; k < 8; ++k)
    EXPECT_NEAR(weights[k], h2 / 3, 1e-15);
  EXPECT_NEAR(weights[8], 4 * h2 / 3, 1e-15);
}

TEST(ContactSurface, StabilityHoldsForTheChessboardAndFailsForFinePatches) {
  const Brick b = paper_brick(4);
  EXPECT_GT(check_stability(b.B, "test").ratio, 0.1);
  // One patch per fine triangle: 2 x more patches than contact nodes can carry, so B^T loses
  // full column rank and the check must refuse it.
  Patches fine;
  for (size_t k = 0; k < b.surface.faces.size(); ++k) {
    fine.faces.push_back({static_cast<Index>(k)});
  }
  fine.area = VectorXd::Constant(static_cast<Index>(fine.faces.size()), 1.0);
  const SparseMatrix Bfine = assemble_b(b.mesh, b.dofs, b.surface, fine);
  EXPECT_THROW(check_stability(Bfine, "test"), NumericalError);
  // The sparse estimate (used beyond dense_limit rows) agrees with the exact ratio to a per cent
  // (it is an estimate of the order of magnitude, the check a margin of 1e6) and refuses
  // the same partition.
  const Brick b8 = paper_brick(8);
  const Real exact = check_stability(b8.B, "test").ratio;
  EXPECT_NEAR(check_stability(b8.B, "test", 1e-8, /*dense_limit=*/0).ratio, exact, 1e-2 * exact);
  EXPECT_THROW(check_stability(Bfine, "test", 1e-8, /*dense_limit=*/0), NumericalError);
}

TEST(ContactSurface, RejectsANonManifoldSurface) {
  // A second copy of a bottom triangle puts each of its edges in three triangles.
  Brick b = paper_brick(4);
  const int z0 = b.mesh.find_tag("z0");
  const Index f = b.surface.faces.front();
  b.mesh.faces.conservativeResize(3, b.mesh.n_faces() + 1);
  b.mesh.faces.col(b.mesh.n_faces() - 1) = b.mesh.faces.col(f);
  b.mesh.face_tag.push_back(z0);
  try {
    make_contact_surface(b.mesh, b.dofs, "z0", "t.toml:3:1: contact.boundary");
    FAIL() << "a non-manifold surface was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), testing::HasSubstr("t.toml:3:1: contact.boundary: the "
                                                          "surface 'z0' is not a manifold"));
  }
}

TEST(ContactSurface, TheObstacleGivesTheBasisAndTheGap) {
  Brick b = paper_brick(4);
  const Vec3 normal = Vec3(0.01, -0.02, 1.0).normalized();
  const Vec3 point(0.0, 0.0, -0.1);
  const ObstaclePtr plane = make_plane(point, normal);
  const RigidContact rigid{plane.get()};
  const ContactSurface s = make_contact_surface(b.mesh, b.dofs, "z0", "test", &rigid);
  EXPECT_LE((s.n + normal).norm(), 1e-15);
  EXPECT_NEAR(s.t1.dot(s.n), 0.0, 1e-15);
  EXPECT_NEAR(s.t2.dot(s.n), 0.0, 1e-15);
  EXPECT_LE((s.t1.cross(s.t2) + s.n).norm(), 1e-15);  // t2 = t1 x n: (t1, t2, -n) right-handed
  EXPECT_FALSE(s.frames_vary);
  const VectorXd gap = obstacle_gap(b.mesh, s, rigid);
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Vec3 x = b.mesh.nodes.col(s.nodes[static_cast<size_t>(k)]);
    EXPECT_NEAR(gap(k), (x - point).dot(normal), 1e-15);
  }
  // A plane is linear: the gap linearized where it is moved is the gap at rest.
  const RigidContact moved{plane.get(), Vec3(1e-3, -2e-3, 0.05)};
  EXPECT_LE((obstacle_gap(b.mesh, s, moved) - gap).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NO_THROW(check_outside_obstacle(b.mesh, s, *plane, "test"));
  const ObstaclePtr above = make_plane(Vec3(0.0, 0.0, 1e-3), normal);
  EXPECT_THROW(check_outside_obstacle(b.mesh, s, *above, "test"), InputError);
}

TEST(ContactSurface, ABallGivesEachNodeItsNormalAndGap) {
  // The brick's bottom z = 0 over a ball below it that touches its centre: every node's n
  // points from it to the centre, its gap is |x - c| - r.
  Brick b = paper_brick(4);
  const Real r = 0.5;
  const Vec3 c(0.5, 0.5, -r);
  const ObstaclePtr ball = make_sphere(c, r);
  const RigidContact rigid{ball.get()};
  const ContactSurface s = make_contact_surface(b.mesh, b.dofs, "z0", "test", &rigid);
  EXPECT_TRUE(s.frames_vary);
  EXPECT_NO_THROW(check_outside_obstacle(b.mesh, s, *ball, "test"));
  const VectorXd gap = obstacle_gap(b.mesh, s, rigid);
  for (Index k = 0; k < s.n_nodes(); ++k) {
    const Vec3 x = b.mesh.nodes.col(s.nodes[static_cast<size_t>(k)]);
    EXPECT_LE((s.node_frames.n.col(k) - (c - x).normalized()).norm(), 1e-14);
    EXPECT_NEAR(gap(k), (x - c).norm() - r, 1e-15);
    EXPECT_NEAR(s.node_frames.t1.col(k).dot(s.node_frames.n.col(k)), 0.0, 1e-15);
  }
  // Moved up by d, the ball's linearized gap is its distance in the moved position plus n . d
  // (the constraint n . (u - d) <= g).
  const Vec3 d(0.0, 0.0, 0.1);
  const RigidContact moved{ball.get(), d};
  const ContactSurface sm = make_contact_surface(b.mesh, b.dofs, "z0", "test", &moved);
  const VectorXd gm = obstacle_gap(b.mesh, sm, moved);
  for (Index k = 0; k < sm.n_nodes(); ++k) {
    const Vec3 x = b.mesh.nodes.col(sm.nodes[static_cast<size_t>(k)]);
    EXPECT_NEAR(gm(k), (x - c - d).norm() - r - sm.node_frames.n.col(k).dot(d), 1e-15);
    EXPECT_LE((sm.node_frames.n.col(k) - (c + d - x).normalized()).norm(), 1e-14);
  }
  // Raised above the bottom by its own centre's height, the ball would start inside the body.
  const ObstaclePtr inside = make_sphere(Vec3(0.5, 0.5, -0.4), r);
  try {
    check_outside_obstacle(b.mesh, s, *inside, "t.toml:4:1: contact.obstacle");
    FAIL() << "a body inside the ball was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()),
                testing::HasSubstr("t.toml:4:1: contact.obstacle: the contact surface 'z0' starts "
                                   "inside the sphere obstacle"));
    EXPECT_THAT(std::string(e.what()), testing::HasSubstr("0.1 m deep"));
  }
}

TEST(ContactSurface, RowsAgainstABallIntegrateTheTurningFrameExactly) {
  // Each row of B against a curved obstacle is int_R v_h . d_h dS, v_h and d_h the P1
  // interpolants of the nodal displacement and of the nodal directions (the patch's frame turned
  // onto each node's normal). The edge-midpoint rule, exact for quadratics, gives it per
  // triangle from the node normals alone.
  Brick b = paper_brick(4);
  const ObstaclePtr ball = make_sphere(Vec3(1.5, 0.5, -1.0), 1.0);
  const RigidContact rigid{ball.get()};
  const ContactSurface s = make_contact_surface(b.mesh, b.dofs, "z0", "test", &rigid);
  const Patches patches = make_patches(PatchKind::Chessboard, b.mesh, s, 0.0, "test");
  const Frames frames = patch_frames(b.mesh, s, patches);
  const std::vector<PatchRowWeights> weights = patch_row_weights(b.mesh, s, patches, frames);
  Eigen::Matrix<Real, 3, Eigen::Dynamic> v =
      Eigen::Matrix<Real, 3, Eigen::Dynamic>::Random(3, s.n_nodes());
  for (Index p = 0; p < patches.size(); ++p) {
    const Mat3 F = frames.rows(p);
    Vec3 expected = Vec3::Zero();
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      std::array<Mat3, 3> d;
      for (int a = 0; a < 3; ++a) {
        const Vec3 n = s.node_frames.n.col(s.face_nodes(a, k));
        const Vec3 t1 = (Vec3(F.row(1)) - F.row(1).dot(n) * n).normalized();
        d[static_cast<size_t>(a)] << n.transpose(), t1.transpose(), t1.cross(n).transpose();
      }
      const Real area = mesh::face_area(b.mesh, s.faces[static_cast<size_t>(k)]);
      for (int a = 0; a < 3; ++a) {
        const int c = (a + 1) % 3;
        const Vec3 vm = 0.5 * (v.col(s.face_nodes(a, k)) + v.col(s.face_nodes(c, k)));
        const Mat3 dm = 0.5 * (d[static_cast<size_t>(a)] + d[static_cast<size_t>(c)]);
        expected += area / 3.0 * dm * vm;
      }
    }
    const PatchRowWeights& w = weights[static_cast<size_t>(p)];
    Vec3 got = Vec3::Zero();
    for (size_t i = 0; i < w.nodes.size(); ++i)
      got += w.W[i] * v.col(w.nodes[i]);
    EXPECT_LE((got - expected).norm(), 1e-14 * expected.norm() + 1e-16) << "patch " << p;
    // The normal row is not the patch's frame times the area: the frame turns inside the patch.
    EXPECT_GT((w.integral.row(0) - patches.area(p) * F.row(0)).norm(), 1e-6 * patches.area(p));
  }
}

TEST(ContactSurface, RejectsMissingAndClampedSurfaces) {
  Brick b = paper_brick(4);
  EXPECT_THROW(make_contact_surface(b.mesh, b.dofs, "bottom", "test"), InputError);
  EXPECT_THROW(make_contact_surface(b.mesh, b.dofs, "x0", "test"), InputError);  // all clamped
}

TEST(FrictionLaw, PaperLawValuesAndLipschitzConstant) {
  const auto F = paper_law(6e4);
  EXPECT_DOUBLE_EQ((*F)(0.0), 0.3);
  EXPECT_DOUBLE_EQ((*F)(1e-5), 0.3);
  EXPECT_NEAR((*F)(1e-5 + 1.0 / 6e4), 0.25, 1e-15);  // halfway down
  EXPECT_NEAR((*F)(1e-5 + 2.0 / 6e4), 0.2, 1e-15);
  EXPECT_DOUBLE_EQ((*F)(1.0), 0.2);
  EXPECT_NEAR(F->lipschitz(), 0.05 * 6e4, 1e-9);
  EXPECT_THROW(paper_law(-1.0), InputError);
}

TEST(FrictionLaw, TableLawIsConstantOutsideAndRejectsBadTables) {
  const auto F = table_law({1e-4, 2e-4, 4e-4}, {0.5, 0.3, 0.4});
  EXPECT_DOUBLE_EQ((*F)(0.0), 0.5);
  EXPECT_NEAR((*F)(1.5e-4), 0.4, 1e-15);
  EXPECT_NEAR((*F)(3e-4), 0.35, 1e-15);
  EXPECT_DOUBLE_EQ((*F)(1.0), 0.4);
  EXPECT_THROW(table_law({1e-4, 1e-4}, {0.3, 0.2}), InputError);
  EXPECT_THROW(table_law({1e-4}, {-0.3}), InputError);
  EXPECT_THROW(table_law({}, {}), InputError);
}

TEST(Radii, ConstantAndLinearSlipsAreIntegratedExactly) {
  const Brick b = paper_brick(4);
  const Index ns = b.surface.n_nodes();
  const VectorXd g = VectorXd::Constant(ns, 2e7);
  const auto F = paper_law(6e4);
  // phi = 0 everywhere: rho = 0.3 g.
  VectorXd rho = patch_radii(b.mesh, b.surface, b.patches, *F, VectorXd::Zero(ns), g);
  EXPECT_NEAR((rho.array() - 0.3 * 2e7).abs().maxCoeff(), 0.0, 1e-6);
  // phi linear in x across the kink region: phi = s x. The mean of F(s x) over a patch
  // [x0, x0 + 2h] is (1/2h) int F(s x) dx, computed here in closed form.
  const Real s = 3e-5;  // m per m: phi goes from 0 to 9e-5 across the brick
  VectorXd phi(ns);
  for (Index k = 0; k < ns; ++k)
    phi(k) = s * b.mesh.nodes(0, b.surface.nodes[static_cast<size_t>(k)]);
  rho = patch_radii(b.mesh, b.surface, b.patches, *F, phi, g);
  const Real t0 = 1e-5, t1 = 1e-5 + 2.0 / 6e4;
  auto antiderivative = [&](Real x) {  // int_0^x F(s y) dy
    const Real a = t0 / s, c = t1 / s;
    if (x <= a) return 0.3 * x;
    const Real slope = 0.05 * 6e4 * s;
    if (x <= c) return 0.3 * x - 0.5 * slope * (x - a) * (x - a);
    return 0.3 * c - 0.5 * slope * (c - a) * (c - a) + 0.2 * (x - c);
  };
  for (Index p = 0; p < b.patches.size(); ++p) {
    const Real x0 = b.patches.centroid(0, p) - 0.25, x1 = b.patches.centroid(0, p) + 0.25;
    const Real exact = 2e7 * (antiderivative(x1) - antiderivative(x0)) / (x1 - x0);
    EXPECT_NEAR(rho(p), exact, 1e-8 * exact) << "patch " << p;
  }
}

TEST(Radii, SurfaceL2NormOfLinearFunction) {
  // int over (0,3)x(0,1) of x^2 = 9.
  const Brick b = paper_brick(4);
  VectorXd v(b.surface.n_nodes());
  for (Index k = 0; k < v.size(); ++k)
    v(k) = b.mesh.nodes(0, b.surface.nodes[static_cast<size_t>(k)]);
  EXPECT_NEAR(surface_l2_norm(b.mesh, b.surface, v), 3.0, 1e-13);
}

TEST(ContactSurface, ADirichletComponentConstrainsThatComponentOnly) {
  // A roller on the contact face itself (u_y = 0 on z0): every node keeps its normal (z) and x
  // components, so every node not on the clamped end is a contact node, B keeps their columns,
  // and the stability check still passes. Fixing z on z0 instead pins the normal motion: no
  // contact node is left, which is refused.
  const Index n = 4;
  const mesh::TetMesh m = mesh::make_brick({Vec3(3, 1, 1), {3 * n, n, n}});
  auto dofs_with = [&m](int component_on_z0) {
    std::vector<std::array<Index, 2>> on_z0;
    for (Index a : m.nodes_with_tag("z0"))
      on_z0.push_back({a, component_on_z0});
    return test::clamped_dofs(m, "x0", on_z0);
  };
  const fe::DofMap roller = dofs_with(1);
  const ContactSurface s = make_contact_surface(m, roller, "z0", "test");
  EXPECT_EQ(s.n_contact_nodes(), 3 * n * (n + 1));
  for (size_t k = 0; k < s.nodes.size(); ++k) {
    EXPECT_TRUE(s.fixed[k][1]);
    EXPECT_EQ(s.contact_node[k], !(s.fixed[k][0] && s.fixed[k][2]));
  }
  const Patches p = chessboard_patches(m, s, "test");
  const SparseMatrix B = assemble_b(m, roller, s, p);
  // The t2 = e2 rows lose every column (u_y is fixed on the whole face): only n and t1 remain.
  for (Index q = 0; q < p.size(); ++q) {
    EXPECT_GT(B.row(3 * q).norm(), 0.0);
    EXPECT_GT(B.row(3 * q + 1).norm(), 0.0);
    EXPECT_EQ(B.row(3 * q + 2).norm(), 0.0);
  }
  const fe::DofMap pinned = dofs_with(2);
  try {
    make_contact_surface(m, pinned, "z0", "t.toml:3:1: contact.boundary");
    ADD_FAILURE() << "a contact face with its normal motion fixed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml:3:1: contact.boundary"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("clamped in the normal direction"), std::string::npos);
  }
}
