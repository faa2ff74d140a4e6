#include "fricon/qp/dual_space.hpp"

#include <cmath>

namespace fricon::qp {

double DualSpace::sum(double value) const {
  Eigen::Matrix<double, 1, 1> v;
  v(0) = value;
  sum(Eigen::Ref<Eigen::VectorXd>(v));
  return v(0);
}

double DualSpace::max_abs(const Eigen::VectorXd& a) const {
  return max(a.size() > 0 ? a.lpNorm<Eigen::Infinity>() : 0.0);
}

Index DualSpace::size(Index n) const {
  return static_cast<Index>(std::llround(sum(static_cast<double>(n))));
}

const DualSpace& whole_space() {
  static const DualSpace space;
  return space;
}

}  // namespace fricon::qp
