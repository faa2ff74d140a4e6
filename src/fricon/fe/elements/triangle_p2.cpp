// fe/elements: the 6-node (P2) triangle, the trace of the 10-node tetrahedron on a face
// (theory.md §2.12): corner functions lambda_a (2 lambda_a - 1), edge functions
// 4 lambda_a lambda_b on the edges 01, 12, 20 (mesh::kTriangleEdge: nodes 3..5). The corner
// functions integrate to zero over a straight triangle, the edge functions to |T|/3.

#include "fricon/fe/elements/lagrange.hpp"
#include "fricon/fe/elements/simplex_shapes.hpp"

namespace fricon::fe {

namespace {

class TriangleP2 final : public Element {
  static constexpr int kCorners = 3;
  static constexpr int kNodes = kCorners + mesh::kTriangleEdges;
  static constexpr int kDim = 2;
  static constexpr Real kReferenceArea = 0.5;
  // Collapsed Gauss points per direction for the mass (degree 4; triangle_rule(n) is exact to
  // 2n - 2).
  static constexpr int kMassGaussPoints = 3;

 public:
  TriangleP2() : mass_(tabulate(triangle_rule(kMassGaussPoints), kReferenceArea)) {}
  std::string_view name() const override { return "6-node triangle"; }
  int dim() const override { return kDim; }
  int order() const override { return 2; }
  int n_nodes() const override { return kNodes; }
  MatrixXd node_points() const override {
    return simplex::quadratic_node_points(kCorners, mesh::kTriangleEdge);
  }
  ShapeValues values(const VectorXd& l) const override {
    return simplex::quadratic_values(l, mesh::kTriangleEdge);
  }
  ShapeDerivatives derivatives(const VectorXd& l) const override {
    return simplex::quadratic_derivatives(l, mesh::kTriangleEdge);
  }
  // A triangle has no stiffness of its own; its mass points serve every surface integral.
  const Tabulation& stiffness_points() const override { return mass_; }
  const Tabulation& mass_points() const override { return mass_; }
  Eigen::MatrixXi linear_pieces() const override {
    // Nodes 3, 4, 5 are the midpoints of 01, 12, 20: three corner triangles and the middle one,
    // each counter-clockwise as the element.
    Eigen::MatrixXi pieces(3, 4);
    pieces << 0, 3, 5, 3,  //
        3, 1, 4, 4,        //
        5, 4, 2, 5;
    return pieces;
  }

 private:
  Tabulation mass_;
};

}  // namespace

const Element& triangle_p2() {
  static const TriangleP2 element;
  return element;
}

}  // namespace fricon::fe
