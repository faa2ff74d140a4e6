#pragma once
// qp: the separable feasible set Omega = Omega_1 x ... x Omega_s of the dual contact problem.
//
// Place in the data flow: `contact` decides which unknowns form a block and computes the disc
// radii (the Tresca bounds); `qp` only sees the block layout below and never a mesh. Two kinds of
// block exist:
//   Bound  one unknown,  x_i >= 0                     (normal multiplier)
//   Disc   two unknowns, ||(x_i, x_{i+1})|| <= rho    (tangential multiplier, rho >= 0)
// A Disc with rho = 0 pins both of its unknowns to zero.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fricon/core/types.hpp"

namespace fricon::qp {

enum class BlockKind {
  Bound,  ///< x_i >= 0, one unknown
  Disc,   ///< ||(x_i, x_{i+1})|| <= radius, two unknowns
};

namespace detail {
/// Euclidean norm of (a, b). Plain sqrt instead of std::hypot, which is several times slower and
/// dominates the O(n) work per MPGP iteration; the values here (multipliers, gradients) are far
/// from the overflow range.
inline double norm2(double a, double b) {
  return std::sqrt(a * a + b * b);
}
}  // namespace detail

/// "bound" / "disc".
std::string to_string(BlockKind kind);

/// Number of unknowns a block of this kind covers (1 or 2).
constexpr Index block_size(BlockKind kind) {
  return kind == BlockKind::Bound ? 1 : 2;
}

/// One block of the feasible set: its kind and the index of its first unknown.
struct Block {
  BlockKind kind = BlockKind::Bound;
  Index offset = 0;  ///< index of the first unknown of the block in the unknown vector
};

/// Block description of Omega. The blocks must cover every unknown exactly once (any order).
struct SeparableConstraints {
  std::vector<Block> blocks;
  /// One entry per block (same order as `blocks`). For a Disc block: its radius, finite and >= 0
  /// (0 pins the block to 0). Ignored for Bound blocks.
  Eigen::VectorXd radius;

  /// Number of unknowns covered by the blocks (sum of the block sizes).
  Index size() const;
  /// Number of Disc blocks.
  Index n_discs() const;
  /// Largest radius of a Disc block, 0 if there is none.
  double max_radius() const;

  /// Throws fricon::InputError if the radius vector has the wrong length, a Disc radius is
  /// negative or not finite, a block has a negative offset, two blocks overlap, or an unknown
  /// below the last covered one is left uncovered (a gap). The message names the blocks and
  /// unknowns involved.
  void validate() const;

  /// Euclidean projection P_Omega, in place, block by block: Bound x_i := max(x_i, 0); Disc
  /// x := x if ||x|| <= rho, else rho x / ||x||. Requires x.size() == size() (checked).
  void project(Eigen::VectorXd& x) const;

  /// Sets the radii of the Disc blocks, in the order the Disc blocks appear in `blocks`.
  /// Throws fricon::InputError if disc_radius.size() != n_discs().
  void set_disc_radii(const Eigen::VectorXd& disc_radius);

  /// The contact layout of n_patches multiplier patches: patch i owns the unknowns 3i (normal,
  /// Bound block) and 3i+1, 3i+2 (the two tangential components, Disc block). The blocks are
  /// stored in the order Bound_0, Disc_0, Bound_1, Disc_1, ...; all radii start at 0
  /// (frictionless), set them with set_disc_radii().
  static SeparableConstraints contact_layout(Index n_patches);
};

}  // namespace fricon::qp
