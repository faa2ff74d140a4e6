#include "fricon/fe/dof_map.hpp"

#include "fricon/core/error.hpp"

namespace fricon::fe {

DofMap::DofMap(Index n_nodes)
    : DofMap(std::vector<bool>(static_cast<size_t>(3 * n_nodes), false)) {}

DofMap::DofMap(const std::vector<bool>& fixed) : dof_(fixed.size(), -1) {
  FRICON_CHECK(fixed.size() % 3 == 0, "fixed flags must come in triples, got " << fixed.size());
  for (size_t k = 0; k < fixed.size(); ++k)
    if (!fixed[k]) dof_[k] = n_free_++;
}

Eigen::Matrix<Real, 3, Eigen::Dynamic> DofMap::to_nodal(const VectorXd& u) const {
  FRICON_CHECK(u.size() == n_free_, "vector of size " << u.size() << ", expected " << n_free_);
  Eigen::Matrix<Real, 3, Eigen::Dynamic> field =
      Eigen::Matrix<Real, 3, Eigen::Dynamic>::Zero(3, n_nodes());
  for (Index a = 0; a < n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      if (dof(a, c) >= 0) field(c, a) = u(dof(a, c));
  return field;
}

VectorXd DofMap::from_nodal(const Eigen::Matrix<Real, 3, Eigen::Dynamic>& field) const {
  FRICON_CHECK(field.cols() == n_nodes(),
               "field has " << field.cols() << " nodes, expected " << n_nodes());
  VectorXd u(n_free_);
  for (Index a = 0; a < n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      if (dof(a, c) >= 0) u(dof(a, c)) = field(c, a);
  return u;
}

std::vector<Index> DofMap::free_dofs(const std::vector<Index>& nodes) const {
  std::vector<Index> out;
  out.reserve(3 * nodes.size());
  for (Index a : nodes)
    for (int c = 0; c < 3; ++c)
      if (dof(a, c) >= 0) out.push_back(dof(a, c));
  return out;
}

}  // namespace fricon::fe
