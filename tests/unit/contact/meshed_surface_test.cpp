// The rigid obstacle of a meshed surface (contact/obstacles/meshed_surface.hpp): the signed
// distance and normal of a meshed unit cube against the cube's exact signed distance (inside,
// outside, near its edges and corners), given with half its faces inward and with random flips;
// tetrahedra with sharp edges and corners, where only the pseudo-normals give the right side;
// an open square facing the body above or below; a fine sphere within its chord error of the
// exact sphere, and against brute force; and the refused surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/contact/obstacle.hpp"
#include "fricon/contact/obstacles/meshed_surface.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/tet_mesh.hpp"

using namespace fricon;
using namespace fricon::contact;

namespace {

using Points = Eigen::Matrix<Real, 3, Eigen::Dynamic>;
using Triangles = Eigen::Matrix<Index, 3, Eigen::Dynamic>;

const std::string kObstacleKey = "problem.toml: contact.obstacle";

mesh::RigidSurface make_surface(const std::string& name, const std::vector<Vec3>& points,
                                const std::vector<std::array<Index, 3>>& triangles) {
  mesh::RigidSurface s{name, Points(3, static_cast<Index>(points.size())),
                       Triangles(3, static_cast<Index>(triangles.size()))};
  for (size_t p = 0; p < points.size(); ++p)
    s.points.col(static_cast<Index>(p)) = points[p];
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      s.triangles(k, static_cast<Index>(t)) = triangles[t][static_cast<size_t>(k)];
  return s;
}

// The surface of the unit cube [0, 1]^3, each face an n x n grid of squares cut in two, on shared
// points. Every triangle's right-hand normal is +e_a on the faces normal to axis a: outward on the
// faces x_a = 1, inward on the faces x_a = 0.
mesh::RigidSurface cube_surface(int n) {
  std::map<std::array<int, 3>, Index> index_of;
  std::vector<Vec3> points;
  const auto point = [&](std::array<int, 3> g) {
    const auto [it, inserted] = index_of.emplace(g, static_cast<Index>(points.size()));
    if (inserted) points.emplace_back(Vec3(g[0], g[1], g[2]) / n);
    return it->second;
  };
  std::vector<std::array<Index, 3>> triangles;
  for (int a = 0; a < 3; ++a)
    for (int side : {0, n})
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          const auto at = [&](int du, int dv) {
            std::array<int, 3> g{};
            g[static_cast<size_t>(a)] = side;
            g[static_cast<size_t>((a + 1) % 3)] = u + du;
            g[static_cast<size_t>((a + 2) % 3)] = v + dv;
            return point(g);
          };
          triangles.push_back({at(0, 0), at(1, 0), at(1, 1)});
          triangles.push_back({at(0, 0), at(1, 1), at(0, 1)});
        }
  return make_surface("cube", points, triangles);
}

// The exact signed distance to the unit cube and its gradient (where it is unique).
std::pair<Real, Vec3> cube_distance(const Vec3& x) {
  const Vec3 c = Vec3::Constant(0.5);
  const Vec3 q = (x - c).cwiseAbs() - Vec3::Constant(0.5);
  const Vec3 sign = (x - c).cwiseSign();
  const Vec3 out = q.cwiseMax(0.0);
  if (out.norm() > 0.0) return {out.norm(), Vec3(out.cwiseProduct(sign) / out.norm())};
  int axis = 0;
  const Real inside = q.maxCoeff(&axis);
  return {inside, sign(axis) * Vec3::Unit(axis)};
}

// Points of every kind around the unit cube: random inside and outside, and just off its edges
// and corners in every direction.
std::vector<Vec3> points_around_cube() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> box(-0.6, 1.6), unit(0.0, 1.0), offset(-0.05, 0.05);
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i)
    points.emplace_back(box(rng), box(rng), box(rng));
  for (int i = 0; i < 400; ++i) {
    // A point on an edge (two coordinates 0 or 1, one free), or a corner, then moved a little.
    Vec3 p(unit(rng) < 0.5 ? 0.0 : 1.0, unit(rng) < 0.5 ? 0.0 : 1.0, unit(rng) < 0.5 ? 0.0 : 1.0);
    if (i % 2 == 0) p(i % 3) = unit(rng);
    const Real scale = i % 4 < 2 ? 1.0 : 1e-3;
    points.push_back(p + scale * Vec3(offset(rng), offset(rng), offset(rng)));
  }
  return points;
}

void expect_cube_distances(const Obstacle& cube) {
  for (const Vec3& x : points_around_cube()) {
    const auto [exact, gradient] = cube_distance(x);
    const Proximity p = cube.closest(x);
    EXPECT_NEAR(p.distance, exact, 1e-12) << x.transpose();
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12) << x.transpose();
    // The nearest point lies on the cube, and the normal is the exact gradient where that is
    // unique (the inside's nearest face is unique for points off its diagonal planes).
    EXPECT_NEAR(cube_distance(x - p.distance * p.normal).first, 0.0, 1e-12) << x.transpose();
    const Vec3 q = (x - Vec3::Constant(0.5)).cwiseAbs();
    std::array<Real, 3> sorted{q(0), q(1), q(2)};
    std::sort(sorted.begin(), sorted.end());
    if (exact > 1e-9 || sorted[2] - sorted[1] > 1e-9) {
      EXPECT_NEAR((p.normal - gradient).norm(), 0.0, 1e-9) << x.transpose();
    }
  }
}

// Whether every triangle faces away from the point `inside`, and 6 times the enclosed volume.
Real oriented_volume_six(const Obstacle& obstacle, const Vec3& inside, bool* all_outward) {
  const auto [points, triangles] = oriented_triangles(obstacle);
  Real six = 0.0;
  *all_outward = triangles.cols() > 0;
  for (Index t = 0; t < triangles.cols(); ++t) {
    const Vec3 a = points.col(triangles(0, t)), b = points.col(triangles(1, t)),
               c = points.col(triangles(2, t));
    six += (a - inside).dot((b - inside).cross(c - inside));
    if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - inside) <= 0.0) *all_outward = false;
  }
  return six;
}

// The distance from x to triangle (a, b, c), computed otherwise than the obstacle does: the
// distance to the plane where x projects inside the triangle, else to the nearest edge.
Real brute_distance(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 y = x - (x - a).dot(n) * n;
  const auto inside = [&](const Vec3& p, const Vec3& q) {
    return (q - p).cross(y - p).dot(n) >= 0;
  };
  if (inside(a, b) && inside(b, c) && inside(c, a)) return std::abs((x - a).dot(n));
  const auto to_segment = [&](const Vec3& p, const Vec3& q) {
    const Real s = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
    return (x - p - s * (q - p)).norm();
  };
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

// @sect: a closed surface.

TEST(MeshedSurface, CubeDistanceIsExactInsideOutsideAndNearEdgesAndCorners) {
  const mesh::RigidSurface surface = cube_surface(3);
  const ObstaclePtr cube = make_meshed_surface(surface, Points(3, 0), kObstacleKey);
  EXPECT_EQ(cube->kind(), "surface");
  EXPECT_FALSE(cube->flat());
  expect_cube_distances(*cube);
  bool outward = false;
  EXPECT_NEAR(oriented_volume_six(*cube, Vec3::Constant(0.5), &outward), 6.0, 1e-12);
  EXPECT_TRUE(outward);
  // The same points, the triangles reoriented and no vertex moved.
  const auto [points, triangles] = oriented_triangles(*cube);
  EXPECT_EQ(points, surface.points);
  EXPECT_EQ(triangles.cols(), surface.triangles.cols());
}

TEST(MeshedSurface, InconsistentOrientationIsFixed) {
  // As made (half the faces inward), all inward, and each triangle flipped at random: the outside
  // is the same.
  std::mt19937 rng(11);
  for (int variant = 0; variant < 3; ++variant) {
    mesh::RigidSurface given = cube_surface(4);
    for (Index t = 0; t < given.triangles.cols(); ++t) {
      const Vec3 centre =
          (given.points.col(given.triangles(0, t)) + given.points.col(given.triangles(1, t)) +
           given.points.col(given.triangles(2, t))) /
          3.0;
      const bool outward = centre.maxCoeff() > 1.0 - 1e-12;  // on a face x_a = 1
      if ((variant == 1 && outward) || (variant == 2 && rng() % 2 == 1))
        std::swap(given.triangles(1, t), given.triangles(2, t));
    }
    const ObstaclePtr cube = make_meshed_surface(given, Points(3, 0), kObstacleKey);
    bool all_outward = false;
    EXPECT_NEAR(oriented_volume_six(*cube, Vec3::Constant(0.5), &all_outward), 6.0, 1e-12);
    EXPECT_TRUE(all_outward) << variant;
    expect_cube_distances(*cube);
  }
}

TEST(MeshedSurface, ParametersAreTheTriangleCountAndTheBoundingBox) {
  mesh::RigidSurface surface = cube_surface(2);
  surface.points.array() += 3.0;
  const ObstaclePtr cube = make_meshed_surface(surface, Points(3, 0), kObstacleKey);
  const std::vector<ObstacleParameter> parameters = cube->parameters();
  ASSERT_EQ(parameters.size(), 2u);
  EXPECT_EQ(parameters[0].name, "triangles");
  EXPECT_EQ(parameters[0].value, std::vector<Real>{48.0});
  EXPECT_EQ(parameters[1].name, "bounding_box");
  EXPECT_EQ(parameters[1].value, (std::vector<Real>{3, 3, 3, 4, 4, 4}));
  EXPECT_FALSE(parameters[0].moves);
  EXPECT_FALSE(parameters[1].moves);
  // Another kind has no triangles.
  const auto [points, triangles] = oriented_triangles(*make_plane(Vec3::Zero(), Vec3::UnitZ()));
  EXPECT_EQ(points.cols(), 0);
  EXPECT_EQ(triangles.cols(), 0);
}

// A tetrahedron's surface, each face cut into four (flat, so that its sharp edges and corners
// are those of the tetrahedron), given with every face inward.
mesh::RigidSurface tetrahedron_surface(const std::array<Vec3, 4>& corners) {
  std::vector<Vec3> points(corners.begin(), corners.end());
  std::vector<std::array<Index, 3>> triangles;
  std::map<std::pair<Index, Index>, Index> middle;
  const auto mid = [&](Index a, Index b) {
    const auto [it, inserted] =
        middle.emplace(std::make_pair(std::min(a, b), std::max(a, b)), points.size());
    if (inserted) points.push_back((points[a] + points[b]) / 2.0);
    return it->second;
  };
  for (int opposite = 0; opposite < 4; ++opposite) {
    std::array<Index, 3> f{};
    int n = 0;
    for (int v = 0; v < 4; ++v)
      if (v != opposite) f[n++] = v;
    const Vec3 normal = (points[f[1]] - points[f[0]]).cross(points[f[2]] - points[f[0]]);
    if (normal.dot(points[static_cast<size_t>(opposite)] - points[f[0]]) < 0.0)
      std::swap(f[1], f[2]);  // facing the opposite corner: inward
    const Index ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
    triangles.push_back({f[0], ab, ca});
    triangles.push_back({f[1], bc, ab});
    triangles.push_back({f[2], ca, bc});
    triangles.push_back({ab, bc, ca});
  }
  return make_surface("tetrahedron", points, triangles);
}

// The exact signed distance to the tetrahedron `corners`: minus the distance to the nearest face
// plane inside, the distance to the nearest face outside.
Real tetrahedron_distance(const std::array<Vec3, 4>& corners, const Vec3& x) {
  Real inside = -std::numeric_limits<Real>::infinity();
  Real outside = std::numeric_limits<Real>::infinity();
  for (int opposite = 0; opposite < 4; ++opposite) {
    const Vec3& a = corners[static_cast<size_t>((opposite + 1) % 4)];
    const Vec3& b = corners[static_cast<size_t>((opposite + 2) % 4)];
    const Vec3& c = corners[static_cast<size_t>((opposite + 3) % 4)];
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(corners[static_cast<size_t>(opposite)] - a) > 0.0) n = -n;
    inside = std::max(inside, (x - a).dot(n));
    outside = std::min(outside, brute_distance(x, a, b, c));
  }
  return inside <= 0.0 ? inside : outside;
}

TEST(MeshedSurface, SharpEdgesAndCornersGetTheRightSide) {
  // A regular tetrahedron (faces at 109 degrees across its edges) and a flat one, whose edges and
  // corners at the base are sharp: beyond them, x - p may point against a face's normal.
  const std::array<std::array<Vec3, 4>, 2> shapes = {
      std::array<Vec3, 4>{Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)},
      std::array<Vec3, 4>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.08)}};
  std::mt19937 rng(13);
  std::uniform_real_distribution<Real> unit(0.0, 1.0), offset(-0.1, 0.1);
  for (const auto& corners : shapes) {
    const ObstaclePtr obstacle =
        make_meshed_surface(tetrahedron_surface(corners), Points(3, 0), kObstacleKey);
    int outside = 0, inside = 0;
    for (int i = 0; i < 2000; ++i) {
      // Near a corner or a point of an edge, or anywhere around.
      const Vec3& a = corners[rng() % 4];
      const Vec3& b = corners[rng() % 4];
      const Vec3 on = i % 3 == 0 ? a : (i % 3 == 1 ? Vec3(a + unit(rng) * (b - a)) : Vec3::Zero());
      const Real scale = i % 3 == 2 ? 15.0 : (i % 2 == 0 ? 1.0 : 1e-3);
      const Vec3 x = on + scale * Vec3(offset(rng), offset(rng), offset(rng));
      const Real exact = tetrahedron_distance(corners, x);
      const Proximity p = obstacle->closest(x);
      EXPECT_NEAR(p.distance, exact, 1e-12) << x.transpose();
      EXPECT_NEAR(tetrahedron_distance(corners, x - p.distance * p.normal), 0.0, 1e-12)
          << x.transpose();
      (exact > 0.0 ? outside : inside) += 1;
    }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 300);
  }
}

// @sect: an open surface.

// The square [0, 1]^2 at z = 0, n x n squares cut in two, each triangle facing +z or (`down`) -z.
mesh::RigidSurface square_surface(int n, bool down) {
  std::vector<Vec3> points;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      points.emplace_back(Real(i) / n, Real(j) / n, 0.0);
  std::vector<std::array<Index, 3>> triangles;
  const auto at = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  if (down)
    for (auto& t : triangles)
      std::swap(t[1], t[2]);
  return make_surface("plate", points, triangles);
}

Points grid_at_height(Real z) {
  Points p(3, 9);
  for (int k = 0; k < 9; ++k)
    p.col(k) = Vec3(0.1 + 0.4 * (k % 3), 0.1 + 0.4 * (k / 3), z);
  return p;
}

TEST(MeshedSurface, OpenSquareFacesTheBody) {
  for (bool down : {false, true}) {
    const mesh::RigidSurface square = square_surface(4, down);
    // The body above: the outside is +z, whatever the file's orientation.
    Points above = grid_at_height(0.5);
    above.col(4) = Vec3(0.5, 0.5, -0.5);  // one point of the body below does not outvote them
    const ObstaclePtr up = make_meshed_surface(square, above, kObstacleKey);
    Proximity p = up->closest(Vec3(0.3, 0.6, 0.25));
    EXPECT_NEAR(p.distance, 0.25, 1e-14) << down;
    EXPECT_NEAR((p.normal - Vec3::UnitZ()).norm(), 0.0, 1e-14) << down;
    p = up->closest(Vec3(0.3, 0.6, -0.25));
    EXPECT_NEAR(p.distance, -0.25, 1e-14) << down;
    EXPECT_NEAR((p.normal - Vec3::UnitZ()).norm(), 0.0, 1e-14) << down;
    // Beyond the rim, the distance to the rim, on the side of its triangles.
    p = up->closest(Vec3(1.3, 0.5, 0.4));
    EXPECT_NEAR(p.distance, 0.5, 1e-14) << down;
    EXPECT_NEAR((p.normal - Vec3(0.6, 0.0, 0.8)).norm(), 0.0, 1e-14) << down;
    p = up->closest(Vec3(-0.3, -0.4, -1.2));  // beyond a corner, below
    EXPECT_NEAR(p.distance, -1.3, 1e-14) << down;
    EXPECT_NEAR((p.normal - Vec3(0.3, 0.4, 1.2) / 1.3).norm(), 0.0, 1e-14) << down;
    // The body below: the sign flips.
    const ObstaclePtr below = make_meshed_surface(square, grid_at_height(-0.5), kObstacleKey);
    p = below->closest(Vec3(0.3, 0.6, 0.25));
    EXPECT_NEAR(p.distance, -0.25, 1e-14) << down;
    EXPECT_NEAR((p.normal + Vec3::UnitZ()).norm(), 0.0, 1e-14) << down;
    const auto [points, triangles] = oriented_triangles(*below);
    for (Index t = 0; t < triangles.cols(); ++t)
      EXPECT_LT((points.col(triangles(1, t)) - points.col(triangles(0, t)))
                    .cross(points.col(triangles(2, t)) - points.col(triangles(0, t)))
                    .z(),
                0.0);
    // No body points, or as many on each side: the file's orientation.
    Points tied(3, 2);
    tied << 0.5, 0.5, 0.5, 0.5, 1.0, -1.0;
    for (const Points& none_or_tied : {Points(3, 0), tied}) {
      p = make_meshed_surface(square, none_or_tied, kObstacleKey)->closest(Vec3(0.5, 0.5, 0.1));
      EXPECT_NEAR(p.distance, down ? -0.1 : 0.1, 1e-14);
    }
    // On the surface: distance 0 and the triangle's normal.
    p = up->closest(Vec3(0.5, 0.25, 0.0));
    EXPECT_NEAR(p.distance, 0.0, 1e-15);
    EXPECT_NEAR((p.normal - Vec3::UnitZ()).norm(), 0.0, 1e-14);
  }
}

TEST(MeshedSurface, TwoOpenComponentsEachFaceTheirPartOfTheBody) {
  // A floor facing up (the body above it) and a ceiling at z = 2 facing down (the body below it),
  // both given facing up.
  mesh::RigidSurface floor = square_surface(2, false);
  mesh::RigidSurface both = floor;
  both.points.resize(3, 2 * floor.points.cols());
  both.points << floor.points, floor.points.colwise() + Vec3(0.0, 0.0, 2.0);
  both.triangles.resize(3, 2 * floor.triangles.cols());
  both.triangles << floor.triangles, floor.triangles.array() + floor.points.cols();
  Points body(3, 18);
  body << grid_at_height(0.2), grid_at_height(1.7);
  const ObstaclePtr obstacle = make_meshed_surface(both, body, kObstacleKey);
  EXPECT_NEAR(obstacle->closest(Vec3(0.5, 0.5, 0.3)).distance, 0.3, 1e-14);
  EXPECT_NEAR(obstacle->closest(Vec3(0.5, 0.5, 1.6)).distance, 0.4, 1e-14);
  EXPECT_NEAR((obstacle->closest(Vec3(0.5, 0.5, 1.6)).normal + Vec3::UnitZ()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(obstacle->closest(Vec3(0.5, 0.5, 2.5)).distance, -0.5, 1e-14);
}

// @sect: a curved surface.

// The unit sphere: an icosahedron refined `levels` times, its points on the sphere, with the
// triangles given in random orientations.
mesh::RigidSurface sphere_surface(int levels) {
  const Real g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : points)
    p.normalize();
  std::vector<std::array<Index, 3>> triangles = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<Index, Index>, Index> middle;
    const auto mid = [&](Index a, Index b) {
      const auto [it, inserted] =
          middle.emplace(std::make_pair(std::min(a, b), std::max(a, b)), points.size());
      if (inserted) points.push_back((points[a] + points[b]).normalized());
      return it->second;
    };
    std::vector<std::array<Index, 3>> finer;
    for (const auto& [a, b, c] : triangles) {
      const Index ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  std::mt19937 rng(3);
  for (auto& t : triangles)
    if (rng() % 2) std::swap(t[1], t[2]);
  return make_surface("ball", points, triangles);
}

TEST(MeshedSurface, SphereDistanceIsWithinTheChordErrorAndExactForItsTriangles) {
  const mesh::RigidSurface ball = sphere_surface(4);  // 5120 triangles
  ASSERT_EQ(ball.triangles.cols(), 5120);
  // The chord error: how far inside the sphere the triangles reach.
  Real chord = 0.0;
  for (Index t = 0; t < ball.triangles.cols(); ++t) {
    const Vec3 a = ball.points.col(ball.triangles(0, t)), b = ball.points.col(ball.triangles(1, t)),
               c = ball.points.col(ball.triangles(2, t));
    chord = std::max(chord, 1.0 - std::abs(a.dot((b - a).cross(c - a).normalized())));
  }
  ASSERT_GT(chord, 1e-4);
  ASSERT_LT(chord, 1e-2);
  const ObstaclePtr sphere = make_meshed_surface(ball, Points(3, 0), kObstacleKey);
  std::mt19937 rng(5);
  std::normal_distribution<Real> normal;
  std::uniform_real_distribution<Real> radius(0.2, 2.0);
  int checked = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 x = radius(rng) * Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Real exact = x.norm() - 1.0;
    if (std::abs(exact) < 2.0 * chord) continue;  // in the band the mesh and the sphere differ
    ++checked;
    const Proximity p = sphere->closest(x);
    EXPECT_NEAR(p.distance, exact, chord * (1.0 + 1e-9)) << x.transpose();
    EXPECT_GT(p.normal.dot(x.normalized()), 0.99) << x.transpose();
    if (i % 10 == 0) {
      Real brute = std::numeric_limits<Real>::infinity();
      for (Index t = 0; t < ball.triangles.cols(); ++t)
        brute = std::min(brute, brute_distance(x, ball.points.col(ball.triangles(0, t)),
                                               ball.points.col(ball.triangles(1, t)),
                                               ball.points.col(ball.triangles(2, t))));
      EXPECT_NEAR(std::abs(p.distance), brute, 1e-12) << x.transpose();
    }
  }
  EXPECT_GT(checked, 400);
  bool outward = false;
  EXPECT_NEAR(oriented_volume_six(*sphere, Vec3::Zero(), &outward) / 6.0, 4.0 / 3.0 * M_PI, 0.02);
  EXPECT_TRUE(outward);
}

// @sect: refused surfaces.

void expect_refused(const mesh::RigidSurface& surface, const std::vector<std::string>& parts) {
  const std::string message =
      test::input_error_of([&] { (void)make_meshed_surface(surface, Points(3, 0), kObstacleKey); });
  ASSERT_FALSE(message.empty()) << "no InputError";
  for (const std::string& part : {kObstacleKey, std::string("'") + surface.name + "'"})
    EXPECT_NE(message.find(part), std::string::npos) << message;
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST(MeshedSurface, RefusesNonManifoldAndNonOrientableSurfaces) {
  // Three triangles on one edge.
  expect_refused(make_surface("fins", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
                              {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}),
                 {"not a manifold", "3 triangles"});
  // Two triangles touching at a point.
  expect_refused(make_surface("bowtie", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, 1, 0}},
                              {{0, 1, 2}, {0, 3, 4}}),
                 {"not a manifold", "point 0"});
  // A Moebius strip.
  constexpr int kSegments = 12;
  std::vector<Vec3> points;
  for (int i = 0; i < kSegments; ++i) {
    const Real phi = 2.0 * M_PI * i / kSegments;
    for (Real w : {0.5, -0.5})
      points.emplace_back((2.0 + w * std::cos(phi / 2)) * std::cos(phi),
                          (2.0 + w * std::cos(phi / 2)) * std::sin(phi), w * std::sin(phi / 2));
  }
  std::vector<std::array<Index, 3>> strip;
  for (Index i = 0; i < kSegments; ++i) {
    const Index top = 2 * i, bottom = 2 * i + 1;
    // After the last segment the strip comes back turned over: top meets bottom.
    const bool last = i + 1 == kSegments;
    const Index next_top = last ? 1 : 2 * (i + 1), next_bottom = last ? 0 : 2 * (i + 1) + 1;
    strip.push_back({top, bottom, next_top});
    strip.push_back({bottom, next_bottom, next_top});
  }
  expect_refused(make_surface("moebius", points, strip), {"cannot be oriented"});
  // Zero area, no triangle, a bad index.
  expect_refused(make_surface("flat", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}),
                 {"zero area"});
  expect_refused(make_surface("empty", {{0, 0, 0}}, {}), {"no triangle"});
  expect_refused(make_surface("bad", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}), {"point 3"});
}

}  // namespace
