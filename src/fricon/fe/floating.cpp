#include "fricon/fe/floating.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "fricon/core/error.hpp"

namespace fricon::fe {

namespace {

// R_I^T R_I is taken as singular below this share of its largest eigenvalue.
constexpr Real kRegularizationRank = 1e-10;

// The fixed flags of `dofs`, 3 n_nodes node-major (as free_rigid_motions reads them).
std::vector<bool> fixed_flags(const DofMap& dofs) {
  std::vector<bool> fixed(static_cast<size_t>(3 * dofs.n_nodes()));
  for (Index a = 0; a < dofs.n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      fixed[static_cast<size_t>(3 * a + c)] = dofs.is_fixed(a, c);
  return fixed;
}

// The node of `nodes` farthest from the point p, or from the line through p along the unit
// direction `axis` when it is given.
Index farthest(const mesh::TetMesh& mesh, const std::vector<Index>& nodes, const Vec3& p,
               const Vec3* axis = nullptr) {
  Index best = nodes.front();
  Real best_d = -1.0;
  for (Index a : nodes) {
    Vec3 v = mesh.nodes.col(a) - p;
    if (axis) v -= v.dot(*axis) * *axis;
    if (v.squaredNorm() > best_d) {
      best_d = v.squaredNorm();
      best = a;
    }
  }
  return best;
}

// Three far-apart nodes of the body (a triangle as large as a quick search finds): their free
// dofs hold every rigid motion of the body that is not already fixed.
std::vector<Index> regularization_nodes(const mesh::TetMesh& mesh, const std::vector<Index>& nodes,
                                        const Vec3& centre) {
  const Index a1 = farthest(mesh, nodes, centre);
  const Index a2 = farthest(mesh, nodes, mesh.nodes.col(a1));
  const Vec3 axis = (mesh.nodes.col(a2) - mesh.nodes.col(a1)).normalized();
  const Index a3 = farthest(mesh, nodes, mesh.nodes.col(a1), &axis);
  std::vector<Index> chosen{a1, a2, a3};
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

}  // namespace

std::string FloatingBody::motion_name(Index j) const {
  return describe_motion(motions.col(j));
}

FloatingBodies find_floating_bodies(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                                    const DofMap& dofs) {
  FloatingBodies f;
  const std::vector<RigidMotionCheck> checks = free_rigid_motions(mesh, bodies, fixed_flags(dofs));
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  Index column = 0;
  for (Index b = 0; b < bodies.n_bodies(); ++b) {
    const RigidMotionCheck& check = checks[static_cast<size_t>(b)];
    if (check.n_free == 0) continue;
    FloatingBody body;
    body.body = b;
    body.centre = check.centre;
    body.motions = check.free;
    body.first_column = column;
    const std::vector<Index>& nodes = bodies.nodes[static_cast<size_t>(b)];
    for (Index j = 0; j < body.n_motions(); ++j, ++column)
      for (Index a : nodes) {
        const Vec3 r = motion_at(body.motions.col(j), body.centre, mesh.nodes.col(a));
        for (int c = 0; c < 3; ++c)
          if (dofs.dof(a, c) >= 0 && r(c) != 0.0)
            entries.emplace_back(dofs.dof(a, c), column, r(c));
      }
    body.regularization_dofs = dofs.free_dofs(regularization_nodes(mesh, nodes, check.centre));
    f.bodies.push_back(std::move(body));
  }
  f.R.resize(dofs.n_free(), column);
  f.R.setFromTriplets(entries.begin(), entries.end());
  f.R.makeCompressed();
  return f;
}

SparseMatrix regularized_stiffness(const SparseMatrix& K, const FloatingBodies& floating) {
  if (floating.empty()) return K;
  std::vector<Eigen::Triplet<Real, SparseIndex>> entries;
  for (const FloatingBody& body : floating.bodies) {
    const std::vector<Index>& I = body.regularization_dofs;
    const auto n_I = static_cast<Index>(I.size());
    // R_I: the body's columns of R at the dofs I.
    MatrixXd R_I(n_I, body.n_motions());
    Real rho = 0.0;  // [N/m]
    for (Index i = 0; i < n_I; ++i) {
      const Index dof = I[static_cast<size_t>(i)];
      for (Index j = 0; j < body.n_motions(); ++j)
        R_I(i, j) = floating.R.coeff(dof, body.first_column + j);
      rho += K.coeff(dof, dof) / static_cast<Real>(n_I);
    }
    const MatrixXd gram = R_I.transpose() * R_I;
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(gram, Eigen::EigenvaluesOnly);
    FRICON_CHECK(eig.eigenvalues().minCoeff() > kRegularizationRank * eig.eigenvalues().maxCoeff(),
                 "the regularization dofs of floating body " << body.body
                                                             << " do not determine its motions");
    const MatrixXd block = rho * R_I * gram.ldlt().solve(R_I.transpose());
    for (Index i = 0; i < n_I; ++i)
      for (Index k = 0; k < n_I; ++k)
        entries.emplace_back(I[static_cast<size_t>(i)], I[static_cast<size_t>(k)], block(i, k));
  }
  SparseMatrix addition(K.rows(), K.cols());
  addition.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix K_reg = K + addition;
  K_reg.makeCompressed();
  return K_reg;
}

}  // namespace fricon::fe
