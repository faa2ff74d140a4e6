// contact: the slip bounds of several contact pairs, each pair's patches by the pair's own
// friction model and law (theory.md §5.7). The merged dual QP keeps one radius per patch; only
// how that radius follows from the state differs from pair to pair.
#include <fmt/format.h>

#include "fricon/contact/slip_bounds.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

// The patches of `all` with the given indices, in that order.
Patches select_patches(const Patches& all, const std::vector<Index>& indices) {
  Patches part;
  const auto n = static_cast<Index>(indices.size());
  part.area.resize(n);
  part.centroid.resize(3, n);
  for (Index i = 0; i < n; ++i) {
    const Index p = indices[static_cast<size_t>(i)];
    part.faces.push_back(all.faces[static_cast<size_t>(p)]);
    part.area(i) = all.area(p);
    part.centroid.col(i) = all.centroid.col(p);
  }
  return part;
}

VectorXd gather(const VectorXd& x, const std::vector<Index>& indices) {
  VectorXd out(static_cast<Index>(indices.size()));
  for (size_t i = 0; i < indices.size(); ++i)
    out(static_cast<Index>(i)) = x(indices[i]);
  return out;
}

void scatter(const VectorXd& part, const std::vector<Index>& indices, VectorXd& x) {
  for (size_t i = 0; i < indices.size(); ++i)
    x(indices[i]) = part(static_cast<Index>(i));
}

// One pair: its patches and surface nodes in the merged discretization, its law, and the bounds
// of its model on its patches (null when a contact search left out all of them).
struct Pair {
  std::vector<Index> patches, nodes;
  PairFriction friction;
  std::unique_ptr<SlipBounds> bounds;
};

class PairBounds final : public SlipBounds {
 public:
  PairBounds(const mesh::TetMesh& mesh, const ContactDiscretization& disc,
             std::vector<PairFriction> frictions)
      : n_patches_(disc.n_patches()), n_nodes_(disc.surface.n_nodes()) {
    FRICON_CHECK(frictions.size() == disc.pairs.size(),
                 "make_pair_bounds: " << frictions.size() << " frictions for " << disc.pairs.size()
                                      << " pairs");
    pairs_.resize(frictions.size());
    for (Index p = 0; p < n_patches_; ++p)
      pairs_[static_cast<size_t>(disc.patch_pair[static_cast<size_t>(p)])].patches.push_back(p);
    for (Index k = 0; k < n_nodes_; ++k)
      pairs_[static_cast<size_t>(disc.surface.node_pair[static_cast<size_t>(k)])].nodes.push_back(
          k);
    for (size_t i = 0; i < pairs_.size(); ++i) {
      Pair& pair = pairs_[i];
      pair.friction = std::move(frictions[i]);
      FRICON_CHECK(pair.friction.law, "make_pair_bounds: pair " << i << " has no law");
      uses_pressure_ = uses_pressure_ ||
                       (pair.friction.model == FrictionModel::Coulomb && !pair.patches.empty());
      if (pair.patches.empty()) continue;
      Patches patches = select_patches(disc.patches, pair.patches);
      const FrictionLaw& F = *pair.friction.law;
      pair.bounds =
          pair.friction.model == FrictionModel::Coulomb
              ? make_coulomb_bounds(mesh, disc.surface, std::move(patches), F,
                                    pair.friction.start_slip_bound)
              : make_tresca_bounds(mesh, disc.surface, std::move(patches), disc.slip_bound, F);
    }
    coulomb_.assign(static_cast<size_t>(n_patches_), false);
    for (const Pair& pair : pairs_)
      for (Index p : pair.patches)
        coulomb_[static_cast<size_t>(p)] = pair.friction.model == FrictionModel::Coulomb;
  }

  bool uses_pressure() const override { return uses_pressure_; }
  bool coulomb_patch(Index p) const override { return coulomb_[static_cast<size_t>(p)]; }

  VectorXd radii(int k, const VectorXd& phi, const VectorXd& lambda_n) const override {
    VectorXd rho = VectorXd::Zero(n_patches_);
    for (const Pair& pair : pairs_) {
      if (!pair.bounds) continue;
      const VectorXd own_lambda_n = pair.bounds->uses_pressure()
                                        ? gather(lambda_n, pair.patches)
                                        : VectorXd::Zero(static_cast<Index>(pair.patches.size()));
      scatter(pair.bounds->radii(k, phi, own_lambda_n), pair.patches, rho);
    }
    return rho;
  }

  VectorXd mean_coefficients(const VectorXd& phi) const override {
    VectorXd F_R = VectorXd::Zero(n_patches_);
    for (const Pair& pair : pairs_)
      if (pair.bounds) scatter(pair.bounds->mean_coefficients(phi), pair.patches, F_R);
    return F_R;
  }

  VectorXd nodal_coefficients(const VectorXd& slip) const override {
    VectorXd F = VectorXd::Zero(n_nodes_);
    for (const Pair& pair : pairs_) {
      if (pair.nodes.empty()) continue;
      const VectorXd own = gather(slip, pair.nodes);
      VectorXd own_F(own.size());
      pair.friction.law->evaluate(
          std::span<const Real>(own.data(), static_cast<size_t>(own.size())),
          std::span<Real>(own_F.data(), static_cast<size_t>(own_F.size())));
      scatter(own_F, pair.nodes, F);
    }
    return F;
  }

  std::vector<const FrictionLaw*> laws() const override {
    std::vector<const FrictionLaw*> out;
    for (const Pair& pair : pairs_)
      if (pair.bounds) out.push_back(pair.friction.law.get());
    return out;
  }

 private:
  Index n_patches_, n_nodes_;
  std::vector<Pair> pairs_;
  std::vector<bool> coulomb_;  // per patch
  bool uses_pressure_ = false;
};

}  // namespace

std::unique_ptr<SlipBounds> make_pair_bounds(const mesh::TetMesh& mesh,
                                             const ContactDiscretization& disc,
                                             std::vector<PairFriction> pairs) {
  return std::make_unique<PairBounds>(mesh, disc, std::move(pairs));
}

}  // namespace fricon::contact
