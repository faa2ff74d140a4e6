// fe/elements: the 10-node (P2) tetrahedron (theory.md §2.12). In barycentric coordinates
// lambda_0..lambda_3 the corner functions are lambda_a (2 lambda_a - 1) and the edge functions
// 4 lambda_a lambda_b, the edges in Gmsh's order (mesh::kTetEdge: nodes 4..9).

#include "fricon/fe/elements/lagrange.hpp"
#include "fricon/fe/elements/simplex_shapes.hpp"

namespace fricon::fe {

namespace {

class TetP2 final : public Element {
  static constexpr int kCorners = 4;
  static constexpr int kNodes = kCorners + mesh::kTetEdges;
  static constexpr int kDim = 3;
  static constexpr Real kReferenceVolume = 1.0 / 6.0;
  // Collapsed Gauss points per direction for the mass (degree 4; tet_rule(n) is exact to 2n - 3).
  static constexpr int kMassGaussPoints = 4;

 public:
  TetP2()
      : stiffness_(tabulate(tet_degree2_rule(), kReferenceVolume)),
        mass_(tabulate(tet_rule(kMassGaussPoints), kReferenceVolume)) {}
  std::string_view name() const override { return "10-node tetrahedron"; }
  int dim() const override { return kDim; }
  int order() const override { return 2; }
  int n_nodes() const override { return kNodes; }
  MatrixXd node_points() const override {
    return simplex::quadratic_node_points(kCorners, mesh::kTetEdge);
  }
  ShapeValues values(const VectorXd& l) const override {
    return simplex::quadratic_values(l, mesh::kTetEdge);
  }
  ShapeDerivatives derivatives(const VectorXd& l) const override {
    return simplex::quadratic_derivatives(l, mesh::kTetEdge);
  }
  const Tabulation& stiffness_points() const override { return stiffness_; }
  const Tabulation& mass_points() const override { return mass_; }
  Eigen::MatrixXi linear_pieces() const override {
    // The four corner tetrahedra and the inner octahedron cut along its diagonal 4-8 (the midpoints
    // of edges 01 and 32) into four, each positively oriented as the element.
    Eigen::MatrixXi pieces(4, 8);
    pieces << 0, 4, 6, 7, 4, 4, 4, 4,  //
        4, 1, 5, 9, 8, 8, 8, 8,        //
        6, 5, 2, 8, 5, 6, 7, 9,        //
        7, 9, 8, 3, 6, 7, 9, 5;
    return pieces;
  }

 private:
  Tabulation stiffness_, mass_;
};

}  // namespace

const Element& tet_p2() {
  static const TetP2 element;
  return element;
}

}  // namespace fricon::fe
