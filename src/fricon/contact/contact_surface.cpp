#include "fricon/contact/contact_surface.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "fricon/core/error.hpp"

namespace fricon::contact {

Index ContactSurface::n_contact_nodes() const {
  return static_cast<Index>(std::count(fixed.begin(), fixed.end(), false));
}

ContactSurface make_contact_surface(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                                    const std::string& tag, const std::string& where) {
  ContactSurface s;
  s.tag = tag;
  s.faces = mesh.faces_with_tag(tag);
  if (s.faces.empty())
    throw InputError(
        fmt::format("{}: contact.boundary: boundary '{}' does not exist on the mesh (tags: {})",
                    where, tag, mesh.tag_list()));
  s.nodes = mesh.nodes_with_tag(tag);
  std::map<Index, Index> position;
  for (size_t k = 0; k < s.nodes.size(); ++k)
    position[s.nodes[k]] = static_cast<Index>(k);
  s.face_nodes.resize(3, static_cast<Index>(s.faces.size()));
  Vec3 normal_sum = Vec3::Zero();
  for (size_t k = 0; k < s.faces.size(); ++k) {
    for (int v = 0; v < 3; ++v)
      s.face_nodes(v, static_cast<Index>(k)) = position[mesh.faces(v, s.faces[k])];
    const Real a = mesh::face_area(mesh, s.faces[k]);
    s.area += a;
    normal_sum += a * mesh::face_normal(mesh, s.faces[k]);
  }
  s.n = normal_sum.normalized();
  for (Index f : s.faces)
    if ((mesh::face_normal(mesh, f) - s.n).norm() > 1e-9)
      throw InputError(fmt::format(
          "{}: contact.boundary: the surface '{}' is not planar (face {} has normal ({:.3g}, "
          "{:.3g}, "
          "{:.3g}), the mean normal is ({:.3g}, {:.3g}, {:.3g})); contact with a rigid half-space "
          "needs a flat surface",
          where, tag, f, mesh::face_normal(mesh, f)(0), mesh::face_normal(mesh, f)(1),
          mesh::face_normal(mesh, f)(2), s.n(0), s.n(1), s.n(2)));
  const Vec3 e = std::abs(s.n(0)) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  s.t1 = (e - e.dot(s.n) * s.n).normalized();
  s.t2 = s.t1.cross(s.n);
  s.fixed.resize(s.nodes.size());
  for (size_t k = 0; k < s.nodes.size(); ++k)
    s.fixed[k] = dofs.is_fixed(s.nodes[k], 0) || dofs.is_fixed(s.nodes[k], 1) ||
                 dofs.is_fixed(s.nodes[k], 2);
  if (s.n_contact_nodes() == 0)
    throw InputError(
        fmt::format("{}: contact.boundary: every node of '{}' is clamped: contact and Dirichlet on "
                    "the same face",
                    where, tag));
  return s;
}

Patches chessboard_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const std::string& where) {
  // Tangential coordinates of the surface nodes, and the grid they lie on.
  std::vector<Real> c1, c2;
  for (Index a : surface.nodes) {
    c1.push_back(surface.t1.dot(mesh.nodes.col(a)));
    c2.push_back(surface.t2.dot(mesh.nodes.col(a)));
  }
  auto grid_lines = [](std::vector<Real> c) {
    std::sort(c.begin(), c.end());
    const Real tol = 1e-9 * (c.back() - c.front());
    std::vector<Real> lines{c.front()};
    for (Real v : c)
      if (v - lines.back() > tol) lines.push_back(v);
    return lines;
  };
  const auto lines1 = grid_lines(c1), lines2 = grid_lines(c2);
  const Index m1 = static_cast<Index>(lines1.size()) - 1,
              m2 = static_cast<Index>(lines2.size()) - 1;
  if (m1 < 2 || m2 < 2 || m1 % 2 != 0 || m2 % 2 != 0 ||
      surface.faces.size() != static_cast<size_t>(2 * m1 * m2))
    throw InputError(fmt::format(
        "{}: contact.patches = \"chessboard\" needs a rectangular contact surface of grid squares "
        "with an even number (>= 2) in each direction; '{}' has {} x {} grid intervals and {} "
        "triangles (on a brick: mesh.cells must be even along both edges of the contact face)",
        where, surface.tag, m1, m2, surface.faces.size()));
  const Real h1 = (lines1.back() - lines1.front()) / static_cast<Real>(m1);
  const Real h2 = (lines2.back() - lines2.front()) / static_cast<Real>(m2);
  const Index n1 = m1 / 2, n2 = m2 / 2;

  Patches p;
  p.faces.resize(static_cast<size_t>(n1 * n2));
  p.area = VectorXd::Zero(n1 * n2);
  p.centroid = Eigen::Matrix<Real, 3, Eigen::Dynamic>::Zero(3, n1 * n2);
  for (size_t k = 0; k < surface.faces.size(); ++k) {
    const Index f = surface.faces[k];
    Vec3 centroid = Vec3::Zero();
    for (int v = 0; v < 3; ++v)
      centroid += mesh.nodes.col(mesh.faces(v, f)) / 3.0;
    const Index a = std::clamp<Index>(
        static_cast<Index>(std::floor((surface.t1.dot(centroid) - lines1.front()) / (2 * h1))), 0,
        n1 - 1);
    const Index b = std::clamp<Index>(
        static_cast<Index>(std::floor((surface.t2.dot(centroid) - lines2.front()) / (2 * h2))), 0,
        n2 - 1);
    const Index patch = a + n1 * b;
    const Real area = mesh::face_area(mesh, f);
    p.faces[static_cast<size_t>(patch)].push_back(static_cast<Index>(k));
    p.area(patch) += area;
    p.centroid.col(patch) += area * centroid;
  }
  for (Index q = 0; q < p.size(); ++q)
    p.centroid.col(q) /= p.area(q);
  return p;
}

SparseMatrix assemble_b(const mesh::TetMesh& mesh, const fe::DofMap& dofs,
                        const ContactSurface& surface, const Patches& patches) {
  std::vector<Eigen::Triplet<Real, SparseIndex>> triplets;
  const Vec3 dirs[3] = {surface.n, surface.t1, surface.t2};
  for (Index p = 0; p < patches.size(); ++p)
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      const Index f = surface.faces[static_cast<size_t>(k)];
      const Real share = mesh::face_area(mesh, f) / 3.0;  // int_T phi_a = |T|/3
      for (int v = 0; v < 3; ++v)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const Index col = dofs.dof(mesh.faces(v, f), c);
            if (col >= 0 && dirs[r](c) != 0.0)
              triplets.emplace_back(3 * p + r, col, share * dirs[r](c));
          }
    }
  SparseMatrix B(3 * patches.size(), dofs.n_free());
  B.setFromTriplets(triplets.begin(), triplets.end());
  return B;
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

Real check_stability(const SparseMatrix& B, const std::string& where, Real min_ratio,
                     Index dense_limit) {
  // sigma(B)^2 are the eigenvalues of B B^T (n_dual x n_dual).
  const SparseMatrix BBt = B * B.transpose();
  Real lmin = 0.0, lmax = 0.0;
  if (BBt.rows() <= dense_limit) {
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(MatrixXd(BBt), Eigen::EigenvaluesOnly);
    lmin = eig.eigenvalues().minCoeff();
    lmax = eig.eigenvalues().maxCoeff();
  } else {
    std::tie(lmin, lmax) = extreme_eigenvalues(BBt);
  }
  const Real ratio = lmax > 0 ? std::sqrt(std::max(lmin, 0.0) / lmax) : 0.0;
  if (!(ratio >= min_ratio))
    throw NumericalError(fmt::format(
        "{}: the multiplier partition is unstable (condition (5.1) fails): B^T does not have full "
        "column rank, sigma_min/sigma_max(B) = {:.3e} < {:.1e}. Every patch needs contact nodes "
        "that are not clamped.",
        where, ratio, min_ratio));
  return ratio;
}

namespace {

struct PolyVertex {
  Vec3 x;
  Real phi, g;
};

// Clips a convex polygon to {phi >= s} (keep_above) or {phi <= s}, interpolating linearly.
std::vector<PolyVertex> clip(const std::vector<PolyVertex>& poly, Real s, bool keep_above) {
  std::vector<PolyVertex> out;
  auto inside = [&](const PolyVertex& v) { return keep_above ? v.phi >= s : v.phi <= s; };
  for (size_t i = 0; i < poly.size(); ++i) {
    const PolyVertex& a = poly[i];
    const PolyVertex& b = poly[(i + 1) % poly.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const Real w = (s - a.phi) / (b.phi - a.phi);
      out.push_back({a.x + w * (b.x - a.x), s, a.g + w * (b.g - a.g)});
    }
  }
  return out;
}

// Integral of F(phi) g over a triangle where F is smooth (linear for the built-in laws):
// the 3-point edge-midpoint rule is exact for quadratics (F linear times g linear).
Real integrate_piece(const PolyVertex& a, const PolyVertex& b, const PolyVertex& c,
                     const FrictionLaw& F) {
  const Real area = 0.5 * (b.x - a.x).cross(c.x - a.x).norm();
  Real sum = 0.0;
  const PolyVertex* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const PolyVertex& p = *v[e];
    const PolyVertex& q = *v[(e + 1) % 3];
    sum += F(0.5 * (p.phi + q.phi)) * 0.5 * (p.g + q.g);
  }
  return area * sum / 3.0;
}

}  // namespace

VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g) {
  FRICON_CHECK(phi.size() == surface.n_nodes() && g.size() == surface.n_nodes(),
               "phi and g need one value per surface node");
  const std::vector<Real> kinks = F.kinks();
  VectorXd rho = VectorXd::Zero(patches.size());
  for (Index p = 0; p < patches.size(); ++p) {
    Real integral = 0.0;
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      std::vector<PolyVertex> tri(3);
      Real lo = INFINITY, hi = -INFINITY;
      for (int v = 0; v < 3; ++v) {
        const Index s = surface.face_nodes(v, k);
        tri[v] = {mesh.nodes.col(surface.nodes[static_cast<size_t>(s)]), phi(s), g(s)};
        lo = std::min(lo, phi(s));
        hi = std::max(hi, phi(s));
      }
      // Slabs between consecutive kinks that cut the triangle.
      std::vector<Real> cuts{lo};
      for (Real t : kinks)
        if (t > lo && t < hi) cuts.push_back(t);
      cuts.push_back(hi);
      for (size_t c = 0; c + 1 < cuts.size(); ++c) {
        std::vector<PolyVertex> piece = tri;
        if (c > 0) piece = clip(piece, cuts[c], true);
        if (c + 2 < cuts.size()) piece = clip(piece, cuts[c + 1], false);
        for (size_t i = 1; i + 1 < piece.size(); ++i)
          integral += integrate_piece(piece[0], piece[i], piece[i + 1], F);
      }
    }
    rho(p) = integral / patches.area(p);
  }
  return rho;
}

Real surface_l2_norm(const mesh::TetMesh& mesh, const ContactSurface& surface, const VectorXd& v) {
  Real sum = 0.0;
  for (size_t k = 0; k < surface.faces.size(); ++k) {
    const Real area = mesh::face_area(mesh, surface.faces[k]);
    Real s = 0.0, sq = 0.0;
    for (int a = 0; a < 3; ++a) {
      const Real va = v(surface.face_nodes(a, static_cast<Index>(k)));
      s += va;
      sq += va * va;
    }
    sum += area / 12.0 * (sq + s * s);  // v^T M v with M = |T|/12 (1 + delta_ab)
  }
  return std::sqrt(sum);
}

}  // namespace fricon::contact
