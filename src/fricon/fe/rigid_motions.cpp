#include "fricon/fe/rigid_motions.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"

namespace fricon::fe {

namespace {
// An eigenvalue of the Gram matrix below this fraction of the largest is a free rigid motion.
constexpr Real kNullTolerance = 1e-12;
constexpr Index kRigidMotions = 6;  // three translations, three rotations
}  // namespace

RigidMotionCheck free_rigid_motions(const mesh::TetMesh& mesh, const std::vector<Index>& nodes,
                                    const std::vector<bool>& fixed) {
  FRICON_CHECK(
      fixed.size() == static_cast<size_t>(3 * mesh.n_nodes()),
      "free_rigid_motions: " << fixed.size() << " flags for " << mesh.n_nodes() << " nodes");
  RigidMotionCheck check;
  if (nodes.empty()) return check;
  const mesh::BoundingBox box = mesh::bounding_box(mesh, nodes);
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  const Real scale = std::max((box.hi - box.lo).maxCoeff(), std::numeric_limits<Real>::min());
  Eigen::Matrix<long double, 6, 6> gram = Eigen::Matrix<long double, 6, 6>::Zero();
  for (Index a : nodes) {
    const Vec3 x = (mesh.nodes.col(a) - centre) / scale;
    for (int c = 0; c < 3; ++c) {
      if (!fixed[static_cast<size_t>(3 * a + c)]) continue;
      ++check.n_fixed;
      // Component c of the translations e_0..e_2 and of the rotations e_k x x.
      Eigen::Matrix<long double, 6, 1> r = Eigen::Matrix<long double, 6, 1>::Zero();
      r(c) = 1.0L;
      for (int k = 0; k < 3; ++k)
        r(3 + k) = static_cast<long double>(Vec3::Unit(k).cross(x)(c));
      gram += r * r.transpose();
    }
  }
  const Eigen::Matrix<Real, 6, 6> g = gram.cast<Real>();
  if (check.n_fixed == 0) {
    check.n_free = kRigidMotions;
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, 6, 6>> eig(g, Eigen::EigenvaluesOnly);
    const Real lmax = eig.eigenvalues().maxCoeff();
    for (Index i = 0; i < kRigidMotions; ++i)
      check.n_free += eig.eigenvalues()(i) <= kNullTolerance * lmax ? 1 : 0;
  }
  std::vector<char> loose;  // components fixed nowhere
  for (int c = 0; c < 3; ++c)
    if (g(c, c) == 0.0) loose.push_back("xyz"[c]);
  for (size_t i = 0; i < loose.size(); ++i)
    check.loose_axes += fmt::format("{}{}",
                                    i == 0                  ? ""
                                    : i + 1 == loose.size() ? " or "
                                                            : ", ",
                                    loose[i]);
  return check;
}

std::vector<RigidMotionCheck> free_rigid_motions(const mesh::TetMesh& mesh,
                                                 const mesh::Bodies& bodies,
                                                 const std::vector<bool>& fixed) {
  std::vector<RigidMotionCheck> checks;
  checks.reserve(bodies.nodes.size());
  for (const auto& nodes : bodies.nodes)
    checks.push_back(free_rigid_motions(mesh, nodes, fixed));
  return checks;
}

}  // namespace fricon::fe
