#pragma once
// dual: the ways fricon applies the dual Hessian Q = B K^-1 B^T (theory.md §3.3), as the user
// names them ([solver] dual_operator). The operators themselves are in dual_operator.hpp.

#include <array>
#include <string_view>
#include <utility>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"

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

/// "auto" forms a dense Q of at most this many multipliers (288 MB) whatever the factor's size.
inline constexpr Index kDenseDualLimit = 6000;

/// Where K is factored, for what "auto" stands for.
enum class FactorLocation {
  OneProcess,   ///< CHOLMOD: the factor is at hand for a forward sweep
  Distributed,  ///< MUMPS across the ranks: Q comes from its Schur complement
};

/// The operator "auto" stands for (theory.md §3.3), the one rule of fricon: on one process
/// Forward while the dense Q (n_dual^2 entries) is no larger than the factor (nnz_L entries) or
/// n_dual <= kDenseDualLimit, else Implicit; distributed, Schur up to kDenseDualLimit, else
/// Implicit. Other kinds are returned as they are. nnz_L is not used when distributed.
DualOperatorKind resolve(DualOperatorKind kind, FactorLocation where, Index n_dual,
                         double nnz_L = 0.0);

}  // namespace fricon::dual

FRICON_ENUM_NAMES(fricon::dual::DualOperatorKind, "solver.dual_operator",
                  {dual::DualOperatorKind::Auto, "auto"},
                  {dual::DualOperatorKind::Implicit, "implicit"},
                  {dual::DualOperatorKind::Forward, "forward"},
                  {dual::DualOperatorKind::Schur, "schur"});
