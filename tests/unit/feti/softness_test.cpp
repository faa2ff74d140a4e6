// feti::subdomain_softness, how soft each subdomain is beyond its rigid motions, against the
// eigenvalues of K_s computed here by a dense eigensolver; and feti::recut_necked on a subdomain
// given a neck by hand: a lobe of three cubes joined to a block by a chain of three tetrahedra
// (theory.md §8.9); and feti::remake_subdomains after a cut against subdomains made afresh.
#include "fricon/feti/softness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "fricon/fe/material.hpp"
#include "fricon/feti/partition.hpp"
#include "fricon/feti/subdomains.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

using namespace fricon;
using namespace fricon::feti;

namespace {

const std::string kWhereSubdomains = "problem.toml:7:14";
// Steel, as the paper's brick.
const std::vector<fe::Material> kSteel = {fe::isotropic(21.19e10, 0.277)};

std::vector<Subdomain> subdomains_of(const mesh::TetMesh& m, const Partition& p) {
  const fe::NodalField applied = fe::NodalField::Zero(3, m.n_nodes());
  return make_subdomains(m, kSteel, p, node_owners(m, p), applied, 2, this_process());
}

// lambda_7(K_s) / mean(diag K_s) by a dense eigensolver: the truth the estimate is held to.
Real exact_relative_softness(const mesh::TetMesh& m, const std::vector<Index>& tets) {
  const MatrixXd K = MatrixXd(subdomain_stiffness(m, kSteel, tets));
  const VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<MatrixXd>(K).eigenvalues();
  EXPECT_LT(std::abs(eigenvalues(kSubdomainMotions - 1)), 1e-9 * eigenvalues(K.rows() - 1))
      << "the rigid motions are K_s's kernel";
  return eigenvalues(kSubdomainMotions) / K.diagonal().mean();
}

TEST(Softness, IsTheSmallestEigenvalueBeyondTheRigidMotionsFromAbove) {
  const mesh::TetMesh m = mesh::make_brick({Vec3(3.0, 1.0, 1.0), {9, 3, 3}});
  const Partition p = partition_mesh(m, mesh::find_bodies(m), 4, kWhereSubdomains);
  const Softness soft = subdomain_softness(subdomains_of(m, p), 2, this_process());
  ASSERT_EQ(static_cast<Index>(soft.relative.size()), p.n_subdomains);
  for (Index s = 0; s < p.n_subdomains; ++s) {
    const Real exact = exact_relative_softness(m, p.tets[static_cast<size_t>(s)]);
    const Real estimate = soft.relative[static_cast<size_t>(s)];
    EXPECT_GE(estimate, exact * (1.0 - 1e-9)) << "subdomain " << s << ": a Rayleigh quotient";
    EXPECT_LE(estimate, 2.0 * exact) << "subdomain " << s;
  }
  EXPECT_LT(soft.ratio, kNeckRatio);
  EXPECT_TRUE(soft.necked.empty());
}

// The box [0,6] x [0,2] x [0,2] in unit cubes; subdomain 0 is the block of cubes x < 2, the lobe
// of cubes x >= 3, and between them a chain of three tetrahedra of cube (2, 0, 0): the corner one
// at grid point (2, 1, 0) (a face on x = 2), the central one and the corner one at (3, 0, 0) (a
// face on x = 3); subdomain 1 is the rest of the slab 2 <= x <= 3, face-connected (the cube's
// other two corner tetrahedra have faces on its neighbours in y and z).
struct Necked {
  mesh::TetMesh mesh = mesh::make_brick({Vec3(6.0, 2.0, 2.0), {6, 2, 2}});
  Partition partition;
};

bool has_corner(const mesh::TetMesh& m, Index t, const Vec3& point) {
  for (int a = 0; a < 4; ++a)
    if ((m.nodes.col(m.tets(a, t)) - point).norm() < 1e-12) return true;
  return false;
}

Necked necked_box() {
  Necked n;
  const mesh::TetMesh& m = n.mesh;
  n.partition.subdomain_of_tet.assign(static_cast<size_t>(m.n_tets()), 1);
  for (Index t = 0; t < m.n_tets(); ++t) {
    Vec3 centre = Vec3::Zero();
    for (int a = 0; a < 4; ++a)
      centre += m.nodes.col(m.tets(a, t));
    const Vec3 cube = (centre / 4.0).array().floor();
    const bool block = cube.x() < 2.0;
    const bool lobe = cube.x() >= 3.0;
    const bool chain_cube = cube.x() == 2.0 && cube.y() == 0.0 && cube.z() == 0.0;
    // In cube (2, 0, 0) the central tetrahedron holds both (2, 0, 0) and (3, 1, 0); a corner one
    // holds its odd corner and the three neighbours of that corner.
    const bool central = has_corner(m, t, Vec3(2, 0, 0)) && has_corner(m, t, Vec3(3, 1, 0));
    const bool first = has_corner(m, t, Vec3(2, 1, 0)) && has_corner(m, t, Vec3(2, 1, 1)) &&
                       has_corner(m, t, Vec3(3, 1, 0));
    const bool last = has_corner(m, t, Vec3(3, 0, 0)) && has_corner(m, t, Vec3(3, 0, 1)) &&
                      has_corner(m, t, Vec3(2, 0, 0));
    if (block || lobe || (chain_cube && (central || first || last)))
      n.partition.subdomain_of_tet[static_cast<size_t>(t)] = 0;
  }
  n.partition.n_subdomains = 2;
  n.partition.tets.resize(2);
  for (Index t = 0; t < m.n_tets(); ++t)
    n.partition.tets[static_cast<size_t>(n.partition.subdomain_of_tet[static_cast<size_t>(t)])]
        .push_back(t);
  return n;
}

TEST(Softness, ANeckIsFoundAndCutAway) {
  const Necked n = necked_box();
  ASSERT_EQ(static_cast<Index>(n.partition.tets[0].size()), 2 * 4 * 5 + 3 * 4 * 5 + 3)
      << "the block, the lobe and the chain";
  const mesh::Bodies bodies = mesh::find_bodies(n.mesh);
  const Softness before = subdomain_softness(subdomains_of(n.mesh, n.partition), 2, this_process());
  EXPECT_EQ(before.softest, 0);
  EXPECT_GE(before.ratio, kNeckRatio);
  ASSERT_EQ(before.necked, std::vector<Index>{0});

  const Partition cut =
      recut_necked(n.mesh, bodies, n.partition, before.necked, 1, kWhereSubdomains);
  // Every tetrahedron in one subdomain, the lists and the labels agreeing.
  Index assigned = 0;
  for (Index s = 0; s < cut.n_subdomains; ++s)
    for (Index t : cut.tets[static_cast<size_t>(s)]) {
      EXPECT_EQ(cut.subdomain_of_tet[static_cast<size_t>(t)], s);
      ++assigned;
    }
  EXPECT_EQ(assigned, n.mesh.n_tets());
  EXPECT_GE(cut.n_subdomains, 2);
  const Softness after = subdomain_softness(subdomains_of(n.mesh, cut), 2, this_process());
  EXPECT_LT(after.ratio, kNeckRatio);
  EXPECT_TRUE(after.necked.empty());
}

}  // namespace

// After a cut, the subdomains outside the cut region keep their factors, and every subdomain is
// what make_subdomains makes of the new partition afresh: the same nodes, torn dofs, loads,
// diagonals, rigid motions and solves.
TEST(Softness, AReCutKeepsTheFactorsOfTheSubdomainsItLeaves) {
  if (!metis_available()) GTEST_SKIP() << "fricon built without METIS (libmetis-dev)";
  const mesh::TetMesh m = mesh::make_brick({{3.0, 1.0, 1.0}, {12, 4, 4}});
  const mesh::Bodies bodies = mesh::find_bodies(m);
  const Partition before = partition_mesh(m, bodies, 12, kWhereSubdomains);
  const Partition cut = recut_necked(m, bodies, before, {0}, 1, kWhereSubdomains);
  fe::NodalField applied = fe::NodalField::Random(3, m.n_nodes());
  const std::vector<Index> owners = node_owners(m, cut);

  std::vector<Subdomain> previous =
      make_subdomains(m, kSteel, before, node_owners(m, before), applied, 2, this_process());
  std::vector<double> seconds_before;  // by first tetrahedron: what the kept ones must show
  std::vector<Index> unchanged;        // the subdomains of `cut` equal to one of `before`
  for (Index i = 0; i < cut.n_subdomains; ++i)
    for (Index j = 0; j < before.n_subdomains; ++j)
      if (cut.tets[static_cast<size_t>(i)] == before.tets[static_cast<size_t>(j)]) {
        unchanged.push_back(i);
        seconds_before.push_back(previous[static_cast<size_t>(j)].factor_seconds);
      }
  ASSERT_GT(unchanged.size(), 0u) << "subdomains outside the region";
  ASSERT_LT(static_cast<Index>(unchanged.size()), cut.n_subdomains) << "the region is cut";

  Index kept = -1;
  const std::vector<Subdomain> remade = remake_subdomains(
      m, kSteel, cut, owners, applied, 2, this_process(), before, std::move(previous), &kept);
  const std::vector<Subdomain> fresh =
      make_subdomains(m, kSteel, cut, owners, applied, 2, this_process());
  EXPECT_EQ(kept, static_cast<Index>(unchanged.size()));
  for (size_t k = 0; k < unchanged.size(); ++k)
    EXPECT_EQ(remade[static_cast<size_t>(unchanged[k])].factor_seconds, seconds_before[k])
        << "subdomain " << unchanged[k] << " was factored again";
  ASSERT_EQ(remade.size(), fresh.size());
  for (size_t i = 0; i < fresh.size(); ++i) {
    const Subdomain& a = remade[i];
    const Subdomain& b = fresh[i];
    EXPECT_EQ(a.nodes, b.nodes) << i;
    EXPECT_EQ(a.first_dof, b.first_dof) << i;
    EXPECT_EQ(a.f, b.f) << i;
    EXPECT_EQ(a.stiffness_diagonal, b.stiffness_diagonal) << i;
    EXPECT_LE((a.R - b.R).norm(), 1e-12 * b.R.norm()) << i;
    const VectorXd x = VectorXd::Random(b.n_dofs());
    const VectorXd ya = a.factor.solve(x), yb = b.factor.solve(x);
    EXPECT_LE((ya - yb).norm(), 1e-10 * yb.norm()) << i;
  }
}
