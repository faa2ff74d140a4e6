#pragma once
// outer: how the successive approximations are accelerated ([solver] acceleration).

#include <array>
#include <string_view>
#include <utility>

#include "fricon/core/enum_names.hpp"

namespace fricon::outer {

enum class Acceleration {
  None,      ///< the paper's plain iteration x^k = Psi(x^(k-1))
  Anderson,  ///< Anderson mixing of the last iterates (theory.md §5.3)
};

}  // namespace fricon::outer

FRICON_ENUM_NAMES(fricon::outer::Acceleration, "solver.acceleration",
                  {outer::Acceleration::None, "none"}, {outer::Acceleration::Anderson, "anderson"});
