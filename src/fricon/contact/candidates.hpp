#pragma once
// contact: the contact search (theory.md §2.7), which patches enter the dual QP. A patch that
// the body cannot reach carries no pressure; leaving it out of the QP saves its three rows of Q
// (forming Q costs one sweep of the reach of B per row) and its share of every product, and
// keeps the far patches' large gaps out of h. The rule:
//
//   1. candidates: the patches whose free penetration a_R (the mean of u0_n - gap over R for the
//      displacement u0 = K^-1 f without contact) is at least -margin * delta, delta = max_R a_R
//      the deepest free penetration [m]: their gap is within margin * delta of closing (and at
//      least the deepest patch);
//   2. after each solve, every patch left out is checked with the displacement w of the whole
//      body: one whose mean of w_n - gap is positive is added and the step is solved again.
//
// Step 2 makes the answer that of the whole QP whatever step 1 chose; step 1 only decides how
// often step 2 has to grow the set.

#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"

namespace fricon::contact {

/// Which patches enter the dual QP ([solver] contact_search).
enum class ContactSearch {
  Off,  ///< every patch, as in [HL09]
  Gap,  ///< the candidates of the rule above, grown until none left out penetrates; default
};

/// Mean normal penetration per patch [m]: ((B w)_n - c_n) / |R|, the mean over R of w_n - gap
/// (the prescribed displacements included), for w over the free dofs [m]. Positive: R
/// penetrates the obstacle.
VectorXd mean_penetration(const ContactDiscretization& disc, const VectorXd& w);

/// The initial candidates of step 1 from the free penetrations a (mean_penetration of u0) and
/// margin >= 0: increasing patch indices, never empty when a is not.
std::vector<Index> initial_candidates(const VectorXd& free_penetration, Real margin);

/// The patches not in `candidates` (increasing) whose penetration exceeds tolerance [m],
/// increasing.
std::vector<Index> penetrating_patches(const VectorXd& penetration,
                                       const std::vector<Index>& candidates, Real tolerance);

/// `candidates` and `added` (both increasing, disjoint) merged, increasing.
std::vector<Index> merge_patches(const std::vector<Index>& candidates,
                                 const std::vector<Index>& added);

/// Which rows of B a restricted discretization keeps.
enum class PatchRows {
  All,     ///< normal and tangential
  Normal,  ///< the normal rows; the tangential ones are zero (frictionless: their multipliers
           ///< are pinned at 0, and a zero row costs nothing when Q is formed)
};

/// The part of `disc` on the patches `subset` (increasing, distinct, in range): the same surface,
/// gap, slip bounds, contact dofs and stability report; the patches and the rows of B and of
/// the offset of the subset, in its order (with PatchRows::Normal the tangential rows of B and
/// of the offset are zero).
ContactDiscretization restrict_to_patches(const ContactDiscretization& disc,
                                          const std::vector<Index>& subset,
                                          PatchRows rows = PatchRows::All);

/// x of the subset's multipliers (3 per patch of `subset`) placed in a vector over every patch
/// of `n_patches` (3 per patch), zero elsewhere; `per_patch` 1 for one value per patch.
VectorXd expand_to_patches(const VectorXd& x, const std::vector<Index>& subset, Index n_patches,
                           Index per_patch);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::ContactSearch, "solver.contact_search",
                  {contact::ContactSearch::Off, "off"}, {contact::ContactSearch::Gap, "gap"});
