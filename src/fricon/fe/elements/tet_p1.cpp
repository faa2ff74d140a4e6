// fe/elements: the 4-node (P1) tetrahedron: shape functions the barycentric coordinates
// lambda_a, constant gradients (theory.md §2.1).

#include "fricon/fe/elements/lagrange.hpp"
#include "fricon/fe/elements/simplex_shapes.hpp"

namespace fricon::fe {

namespace {

class TetP1 final : public Element {
  static constexpr int kNodes = 4;
  static constexpr int kDim = 3;
  static constexpr Real kReferenceVolume = 1.0 / 6.0;

 public:
  TetP1()
      : stiffness_(tabulate(tet_centroid_rule(), kReferenceVolume)),
        mass_(tabulate(tet_degree2_rule(), kReferenceVolume)) {}
  std::string_view name() const override { return "4-node tetrahedron"; }
  int dim() const override { return kDim; }
  int order() const override { return 1; }
  int n_nodes() const override { return kNodes; }
  MatrixXd node_points() const override { return MatrixXd::Identity(kNodes, kNodes); }
  ShapeValues values(const VectorXd& bary) const override { return bary; }
  ShapeDerivatives derivatives(const VectorXd&) const override {
    return simplex::linear_derivatives(kDim);
  }
  const Tabulation& stiffness_points() const override { return stiffness_; }
  const Tabulation& mass_points() const override { return mass_; }
  Eigen::MatrixXi linear_pieces() const override {
    return Eigen::MatrixXi(Eigen::Vector4i(0, 1, 2, 3));
  }

 private:
  Tabulation stiffness_, mass_;
};

}  // namespace

const Element& tet_p1() {
  static const TetP1 element;
  return element;
}

}  // namespace fricon::fe
