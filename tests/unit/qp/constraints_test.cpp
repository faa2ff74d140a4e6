// Unit tests of the separable feasible set: layout validation and the projection P_Omega.

#include "fricon/qp/constraints.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fricon/core/error.hpp"

namespace fricon::qp {
namespace {

SeparableConstraints single_disc(double rho) {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Disc, 0}};
  c.radius = Eigen::VectorXd::Constant(1, rho);
  return c;
}

TEST(SeparableConstraints, ContactLayoutPlacesBoundThenDiscPerPatch) {
  const auto c = SeparableConstraints::contact_layout(3);
  ASSERT_EQ(c.blocks.size(), 6u);
  EXPECT_EQ(c.size(), 9);
  EXPECT_EQ(c.n_discs(), 3);
  for (Index i = 0; i < 3; ++i) {
    const auto& bound = c.blocks[static_cast<std::size_t>(2 * i)];
    const auto& disc = c.blocks[static_cast<std::size_t>(2 * i + 1)];
    EXPECT_EQ(bound.kind, BlockKind::Bound);
    EXPECT_EQ(bound.offset, 3 * i);
    EXPECT_EQ(disc.kind, BlockKind::Disc);
    EXPECT_EQ(disc.offset, 3 * i + 1);
  }
  EXPECT_NO_THROW(c.validate());
  EXPECT_EQ(SeparableConstraints::contact_layout(0).size(), 0);
  EXPECT_THROW(SeparableConstraints::contact_layout(-1), InputError);
}

TEST(SeparableConstraints, SetDiscRadiiFillsOnlyDiscEntries) {
  auto c = SeparableConstraints::contact_layout(2);
  c.set_disc_radii(Eigen::Vector2d(0.5, 2.0));
  EXPECT_EQ(c.radius(1), 0.5);
  EXPECT_EQ(c.radius(3), 2.0);
  EXPECT_EQ(c.radius(0), 0.0);
  EXPECT_EQ(c.radius(2), 0.0);
  EXPECT_EQ(c.max_radius(), 2.0);
  EXPECT_THROW(c.set_disc_radii(Eigen::Vector3d(1, 1, 1)), InputError);
}

TEST(SeparableConstraints, ValidateAcceptsBlocksInAnyOrder) {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Disc, 2}, {BlockKind::Bound, 1}, {BlockKind::Bound, 0}};
  c.radius = Eigen::Vector3d(1.0, -7.0 /* ignored for a bound */, 0.0);
  EXPECT_EQ(c.size(), 4);
  EXPECT_NO_THROW(c.validate());
}

TEST(SeparableConstraints, ValidateRejectsBadLayouts) {
  SeparableConstraints overlap;
  overlap.blocks = {{BlockKind::Disc, 0}, {BlockKind::Bound, 1}};
  overlap.radius = Eigen::Vector2d(1.0, 0.0);
  EXPECT_THROW(overlap.validate(), InputError);

  SeparableConstraints gap;
  gap.blocks = {{BlockKind::Bound, 0}, {BlockKind::Bound, 2}};
  gap.radius = Eigen::Vector2d::Zero();
  try {
    gap.validate();
    FAIL() << "gap not detected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown 1"), std::string::npos) << e.what();
  }

  SeparableConstraints negative_offset;
  negative_offset.blocks = {{BlockKind::Bound, -1}};
  negative_offset.radius = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(negative_offset.validate(), InputError);

  auto wrong_length = SeparableConstraints::contact_layout(2);
  wrong_length.radius = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(wrong_length.validate(), InputError);

  EXPECT_THROW(single_disc(-1e-3).validate(), InputError);
  EXPECT_THROW(single_disc(NAN).validate(), InputError);
  EXPECT_THROW(single_disc(INFINITY).validate(), InputError);
  EXPECT_NO_THROW(single_disc(0.0).validate());
}

TEST(SeparableConstraints, FreeBlockKindBasics) {
  static_assert(block_size(BlockKind::Free) == 1);
  static_assert(block_size(BlockKind::Bound) == 1);
  static_assert(block_size(BlockKind::Disc) == 2);
  EXPECT_EQ(to_string(BlockKind::Free), "free");
  EXPECT_EQ(to_string(BlockKind::Bound), "bound");
  EXPECT_EQ(to_string(BlockKind::Disc), "disc");
}

// The equality multipliers of TFETI follow the contact ones: contact_layout(2) covers 0 ... 5, so
// three Free blocks take 6, 7, 8, and the disc radii already set stay where they are.
TEST(SeparableConstraints, AppendFreeFollowsTheContactLayout) {
  auto c = SeparableConstraints::contact_layout(2);
  c.set_disc_radii(Eigen::Vector2d(0.5, 2.0));
  c.append_free(3);
  ASSERT_EQ(c.blocks.size(), 7u);
  ASSERT_EQ(c.radius.size(), 7);
  for (Index i = 0; i < 3; ++i) {
    const Block& blk = c.blocks[static_cast<std::size_t>(4 + i)];
    EXPECT_EQ(blk.kind, BlockKind::Free);
    EXPECT_EQ(blk.offset, 6 + i);
    EXPECT_EQ(c.radius(4 + i), 0.0);
  }
  EXPECT_EQ(c.radius(1), 0.5);
  EXPECT_EQ(c.radius(3), 2.0);
  EXPECT_EQ(c.size(), 9);
  EXPECT_EQ(c.n_discs(), 2);
  EXPECT_EQ(c.max_radius(), 2.0);
  EXPECT_NO_THROW(c.validate());
  // Radii set after the append still go to the discs only.
  c.set_disc_radii(Eigen::Vector2d(3.0, 4.0));
  EXPECT_EQ(c.radius, (Eigen::VectorXd(7) << 0, 3, 0, 4, 0, 0, 0).finished());

  c.append_free(0);
  EXPECT_EQ(c.blocks.size(), 7u);
  EXPECT_EQ(c.radius.size(), 7);
}

TEST(SeparableConstraints, AppendFreeStartsAfterTheLastCoveredUnknown) {
  SeparableConstraints empty;
  empty.append_free(2);
  ASSERT_EQ(empty.blocks.size(), 2u);
  EXPECT_EQ(empty.blocks[0].offset, 0);
  EXPECT_EQ(empty.blocks[1].offset, 1);
  EXPECT_EQ(empty.radius, Eigen::Vector2d::Zero());
  EXPECT_NO_THROW(empty.validate());

  // Blocks out of order: the last covered unknown is 3 (the disc at 2), not that of the last
  // block in the list.
  SeparableConstraints unordered;
  unordered.blocks = {{BlockKind::Disc, 2}, {BlockKind::Bound, 1}, {BlockKind::Bound, 0}};
  unordered.radius = Eigen::Vector3d(1.0, 0.0, 0.0);
  unordered.append_free(1);
  ASSERT_EQ(unordered.blocks.size(), 4u);
  EXPECT_EQ(unordered.blocks[3].kind, BlockKind::Free);
  EXPECT_EQ(unordered.blocks[3].offset, 4);
  EXPECT_EQ(unordered.size(), 5);
  EXPECT_NO_THROW(unordered.validate());
}

TEST(SeparableConstraints, AppendFreeRejectsBadInput) {
  auto c = SeparableConstraints::contact_layout(1);
  EXPECT_THROW(c.append_free(-1), InputError);
  auto inconsistent = SeparableConstraints::contact_layout(1);
  inconsistent.radius = Eigen::VectorXd::Zero(1);  // 2 blocks
  EXPECT_THROW(inconsistent.append_free(1), InputError);
  EXPECT_EQ(inconsistent.blocks.size(), 2u);  // unchanged
}

TEST(SeparableConstraints, ValidateAcceptsFreeBlocksAndChecksTheirPlace) {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Free, 0}, {BlockKind::Disc, 1}, {BlockKind::Free, 3}};
  c.radius = Eigen::Vector3d(-7.0 /* ignored for a free block */, 1.0, NAN /* ignored */);
  EXPECT_EQ(c.size(), 4);
  EXPECT_EQ(c.n_discs(), 1);
  EXPECT_EQ(c.max_radius(), 1.0);
  EXPECT_NO_THROW(c.validate());

  SeparableConstraints overlap;
  overlap.blocks = {{BlockKind::Disc, 0}, {BlockKind::Free, 1}};
  overlap.radius = Eigen::Vector2d(1.0, 0.0);
  EXPECT_THROW(overlap.validate(), InputError);

  SeparableConstraints gap;
  gap.blocks = {{BlockKind::Free, 0}, {BlockKind::Free, 2}};
  gap.radius = Eigen::Vector2d::Zero();
  EXPECT_THROW(gap.validate(), InputError);

  constexpr int kNotAKind = 7;
  SeparableConstraints cast;
  cast.blocks = {{static_cast<BlockKind>(kNotAKind), 0}};
  cast.radius = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(cast.validate(), InputError);
}

TEST(SeparableConstraints, ProjectionLeavesFreeUnknownsUnchanged) {
  auto c = SeparableConstraints::contact_layout(2);
  c.set_disc_radii(Eigen::Vector2d(1.0, 0.0));
  c.append_free(3);
  Eigen::VectorXd x(9);
  x << -2.0, 3.0, -4.0, 5.0, 1.0, 1.0,  // bound clipped, disc scaled, bound kept, disc pinned
      -1e6, 0.0, 2.5;                   // free: any value, negative included
  c.project(x);
  Eigen::VectorXd expected(9);
  expected << 0.0, 0.6, -0.8, 5.0, 0.0, 0.0, -1e6, 0.0, 2.5;
  EXPECT_LE((x - expected).lpNorm<Eigen::Infinity>(), 1e-15) << x.transpose();
  EXPECT_EQ(x.tail<3>(), expected.tail<3>());  // bit for bit
}

TEST(SeparableConstraints, BoundProjectionClipsNegativesOnly) {
  SeparableConstraints c;
  c.blocks = {{BlockKind::Bound, 0}, {BlockKind::Bound, 1}, {BlockKind::Bound, 2}};
  c.radius = Eigen::Vector3d::Zero();
  Eigen::VectorXd x = Eigen::Vector3d(-2.5, 0.0, 3.25);
  c.project(x);
  EXPECT_EQ(x, Eigen::Vector3d(0.0, 0.0, 3.25));
}

TEST(SeparableConstraints, DiscProjectionMatchesHandValues) {
  const auto c = single_disc(1.0);
  Eigen::VectorXd x = Eigen::Vector2d(3.0, -4.0);  // norm 5
  c.project(x);
  EXPECT_NEAR(x(0), 0.6, 1e-15);
  EXPECT_NEAR(x(1), -0.8, 1e-15);
  Eigen::VectorXd inside = Eigen::Vector2d(0.3, 0.4);
  c.project(inside);
  EXPECT_EQ(inside, Eigen::Vector2d(0.3, 0.4));
}

TEST(SeparableConstraints, ZeroRadiusProjectsToZero) {
  const auto c = single_disc(0.0);
  Eigen::VectorXd x = Eigen::Vector2d(1e-3, -2.0);
  c.project(x);
  EXPECT_EQ(x, Eigen::Vector2d::Zero());
}

// Random points around a contact layout with radii in [0, 2].
struct RandomCase {
  SeparableConstraints c;
  std::vector<Eigen::VectorXd> points;
};

RandomCase random_case(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-3.0, 3.0), R(0.0, 2.0);
  RandomCase rc;
  rc.c = SeparableConstraints::contact_layout(5);
  Eigen::VectorXd r(5);
  for (Index i = 0; i < 5; ++i)
    r(i) = i == 0 ? 0.0 : R(rng);
  rc.c.set_disc_radii(r);
  for (int k = 0; k < 200; ++k) {
    Eigen::VectorXd x(15);
    for (Index i = 0; i < 15; ++i)
      x(i) = U(rng);
    rc.points.push_back(x);
  }
  return rc;
}

bool feasible(const SeparableConstraints& c, const Eigen::VectorXd& x, double tol) {
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Index o = c.blocks[k].offset;
    if (c.blocks[k].kind == BlockKind::Bound) {
      if (x(o) < -tol) return false;
    } else if (std::hypot(x(o), x(o + 1)) > c.radius(static_cast<Index>(k)) + tol) {
      return false;
    }
  }
  return true;
}

TEST(SeparableConstraints, ProjectionIsFeasibleAndIdempotent) {
  const auto rc = random_case(11);
  for (const auto& x0 : rc.points) {
    Eigen::VectorXd p = x0;
    rc.c.project(p);
    EXPECT_TRUE(feasible(rc.c, p, 1e-15));
    Eigen::VectorXd pp = p;
    rc.c.project(pp);
    EXPECT_LE((pp - p).lpNorm<Eigen::Infinity>(), 1e-15);
  }
}

TEST(SeparableConstraints, ProjectionIsNonExpansive) {
  const auto rc = random_case(12);
  for (std::size_t k = 0; k + 1 < rc.points.size(); ++k) {
    Eigen::VectorXd p = rc.points[k], q = rc.points[k + 1];
    rc.c.project(p);
    rc.c.project(q);
    EXPECT_LE((p - q).norm(), (rc.points[k] - rc.points[k + 1]).norm() * (1 + 1e-15));
  }
}

// P(y) is the projection iff (y - P(y))^T (z - P(y)) <= 0 for every z in Omega: test against
// random feasible z (an independent characterisation of the nearest point).
TEST(SeparableConstraints, ProjectionSatisfiesVariationalInequality) {
  const auto rc = random_case(13);
  std::vector<Eigen::VectorXd> feasible_points;
  for (const auto& z : rc.points) {
    if (feasible(rc.c, z, 0.0)) feasible_points.push_back(z);
    Eigen::VectorXd shrunk = 0.1 * z;
    for (Index o = 0; o < 15; o += 3) {
      shrunk(o) = std::abs(shrunk(o));
      shrunk.segment<2>(o + 1) *=
          0.5 * rc.c.radius(o / 3 * 2 + 1) / std::max(shrunk.segment<2>(o + 1).norm(), 1e-300);
    }
    feasible_points.push_back(shrunk);
  }
  ASSERT_GT(feasible_points.size(), 150u);
  for (const auto& y : rc.points) {
    Eigen::VectorXd p = y;
    rc.c.project(p);
    for (const auto& z : feasible_points) {
      ASSERT_TRUE(feasible(rc.c, z, 1e-15));
      EXPECT_LE((y - p).dot(z - p), 1e-12);
    }
  }
}

}  // namespace
}  // namespace fricon::qp
