// Verification of the elasticity core at orders 1 and 2 against independent truth:
//  - a manufactured solution on a brick, whose observed convergence orders must be p + 1 in L2
//    and p in the H1 seminorm over three meshes (2 and 1 for linear, 3 and 2 for quadratic
//    tetrahedra);
//  - a cantilever under an end shear load, whose tip deflection must approach Timoshenko beam
//    theory as the mesh is refined (linear), and be within 1 % of it with 4 quadratic elements
//    through the height (theory.md §2.12), linear on the same mesh reported beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/fixtures.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/element.hpp"
#include "fricon/fe/quadrature.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::fe;

namespace {

constexpr Real kPi = std::numbers::pi;

// u = S(x) a with S = sin(pi x/Lx) sin(pi y/Ly) sin(pi z/Lz), zero on the whole boundary.
struct Manufactured {
  Vec3 L{1.5, 1.0, 1.0};
  Vec3 a{1e-3, -2e-3, 1.5e-3};  // m
  Real lambda, mu;

  Vec3 k() const { return Vec3(kPi / L(0), kPi / L(1), kPi / L(2)); }
  Real S(const Vec3& x) const {
    return std::sin(k()(0) * x(0)) * std::sin(k()(1) * x(1)) * std::sin(k()(2) * x(2));
  }
  Vec3 u(const Vec3& x) const { return S(x) * a; }
  // sin(k_d x_d) and cos(k_d x_d) per direction.
  void sin_cos(const Vec3& x, Vec3& s, Vec3& c) const {
    for (int d = 0; d < 3; ++d) {
      s(d) = std::sin(k()(d) * x(d));
      c(d) = std::cos(k()(d) * x(d));
    }
  }
  Vec3 grad_S(const Vec3& x) const {
    const Vec3 kk = k();
    Vec3 s, c;
    sin_cos(x, s, c);
    return Vec3(kk(0) * c(0) * s(1) * s(2), kk(1) * s(0) * c(1) * s(2), kk(2) * s(0) * s(1) * c(2));
  }
  Mat3 grad_u(const Vec3& x) const { return a * grad_S(x).transpose(); }  // (du_i/dx_j)
  Mat3 hessian_S(const Vec3& x) const {
    const Vec3 kk = k();
    Vec3 s, c;
    sin_cos(x, s, c);
    Mat3 H;
    H(0, 0) = -kk(0) * kk(0) * s(0) * s(1) * s(2);
    H(1, 1) = -kk(1) * kk(1) * s(0) * s(1) * s(2);
    H(2, 2) = -kk(2) * kk(2) * s(0) * s(1) * s(2);
    H(0, 1) = H(1, 0) = kk(0) * kk(1) * c(0) * c(1) * s(2);
    H(0, 2) = H(2, 0) = kk(0) * kk(2) * c(0) * s(1) * c(2);
    H(1, 2) = H(2, 1) = kk(1) * kk(2) * s(0) * c(1) * c(2);
    return H;
  }
  // Body force b = -div sigma = -(mu Laplace u + (lambda + mu) grad div u).
  Vec3 body_force(const Vec3& x) const {
    const Mat3 H = hessian_S(x);
    return -(mu * H.trace() * a + (lambda + mu) * H * a);
  }
};

struct Errors {
  Real l2 = 0, h1 = 0;
};

// The brick (0, Lx) x (0, Ly) x (0, Lz) with n cells across, at `order`.
mesh::TetMesh brick(const Vec3& size, std::array<Index, 3> cells, int order) {
  mesh::TetMesh m = mesh::make_brick({size, cells});
  if (order == 2) mesh::add_edge_midpoints(m);
  return m;
}

Errors solve_and_measure(const Manufactured& ms, Index n, int order) {
  const mesh::TetMesh m = brick(ms.L, {3 * n / 2, n, n}, order);
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (Index f = 0; f < m.n_faces(); ++f)
    for (int v = 0; v < m.nodes_per_face(); ++v)
      for (int c = 0; c < 3; ++c)
        fixed[static_cast<size_t>(3 * m.face_node(f, v) + c)] = true;
  const DofMap dofs(fixed);
  const Material mat = isotropic(2e11, 0.3);
  const Element& element = elements_of(m).cell;

  // Load: the body force integrated with a rule of high order (not an interpolant), so that the
  // observed errors are those of the discretization alone; the errors likewise.
  const QuadratureRule rule = tet_rule(5);
  std::vector<ShapeValues> N;
  std::vector<ShapeDerivatives> dN;
  for (Index q = 0; q < rule.weights.size(); ++q) {
    N.push_back(element.values(rule.points.col(q)));
    dN.push_back(element.derivatives(rule.points.col(q)));
  }
  VectorXd f = VectorXd::Zero(dofs.n_free());
  for (Index t = 0; t < m.n_tets(); ++t) {
    const ElementNodes x = tet_points(m, t);
    for (Index q = 0; q < rule.weights.size(); ++q) {
      const Vec3 xq = x * N[static_cast<size_t>(q)];
      const Real w = rule.weights(q) / 6.0 * map_cell(x, dN[static_cast<size_t>(q)]).det;
      const Vec3 b = ms.body_force(xq);
      for (int a = 0; a < element.n_nodes(); ++a)
        for (int c = 0; c < 3; ++c) {
          const Index k = dofs.dof(m.tet_node(t, a), c);
          if (k >= 0) f(k) += w * N[static_cast<size_t>(q)](a) * b(c);
        }
    }
  }
  linalg::CholeskyFactor chol;
  chol.factorize(assemble_stiffness(m, mat, dofs));
  const NodalField uh = dofs.to_nodal(chol.solve(f));

  Errors e;
  for (Index t = 0; t < m.n_tets(); ++t) {
    const ElementNodes x = tet_points(m, t);
    MatrixXd ue(3, element.n_nodes());
    for (int a = 0; a < element.n_nodes(); ++a)
      ue.col(a) = uh.col(m.tet_node(t, a));
    for (Index q = 0; q < rule.weights.size(); ++q) {
      const CellMap map = map_cell(x, dN[static_cast<size_t>(q)]);
      const Vec3 xq = x * N[static_cast<size_t>(q)];
      const Real w = rule.weights(q) / 6.0 * map.det;
      const Mat3 grad_uh = ue * map.grad;
      e.l2 += w * (ms.u(xq) - ue * N[static_cast<size_t>(q)]).squaredNorm();
      e.h1 += w * (ms.grad_u(xq) - grad_uh).squaredNorm();
    }
  }
  e.l2 = std::sqrt(e.l2);
  e.h1 = std::sqrt(e.h1);
  return e;
}

// Observed orders between successive meshes, printed; checked against p + 1 (L2) and p (H1).
void expect_orders(const std::vector<Index>& meshes, int order, Real first_tolerance,
                   Real tolerance) {
  Manufactured ms;
  const auto [lambda, mu] = lame(2e11, 0.3);
  ms.lambda = lambda;
  ms.mu = mu;
  std::vector<Errors> errors;
  for (Index n : meshes)
    errors.push_back(solve_and_measure(ms, n, order));
  for (size_t i = 1; i < meshes.size(); ++i) {
    const Real ratio = static_cast<Real>(meshes[i]) / static_cast<Real>(meshes[i - 1]);
    const Real order_l2 = std::log(errors[i - 1].l2 / errors[i].l2) / std::log(ratio);
    const Real order_h1 = std::log(errors[i - 1].h1 / errors[i].h1) / std::log(ratio);
    std::printf(
        "order %d, n = %2ld -> %2ld: L2 error %.3e -> %.3e (order %.3f), H1 error %.3e -> %.3e "
        "(order %.3f)\n",
        order, static_cast<long>(meshes[i - 1]), static_cast<long>(meshes[i]), errors[i - 1].l2,
        errors[i].l2, order_l2, errors[i - 1].h1, errors[i].h1, order_h1);
    // The first pair of meshes is slightly pre-asymptotic.
    EXPECT_NEAR(order_l2, order + 1.0, i == 1 ? first_tolerance : tolerance);
    EXPECT_NEAR(order_h1, order, i == 1 ? first_tolerance : tolerance);
  }
}

// Tip deflection [m] of the cantilever (0,L)x(0,b)x(0,h) clamped at x = 0 under the shear
// traction P/(b h) in -z on x = L, with `through` cells through the height: the mean of -u_z
// over the end face, f . u / P with f the consistent load of the traction.
Real cantilever_tip(Real L, Real b, Real h, Real E, Real nu, Real P, Index through, int order) {
  const mesh::TetMesh m = brick(
      Vec3(L, b, h), {static_cast<Index>(std::lround(L / h)) * through, through, through}, order);
  const DofMap dofs = test::clamped_dofs(m);
  VectorXd f = VectorXd::Zero(dofs.n_free());
  add_traction(m, dofs, m.faces_with_tag("x1"), Vec3(0, 0, -P / (b * h)), f);
  linalg::CholeskyFactor chol;
  chol.factorize(assemble_stiffness(m, isotropic(E, nu), dofs));
  return f.dot(chol.solve(f)) / P;
}

}  // namespace

TEST(Verification, ManufacturedSolutionConvergesWithOrdersTwoAndOne) {
  expect_orders({4, 8, 16}, 1, 0.1, 0.05);
}

TEST(Verification, QuadraticManufacturedSolutionConvergesWithOrdersThreeAndTwo) {
  expect_orders({2, 4, 8}, 2, 0.25, 0.1);
}

TEST(Verification, CantileverTipDeflectionApproachesBeamTheory) {
  // Beam (0,L)x(0,b)x(0,h) clamped at x = 0, shear traction P/(b h) in -z on x = L.
  // Timoshenko: delta = P L^3 / (3 E I) + P L / (kappa G A), I = b h^3 / 12, kappa = 5/6.
  const Real L = 6.0, b = 1.0, h = 1.0, E = 2e11, nu = 0.3, P = 1e6;
  const Real I = b * h * h * h / 12.0, G = E / (2 * (1 + nu)), A = b * h;
  const Real delta = P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * A);
  std::vector<Real> rel_error;
  for (Index n : {2, 4, 8}) {
    const mesh::TetMesh m = mesh::make_brick({Vec3(L, b, h), {6 * n, n, n}});
    const DofMap dofs = test::clamped_dofs(m);
    VectorXd f = VectorXd::Zero(dofs.n_free());
    add_traction(m, dofs, m.faces_with_tag("x1"), Vec3(0, 0, -P / A), f);
    linalg::CholeskyFactor chol;
    chol.factorize(assemble_stiffness(m, isotropic(E, nu), dofs));
    const NodalField u = dofs.to_nodal(chol.solve(f));
    // Mean vertical deflection of the loaded end face (nodes are uniformly spaced).
    Real sum = 0;
    const auto tip = m.nodes_with_tag("x1");
    for (Index a : tip)
      sum += -u(2, a);
    rel_error.push_back(std::abs(sum / static_cast<Real>(tip.size()) - delta) / delta);
    std::printf("cantilever %ld cells through the depth: tip deflection error %.2f %%\n",
                static_cast<long>(n), 100 * rel_error.back());
  }
  // P1 tetrahedra are too stiff in bending: the error decreases roughly like h^2 and the finest
  // mesh is within a few per cent (the clamp's 3D effects are not in beam theory).
  EXPECT_GT(rel_error[0], rel_error[1]);
  EXPECT_GT(rel_error[1], rel_error[2]);
  EXPECT_GT(rel_error[0] / rel_error[1], 2.5);
  EXPECT_LT(rel_error[2], 0.05);
}

TEST(Verification, QuadraticCantileverIsWithinOnePercentOfTimoshenko) {
  // The cantilever: length 10, height and width 1, 4 cells through the height. P1 locks
  // in bending on this mesh; 10-node tetrahedra must be within 1 % of Timoshenko's deflection.
  const Real L = 10.0, b = 1.0, h = 1.0, E = 2e11, nu = 0.3, P = 1e6;
  const Real I = b * h * h * h / 12.0, G = E / (2 * (1 + nu)), A = b * h;
  const Real delta = P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * A);
  const Index through = 4;
  const Real linear = cantilever_tip(L, b, h, E, nu, P, through, 1);
  const Real quadratic = cantilever_tip(L, b, h, E, nu, P, through, 2);
  std::printf(
      "cantilever L = 10, 4 cells through the height: Timoshenko %.6e m, order 1 %.6e m (%+.2f "
      "%%), order 2 %.6e m (%+.2f %%)\n",
      delta, linear, 100 * (linear / delta - 1), quadratic, 100 * (quadratic / delta - 1));
  RecordProperty("order1_error_percent", std::to_string(100 * (linear / delta - 1)));
  RecordProperty("order2_error_percent", std::to_string(100 * (quadratic / delta - 1)));
  EXPECT_NEAR(quadratic / delta, 1.0, 0.01);
  EXPECT_LT(linear / delta, 0.95);  // P1 locks: more than 5 % too stiff on this mesh
}
