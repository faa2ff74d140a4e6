#pragma once
// dual: the ways fricon applies the dual Hessian Q = B K^-1 B^T (theory.md §3.3), as the user
// names them ([solver] dual_operator). The operators themselves are in dual_operator.hpp.

#include <array>
#include <string_view>
#include <utility>

#include "fricon/core/enum_names.hpp"

namespace fricon::dual {

enum class DualOperatorKind {
  /// Forward while the dense Q is no larger than the factor of K (or n_dual <= 6000), else
  /// implicit (theory.md §3.3).
  Auto,
  /// Each product with Q is one solve with the factor of K (the paper's way).
  Implicit,
  /// Q formed once by a forward sweep over the part of the factor the contact dofs reach.
  Forward,
  /// K factored with the contact dofs last; Q from the trailing block of the factor.
  Schur,
};

}  // namespace fricon::dual

FRICON_ENUM_NAMES(fricon::dual::DualOperatorKind, "solver.dual_operator",
                  {dual::DualOperatorKind::Auto, "auto"},
                  {dual::DualOperatorKind::Implicit, "implicit"},
                  {dual::DualOperatorKind::Forward, "forward"},
                  {dual::DualOperatorKind::Schur, "schur"});
