#pragma once
// feti: how soft each subdomain is beyond its rigid motions (docs/theory.md §8.9). A METIS part
// can be a lobe joined to the rest of its subdomain by a neck a few tetrahedra wide: it is
// face-connected, yet K_s has a deformation almost as free as a rigid motion. F then has large
// entries along that mode that the natural coarse space does not remove and the Dirichlet
// preconditioner does not undo, and MPGP's conjugate gradients need many times their usual
// steps. The measure of a subdomain is the smallest non-zero eigenvalue of K_s over the mean of
// its diagonal; a neck shows as a value far below the run's median.

#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/feti/feti_options.hpp"
#include "fricon/feti/ranks.hpp"
#include "fricon/feti/subdomains.hpp"

namespace fricon::feti {

/// Power steps with K_s^+ per subdomain: enough to bring the estimate within a factor of about
/// two of the softest eigenvalue, and to within a few per cent where a neck sets it far apart from
/// the next one (the case it is for). Each costs one solve with the subdomain's factor.
inline constexpr int kSoftnessSteps = 16;
/// A subdomain is joined by a neck when its measure is this many times below the run's median.
/// On the paper's brick the METIS partitions with long inner solves had 36.5 to 78.4, the others
/// 1.6 to 12.7 (docs/benchmarks.md, "Subdomains joined by a neck").
inline constexpr Real kNeckRatio = 20.0;

/// The softness of every subdomain of `subdomains` (each with its factor of the regularized K_s
/// and R_s: make_subdomains), by kSoftnessSteps power steps with P K_s^+ P, P the orthogonal
/// projector onto the complement of R_s, whose largest eigenvalue is 1 / lambda_7(K_s)
/// (theory.md §8.9). Runs the subdomains of this process's block on `threads` threads and sums
/// the values over `ranks` (collective), so that every process returns the same.
Softness subdomain_softness(const std::vector<Subdomain>& subdomains, int threads,
                            const Ranks& ranks);

}  // namespace fricon::feti
