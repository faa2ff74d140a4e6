// The contact integrals of the face elements (contact/surface_integrals.hpp, theory.md §2.12):
// on straight triangles the closed forms of the 3-node and 6-node mass matrices, a row sum of
// 0 at the corners of a 6-node triangle, and B's rows integrating a quadratic field exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "fricon/contact/b_matrix.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::contact;

namespace {

// A skewed box's bottom as the contact surface, with every node free, at `order`.
struct BottomSurface {
  mesh::TetMesh mesh;
  fe::DofMap dofs{0};
  ContactSurface surface;
};
BottomSurface bottom(int order) {
  BottomSurface s;
  s.mesh = mesh::make_brick({Vec3(1.3, 0.7, 0.5), {4, 2, 1}});
  if (order == 2) mesh::add_edge_midpoints(s.mesh);
  s.dofs = fe::DofMap(s.mesh.n_nodes());
  s.surface = make_contact_surface(s.mesh, s.dofs, "z0", "test");
  return s;
}

// The mass matrix of a straight triangle of area A over 180 / A (6-node, nodes 3, 4, 5 on the
// edges 01, 12, 20: corner a lies opposite the edge node 3 + (a + 1) % 3) and over 12 / A
// (3-node).
MatrixXd reference_mass(int order) {
  if (order == 1) return MatrixXd::Ones(3, 3) + MatrixXd::Identity(3, 3);
  MatrixXd M = MatrixXd::Zero(6, 6);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      M(a, b) = a == b ? 6.0 : -1.0;
    M(a, 3 + (a + 1) % 3) = M(3 + (a + 1) % 3, a) = -4.0;
  }
  for (int e = 3; e < 6; ++e)
    for (int f = 3; f < 6; ++f)
      M(e, f) = e == f ? 32.0 : 16.0;
  return M;
}

}  // namespace

TEST(SurfaceIntegrals, StraightTrianglesHaveTheClosedFormMassMatrices) {
  for (int order : {1, 2}) {
    const BottomSurface s = bottom(order);
    const Real scale = order == 1 ? 12.0 : 180.0;
    for (Index k = 0; k < static_cast<Index>(s.surface.faces.size()); ++k) {
      const Real area = mesh::face_area(s.mesh, s.surface.faces[static_cast<size_t>(k)]);
      const FaceIntegrals I = face_integrals(s.mesh, s.surface, k);
      EXPECT_NEAR((I.mass * scale / area - reference_mass(order)).cwiseAbs().maxCoeff(), 0.0, 1e-12)
          << "order " << order << ", face " << k;
      EXPECT_NEAR(I.shape.sum(), area, 1e-15);
      for (Index a = 0; a < I.shape.size(); ++a)  // corners 0 and edges |T|/3 at order 2
        EXPECT_NEAR(I.shape(a), order == 1 || a >= 3 ? area / 3.0 : 0.0, 1e-15);
    }
  }
}

TEST(SurfaceIntegrals, RowsOfBIntegrateAQuadraticFieldExactly) {
  // B's normal row of a patch applied to the nodal values of u_z = q(x, y), a quadratic, is
  // -int_R q dS (the outward normal of the bottom is -z): exact at order 2 on straight faces,
  // where the 6-node trace interpolates q exactly, and only approximate at order 1.
  const auto q = [](const Vec3& x) {
    return 0.3 + 1.1 * x(0) * x(0) - 0.7 * x(0) * x(1) + 0.4 * x(1);
  };
  // int over the rectangle [x0, x1] x [y0, y1] of q, by the antiderivative.
  const auto exact = [](Real x0, Real x1, Real y0, Real y1) {
    const auto F = [](Real x, Real y) {
      return 0.3 * x * y + 1.1 * x * x * x / 3.0 * y - 0.7 * x * x / 2.0 * y * y / 2.0 +
             0.4 * x * y * y / 2.0;
    };
    return F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
  };
  for (int order : {1, 2}) {
    const BottomSurface s = bottom(order);
    const Patches patches = chessboard_patches(s.mesh, s.surface, "test");
    const SparseMatrix B = assemble_b(s.mesh, s.dofs, s.surface, patches);
    fe::NodalField u = fe::NodalField::Zero(3, s.mesh.n_nodes());
    for (Index a = 0; a < s.mesh.n_nodes(); ++a)
      u(2, a) = q(s.mesh.nodes.col(a));
    const VectorXd Bu = B * s.dofs.from_nodal(u);
    Real worst = 0.0;
    for (Index p = 0; p < patches.size(); ++p) {
      // Each chessboard patch is a 2 x 2 block of cells: its box from its centroid and area.
      Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
      for (Index k : patches.faces[static_cast<size_t>(p)])
        for (int v = 0; v < 3; ++v) {
          const Vec3 x = s.mesh.nodes.col(s.mesh.faces(v, s.surface.faces[static_cast<size_t>(k)]));
          lo = lo.cwiseMin(x);
          hi = hi.cwiseMax(x);
        }
      const Real truth = -exact(lo(0), hi(0), lo(1), hi(1));
      worst = std::max(worst, std::abs(Bu(3 * p) - truth) / std::abs(truth));
    }
    if (order == 2)
      EXPECT_LT(worst, 1e-13);
    else
      EXPECT_GT(worst, 1e-6);  // the P1 trace cannot hold the quadratic: the test can fail
  }
}

TEST(SurfaceIntegrals, APatchWhoseEdgeNodesAreAllHeldIsRefused) {
  // Every edge node of the bottom held along z, the corners free: each patch's normal row
  // integrates only the corners' functions, zero on straight 6-node triangles. Its contact nodes
  // would be unconstrained: condition (5.1) fails per patch and the partition is refused.
  mesh::TetMesh m = mesh::make_brick({Vec3(1.3, 0.7, 0.5), {4, 2, 1}});
  mesh::add_edge_midpoints(m);
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (Index f : m.faces_with_tag("z0"))
    for (int e = 3; e < m.nodes_per_face(); ++e)
      fixed[static_cast<size_t>(3 * m.face_node(f, e) + 2)] = true;
  const fe::DofMap dofs(fixed);
  const ContactSurface surface = make_contact_surface(m, dofs, "z0", "test");
  const Patches patches = chessboard_patches(m, surface, "test");
  const SparseMatrix B = assemble_b(m, dofs, surface, patches);
  EXPECT_THROW(require_active_patches(surface, patches, B, "test"), NumericalError);
  // With the edge nodes free every patch is active.
  const BottomSurface free = bottom(2);
  const Patches free_patches = chessboard_patches(free.mesh, free.surface, "test");
  EXPECT_NO_THROW(
      require_active_patches(free.surface, free_patches,
                             assemble_b(free.mesh, free.dofs, free.surface, free_patches), "test"));
}
