#pragma once
// qp: the separable feasible set Omega = Omega_1 x ... x Omega_s of the dual contact problem.
//
// Place in the data flow: `contact` decides which unknowns form a block and computes the disc
// radii (the Tresca bounds); `qp` only sees the block layout below and never a mesh. Three kinds
// of block exist:
//   Bound  one unknown,  x_i >= 0                     (normal multiplier)
//   Disc   two unknowns, ||(x_i, x_{i+1})|| <= rho    (tangential multiplier, rho >= 0)
//   Free   one unknown,  x_i in R, no constraint      (equality multiplier of domain
//                                                      decomposition: TFETI gluing, Dirichlet)
// A Disc with rho = 0 pins both of its unknowns to zero. Free blocks let the equality multipliers
// of a torn problem join the contact multipliers in one dual QP, solved by the same MPGP: on them
// the projection is the identity and the projected gradient is the gradient itself.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fricon/core/types.hpp"

namespace fricon::qp {

enum class BlockKind {
  Bound,  ///< x_i >= 0, one unknown
  Disc,   ///< ||(x_i, x_{i+1})|| <= radius, two unknowns
  /// x_i in R, one unknown with no constraint: an equality multiplier (a gluing or Dirichlet row
  /// of TFETI). Never active; its radius entry is ignored.
  Free,
};

namespace detail {
/// Euclidean norm of (a, b). Plain sqrt instead of std::hypot, which is several times slower and
/// dominates the O(n) work per MPGP iteration; the values here (multipliers, gradients) are far
/// from the overflow range.
inline double norm2(double a, double b) {
  return std::sqrt(a * a + b * b);
}
}  // namespace detail

/// "bound" / "disc" / "free" ("unknown" for a value that is no enumerator).
std::string to_string(BlockKind kind);

/// Number of unknowns a block of this kind covers (1 or 2); 0 for a value that is no enumerator
/// (validate() rejects such a block).
constexpr Index block_size(BlockKind kind) {
  switch (kind) {
    case BlockKind::Bound:
    case BlockKind::Free:
      return 1;
    case BlockKind::Disc:
      return 2;
  }
  return 0;
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
  /// (0 pins the block to 0). Ignored for Bound and Free blocks.
  Eigen::VectorXd radius;

  /// Number of unknowns covered by the blocks (sum of the block sizes).
  Index size() const;
  /// Number of Disc blocks.
  Index n_discs() const;
  /// Largest radius of a Disc block, 0 if there is none.
  double max_radius() const;

  /// Throws fricon::InputError if the radius vector has the wrong length, a block's kind is no
  /// BlockKind enumerator, a Disc radius is negative or not finite, a block has a negative
  /// offset, two blocks overlap, or an unknown below the last covered one is left uncovered (a
  /// gap). The message names the blocks and unknowns involved.
  void validate() const;

  /// Euclidean projection P_Omega, in place, block by block: Bound x_i := max(x_i, 0); Disc
  /// x := x if ||x|| <= rho, else rho x / ||x||; Free x_i unchanged. Requires x.size() == size()
  /// (checked).
  void project(Eigen::VectorXd& x) const;

  /// Sets the radii of the Disc blocks, in the order the Disc blocks appear in `blocks`.
  /// Throws fricon::InputError if disc_radius.size() != n_discs().
  void set_disc_radii(const Eigen::VectorXd& disc_radius);

  /// The contact layout of n_patches multiplier patches: patch i owns the unknowns 3i (normal,
  /// Bound block) and 3i+1, 3i+2 (the two tangential components, Disc block). The blocks are
  /// stored in the order Bound_0, Disc_0, Bound_1, Disc_1, ...; all radii start at 0
  /// (frictionless), set them with set_disc_radii().
  static SeparableConstraints contact_layout(Index n_patches);

  /// Appends n Free blocks, one unknown each, numbered consecutively from one past the last
  /// unknown any block covers (from 0 if there is none), with radius entries 0, so that the
  /// equality multipliers follow the contact ones: contact_layout(p) then append_free(m) covers
  /// unknowns 0 ... 3p + m - 1. Throws fricon::InputError if n < 0 or if the radius vector does
  /// not have one entry per block before the call (the new entries could not be placed).
  void append_free(Index n);
};

}  // namespace fricon::qp
