// The Lagrange elements (fe/element.hpp): interpolation, derivatives, the stiffness's symmetry
// and rigid kernel, uniform-strain energy, quadrature exactness, the Jacobian check, and Gmsh's
// 10-node ordering through the volume of a curved tetrahedron read from a file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/element.hpp"
#include "fricon/fe/quadrature.hpp"
#include "fricon/fe/stiffness.hpp"
#include "fricon/mesh/gmsh_file.hpp"

using namespace fricon;
using namespace fricon::fe;

namespace {
// A skewed tetrahedron's corners.
Eigen::Matrix<Real, 3, 4> skewed_corners() {
  Eigen::Matrix<Real, 3, 4> x;
  x << 0.1, 1.3, 0.2, 0.4,  //
      0.0, 0.2, 0.9, 0.3,   //
      0.05, 0.1, 0.2, 1.1;
  return x;
}

// The nodes of `element` on the straight cell with the given corners.
ElementNodes straight_nodes(const Element& element, const Eigen::Matrix<Real, 3, 4>& corners) {
  return corners * element.node_points();
}

// The six rigid motions at the nodes, as 3 n-vectors.
MatrixXd rigid_modes(const ElementNodes& x) {
  MatrixXd R = MatrixXd::Zero(3 * x.cols(), 6);
  for (Index a = 0; a < x.cols(); ++a) {
    for (int c = 0; c < 3; ++c)
      R(3 * a + c, c) = 1.0;
    for (int r = 0; r < 3; ++r)
      R.block<3, 1>(3 * a, 3 + r) = Vec3::Unit(r).cross(Vec3(x.col(a)));
  }
  return R;
}

const Element* const kAllElements[] = {&lagrange_elements(1).cell, &lagrange_elements(1).face,
                                       &lagrange_elements(2).cell, &lagrange_elements(2).face};
}  // namespace

TEST(Element, ShapeFunctionsInterpolateAtTheNodesAndSumToOne) {
  for (const Element* e : kAllElements) {
    const MatrixXd nodes = e->node_points();
    ASSERT_EQ(nodes.cols(), e->n_nodes()) << e->name();
    for (Index b = 0; b < nodes.cols(); ++b) {
      const ShapeValues N = e->values(nodes.col(b));
      for (Index a = 0; a < N.size(); ++a)
        EXPECT_NEAR(N(a), a == b ? 1.0 : 0.0, 1e-15) << e->name() << " node " << b;
    }
    const VectorXd inside = VectorXd::LinSpaced(e->dim() + 1, 1.0, 2.0).normalized().cwiseAbs2();
    EXPECT_NEAR(e->values(inside).sum(), 1.0, 1e-14) << e->name();
    EXPECT_NEAR(e->derivatives(inside).colwise().sum().norm(), 0.0, 1e-14) << e->name();
  }
}

TEST(Element, DerivativesAreThoseOfTheValues) {
  // Central differences along reference coordinate i (barycentric i up, barycentric 0 down).
  const Real h = 1e-6;
  for (const Element* e : kAllElements) {
    VectorXd point = VectorXd::LinSpaced(e->dim() + 1, 1.0, 3.0);
    point /= point.sum();
    const ShapeDerivatives d = e->derivatives(point);
    for (int i = 1; i <= e->dim(); ++i) {
      VectorXd up = point, down = point;
      up(i) += h;
      up(0) -= h;
      down(i) -= h;
      down(0) += h;
      const VectorXd fd = (e->values(up) - e->values(down)) / (2 * h);
      EXPECT_NEAR((fd - d.col(i - 1)).norm(), 0.0, 1e-8) << e->name() << " along " << i;
    }
  }
}

TEST(Element, RulesIntegrateTheirDegreesExactly) {
  // Over the simplex of dimension d the mean of l1^a l2^b (l3^c) is a! b! c! d! / (a+b+c+d)!.
  auto fact = [](int k) { return std::tgamma(k + 1.0); };
  for (const Element* e : kAllElements) {
    for (const Tabulation* t : {&e->stiffness_points(), &e->mass_points()}) {
      const int degree = t == &e->mass_points() ? 2 * e->order() : 2 * (e->order() - 1);
      const int c_max = e->dim() == 3 ? degree : 0;
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; a + b <= degree; ++b)
          for (int c = 0; a + b + c <= degree && c <= c_max; ++c) {
            Real sum = 0;
            for (Index q = 0; q < t->size(); ++q)
              sum += t->rule.weights(q) * std::pow(t->rule.points(1, q), a) *
                     std::pow(t->rule.points(2, q), b) *
                     (e->dim() == 3 ? std::pow(t->rule.points(3, q), c) : 1.0);
            EXPECT_NEAR(sum,
                        fact(a) * fact(b) * fact(c) * fact(e->dim()) / fact(a + b + c + e->dim()),
                        1e-14)
                << e->name() << " degree " << a << " " << b << " " << c;
          }
    }
  }
}

TEST(Element, LinearPiecesTileTheCell) {
  // The pieces' reference measures add up to the cell's, each positive.
  for (const Element* e : kAllElements) {
    const MatrixXd nodes = e->node_points();
    const Eigen::MatrixXi pieces = e->linear_pieces();
    Real sum = 0.0;
    for (Index j = 0; j < pieces.cols(); ++j) {
      MatrixXd edges(e->dim(), e->dim());
      for (int i = 0; i < e->dim(); ++i)
        edges.col(i) = (nodes.col(pieces(i + 1, j)) - nodes.col(pieces(0, j))).bottomRows(e->dim());
      const Real measure = edges.determinant() / std::tgamma(e->dim() + 1.0);
      EXPECT_GT(measure, 0.0) << e->name() << " piece " << j;
      sum += measure;
    }
    EXPECT_NEAR(sum, 1.0 / std::tgamma(e->dim() + 1.0), 1e-15) << e->name();
  }
}

TEST(Element, StiffnessIsSymmetricWithRigidKernelOfRankSix) {
  for (int order : {1, 2}) {
    const Element& e = lagrange_elements(order).cell;
    const ElementNodes x = straight_nodes(e, skewed_corners());
    const ElementMatrix K = element_stiffness(e, x, isotropic(2e11, 0.3));
    EXPECT_NEAR((K - K.transpose()).norm() / K.norm(), 0.0, 1e-15);
    EXPECT_NEAR((K * rigid_modes(x)).norm() / K.norm(), 0.0, 1e-14);
    const MatrixXd dense = K;
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(dense);
    for (int i = 0; i < 6; ++i)
      EXPECT_LT(std::abs(eig.eigenvalues()(i)), 1e-6 * K.norm()) << "order " << order;
    for (Index i = 6; i < K.rows(); ++i)
      EXPECT_GT(eig.eigenvalues()(i), 1e-6 * K.norm()) << "order " << order;
  }
}

TEST(Element, EnergyOfUniformStrainMatchesHandValue) {
  // A uniform extension u = (e x, 0, 0) stores |T| (lambda + 2 mu) e^2 / 2 at either order.
  const Real E = 1e9, nu = 0.25, e = 1e-3;
  const auto [lambda, mu] = lame(E, nu);
  const Eigen::Matrix<Real, 3, 4> corners = skewed_corners();
  Mat3 edges;
  edges << corners.col(1) - corners.col(0), corners.col(2) - corners.col(0),
      corners.col(3) - corners.col(0);
  const Real volume = edges.determinant() / 6.0;
  for (int order : {1, 2}) {
    const Element& element = lagrange_elements(order).cell;
    const ElementNodes x = straight_nodes(element, corners);
    const ElementMatrix K = element_stiffness(element, x, isotropic(E, nu));
    VectorXd u = VectorXd::Zero(K.rows());
    for (Index a = 0; a < x.cols(); ++a)
      u(3 * a) = e * x(0, a);
    EXPECT_NEAR(0.5 * u.dot(K * u), 0.5 * volume * (lambda + 2 * mu) * e * e, 1e-12 * E * e * e)
        << "order " << order;
  }
}

namespace {
// One 10-node tetrahedron in MSH 2.2, nodes in Gmsh's order (corners, then the midpoints of
// the edges 01, 12, 20, 30, 32, 31), the reference corners, with the midpoint of edge 3-2 (node
// 9 of the file, the element's 9th node) moved by `bulge` along y.
std::string curved_tet_msh(Real bulge) {
  return fmt::format(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n"
      "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
      "5 0.5 0 0\n6 0.5 0.5 0\n7 0 0.5 0\n8 0 0 0.5\n9 0 {} 0.5\n10 0.5 0 0.5\n"
      "$EndNodes\n$Elements\n1\n1 11 2 1 1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n",
      0.5 + bulge);
}
}  // namespace

class CurvedTet : public test::TempDirTest {};

TEST_F(CurvedTet, VolumeOfTheFileIsTheExactVolumeOfItsQuadraticMap) {
  // Moving the midpoint of edge 3-2 by delta along y makes the map x = xi + 4 delta xi2 xi3 e_y,
  // with det J = 1 + 4 delta xi3: the volume is 1/6 + delta/6. Had the reader or the element
  // swapped nodes 8 and 9 (edge 3-1, Gmsh's last), the bulge would sit on edge 3-1, det J = 1
  // and the volume 1/6.
  const Real delta = 0.2;
  const std::filesystem::path file = dir_.path() / "curved.msh";
  std::ofstream(file) << curved_tet_msh(delta);
  const mesh::TetMesh m = mesh::read_gmsh(file);
  ASSERT_EQ(m.order(), 2);
  const Element& e = elements_of(m).cell;
  const Tabulation& t = e.mass_points();
  const ElementNodes x = tet_points(m, 0);
  Real volume = 0.0;
  for (Index q = 0; q < t.size(); ++q)
    volume += t.weight(q) * map_cell(x, t.derivatives[static_cast<size_t>(q)]).det;
  EXPECT_NEAR(volume, (1.0 + delta) / 6.0, 1e-14);
  EXPECT_NO_THROW(check_jacobians(m, "curved.msh"));
}

TEST_F(CurvedTet, AFoldedElementIsRefusedByName) {
  // A midpoint pushed past the opposite face folds the map: det J < 0 near corner 3.
  const std::filesystem::path file = dir_.path() / "folded.msh";
  std::ofstream(file) << curved_tet_msh(-0.9);
  const mesh::TetMesh m = mesh::read_gmsh(file);
  try {
    check_jacobians(m, "folded.msh");
    FAIL() << "a folded element passed";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("folded.msh: tetrahedron 0"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("folds"), std::string::npos) << error.what();
  }
}

TEST(Quadrature, GaussLegendreIsExact) {
  for (int n = 1; n <= 8; ++n) {
    const QuadratureRule r = gauss_legendre(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      Real sum = 0;
      for (int q = 0; q < n; ++q)
        sum += r.weights(q) * std::pow(r.points(1, q), p);
      EXPECT_NEAR(sum, 1.0 / (p + 1), 1e-14) << "n = " << n << ", degree " << p;
    }
  }
}

TEST(Quadrature, TetRuleIntegratesMonomials) {
  // Over the unit simplex, the mean of l1^a l2^b l3^c is a! b! c! 3! / (a+b+c+3)!.
  const QuadratureRule r = tet_rule(4);
  EXPECT_NEAR(r.weights.sum(), 1.0, 1e-14);
  auto fact = [](int k) { return std::tgamma(k + 1.0); };
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; b <= 3 - a; ++b)
      for (int c = 0; c <= 3 - a - b; ++c) {
        Real sum = 0;
        for (Index q = 0; q < r.weights.size(); ++q)
          sum += r.weights(q) * std::pow(r.points(1, q), a) * std::pow(r.points(2, q), b) *
                 std::pow(r.points(3, q), c);
        EXPECT_NEAR(sum, fact(a) * fact(b) * fact(c) * 6.0 / fact(a + b + c + 3), 1e-14);
      }
}
