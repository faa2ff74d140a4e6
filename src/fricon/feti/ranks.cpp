#include "fricon/feti/ranks.hpp"

namespace fricon::feti {

std::pair<Index, Index> Ranks::block_of(int q, Index n) const {
  const auto r = static_cast<Index>(q), p = static_cast<Index>(size());
  return {n * r / p, n * (r + 1) / p};
}

bool Ranks::owns(Index i, Index n) const {
  const auto [first, last] = block(n);
  return first <= i && i < last;
}

const Ranks& this_process() {
  static const Ranks alone;
  return alone;
}

}  // namespace fricon::feti
