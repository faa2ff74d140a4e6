#include "fricon/qp/constraints.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::qp {

std::string to_string(BlockKind kind) {
  switch (kind) {
    case BlockKind::Bound:
      return "bound";
    case BlockKind::Disc:
      return "disc";
    case BlockKind::Free:
      return "free";
  }
  return "unknown";
}

Index SeparableConstraints::size() const {
  Index n = 0;
  for (const Block& blk : blocks)
    n += block_size(blk.kind);
  return n;
}

Index SeparableConstraints::n_discs() const {
  return static_cast<Index>(std::count_if(
      blocks.begin(), blocks.end(), [](const Block& b) { return b.kind == BlockKind::Disc; }));
}

double SeparableConstraints::max_radius() const {
  double r = 0.0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (blocks[k].kind == BlockKind::Disc) r = std::max(r, radius(static_cast<Index>(k)));
  }
  return r;
}

void SeparableConstraints::validate() const {
  const Index n_blocks = static_cast<Index>(blocks.size());
  if (radius.size() != n_blocks) {
    throw InputError(fmt::format(
        "SeparableConstraints: radius has {} entries, expected one per block ({} blocks)",
        radius.size(), n_blocks));
  }
  // Extent of the layout: one past the last unknown any block touches. Overlaps and gaps are
  // reported separately against it (size() alone would turn a gap into an out-of-range block).
  Index extent = 0;
  for (Index k = 0; k < n_blocks; ++k) {
    const Block& blk = blocks[static_cast<std::size_t>(k)];
    // A kind that is no enumerator (a cast integer) has block_size 0 and would cover nothing.
    if (block_size(blk.kind) == 0) {
      throw InputError(
          fmt::format("SeparableConstraints: block {} (offset {}) has kind {}, "
                      "expected bound, disc or free",
                      k, blk.offset, static_cast<int>(blk.kind)));
    }
    if (blk.offset < 0) {
      throw InputError(fmt::format("SeparableConstraints: {} block {} has negative offset {}",
                                   to_string(blk.kind), k, blk.offset));
    }
    if (blk.kind == BlockKind::Disc && !(std::isfinite(radius(k)) && radius(k) >= 0.0)) {
      throw InputError(fmt::format(
          "SeparableConstraints: disc block {} (offset {}) has radius {}, expected a finite "
          "value >= 0",
          k, blk.offset, radius(k)));
    }
    extent = std::max(extent, blk.offset + block_size(blk.kind));
  }
  // owner[i] = index of the block covering unknown i, or -1.
  std::vector<Index> owner(static_cast<std::size_t>(extent), -1);
  for (Index k = 0; k < n_blocks; ++k) {
    const Block& blk = blocks[static_cast<std::size_t>(k)];
    for (Index i = blk.offset; i < blk.offset + block_size(blk.kind); ++i) {
      Index& o = owner[static_cast<std::size_t>(i)];
      if (o >= 0) {
        throw InputError(
            fmt::format("SeparableConstraints: blocks {} and {} overlap at unknown {}", o, k, i));
      }
      o = k;
    }
  }
  const auto gap = std::find(owner.begin(), owner.end(), Index{-1});
  if (gap != owner.end()) {
    throw InputError(fmt::format(
        "SeparableConstraints: unknown {} is covered by no block (the blocks reach up to {})",
        gap - owner.begin(), extent));
  }
}

void SeparableConstraints::project(Eigen::VectorXd& x) const {
  FRICON_CHECK(x.size() == size(),
               "vector of size " << x.size() << " for " << size() << " unknowns");
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Index o = blocks[k].offset;
    if (blocks[k].kind == BlockKind::Free) continue;  // Omega_k = R: P is the identity
    if (blocks[k].kind == BlockKind::Bound) {
      x(o) = std::max(x(o), 0.0);
    } else {
      const double rho = radius(static_cast<Index>(k));
      const double nrm = detail::norm2(x(o), x(o + 1));
      if (nrm > rho) {
        const double s = rho / nrm;
        x(o) *= s;
        x(o + 1) *= s;
      }
    }
  }
}

void SeparableConstraints::set_disc_radii(const Eigen::VectorXd& disc_radius) {
  const Index nd = n_discs();
  if (disc_radius.size() != nd) {
    throw InputError(fmt::format("SeparableConstraints::set_disc_radii: {} radii for {} discs",
                                 disc_radius.size(), nd));
  }
  if (radius.size() != static_cast<Index>(blocks.size())) {
    radius = Eigen::VectorXd::Zero(static_cast<Index>(blocks.size()));
  }
  Index d = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (blocks[k].kind == BlockKind::Disc) radius(static_cast<Index>(k)) = disc_radius(d++);
  }
}

SeparableConstraints SeparableConstraints::contact_layout(Index n_patches) {
  if (n_patches < 0) {
    throw InputError(fmt::format("contact_layout: n_patches = {} must be >= 0", n_patches));
  }
  SeparableConstraints c;
  c.blocks.reserve(static_cast<std::size_t>(2 * n_patches));
  for (Index i = 0; i < n_patches; ++i) {
    c.blocks.push_back({BlockKind::Bound, 3 * i});
    c.blocks.push_back({BlockKind::Disc, 3 * i + 1});
  }
  c.radius = Eigen::VectorXd::Zero(2 * n_patches);
  return c;
}

void SeparableConstraints::append_free(Index n) {
  if (n < 0) {
    throw InputError(fmt::format("SeparableConstraints::append_free: n = {} must be >= 0", n));
  }
  const Index n_blocks = static_cast<Index>(blocks.size());
  if (radius.size() != n_blocks) {
    throw InputError(fmt::format(
        "SeparableConstraints::append_free: radius has {} entries for {} blocks; expected one "
        "per block",
        radius.size(), n_blocks));
  }
  // One past the last covered unknown (not size(), which a gap in the layout would shorten): the
  // new unknowns must not overlap any existing block.
  Index first = 0;
  for (const Block& blk : blocks)
    first = std::max(first, blk.offset + block_size(blk.kind));
  blocks.reserve(blocks.size() + static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
    blocks.push_back({BlockKind::Free, first + i});
  radius.conservativeResize(n_blocks + n);
  radius.tail(n).setZero();
}

}  // namespace fricon::qp
