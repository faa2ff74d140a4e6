#pragma once
// fe: the finite element space's degrees of freedom. Each node (corners and, on a quadratic
// mesh, edge nodes alike) carries three displacement components;
// components fixed by homogeneous Dirichlet conditions are eliminated, the others are numbered
// in node-major order (node 0 x, y, z, node 1 x, ...), so K has only free dofs.

#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::fe {

class DofMap {
 public:
  /// All 3 n_nodes components free (the unconstrained space, whose K has the rigid motions in its
  /// kernel).
  explicit DofMap(Index n_nodes);
  /// `fixed[3*node + c]` true fixes component c of node (zero displacement).
  explicit DofMap(const std::vector<bool>& fixed);

  Index n_nodes() const { return static_cast<Index>(dof_.size()) / 3; }
  /// Number of free dofs (the paper's n_p).
  Index n_free() const { return n_free_; }
  /// Dof index of component c in {0,1,2} of node, or -1 if fixed.
  Index dof(Index node, int c) const { return dof_[static_cast<size_t>(3 * node + c)]; }
  bool is_fixed(Index node, int c) const { return dof(node, c) < 0; }
  /// The free dofs of the given nodes, node by node (x, y, z), fixed components skipped.
  std::vector<Index> free_dofs(const std::vector<Index>& nodes) const;

  /// Nodal field (3 x n_nodes) from a vector of free dofs, with zeros at fixed components.
  Eigen::Matrix<Real, 3, Eigen::Dynamic> to_nodal(const VectorXd& u) const;
  /// Vector of free dofs sampled from a nodal field (fixed components are dropped).
  VectorXd from_nodal(const Eigen::Matrix<Real, 3, Eigen::Dynamic>& field) const;

 private:
  std::vector<Index> dof_;
  Index n_free_ = 0;
};

}  // namespace fricon::fe
