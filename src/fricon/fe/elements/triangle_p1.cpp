// fe/elements: the 3-node (P1) triangle, the trace of the 4-node tetrahedron on a face.

#include "fricon/fe/elements/lagrange.hpp"
#include "fricon/fe/elements/simplex_shapes.hpp"

namespace fricon::fe {

namespace {

class TriangleP1 final : public Element {
  static constexpr int kNodes = 3;
  static constexpr int kDim = 2;
  static constexpr Real kReferenceArea = 0.5;

 public:
  TriangleP1() : mass_(tabulate(triangle_degree2_rule(), kReferenceArea)) {}
  std::string_view name() const override { return "3-node triangle"; }
  int dim() const override { return kDim; }
  int order() const override { return 1; }
  int n_nodes() const override { return kNodes; }
  MatrixXd node_points() const override { return MatrixXd::Identity(kNodes, kNodes); }
  ShapeValues values(const VectorXd& bary) const override { return bary; }
  ShapeDerivatives derivatives(const VectorXd&) const override {
    return simplex::linear_derivatives(kDim);
  }
  // A triangle has no stiffness of its own; its mass points serve every surface integral.
  const Tabulation& stiffness_points() const override { return mass_; }
  const Tabulation& mass_points() const override { return mass_; }
  Eigen::MatrixXi linear_pieces() const override {
    return Eigen::MatrixXi(Eigen::Vector3i(0, 1, 2));
  }

 private:
  Tabulation mass_;
};

}  // namespace

const Element& triangle_p1() {
  static const TriangleP1 element;
  return element;
}

}  // namespace fricon::fe
