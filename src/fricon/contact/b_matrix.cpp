#include "fricon/contact/b_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "fricon/core/error.hpp"

namespace fricon::contact {

Frames patch_frames(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches) {
  if (surface.master.size() == 0)
    return Frames::constant(surface.n, surface.t1, surface.t2, patches.size());
  Frames f;
  f.n.resize(3, patches.size());
  f.t1.resize(3, patches.size());
  f.t2.resize(3, patches.size());
  // Against a body: the area-weighted mean of the nodes' contact normals (theory.md §2.8).
  for (Index p = 0; p < patches.size(); ++p) {
    Vec3 sum = Vec3::Zero();
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index face = surface.faces[static_cast<size_t>(k)];
      Vec3 nodal = Vec3::Zero();
      for (int v = 0; v < 3; ++v)
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

SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches, const Frames& frames,
                        const SparseMatrix* mortar) {
  std::vector<Eigen::Triplet<Real, SparseIndex>> triplets;
  // @sect: the slave's part, int_R phi_a dir dS over R's triangles.
  for (Index p = 0; p < patches.size(); ++p) {
    const Mat3 dirs = frames.rows(p);
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index f = surface.faces[static_cast<size_t>(k)];
      const Real share = mesh::face_area(mesh, f) / 3.0;  // int_T phi_a = |T|/3
      for (int v = 0; v < 3; ++v)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const Index col = dofs.dof(mesh.faces(v, f), c);
            if (col >= 0 && dirs(r, c) != 0.0)
              triplets.emplace_back(3 * p + r, col, share * dirs(r, c));
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
