#include "fricon/fe/rigid_motions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"

namespace fricon::fe {

namespace {
// An eigenvalue of the Gram matrix below this fraction of the largest is a free rigid motion.
constexpr Real kNullTolerance = 1e-12;
constexpr Index kRigidMotions = 6;  // three translations, three rotations
// A coefficient of a free motion below this share of its largest is rounding (set to zero).
constexpr Real kCoefficientRounding = 1e-9;

// The columns of `null` (6 x k) brought to reduced echelon form over the modes in the order
// tx .. rz (Gauss-Jordan on the transpose, pivoting on the largest entry of each mode), so that
// a mode free alone becomes a unit column. The column space is unchanged.
Eigen::Matrix<Real, 6, Eigen::Dynamic> echelon(Eigen::Matrix<Real, 6, Eigen::Dynamic> null) {
  Eigen::Matrix<Real, Eigen::Dynamic, 6> rows = null.transpose();
  const Index k = rows.rows();
  Index pivot_row = 0;
  for (Index mode = 0; mode < 6 && pivot_row < k; ++mode) {
    Index best = pivot_row;
    rows.col(mode).segment(pivot_row, k - pivot_row).cwiseAbs().maxCoeff(&best);
    best += pivot_row;
    if (std::abs(rows(best, mode)) <= kCoefficientRounding * rows.cwiseAbs().maxCoeff()) continue;
    rows.row(pivot_row).swap(rows.row(best));
    rows.row(pivot_row) /= rows(pivot_row, mode);
    for (Index r = 0; r < k; ++r)
      if (r != pivot_row) rows.row(r) -= rows(r, mode) * rows.row(pivot_row);
    ++pivot_row;
  }
  for (Index r = 0; r < k; ++r) {
    const Real largest = rows.row(r).cwiseAbs().maxCoeff();
    for (Index c = 0; c < 6; ++c)
      if (std::abs(rows(r, c)) <= kCoefficientRounding * largest) rows(r, c) = 0.0;
  }
  return rows.transpose();
}
}  // namespace

std::string describe_motion(const MotionCoefficients& c) {
  static const char* const names[6] = {"translation x",    "translation y",    "translation z",
                                       "rotation about x", "rotation about y", "rotation about z"};
  static const char* const symbols[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  Index n_nonzero = 0, only = 0;
  for (Index i = 0; i < 6; ++i)
    if (c(i) != 0.0) {
      ++n_nonzero;
      only = i;
    }
  if (n_nonzero == 1) return names[only];
  std::string s;
  for (Index i = 0; i < 6; ++i)
    if (c(i) != 0.0) s += fmt::format("{}{:.3g} {}", s.empty() ? "" : " + ", c(i), symbols[i]);
  return s.empty() ? "none" : s;
}

Vec3 motion_at(const MotionCoefficients& c, const Vec3& centre, const Vec3& x) {
  return c.head<3>() + c.tail<3>().cross(x - centre);
}

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
  check.centre = centre;
  // The null space of the Gram matrix, in the scaled coordinates (x - centre) / scale; a
  // rotation coefficient there is scale times the physical one.
  Eigen::Matrix<Real, 6, Eigen::Dynamic> null;
  if (check.n_fixed == 0) {
    check.n_free = kRigidMotions;
    null = Eigen::Matrix<Real, 6, 6>::Identity();
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, 6, 6>> eig(g);
    const Real lmax = eig.eigenvalues().maxCoeff();
    for (Index i = 0; i < kRigidMotions; ++i)
      check.n_free += eig.eigenvalues()(i) <= kNullTolerance * lmax ? 1 : 0;
    null = eig.eigenvectors().leftCols(check.n_free);  // eigenvalues ascending
  }
  null.bottomRows<3>() /= scale;
  check.free = echelon(null);
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
