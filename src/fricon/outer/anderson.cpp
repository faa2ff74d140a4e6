#include "fricon/outer/anderson.hpp"

#include <Eigen/QR>

namespace fricon::outer {

AndersonMixing::AndersonMixing(int depth, Real lower_bound)
    : depth_(static_cast<size_t>(depth > 0 ? depth : 0)), lower_bound_(lower_bound) {}

VectorXd AndersonMixing::next(const VectorXd& x, const VectorXd& g) {
  const VectorXd f = g - x;
  if (g_last_.size() == g.size()) {
    dF_.push_back(f - f_last_);
    dG_.push_back(g - g_last_);
    if (dF_.size() > depth_) {
      dF_.erase(dF_.begin());
      dG_.erase(dG_.begin());
    }
  } else {
    dF_.clear();
    dG_.clear();
  }
  f_last_ = f;
  g_last_ = g;
  if (dF_.empty()) return g;
  MatrixXd F(f.size(), static_cast<Index>(dF_.size())), G(g.size(), F.cols());
  for (size_t i = 0; i < dF_.size(); ++i) {
    F.col(static_cast<Index>(i)) = dF_[i];
    G.col(static_cast<Index>(i)) = dG_[i];
  }
  const VectorXd gamma = F.colPivHouseholderQr().solve(f);
  return (g - G * gamma).cwiseMax(lower_bound_);
}

}  // namespace fricon::outer
