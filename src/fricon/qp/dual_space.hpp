#pragma once
// qp: where the QP's vectors live (docs/theory.md §8.8). MPGP and SMALSE-M hold every vector of
// the unknowns (x, g, p, b, ...) as the part that this process holds of it; the parts of the
// processes together are the whole vector, and each holds whole blocks of the feasible set, so
// that projections, splits and the steps' updates are local. What needs the whole goes through a
// DualSpace: inner products, norms and maxima, and the sums over the processes of the products
// G x with the rows of an equality (qp/coarse_space.hpp). One process holding everything is
// whole_space(), whose reductions are the local values themselves: the serial solve computes
// the same bits with or without this seam. Under MPI every reduction is collective and gives
// every process the same bits, so that all take the same decisions.

#include <cmath>

#include <Eigen/Core>

#include "fricon/core/types.hpp"

namespace fricon::qp {

class DualSpace {
 public:
  virtual ~DualSpace() = default;

  /// v <- the entrywise sum of v over the processes, the same bits on every one. Collective:
  /// every process calls it with a vector of the same size.
  virtual void sum(Eigen::Ref<Eigen::VectorXd> v) const { (void)v; }
  /// The largest `value` of the processes, on every one. Collective.
  virtual double max(double value) const { return value; }
  /// The `local` vectors of every process, one after another in rank order, on every one.
  /// Collective (the sizes may differ).
  virtual Eigen::VectorXd concat(const Eigen::VectorXd& local) const { return local; }
  /// Whether the unknowns are shared by more than one process.
  virtual bool distributed() const { return false; }

  /// The sum of `value` over the processes. Collective.
  double sum(double value) const;
  /// The smallest `value` of the processes. Collective.
  double min(double value) const { return -max(-value); }
  /// a^T b of the whole vectors. Collective.
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const { return sum(a.dot(b)); }
  /// ||a||^2 and ||a|| of the whole vector. Collective.
  double squared_norm(const Eigen::VectorXd& a) const { return sum(a.squaredNorm()); }
  double norm(const Eigen::VectorXd& a) const { return std::sqrt(squared_norm(a)); }
  /// ||a||_inf of the whole vector (0 for none). Collective.
  double max_abs(const Eigen::VectorXd& a) const;
  /// The number of unknowns of the whole vector, of which this process holds `n`. Collective.
  Index size(Index n) const;
};

/// One process holding every unknown: no communication.
const DualSpace& whole_space();

}  // namespace fricon::qp
