// Verification of contact between two elastic bodies (theory.md §2.8): a block [0,1]^2 x [1,2] m
// (the upper block, whose bottom "up_z0" is the slave surface and carries the patches) on a block
// [0,1]^2 x [0,1] m (the lower block, whose top "lo_z1" is the master), the lower block clamped
// at its bottom and the upper one driven by a prescribed displacement of its top. The truths are
// exact solutions and exact identities, not fricon's own earlier output:
//   - the patch test (non-matching meshes either way round, the slave above or below, with an
//     initial gap, the whole problem rotated, the master moved by Dirichlet conditions): with
//     nu = 0 the uniaxial compression is the exact solution of the continuous problem and lies in
//     the P1 space of both meshes, so the discrete solution is that field: uniform stress, the
//     same contact pressure on every patch, no tangential multiplier; and B annihilates every
//     affine field on a flat interface at zero gap;
//   - a master 1e4 times stiffer than the slave is a rigid plane up to the compliance ratio;
//   - with matching meshes the mortar coupling is the conforming node-to-node one: B annihilates
//     every field that is continuous across the interface, and the mirror symmetry of the problem
//     about the interface is that of its solution;
//   - Coulomb friction: a small shear sticks everywhere (no patch-averaged slip, the friction
//     coefficient does not matter), a large one slips everywhere (||lambda_t|| = mu lambda_n on
//     every patch, the slip along the friction force), and the reaction of the clamped bottom,
//     recomputed from the stresses, balances the contact force of the multipliers;
//   - the pairs that cannot be built are refused with a message that says why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/fixtures.hpp"
#include "fricon/driver/contact_solver.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

// A named namespace, not an anonymous one: the unity build compiles several test files as one.
namespace two_bodies_contact_test {

using namespace fricon;
using namespace fricon::driver;
using testing::HasSubstr;

constexpr Real kYoung = 1.0e9;   // [Pa], both blocks unless said otherwise
constexpr Real kDelta = 1.0e-4;  // [m], how far the upper block's top is pushed down
constexpr Real kQpTolerance = 1e-12;
constexpr Real kOuterTolerance = 1e-10;
// With nu = 0 each block (height 1 m) takes half the approach: strain -delta/2, stress -E delta/2.
constexpr Real kPatchPressure = kYoung * kDelta / 2.0;  // [Pa]
// The patch test's solution lies in the discrete space: only the QP tolerance and round-off
// separate fricon's answer from it.
constexpr Real kPatchTestError = 1e-8;  // relative to the pressure
// The bound for lambda_n on quadratic meshes (relative).
constexpr Real kQuadraticPatchTestError = 1e-10;

// Block sizes (unit cubes) and meshes: the interface of the lower block (4 x 4 squares) and of
// the upper block (5 x 5 squares, or 3 x 3) do not match; kMatching is the same brick for both.
const Vec3 kUnitCube(1.0, 1.0, 1.0);  // [m]
const std::array<Index, 3> kLowerCells{4, 4, 2};
const std::array<Index, 3> kUpperCells{5, 5, 3};
const std::array<Index, 3> kCoarseCells{3, 3, 2};
const std::array<Index, 3> kMatchingCells{4, 4, 2};  // nz even: see MatchingMeshes... below

/// The two blocks as one mesh of two bodies: the lower one [0,1]^2 x [0,1] (tags "lo_x0" ...
/// "lo_z1", region "lo_body"), the upper one [0,1]^2 x [1 + lift, 2 + lift] ("up_...",
/// "up_body"), all node coordinates then rotated by R; of elements of order `order`.
mesh::TetMesh stacked_blocks(const std::array<Index, 3>& lower_cells,
                             const std::array<Index, 3>& upper_cells,
                             const Mat3& R = Mat3::Identity(), Real lift = 0.0, int order = 1) {
  mesh::TetMesh lower = mesh::make_brick({kUnitCube, lower_cells});
  mesh::TetMesh upper = mesh::make_brick({kUnitCube, upper_cells});
  if (order == 2) {  // 10-node tetrahedra with straight edges (theory.md §2.12)
    mesh::add_edge_midpoints(lower);
    mesh::add_edge_midpoints(upper);
  }
  upper.nodes.row(2).array() += 1.0 + lift;
  mesh::TetMesh both = mesh::disjoint_union({lower, upper}, {"lo_", "up_"});
  both.nodes = R * both.nodes;
  return both;
}

/// The frictionless pair "up_z0" (slave) against "lo_z1" (master), agglomerate patches.
ContactOptions frictionless_pair() {
  ContactOptions c;
  c.boundary = "up_z0";
  c.obstacle = ObstacleOptions{ObstacleKind::Body, Vec3::Zero(), Vec3::UnitZ(), "lo_z1"};
  c.patches = contact::PatchKind::Agglomerate;
  c.model = contact::FrictionModel::Tresca;
  c.slip_bound = 0.0;
  c.friction.law = contact::FrictionLawKind::Constant;
  c.friction.value = 0.0;
  return c;
}

/// The stacked blocks of `mesh`, material (E, nu) everywhere: the lower block's bottom clamped,
/// the upper block's top moved by `top` (all three components prescribed), the frictionless pair.
Problem stacked_problem(const mesh::TetMesh& mesh, Real poisson, const Vec3& top) {
  Problem p;
  p.source = "two_bodies_contact_test";
  p.mesh.kind = MeshKind::Arrays;
  p.mesh.given = std::make_shared<const mesh::TetMesh>(mesh);
  p.material.young = kYoung;
  p.material.poisson = poisson;
  p.dirichlet.push_back({"lo_z0", {true, true, true}, Vec3::Zero()});
  p.dirichlet.push_back({"up_z1", {true, true, true}, top});
  p.contact.push_back(frictionless_pair());
  p.solver.qp.rel_tolerance = kQpTolerance;
  p.solver.outer.tol = kOuterTolerance;
  return p;
}

/// The run of `p`, expected to converge; throws (a failure of the calling test) without contact
/// fields.
RunResult run_converged(const Problem& p) {
  validate(p);
  RunResult r = run(p);
  EXPECT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  if (!r.contact || !r.report.contact) throw std::runtime_error("the run has no contact fields");
  return r;
}

/// The stress of tetrahedron t as a symmetric tensor (RunResult::stress is Voigt
/// 11,22,33,23,13,12).
Mat3 stress_tensor(const RunResult& r, Index t) {
  const auto s = r.stress.col(t);
  Mat3 m;
  m << s(0), s(5), s(4), s(5), s(1), s(3), s(4), s(3), s(2);
  return m;
}

/// The patch test's exact solution, in the frame rotated by R: the contact pressure, and the
/// uniaxial stress sigma_zz of each block (all other components zero).
struct Uniaxial {
  Real pressure = 0.0;      // [Pa]
  Real lower_stress = 0.0;  // [Pa]
  Real upper_stress = 0.0;  // [Pa]
  Mat3 R = Mat3::Identity();
};

/// The patch test's checks: lambda_n = pressure and lambda_t = 0 on every patch, the stress
/// R diag(0, 0, sigma_zz) R^T of its block in every tetrahedron, and no relative displacement
/// (slave minus master at the node's projection) beyond the closing of the gap at any slave node:
/// w_n = gap, w_t = 0. Returns the largest deviations (lambda_n, lambda_t, stress relative to
/// the pressure; w relative to delta) for the log.
std::array<Real, 4> expect_patch_test(const RunResult& r, const Uniaxial& exact) {
  const ContactFields& c = *r.contact;
  const Real p0 = exact.pressure;
  EXPECT_GT(c.patches.size(), 1);
  std::array<Real, 4> worst{0.0, 0.0, 0.0, 0.0};
  std::array<Index, 4> where{0, 0, 0, 0};  // the patch, tetrahedron or surface node of each
  const auto keep = [&](int i, Real d, Index at) {
    if (d > worst[static_cast<size_t>(i)]) {
      worst[static_cast<size_t>(i)] = d;
      where[static_cast<size_t>(i)] = at;
    }
  };
  for (Index p = 0; p < c.patches.size(); ++p) {
    keep(0, std::abs(c.lambda(3 * p) - p0) / p0, p);
    keep(1, c.lambda.segment<2>(3 * p + 1).norm() / p0, p);
  }
  const mesh::Bodies& bodies = r.model.bodies;
  EXPECT_EQ(bodies.n_bodies(), 2);
  for (Index t = 0; t < r.model.mesh.n_tets(); ++t) {
    // Body 0 holds tetrahedron 0, the lower block's first.
    const Real zz =
        bodies.tet_body[static_cast<size_t>(t)] == 0 ? exact.lower_stress : exact.upper_stress;
    const Mat3 sigma = exact.R * Vec3(0.0, 0.0, zz).asDiagonal() * exact.R.transpose();
    keep(2, (stress_tensor(r, t) - sigma).cwiseAbs().maxCoeff() / p0, t);
  }
  for (Index k = 0; k < c.surface.n_nodes(); ++k)
    keep(3, Vec3(c.wn(k) - c.gap(k), c.wt1(k), c.wt2(k)).cwiseAbs().maxCoeff() / kDelta, k);
  EXPECT_LT(worst[0], kPatchTestError)
      << "lambda_n of patch " << where[0] << ": " << c.lambda(3 * where[0]) << " Pa, not " << p0;
  EXPECT_LT(worst[1], kPatchTestError) << "lambda_t of patch " << where[1];
  EXPECT_LT(worst[2], kPatchTestError) << "stress of tetrahedron " << where[2] << ":\n"
                                       << stress_tensor(r, where[2]);
  EXPECT_LT(worst[3], kPatchTestError)
      << "relative displacement at surface node " << where[3] << " (mesh node "
      << c.surface.nodes[static_cast<size_t>(where[3])] << ")";
  return worst;
}

/// B applied to the nodal values of an affine field v(x) = A x + b on both blocks, relative to B
/// applied to those of the slave alone. On a flat interface at zero gap the point of the master
/// along the normal is the slave point itself and both P1 spaces hold v, so the mortar integrals
/// of v over each patch are those of the slave's: B v = 0 to round-off. Unlike the patch test's
/// own field (constant on the interface), an arbitrary affine field also sees which master
/// vertex each integral belongs to.
Real affine_mortar_defect(const Problem& p, const RunResult& r) {
  const contact::ContactDiscretization d = discretize_contact(p, r.model.mesh, r.model.dofs);
  const mesh::TetMesh& m = r.model.mesh;
  Mat3 A;
  A << 0.3, -1.1, 0.7, 0.9, 0.2, -0.4, -0.6, 1.3, 0.5;
  const Vec3 b(0.1, -0.2, 0.3);
  const fe::NodalField v = (A * m.nodes).colwise() + b;
  fe::NodalField slave = fe::NodalField::Zero(3, m.n_nodes());
  for (Index a : m.nodes_with_tag(p.contact.front().boundary))
    slave.col(a) = v.col(a);
  const VectorXd bv = d.B * r.model.dofs.from_nodal(v);
  const VectorXd bs = d.B * r.model.dofs.from_nodal(slave);
  EXPECT_GT(bs.cwiseAbs().maxCoeff(), 0.0);
  return bv.cwiseAbs().maxCoeff() / bs.cwiseAbs().maxCoeff();
}

/// One line of the log: the patch test's deviations (expect_patch_test) and the affine field's
/// (affine_mortar_defect; negative: not measured).
void log_patch_test(const char* name, const RunResult& r, const std::array<Real, 4>& worst,
                    Real mortar) {
  std::printf(
      "patch test (%s): %td patches; max rel. deviation lambda_n %.2e, |lambda_t| %.2e, stress "
      "%.2e, nodal w %.2e",
      name, r.contact->patches.size(), worst[0], worst[1], worst[2], worst[3]);
  if (mortar >= 0.0) std::printf("; |B v_affine| / |B v_slave| %.2e", mortar);
  std::printf("\n");
}

// ------------------------------------------------------------------------------------------
// 1-2. The patch test.
//
// Both blocks have E = 1e9 Pa and nu = 0, the lower one clamped at z = 0 and the upper one's top
// moved by (0, 0, -delta). With nu = 0 the clamps do not restrain a lateral expansion (there is
// none), so the exact solution is uniaxial: u = (0, 0, -delta z / 2) in both blocks (continuous
// across the interface, no gap opens), strain eps_zz = -delta / 2, stress sigma_zz =
// -E delta / 2 = -p and all other components zero, contact pressure p on the whole interface,
// no shear. The field is linear, hence exactly representable on both meshes, and the mortar
// constraints (integrals of w_slave - w_master(projection) over each patch) vanish for it; the
// multipliers p on the slave patches give the slave's consistent nodal forces of a uniform
// pressure and, through the mortar integrals over the fully covered master, the master's. So
// the discrete problem has this exact solution whatever the two meshes, which do not match here:
// a fine slave on a coarse master (5 x 5 squares on 4 x 4), a coarse one on a fine one (3 x 3 on
// 5 x 5), the slave below the master (4 x 4 under 5 x 5), and, with the upper block starting
// a gap g0 above the lower one (closed by the load), the pressure E (delta - g0) / 2.

constexpr Real kMortarRoundoff = 1e-12;  // relative

const Uniaxial kHalfEach{kPatchPressure, -kPatchPressure, -kPatchPressure, Mat3::Identity()};

/// One case of the non-matching patch test.
struct PatchCase {
  const char* name;
  std::array<Index, 3> lower_cells, upper_cells;
  bool slave_below = false;  // the slave is the lower block's top, the master the upper's bottom
  Real gap = 0.0;            // the upper block starts this far above the lower one [m]
};

constexpr Real kInitialGap = 2.0e-5;  // [m]

TEST(TwoBodiesContact, PatchTestNonMatching) {
  const PatchCase cases[] = {
      {"fine slave on a coarse master", kLowerCells, kUpperCells},
      {"coarse slave on a fine master", kUpperCells, kCoarseCells},
      {"slave below the master", kLowerCells, kUpperCells, true},
      {"initial gap", kLowerCells, kUpperCells, false, kInitialGap},
  };
  for (const PatchCase& k : cases) {
    SCOPED_TRACE(k.name);
    Problem p =
        stacked_problem(stacked_blocks(k.lower_cells, k.upper_cells, Mat3::Identity(), k.gap), 0.0,
                        Vec3(0.0, 0.0, -kDelta));
    if (k.slave_below) {
      p.contact.front().boundary = "lo_z1";
      p.contact.front().obstacle->boundary = "up_z0";
    }
    const RunResult r = run_converged(p);
    // Each block takes half of the approach left once the gap is closed.
    const Real pressure = kYoung * (kDelta - k.gap) / 2.0;
    const std::array<Real, 4> worst =
        expect_patch_test(r, Uniaxial{pressure, -pressure, -pressure, Mat3::Identity()});
    EXPECT_NEAR(r.report.contact->pairs.front().info.master_coverage, 1.0, kMortarRoundoff);
    // With a gap the master's point lies g0 along the normal, where v differs by A g0 n.
    const Real mortar = k.gap == 0.0 ? affine_mortar_defect(p, r) : 0.0;
    EXPECT_LT(mortar, kMortarRoundoff);
    log_patch_test(k.name, r, worst, k.gap == 0.0 ? mortar : -1.0);
  }
}

// The same with 10-node tetrahedra on both non-matching meshes: the uniaxial field lies in the
// quadratic spaces too, the slave's rows integrate its 6-node traces and the mortar integrals the
// master's 6-node shape functions at the projection (theory.md §2.12), so the patch test holds
// as tightly.
TEST(TwoBodiesContact, PatchTestNonMatchingQuadratic) {
  const PatchCase cases[] = {
      {"quadratic, fine slave on a coarse master", kLowerCells, kUpperCells},
      {"quadratic, coarse slave on a fine master", kUpperCells, kCoarseCells},
  };
  for (const PatchCase& k : cases) {
    SCOPED_TRACE(k.name);
    const Problem p =
        stacked_problem(stacked_blocks(k.lower_cells, k.upper_cells, Mat3::Identity(), 0.0, 2), 0.0,
                        Vec3(0.0, 0.0, -kDelta));
    const RunResult r = run_converged(p);
    ASSERT_EQ(r.model.mesh.order(), 2);
    const std::array<Real, 4> worst = expect_patch_test(r, kHalfEach);
    EXPECT_LT(worst[0], kQuadraticPatchTestError);
    EXPECT_NEAR(r.report.contact->pairs.front().info.master_coverage, 1.0, kMortarRoundoff);
    const Real mortar = affine_mortar_defect(p, r);
    EXPECT_LT(mortar, kMortarRoundoff);
    log_patch_test(k.name, r, worst, mortar);
  }
}

// The same problem rotated by an arbitrary R (mesh and prescribed displacement): the exact
// solution is the rotated one, u = R (0, 0, -delta z' / 2) with z' the unrotated height, stress
// R diag(0, 0, -p) R^T; the contact pressure is p on every patch whatever the patch frames.
TEST(TwoBodiesContact, PatchTestTilted) {
  const Mat3 R = Eigen::AngleAxis<Real>(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const Problem p = stacked_problem(stacked_blocks(kLowerCells, kUpperCells, R), 0.0,
                                    R * Vec3(0.0, 0.0, -kDelta));
  const RunResult r = run_converged(p);
  Uniaxial exact = kHalfEach;
  exact.R = R;
  const std::array<Real, 4> worst = expect_patch_test(r, exact);
  // The patch normals are the rotated slave normal, -R e_z.
  const ContactFields& c = *r.contact;
  for (Index q = 0; q < c.patches.size(); ++q)
    EXPECT_LT((c.patch_frames.n.col(q) + R.col(2)).norm(), kMortarRoundoff) << "patch " << q;
  const Real mortar = affine_mortar_defect(p, r);
  EXPECT_LT(mortar, kMortarRoundoff);
  log_patch_test("tilted", r, worst, mortar);
}

// The master moved by Dirichlet conditions: the lower block's top (the whole master surface) is
// lifted by delta and the upper block's top held at 0. The master has no free dof at the
// interface: it enters only through the constant part of the constraints, the mortar integrals
// of its prescribed displacement (ContactDiscretization::offset). The upper block is squeezed by
// delta over its height of 1 m: strain -delta, sigma_zz = -E delta, pressure E delta; the lower
// block is stretched by delta between its clamped bottom and its lifted top: sigma_zz = E delta.
TEST(TwoBodiesContact, PatchTestPrescribedMaster) {
  Problem p = stacked_problem(stacked_blocks(kLowerCells, kUpperCells), 0.0, Vec3::Zero());
  p.dirichlet.push_back({"lo_z1", {true, true, true}, Vec3(0.0, 0.0, kDelta)});
  const RunResult r = run_converged(p);
  const Real squeeze = kYoung * kDelta;  // [Pa]
  const std::array<Real, 4> worst =
      expect_patch_test(r, Uniaxial{squeeze, squeeze, -squeeze, Mat3::Identity()});
  log_patch_test("prescribed master", r, worst, -1.0);
}

// ------------------------------------------------------------------------------------------
// 3. A stiff master is a rigid plane.
//
// The upper block (E = 1e9 Pa, nu = 0.3) is pushed down by its top, which is clamped laterally:
// the Poisson expansion is restrained at the top and free at the frictionless bottom, so the
// contact pressure is not uniform. Its master is a lower block 1e4 times stiffer (same nu, same
// size, clamped bottom): the master moves by about 1e-4 of the slave's deformation, so the
// multipliers are those against the rigid plane z = 1 up to a relative O(1e-4). The plane run
// uses the same mesh (the lower block is then clamped, unloaded and untouched), the same slave
// surface and patch kind, so the patches are the same and are compared one by one.

constexpr Real kStiffRatio = 1.0e4;
constexpr Real kRigidPlaneTolerance = 1e-3;  // relative to the largest pressure

TEST(TwoBodiesContact, StiffMasterIsARigidPlane) {
  const mesh::TetMesh m = stacked_blocks(kLowerCells, kUpperCells);
  Problem body = stacked_problem(m, 0.3, Vec3(0.0, 0.0, -kDelta));
  MaterialOptions upper = body.material, lower = body.material;
  upper.region = "up_body";
  lower.region = "lo_body";
  lower.young = kStiffRatio * kYoung;
  body.materials = {lower, upper};
  Problem plane = body;
  plane.contact.front().obstacle =
      ObstacleOptions{ObstacleKind::Plane, Vec3(0.0, 0.0, 1.0), Vec3::UnitZ(), ""};

  const RunResult a = run_converged(body);
  const RunResult b = run_converged(plane);
  const ContactFields& ca = *a.contact;
  const ContactFields& cb = *b.contact;
  ASSERT_EQ(ca.patches.size(), cb.patches.size());
  ASSERT_LT((ca.patches.centroid - cb.patches.centroid).cwiseAbs().maxCoeff(), 1e-14);
  Real max_pressure = 0.0, min_pressure = INFINITY;
  for (Index p = 0; p < cb.patches.size(); ++p) {
    max_pressure = std::max(max_pressure, cb.lambda(3 * p));
    min_pressure = std::min(min_pressure, cb.lambda(3 * p));
  }
  // Not the trivial uniform case: the pressure varies by more than 10 per cent.
  EXPECT_GT(max_pressure, 1.1 * min_pressure);
  Real worst = 0.0;
  for (Index p = 0; p < cb.patches.size(); ++p) {
    const Real d = std::abs(ca.lambda(3 * p) - cb.lambda(3 * p)) / max_pressure;
    EXPECT_LT(d, kRigidPlaneTolerance) << "patch " << p;
    worst = std::max(worst, d);
  }
  const Real na = a.report.contact->total_normal_force, nb = b.report.contact->total_normal_force;
  EXPECT_NEAR(na, nb, kRigidPlaneTolerance * nb);
  std::printf(
      "stiff master vs plane: %td patches, pressure %.4g..%.4g Pa, max rel. deviation "
      "lambda_n %.2e, total force %.2e\n",
      cb.patches.size(), min_pressure, max_pressure, worst, std::abs(na - nb) / nb);
}

// ------------------------------------------------------------------------------------------
// 4. Matching meshes through the mortar path.
//
// A glued (one-body) computation is no truth for a frictionless contact: the glued interface
// carries shear. What is exact with matching meshes (the same 4 x 4 squares and the same
// diagonals on both sides: the brick's diagonals alternate with the parity of i + j + k, so the
// lower block's top, at k = nz, matches the upper block's bottom, at k = 0, when nz is even):
//  (a) each slave triangle overlaps exactly one master triangle, itself, so the mortar integral
//      of a master node's shape function over a patch is the slave's integral of the
//      coincident node's: the rows of B are those of the conforming node-to-node coupling, and
//      B v = 0 for every v equal at coincident nodes (a field continuous across the interface),
//      to round-off. Degenerate clipping (shared edges and vertices everywhere) would show here
//      as lost or doubled overlaps.
//  (b) the problem is symmetric under the mirror z -> 2 - z: with nz even the mirror maps the
//      mesh onto itself (lower block onto upper block), the constraint integral of
//      (w_slave - w_master).n onto itself by (a), and the boundary conditions (lower bottom fixed
//      at 0, upper top at -delta) onto themselves up to the uniform translation -delta/2 e_z,
//      which a contact between two bodies does not see. The solution being unique (frictionless,
//      K positive definite), it has the symmetry: at mirror nodes a (lower) and a' (upper),
//      u_x, u_y equal and u_z(a) + u_z(a') = -delta. With nu = 0.3 and both ends clamped, the
//      field is not uniform, so this tests the coupling, not just a constant state.

constexpr Real kRoundoff = 1e-12;
constexpr Real kSymmetryTolerance = 1e-8;  // relative to delta

TEST(TwoBodiesContact, MatchingMeshesSameAsNonMatchingPath) {
  const mesh::TetMesh m = stacked_blocks(kMatchingCells, kMatchingCells);
  const Problem p = stacked_problem(m, 0.3, Vec3(0.0, 0.0, -kDelta));
  const RunResult r = run_converged(p);
  const mesh::BrickSpec spec{kUnitCube, kMatchingCells};
  const Index nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  const Index shift = (nx + 1) * (ny + 1) * (nz + 1);  // the upper block's first node
  const auto lower_node = [&](Index i, Index j, Index k) {
    return mesh::brick_node(spec, i, j, k);
  };
  const auto upper_node = [&](Index i, Index j, Index k) {
    return shift + mesh::brick_node(spec, i, j, k);
  };

  // (a) B on fields continuous across the interface, and on the slave's nodes alone.
  const contact::ContactDiscretization d = discretize_contact(p, r.model.mesh, r.model.dofs);
  fe::NodalField glued = fe::NodalField::Zero(3, m.n_nodes());
  fe::NodalField slave_only = glued;
  for (Index j = 0; j <= ny; ++j)
    for (Index i = 0; i <= nx; ++i) {
      ASSERT_LT((m.nodes.col(lower_node(i, j, nz)) - m.nodes.col(upper_node(i, j, 0))).norm(),
                kRoundoff);
      const Vec3 v(std::sin(1.0 + 3 * i + j), std::cos(2.0 * j - i), std::sin(0.5 + i * j));
      glued.col(lower_node(i, j, nz)) = v;
      glued.col(upper_node(i, j, 0)) = v;
      slave_only.col(upper_node(i, j, 0)) = v;
    }
  const VectorXd b_glued = d.B * r.model.dofs.from_nodal(glued);
  const VectorXd b_slave = d.B * r.model.dofs.from_nodal(slave_only);
  ASSERT_GT(b_slave.cwiseAbs().maxCoeff(), 0.0);
  const Real mortar_error = b_glued.cwiseAbs().maxCoeff() / b_slave.cwiseAbs().maxCoeff();
  EXPECT_LT(mortar_error, kRoundoff);
  EXPECT_NEAR(r.report.contact->pairs.front().info.master_coverage, 1.0, kRoundoff);

  // (b) The mirror symmetry of the solution.
  const fe::NodalField& u = r.displacement;
  Real worst = 0.0;
  for (Index k = 0; k <= nz; ++k)
    for (Index j = 0; j <= ny; ++j)
      for (Index i = 0; i <= nx; ++i) {
        const Vec3 a = u.col(lower_node(i, j, k)), b = u.col(upper_node(i, j, nz - k));
        const Vec3 defect(a(0) - b(0), a(1) - b(1), a(2) + b(2) + kDelta);
        worst = std::max(worst, defect.cwiseAbs().maxCoeff() / kDelta);
      }
  EXPECT_LT(worst, kSymmetryTolerance);
  // The symmetric field is not the trivial uniaxial one: the lateral displacement is of the order
  // of nu delta somewhere.
  EXPECT_GT(u.row(0).cwiseAbs().maxCoeff(), 0.01 * kDelta);
  std::printf("matching meshes: |B v_glued| / |B v_slave| = %.2e, mirror defect %.2e delta\n",
              mortar_error, worst);
}

// ------------------------------------------------------------------------------------------
// 5. Coulomb friction between the blocks: stick, then slip.
//
// The upper block's top is moved by (delta_x, 0, -delta_z), mu = 0.3 (constant law), nu = 0.3.
//  - delta_x = delta_z / 100: the shear asked for is far below mu times the pressure, the blocks
//    stick on every patch: ||lambda_t|| < mu lambda_n, the slip averaged over each patch,
//    (B w)_t, vanishes, and the answer does not depend on mu (the same with mu = 3).
//  - delta_x = 10 delta_z: the upper block cannot follow by deformation alone, it slides on every
//    patch: ||lambda_t|| = mu lambda_n on each, so sum ||lambda_t|| |R| = mu sum lambda_n |R|,
//    and the patch-averaged slip (B w)_t points along lambda_t (the friction force on the slave,
//    -lambda_t, opposes its slip). The multipliers give the force of the slave on the master,
//    sum_p (lambda_n n_p + lambda_t1 t1_p + lambda_t2 t2_p) |R_p| (n_p the slave's outward
//    normal); the reactions of the clamped bottom and of the driven top, recomputed from the
//    stresses (the internal forces at their nodes), must balance it: bottom = -force,
//    top = +force, their sum (RunReport::reaction_force) zero.

constexpr Real kMu = 0.3;
constexpr Real kDeltaZ = 1.0e-4;                // [m]
constexpr Real kStickShear = 1.0e-2 * kDeltaZ;  // [m]
constexpr Real kSlipShear = 10.0 * kDeltaZ;     // [m]
constexpr Real kCoulombTolerance = 1e-7;        // relative (outer and QP tolerances below)
constexpr Real kEquilibrium = 1e-8;

Problem coulomb_blocks(Real shear, Real mu) {
  Problem p =
      stacked_problem(stacked_blocks(kLowerCells, kUpperCells), 0.3, Vec3(shear, 0.0, -kDeltaZ));
  ContactOptions& c = p.contact.front();
  c.model = contact::FrictionModel::Coulomb;
  c.friction.value = mu;
  p.solver.qp.rel_tolerance = 1e-11;
  p.solver.outer.tol = 1e-10;
  return p;
}

/// (B w - c) per patch: the patch-averaged relative displacement times |R| [m^3], from the
/// result's displacement and B assembled again.
VectorXd patch_gaps(const Problem& p, const RunResult& r) {
  const contact::ContactDiscretization d = discretize_contact(p, r.model.mesh, r.model.dofs);
  return d.B * r.model.dofs.from_nodal(r.displacement) - d.offset;
}

/// The force of the slave on the master from the multipliers [N].
Vec3 force_on_master(const ContactFields& c) {
  Vec3 f = Vec3::Zero();
  for (Index p = 0; p < c.patches.size(); ++p)
    f += c.patches.area(p) * (c.lambda(3 * p) * c.patch_frames.n.col(p) +
                              c.lambda(3 * p + 1) * c.patch_frames.t1.col(p) +
                              c.lambda(3 * p + 2) * c.patch_frames.t2.col(p));
  return f;
}

/// The reaction of the support on the nodes of tag `tag` [N]: their internal forces.
Vec3 reaction_on(const RunResult& r, const std::string& tag) {
  const fe::NodalField internal =
      fe::internal_forces(r.model.mesh, r.model.materials, r.displacement);
  Vec3 f = Vec3::Zero();
  for (Index a : r.model.mesh.nodes_with_tag(tag))
    f += internal.col(a);
  return f;
}

TEST(TwoBodiesContact, CoulombBlocksStickThenSlip) {
  // Stick.
  const Problem stick = coulomb_blocks(kStickShear, kMu);
  const RunResult s = run_converged(stick);
  const ContactFields& cs = *s.contact;
  const VectorXd gs = patch_gaps(stick, s);
  Real max_ratio = 0.0;
  for (Index p = 0; p < cs.patches.size(); ++p) {
    EXPECT_EQ(cs.state[static_cast<size_t>(p)], PatchState::Stick) << "patch " << p;
    ASSERT_GT(cs.lambda(3 * p), 0.0) << "patch " << p;
    const Real ratio = cs.lambda.segment<2>(3 * p + 1).norm() / cs.lambda(3 * p);
    EXPECT_LT(ratio, kMu) << "patch " << p;
    max_ratio = std::max(max_ratio, ratio);
    // No patch-averaged slip, and no penetration, at stick; relative to int_R |u_top| dS.
    const Real reference = cs.patches.area(p) * kDeltaZ;
    EXPECT_LT(gs.segment<3>(3 * p).cwiseAbs().maxCoeff(), kCoulombTolerance * reference)
        << "patch " << p;
  }
  EXPECT_GT(max_ratio, 0.0);  // the shear is felt
  const RunResult s3 = run_converged(coulomb_blocks(kStickShear, 10.0 * kMu));
  const Real mu_effect =
      (s3.contact->lambda - cs.lambda).cwiseAbs().maxCoeff() / cs.lambda.cwiseAbs().maxCoeff();
  EXPECT_LT(mu_effect, kCoulombTolerance);

  // Slip.
  const Problem slip = coulomb_blocks(kSlipShear, kMu);
  const RunResult r = run_converged(slip);
  const ContactFields& c = *r.contact;
  const VectorXd g = patch_gaps(slip, r);
  Real normal = 0.0, tangential = 0.0, worst_cone = 0.0, worst_angle = 0.0;
  for (Index p = 0; p < c.patches.size(); ++p) {
    EXPECT_EQ(c.state[static_cast<size_t>(p)], PatchState::Slip) << "patch " << p;
    const Real ln = c.lambda(3 * p);
    const Vec3 lt3(0.0, c.lambda(3 * p + 1), c.lambda(3 * p + 2));
    const Real lt = lt3.norm();
    ASSERT_GT(ln, 0.0) << "patch " << p;
    const Real cone = std::abs(lt - kMu * ln) / (kMu * ln);
    EXPECT_LT(cone, kCoulombTolerance) << "patch " << p;
    worst_cone = std::max(worst_cone, cone);
    // The slip along lambda_t: the angle between (B w)_t and lambda_t.
    const Vec3 slip_t(0.0, g(3 * p + 1), g(3 * p + 2));
    ASSERT_GT(slip_t.norm(), 0.0) << "patch " << p;
    const Real sine = slip_t.cross(lt3).norm() / (slip_t.norm() * lt);
    EXPECT_LT(sine, 1e-6) << "patch " << p;
    EXPECT_GT(slip_t.dot(lt3), 0.0) << "patch " << p;
    worst_angle = std::max(worst_angle, sine);
    // In contact: no patch-averaged penetration or opening.
    EXPECT_LT(std::abs(g(3 * p)), kCoulombTolerance * c.patches.area(p) * kDeltaZ) << "patch " << p;
    normal += ln * c.patches.area(p);
    tangential += lt * c.patches.area(p);
  }
  EXPECT_NEAR(tangential, kMu * normal, kCoulombTolerance * kMu * normal);

  // Equilibrium: the bottom's reaction (from the stresses) and the multipliers' force.
  const Vec3 on_master = force_on_master(c);
  const Vec3 bottom = reaction_on(r, "lo_z0");
  const Vec3 top = reaction_on(r, "up_z1");
  EXPECT_LT((bottom + on_master).norm(), kEquilibrium * on_master.norm());
  EXPECT_LT((top - on_master).norm(), kEquilibrium * on_master.norm());
  EXPECT_LT(r.report.equilibrium_residual, kEquilibrium);
  EXPECT_LT(r.report.reaction_force.norm(), kEquilibrium * on_master.norm());
  // The bottom carries the normal force and mu times it sideways (the slip is along x, up to the
  // small lateral part that the Poisson expansion adds).
  EXPECT_NEAR(bottom.z(), normal, kEquilibrium * normal);
  const Real bottom_shear = bottom.head<2>().norm();
  EXPECT_LE(bottom_shear, kMu * normal * (1.0 + kCoulombTolerance));
  EXPECT_GT(bottom_shear, 0.99 * kMu * normal);
  EXPECT_LT(bottom.x(), 0.0);  // the support holds the dragged lower block back
  EXPECT_TRUE(r.report.contact->pairs.front().small_sliding);
  std::printf(
      "Coulomb: stick max |lambda_t|/lambda_n %.3f, lambda(mu = 3) - lambda(mu = 0.3) %.2e; "
      "slip %td patches, max | |lambda_t| - "
      "mu lambda_n | / (mu lambda_n) %.2e, max sin(slip, lambda_t) %.2e, sum |lambda_t| "
      "|R| / (mu N) - 1 = %.2e, bottom shear / (mu N) = %.6f, |bottom + force on "
      "master| / |force| %.2e\n",
      max_ratio, mu_effect, c.patches.size(), worst_cone, worst_angle,
      tangential / (kMu * normal) - 1, bottom_shear / (kMu * normal),
      (bottom + on_master).norm() / on_master.norm());
}

// ------------------------------------------------------------------------------------------
// 5b. Loading paths between the blocks (theory.md §2.9).
//  - Coulomb, the top pressed and sheared along [0, 0.5, 1, 1, 0]: released to exactly zero,
//    nothing presses the blocks together, so the last step's exact answer is lambda = 0.
//  - Frictionless, the upper block pressed, slid along x by far more than the master's element
//    at step 2 and slid back at step 3: without friction the upper block follows its top, so the
//    relative tangential displacement at step 2 is the slide itself, and the pairing (computed
//    once) no longer held then, whatever step 3 does: small sliding is checked at every step and
//    the worst step reported.

TEST(TwoBodiesContact, CoulombPathReleasedToZeroEndsWithoutPressure) {
  Problem p = coulomb_blocks(kStickShear, kMu);
  p.loading.steps = 5;
  p.dirichlet[1].path = {0.0, 0.5, 1.0, 1.0, 0.0};
  p.solver.certificate_tol = 1e-9;
  validate(p);
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_EQ(r.report.steps.size(), 5u);
  const Real pressed = r.report.steps[3].normal_force;
  ASSERT_GT(pressed, 0.0);
  EXPECT_LE(std::abs(r.report.steps[4].normal_force), 1e-8 * pressed);
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.contact->lambda.cwiseAbs().maxCoeff(), 1e-8 * r.contact->lambda.size() * pressed);
}

constexpr Real kSlide = 0.4;  // [m], over twice the master's element size (about 0.3 m)

TEST(TwoBodiesContact, SmallSlidingIsCheckedAtEveryStepOfAPath) {
  Problem p =
      stacked_problem(stacked_blocks(kLowerCells, kUpperCells), 0.0, Vec3(0.0, 0.0, -kDelta));
  p.dirichlet[1].components = {false, true, true};
  DirichletOptions slide{"up_z1", {true, false, false}, Vec3(kSlide, 0.0, 0.0)};
  slide.path = {0.0, 1.0, 0.0};
  p.dirichlet.push_back(slide);
  p.loading.steps = 3;
  validate(p);
  const RunResult r = run(p);
  ASSERT_EQ(r.report.status, RunStatus::Converged) << r.report.message;
  ASSERT_TRUE(r.report.contact);
  const PairReport& pair = r.report.contact->pairs.front();
  const Real limit = kSmallSlidingShare * pair.info.master_element_size;
  ASSERT_LT(limit, kSlide);
  EXPECT_FALSE(pair.small_sliding) << "slid " << kSlide << " m at step 2, limit " << limit;
  EXPECT_NEAR(pair.max_slip, kSlide, 1e-6 * kSlide);
  EXPECT_EQ(pair.max_slip_step, 2);
}

// ------------------------------------------------------------------------------------------
// 5c. Which surface is the slave (theory.md §2.8): a punch [0.5, 1.5]^2 x [1, 2] m pressed into a
// slab [0, 2]^2 x [0, 1] m, the punch's bottom meshed four times finer than the slab's top.
// The constraints keep the slave out of the master only; with the coarse slab as the slave, the
// punch's nodes sink into it between the slab's nodes. The interface is flat (z = 1) and the
// displacements small, so the penetration of a master node is, independently of fricon's rays,
// the slave's displacement interpolated on its triangle below the node minus the node's own,
// along the normal. With the fine punch as the slave it stays small.

constexpr Real kPunchPress = 1.0e-4;  // [m]

struct PunchResult {
  RunResult run;
  Real depth = 0.0;  // the largest master penetration measured here [m]
};

/// The punch on the slab, the slave being the slab's top ("lo_z1") or the punch's bottom.
PunchResult punch_on_slab(bool slave_is_slab) {
  const mesh::TetMesh slab = mesh::make_brick({Vec3(2.0, 2.0, 1.0), {4, 4, 2}});
  mesh::TetMesh punch = mesh::make_brick({Vec3(1.0, 1.0, 1.0), {8, 8, 4}});
  punch.nodes.colwise() += Vec3(0.5, 0.5, 1.0);
  const mesh::TetMesh both = mesh::disjoint_union({slab, punch}, {"lo_", "up_"});
  Problem p = stacked_problem(both, 0.3, Vec3(0.0, 0.0, -kPunchPress));
  const std::string slave = slave_is_slab ? "lo_z1" : "up_z0";
  const std::string master = slave_is_slab ? "up_z0" : "lo_z1";
  p.contact.front().boundary = slave;
  p.contact.front().obstacle->boundary = master;
  PunchResult out{run_converged(p), 0.0};
  // The master's nodes over the slave's triangles (2D barycentric coordinates in z = 1).
  const mesh::TetMesh& m = out.run.model.mesh;
  const fe::NodalField& u = out.run.displacement;
  const Real sign = slave_is_slab ? 1.0 : -1.0;  // the slave below (slab) or above (punch)
  for (Index a : m.nodes_with_tag(master))
    for (Index f : m.faces_with_tag(slave)) {
      const Vec3 x0 = m.nodes.col(m.faces(0, f)), x1 = m.nodes.col(m.faces(1, f)),
                 x2 = m.nodes.col(m.faces(2, f)), x = m.nodes.col(a);
      Eigen::Matrix2d J;
      J << x1(0) - x0(0), x2(0) - x0(0), x1(1) - x0(1), x2(1) - x0(1);
      const Eigen::Vector2d b = J.inverse() * Eigen::Vector2d(x(0) - x0(0), x(1) - x0(1));
      const Real l0 = 1.0 - b(0) - b(1);
      if (std::min({l0, b(0), b(1)}) < -1e-12) continue;
      const Real slave_z =
          l0 * u(2, m.faces(0, f)) + b(0) * u(2, m.faces(1, f)) + b(1) * u(2, m.faces(2, f));
      // Slab below: the punch's node penetrates when it goes below the slab's surface.
      out.depth = std::max(out.depth, sign * (slave_z - u(2, a)));
    }
  return out;
}

TEST(TwoBodiesContact, AMasterFinerThanItsSlavePenetratesItAndIsFlagged) {
  const PunchResult swapped = punch_on_slab(/*slave_is_slab=*/true);
  const PairReport& bad = swapped.run.report.contact->pairs.front();
  ASSERT_GT(swapped.depth, 0.0);
  EXPECT_NEAR(bad.master_penetration, swapped.depth, 1e-9 * kPunchPress);
  EXPECT_GT(bad.normal_displacement, 0.0);  // the surfaces move less than the punch's top
  EXPECT_LT(bad.normal_displacement, kPunchPress);
  EXPECT_FALSE(bad.master_kept_out);
  const PunchResult right = punch_on_slab(/*slave_is_slab=*/false);
  const PairReport& good = right.run.report.contact->pairs.front();
  EXPECT_NEAR(good.master_penetration, right.depth, 1e-9 * kPunchPress);
  EXPECT_TRUE(good.master_kept_out);
  std::printf(
      "punch on slab: master penetration %.3e m = %.3f of the normal displacement (slab as "
      "slave) against %.3e m = %.3f (punch as slave); normal force %.6e N against %.6e N\n",
      bad.master_penetration, bad.master_penetration / bad.normal_displacement,
      good.master_penetration, good.master_penetration / good.normal_displacement, bad.normal_force,
      good.normal_force);
}

// ------------------------------------------------------------------------------------------
// 6. Pairs that cannot be built.

std::string run_error(const Problem& p) {
  return test::input_error_of([&] {
    validate(p);
    (void)run(p);
  });
}

TEST(TwoBodiesContact, BadInput) {
  const mesh::TetMesh m = stacked_blocks(kLowerCells, kUpperCells);
  const Problem good = stacked_problem(m, 0.0, Vec3(0.0, 0.0, -kDelta));

  Problem no_tag = good;
  no_tag.contact.front().obstacle->boundary = "lo_top";
  EXPECT_THAT(run_error(no_tag), HasSubstr("boundary 'lo_top' does not exist on the mesh"));

  // The upper block's top against its own bottom: one body.
  Problem self = good;
  self.contact.front().obstacle->boundary = "up_z1";
  const std::string self_error = run_error(self);
  EXPECT_THAT(self_error, HasSubstr("are on the same body"));
  EXPECT_THAT(self_error, HasSubstr("self-contact is not supported"));

  // The lower block's bottom, 1 m below the slave and facing down like it: within a search
  // distance of 1.5 m the rays meet it, but it faces away.
  Problem away = good;
  away.contact.front().obstacle->boundary = "lo_z0";
  away.contact.front().search_distance = 1.5;
  EXPECT_THAT(run_error(away), HasSubstr("do not face each other"));

  // The upper block lifted by 0.5 m, looked for within 1 cm.
  Problem far = stacked_problem(stacked_blocks(kLowerCells, kUpperCells, Mat3::Identity(), 0.5),
                                0.0, Vec3(0.0, 0.0, -kDelta));
  far.contact.front().search_distance = 0.01;
  EXPECT_THAT(run_error(far), HasSubstr("the pair has no overlap"));
}

}  // namespace two_bodies_contact_test
