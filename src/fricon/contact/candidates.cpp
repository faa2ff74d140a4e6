#include "fricon/contact/candidates.hpp"

#include <algorithm>
#include <iterator>

#include "fricon/core/error.hpp"

namespace fricon::contact {

VectorXd mean_penetration(const ContactDiscretization& disc, const VectorXd& w) {
  const VectorXd Bw = disc.B * w;
  VectorXd a(disc.n_patches());
  for (Index p = 0; p < disc.n_patches(); ++p)
    a(p) = (Bw(3 * p) - disc.offset(3 * p)) / disc.patches.area(p);
  return a;
}

std::vector<Index> initial_candidates(const VectorXd& free_penetration, Real margin) {
  FRICON_CHECK(margin >= 0.0, "initial_candidates: margin " << margin << " < 0");
  std::vector<Index> candidates;
  if (free_penetration.size() == 0) return candidates;
  Index deepest = 0;
  const Real delta = free_penetration.maxCoeff(&deepest);
  const Real threshold = -margin * delta;
  for (Index p = 0; p < free_penetration.size(); ++p)
    if (p == deepest || (delta > 0.0 && free_penetration(p) >= threshold)) candidates.push_back(p);
  return candidates;
}

std::vector<Index> penetrating_patches(const VectorXd& penetration,
                                       const std::vector<Index>& candidates, Real tolerance) {
  std::vector<Index> added;
  auto next = candidates.begin();
  for (Index p = 0; p < penetration.size(); ++p) {
    if (next != candidates.end() && *next == p) {
      ++next;
      continue;
    }
    if (penetration(p) > tolerance) added.push_back(p);
  }
  return added;
}

std::vector<Index> merge_patches(const std::vector<Index>& candidates,
                                 const std::vector<Index>& added) {
  std::vector<Index> merged;
  merged.reserve(candidates.size() + added.size());
  std::merge(candidates.begin(), candidates.end(), added.begin(), added.end(),
             std::back_inserter(merged));
  return merged;
}

namespace {

// The rows 3p, 3p+1, 3p+2 of m (only 3p for PatchRows::Normal, the others zero) for the patches p
// of subset, in its order.
SparseMatrix patch_rows(const SparseMatrix& m, const std::vector<Index>& subset, PatchRows kept) {
  std::vector<Eigen::Triplet<Real>> entries;
  const Eigen::SparseMatrix<Real, Eigen::RowMajor> rows(m);
  const Index n_kept = kept == PatchRows::Normal ? 1 : 3;
  for (size_t i = 0; i < subset.size(); ++i)
    for (Index k = 0; k < n_kept; ++k)
      for (Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(rows, 3 * subset[i] + k);
           it; ++it)
        entries.emplace_back(static_cast<Index>(3 * i) + k, it.col(), it.value());
  SparseMatrix out(static_cast<Index>(3 * subset.size()), m.cols());
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace

ContactDiscretization restrict_to_patches(const ContactDiscretization& disc,
                                          const std::vector<Index>& subset, PatchRows rows) {
  for (size_t i = 0; i < subset.size(); ++i)
    FRICON_CHECK(
        subset[i] >= 0 && subset[i] < disc.n_patches() && (i == 0 || subset[i - 1] < subset[i]),
        "restrict_to_patches: patch " << subset[i] << " out of order or range");
  ContactDiscretization sub;
  sub.surface = disc.surface;
  sub.slip_bound = disc.slip_bound;
  sub.gap = disc.gap;
  sub.dofs = disc.dofs;
  sub.stability = disc.stability;
  sub.partition_note = disc.partition_note;
  sub.radius_integration = disc.radius_integration;
  sub.pairs = disc.pairs;
  const auto n = static_cast<Index>(subset.size());
  sub.patches.area.resize(n);
  sub.patches.centroid.resize(3, n);
  sub.patch_frames.n.resize(3, n);
  sub.patch_frames.t1.resize(3, n);
  sub.patch_frames.t2.resize(3, n);
  sub.offset.resize(3 * n);
  for (Index i = 0; i < n; ++i) {
    const Index p = subset[static_cast<size_t>(i)];
    sub.patches.faces.push_back(disc.patches.faces[static_cast<size_t>(p)]);
    sub.patches.area(i) = disc.patches.area(p);
    sub.patches.centroid.col(i) = disc.patches.centroid.col(p);
    sub.patch_frames.n.col(i) = disc.patch_frames.n.col(p);
    sub.patch_frames.t1.col(i) = disc.patch_frames.t1.col(p);
    sub.patch_frames.t2.col(i) = disc.patch_frames.t2.col(p);
    sub.patch_pair.push_back(disc.patch_pair[static_cast<size_t>(p)]);
    sub.frame_integrals.push_back(disc.frame_integrals[static_cast<size_t>(p)]);
    sub.offset.segment<3>(3 * i) = disc.offset.segment<3>(3 * p);
    if (rows == PatchRows::Normal) sub.offset.segment<2>(3 * i + 1).setZero();
  }
  sub.B = patch_rows(disc.B, subset, rows);
  return sub;
}

VectorXd expand_to_patches(const VectorXd& x, const std::vector<Index>& subset, Index n_patches,
                           Index per_patch) {
  FRICON_CHECK(x.size() == per_patch * static_cast<Index>(subset.size()),
               "expand_to_patches: " << x.size() << " values for " << subset.size() << " patches");
  VectorXd out = VectorXd::Zero(per_patch * n_patches);
  for (size_t i = 0; i < subset.size(); ++i)
    out.segment(per_patch * subset[i], per_patch) =
        x.segment(per_patch * static_cast<Index>(i), per_patch);
  return out;
}

}  // namespace fricon::contact
