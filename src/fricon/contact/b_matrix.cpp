#include "fricon/contact/b_matrix.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

Frames patch_frames(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches) {
  if (surface.master.size() == 0 && !surface.frames_vary)
    return Frames::constant(surface.n, surface.t1, surface.t2, patches.size());
  Frames f;
  f.n.resize(3, patches.size());
  f.t1.resize(3, patches.size());
  f.t2.resize(3, patches.size());
  // Against a body or a curved obstacle: the area-weighted mean of the nodes' contact normals
  // (theory.md §2.8, §2.11).
  for (Index p = 0; p < patches.size(); ++p) {
    Vec3 sum = Vec3::Zero();
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index face = surface.faces[static_cast<size_t>(k)];
      Vec3 nodal = Vec3::Zero();
      for (int v = 0; v < 3; ++v)  // the corners' normals
        nodal += surface.node_frames.n.col(surface.face_nodes(v, k));
      sum += mesh::face_area(mesh, face) * nodal;
    }
    const Vec3 n = sum.normalized();
    const auto [t1, t2] = Frames::tangents(n);
    f.n.col(p) = n;
    f.t1.col(p) = t1;
    f.t2.col(p) = t2;
  }
  return f;
}

namespace {

/// The directions (rows n, t1, t2) at surface node k inside patch frame F: F itself, or against
/// a curved obstacle F turned onto the node's normal (t1 the projection of F's t1 on the node's
/// tangent plane, t2 = t1 x n), so that the frame varies smoothly inside the patch.
Mat3 node_directions(const ContactSurface& surface, const Mat3& F, Index k) {
  if (!surface.frames_vary) return F;
  const Vec3 n = surface.node_frames.n.col(k);
  const Vec3 t1 = (Vec3(F.row(1)) - F.row(1).dot(n) * n).normalized();
  Mat3 d;
  d.row(0) = n.transpose();
  d.row(1) = t1.transpose();
  d.row(2) = t1.cross(n).transpose();
  return d;
}

}  // namespace

std::vector<PatchRowWeights> patch_row_weights(const mesh::TetMesh& mesh,
                                               const ContactSurface& surface,
                                               const Patches& patches, const Frames& frames) {
  std::vector<PatchRowWeights> out(static_cast<size_t>(patches.size()));
  std::vector<Index> slot(static_cast<size_t>(surface.n_nodes()), -1);
  for (Index p = 0; p < patches.size(); ++p) {
    PatchRowWeights& w = out[static_cast<size_t>(p)];
    const Mat3 F = frames.rows(p);
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      // int_T phi_a d dS with d = sum_b phi_b d_b: the face mass matrix applied to the nodes'
      // directions; with one frame, (int_T phi_a dS) F.
      const FaceIntegrals integrals = face_integrals(mesh, surface, k);
      const Index n = surface.face_nodes.rows();
      std::vector<Mat3> d(static_cast<size_t>(n));
      for (Index v = 0; v < n; ++v)
        d[static_cast<size_t>(v)] = node_directions(surface, F, surface.face_nodes(v, k));
      for (Index a = 0; a < n; ++a) {
        const Index node = surface.face_nodes(a, k);
        Index& s = slot[static_cast<size_t>(node)];
        if (s < 0) {
          s = static_cast<Index>(w.nodes.size());
          w.nodes.push_back(node);
          w.W.push_back(Mat3::Zero());
        }
        Mat3& W = w.W[static_cast<size_t>(s)];
        if (!surface.frames_vary) {
          W += integrals.shape(a) * F;
          continue;
        }
        for (Index b = 0; b < n; ++b)
          W += integrals.mass(a, b) * d[static_cast<size_t>(b)];
      }
    }
    for (size_t i = 0; i < w.nodes.size(); ++i) {
      w.integral += w.W[i];
      slot[static_cast<size_t>(w.nodes[i])] = -1;
    }
  }
  return out;
}

SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches, const Frames& frames,
                        const SparseMatrix* mortar) {
  std::vector<Eigen::Triplet<Real, SparseIndex>> triplets;
  // @sect: the slave's part, int_R phi_a d dS (patch_row_weights).
  const std::vector<PatchRowWeights> weights = patch_row_weights(mesh, surface, patches, frames);
  for (Index p = 0; p < patches.size(); ++p) {
    const PatchRowWeights& w = weights[static_cast<size_t>(p)];
    for (size_t i = 0; i < w.nodes.size(); ++i) {
      const Index node = surface.nodes[static_cast<size_t>(w.nodes[i])];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const Index col = dofs.dof(node, c);
          if (col >= 0 && w.W[i](r, c) != 0.0) triplets.emplace_back(3 * p + r, col, w.W[i](r, c));
        }
    }
  }
  // @sect: the master's part, minus int_R phi_a(projection) dir dS.
  if (mortar != nullptr)
    for (Index node = 0; node < mortar->outerSize(); ++node)
      for (SparseMatrix::InnerIterator it(*mortar, node); it; ++it) {
        const Index p = it.row();
        const Mat3 dirs = frames.rows(p);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const Index col = dofs.dof(node, c);
            if (col >= 0 && dirs(r, c) != 0.0)
              triplets.emplace_back(3 * p + r, col, -it.value() * dirs(r, c));
          }
      }
  SparseMatrix B(3 * patches.size(), dofs.n_free());
  B.setFromTriplets(triplets.begin(), triplets.end());
  return B;
}

SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches) {
  return assemble_b(mesh, dofs, surface, patches, patch_frames(mesh, surface, patches));
}

void require_active_patches(const ContactSurface& surface, const Patches& patches,
                            const SparseMatrix& B, const std::string& where) {
  // A row's entries [m^2] summed in magnitude; it vanishes below rounding of the patch's area
  // (quadrature gives the corners' zero integrals to rounding).
  constexpr Real kVanishingRow = 1e-12;
  VectorXd row_sum = VectorXd::Zero(B.rows());
  for (Index c = 0; c < B.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(B, c); it; ++it)
      row_sum(it.row()) += std::abs(it.value());
  for (Index p = 0; p < patches.size(); ++p) {
    if (row_sum(3 * p) > kVanishingRow * patches.area(p)) continue;
    for (Index k : patches.faces[static_cast<size_t>(p)])
      for (Index v = 0; v < surface.face_nodes.rows(); ++v)
        if (surface.contact_node[static_cast<size_t>(surface.face_nodes(v, k))])
          throw NumericalError(fmt::format(
              "{}: patch {} has contact nodes free along its normal, but its row of B vanishes "
              "(condition (5.1) fails for it: the nodes that carry its integral are held by "
              "Dirichlet conditions); make the patches larger or hold the surface differently",
              where, p));
  }
}

namespace {
// Iterations of the power and inverse iterations of the sparse stability estimate: enough to
// separate a full-rank B (ratios of 1e-1..1e-3 on patch partitions) from a rank-deficient one
// (below 1e-8) with a wide margin.
constexpr int kStabilityIterations = 100;

// Extreme eigenvalues of the sparse SPD matrix A = B B^T, estimated: lambda_max by power
// iteration, lambda_min by inverse iteration on a sparse Cholesky factor (the Rayleigh quotient
// of the iterate, an upper bound that converges quickly). lambda_min = 0 if A is not positive
// definite.
std::pair<Real, Real> extreme_eigenvalues(const SparseMatrix& A) {
  const Index n = A.rows();
  VectorXd v = VectorXd::LinSpaced(n, 1.0, 2.0).normalized();
  for (int k = 0; k < kStabilityIterations; ++k)
    v = (A * v).normalized();
  const Real lmax = v.dot(A * v);
  Eigen::SimplicialLLT<SparseMatrix> llt(A);
  if (llt.info() != Eigen::Success) return {0.0, lmax};
  v = VectorXd::LinSpaced(n, 2.0, 1.0).normalized();
  for (int k = 0; k < kStabilityIterations; ++k) {
    v = llt.solve(v);
    if (!v.allFinite() || v.norm() == 0.0) return {0.0, lmax};
    v.normalize();
  }
  return {v.dot(A * v), lmax};
}
}  // namespace

StabilityReport check_stability(const SparseMatrix& B, const std::string& where, Real min_ratio,
                                Index dense_limit) {
  // A row of B without entries belongs to a multiplier component whose direction Dirichlet
  // conditions fix on the whole patch (a roller on the contact face): it acts on nothing, its
  // multiplier stays zero, and it is left out of the check. The other rows must be independent.
  StabilityReport report;
  const SparseMatrix Bt = B.transpose();  // column-major: the columns of Bt are the rows of B
  std::vector<Eigen::Triplet<Real, SparseIndex>> select;
  for (Index r = 0; r < Bt.cols(); ++r) {
    if (Bt.col(r).nonZeros() == 0) {
      ++report.n_inactive;
      continue;
    }
    select.emplace_back(static_cast<Index>(select.size()), r, 1.0);
  }
  SparseMatrix S(static_cast<Index>(select.size()), B.rows());
  S.setFromTriplets(select.begin(), select.end());
  const SparseMatrix active = S * B;
  // sigma(B)^2 are the eigenvalues of B B^T (n_dual x n_dual).
  const SparseMatrix BBt = active * active.transpose();
  Real lmin = 0.0, lmax = 0.0;
  report.estimated = BBt.rows() > dense_limit;
  if (!report.estimated) {
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(BBt), Eigen::EigenvaluesOnly);
    lmin = eig.eigenvalues().minCoeff();
    lmax = eig.eigenvalues().maxCoeff();
  } else {
    std::tie(lmin, lmax) = extreme_eigenvalues(BBt);
  }
  const Real ratio = lmax > 0 ? std::sqrt(std::max(lmin, 0.0) / lmax) : 0.0;
  report.ratio = ratio;
  if (!(ratio >= min_ratio))
    throw NumericalError(fmt::format(
        "{}: the multiplier partition is unstable (condition (5.1) fails): B^T does not have full "
        "column rank, sigma_min/sigma_max(B) = {:.3e} < {:.1e}. Every patch needs contact nodes "
        "that are not clamped.",
        where, ratio, min_ratio));
  return report;
}

}  // namespace fricon::contact
