// The geometry of mortar contact between two triangulated surfaces (mortar_geometry.hpp): convex
// clipping against hand-computed polygons, the locator's ray hits and box queries against the
// structure of the meshes and brute force, and the mortar integrals against exact integrals of
// affine functions over the slave triangle, on flat, tilted, rotated and curved masters.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "fricon/contact/mortar_geometry.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/tet_mesh.hpp"

using namespace fricon;
using namespace fricon::contact;

namespace {

// Relative accuracy of sums of exact integrals (a few hundred rounding errors).
constexpr Real kExact = 1e-12;

// ---------------------------------------------------------------------------------------------
// Plane polygons

// Shoelace area of a polygon, written here independently of polygon_area.
Real shoelace(const std::vector<Vec2>& p) {
  Real twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

// Whether every point of `expected` is a vertex of `polygon` and vice versa (to 1e-14).
bool same_vertices(const std::vector<Vec2>& polygon, const std::vector<Vec2>& expected) {
  auto contains = [](const std::vector<Vec2>& set, const Vec2& p) {
    return std::any_of(set.begin(), set.end(),
                       [&](const Vec2& q) { return (q - p).norm() < 1e-14; });
  };
  if (polygon.size() != expected.size()) return false;
  for (const Vec2& p : expected)
    if (!contains(polygon, p)) return false;
  for (const Vec2& p : polygon)
    if (!contains(expected, p)) return false;
  return true;
}

std::vector<Vec2> square(Real x0, Real y0, Real side) {
  return {Vec2(x0, y0), Vec2(x0 + side, y0), Vec2(x0 + side, y0 + side), Vec2(x0, y0 + side)};
}

// ---------------------------------------------------------------------------------------------
// Triangulated surfaces

struct Surface {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> nodes;
  Eigen::Matrix<Index, 3, Eigen::Dynamic> triangles;
  std::vector<Index> all() const {
    std::vector<Index> f(static_cast<size_t>(triangles.cols()));
    for (Index i = 0; i < triangles.cols(); ++i)
      f[static_cast<size_t>(i)] = i;
    return f;
  }
};

// The grid of k x k squares over the unit square [0, 1]^2, each split in two triangles along
// alternating diagonals, counter-clockwise seen from +z, the vertex (u, v) placed at place(u, v).
// Triangles 2 c and 2 c + 1 are those of square c = i + k j; the first is the one below the
// diagonal (it holds the square's corner (i + 1, j)).
template <class Place>
Surface grid_surface(Index k, Place place) {
  Surface s;
  s.nodes.resize(3, (k + 1) * (k + 1));
  for (Index j = 0; j <= k; ++j)
    for (Index i = 0; i <= k; ++i)
      s.nodes.col(i + (k + 1) * j) = place(static_cast<Real>(i) / static_cast<Real>(k),
                                           static_cast<Real>(j) / static_cast<Real>(k));
  s.triangles.resize(3, 2 * k * k);
  for (Index j = 0; j < k; ++j)
    for (Index i = 0; i < k; ++i) {
      const Index v00 = i + (k + 1) * j, v10 = v00 + 1, v01 = v00 + k + 1, v11 = v01 + 1;
      const Index c = i + k * j;
      if ((i + j) % 2 == 0) {  // diagonal v00-v11
        s.triangles.col(2 * c) << v00, v10, v11;
        s.triangles.col(2 * c + 1) << v00, v11, v01;
      } else {  // diagonal v10-v01
        s.triangles.col(2 * c) << v00, v10, v01;
        s.triangles.col(2 * c + 1) << v10, v11, v01;
      }
    }
  return s;
}

// The unit square [0, 1]^2 at height z, k x k squares.
Surface flat_square(Index k, Real z = 0.0) {
  return grid_surface(k, [z](Real u, Real v) { return Vec3(u, v, z); });
}

// The face of flat_square(k) that holds the point (x, y) strictly inside it (the structure of the
// grid: the square, then the side of its diagonal).
Index flat_square_face(Index k, Real x, Real y) {
  const Real kr = static_cast<Real>(k);
  const Index i = static_cast<Index>(std::floor(x * kr)),
              j = static_cast<Index>(std::floor(y * kr));
  const Real u = x * kr - static_cast<Real>(i), v = y * kr - static_cast<Real>(j);
  const Index c = i + k * j;
  const bool first = (i + j) % 2 == 0 ? v < u : u + v < 1.0;
  return first ? 2 * c : 2 * c + 1;
}

// A cap of the sphere of radius `radius` about the origin: the grid over [-0.8, 0.8]^2 in the
// plane z = 1, projected on the sphere (a face of a cubed sphere), outward normals.
Surface sphere_cap(Index k, Real radius) {
  return grid_surface(k, [radius](Real u, Real v) {
    return Vec3(radius * Vec3(1.6 * u - 0.8, 1.6 * v - 0.8, 1.0).normalized());
  });
}

// The Halton sequence in base b: deterministic, well spread points of [0, 1).
Real halton(Index i, Index b) {
  Real f = 1.0, r = 0.0;
  for (Index n = i + 1; n > 0; n /= b) {
    f /= static_cast<Real>(b);
    r += f * static_cast<Real>(n % b);
  }
  return r;
}

Triangle3 vertices(const Surface& s, Index f) {
  return {s.nodes.col(s.triangles(0, f)), s.nodes.col(s.triangles(1, f)),
          s.nodes.col(s.triangles(2, f))};
}

// Coordinates (l1, l2, h) of p = x0 + l1 (x1 - x0) + l2 (x2 - x0) + h * unit normal: the
// barycentrics (1 - l1 - l2, l1, l2) of p's projection and p's height above the triangle.
Vec3 triangle_coordinates(const Triangle3& x, const Vec3& p) {
  Mat3 a;
  a.col(0) = x[1] - x[0];
  a.col(1) = x[2] - x[0];
  a.col(2) = a.col(0).cross(a.col(1)).normalized();
  return a.fullPivLu().solve(p - x[0]);
}

// Expects p to lie on triangle x: in its plane and inside it, with barycentrics `lambda`.
void expect_on_triangle(const Triangle3& x, const std::array<Real, 3>& lambda, const Vec3& p) {
  const Vec3 c = triangle_coordinates(x, p);
  EXPECT_NEAR(c(2), 0.0, 1e-12);
  EXPECT_GE(1.0 - c(0) - c(1), -1e-9);
  EXPECT_GE(c(0), -1e-9);
  EXPECT_GE(c(1), -1e-9);
  EXPECT_NEAR(lambda[1], c(0), 1e-12);
  EXPECT_NEAR(lambda[2], c(1), 1e-12);
  EXPECT_NEAR(lambda[0] + lambda[1] + lambda[2], 1.0, 1e-12);
}

Real triangle_area(const Triangle3& x) {
  return 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
}

Vec3 centroid(const Triangle3& x) {
  return (x[0] + x[1] + x[2]) / 3.0;
}

// The sums of the mortar integrals over all overlaps of a slave triangle, with the P1
// interpolants of the affine function f(X) = e . X: the area, the integral of the master's
// interpolant (at the master points) and that of the slave's. Checks on the way that each
// overlap's slave and master integrals add up to its area.
struct MortarSums {
  Real area = 0.0, master_f = 0.0, slave_f = 0.0;
  std::array<Real, 3> slave_integrals = {0.0, 0.0, 0.0};
  size_t n_overlaps = 0;
};

MortarSums mortar_sums(const Triangle3& slave, const Vec3& n, const SurfaceLocator& master,
                       Real max_distance, const Vec3& e) {
  MortarSums sums;
  const std::vector<MortarOverlap> overlaps = mortar_overlaps(slave, n, master, max_distance);
  sums.n_overlaps = overlaps.size();
  for (const MortarOverlap& o : overlaps) {
    EXPECT_GT(o.area, 0.0);
    EXPECT_NEAR(o.slave_integrals[0] + o.slave_integrals[1] + o.slave_integrals[2], o.area,
                kExact * o.area);
    EXPECT_NEAR(o.master_integrals[0] + o.master_integrals[1] + o.master_integrals[2], o.area,
                kExact * o.area);
    const Triangle3& m = master.triangle(o.master_face);
    sums.area += o.area;
    for (size_t i = 0; i < 3; ++i) {
      sums.master_f += o.master_integrals[i] * e.dot(m[i]);
      sums.slave_f += o.slave_integrals[i] * e.dot(slave[i]);
      sums.slave_integrals[i] += o.slave_integrals[i];
    }
  }
  return sums;
}

// Expects the mortar sums of a slave covered once by the master, which lies at the distance
// `gap` along n from it: area = the slave's area, each slave shape function integrates to a
// third of it, and the interpolants of f integrate to the exact integrals of f over the slave
// (the master's at the points shifted by gap * n).
void expect_covered(const MortarSums& sums, const Triangle3& slave, const Vec3& n, Real gap,
                    const Vec3& e) {
  const Real area = triangle_area(slave);
  EXPECT_NEAR(sums.area, area, kExact * area);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(sums.slave_integrals[i], area / 3.0, kExact * area);
  const Real scale = area * e.norm();
  EXPECT_NEAR(sums.slave_f, area * e.dot(centroid(slave)), kExact * scale);
  EXPECT_NEAR(sums.master_f, area * e.dot(centroid(slave) + gap * n), kExact * scale);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Clipping

TEST(MortarClip, OffsetSquaresOverlapInAQuarter) {
  const std::vector<Vec2> overlap = clip_convex(square(0.0, 0.0, 1.0), square(0.5, 0.5, 1.0));
  EXPECT_NEAR(shoelace(overlap), 0.25, 1e-15);  // counter-clockwise: positive
  EXPECT_TRUE(same_vertices(overlap, square(0.5, 0.5, 0.5)));
  EXPECT_NEAR(polygon_area(overlap), 0.25, 1e-15);
}

TEST(MortarClip, EitherOrientationGivesTheSameCounterClockwiseOverlap) {
  std::vector<Vec2> a = square(0.0, 0.0, 1.0), b = square(0.5, 0.5, 1.0);
  std::reverse(a.begin(), a.end());
  const std::vector<Vec2> ab = clip_convex(a, b);
  std::reverse(b.begin(), b.end());
  const std::vector<Vec2> ba = clip_convex(b, a);
  EXPECT_NEAR(shoelace(ab), 0.25, 1e-15);
  EXPECT_NEAR(shoelace(ba), 0.25, 1e-15);
  EXPECT_TRUE(same_vertices(ab, square(0.5, 0.5, 0.5)));
  EXPECT_TRUE(same_vertices(ba, square(0.5, 0.5, 0.5)));
}

TEST(MortarClip, ATriangleInsideAnotherIsItself) {
  const std::vector<Vec2> outer = {Vec2(0.0, 0.0), Vec2(4.0, 0.0), Vec2(0.0, 4.0)};
  // Clockwise, strictly inside.
  const std::vector<Vec2> inner = {Vec2(0.5, 0.5), Vec2(0.7, 2.1), Vec2(1.9, 0.6)};
  for (const std::vector<Vec2>& overlap : {clip_convex(inner, outer), clip_convex(outer, inner)}) {
    EXPECT_TRUE(same_vertices(overlap, inner));
    EXPECT_NEAR(shoelace(overlap), -shoelace(inner), 1e-14);
  }
}

TEST(MortarClip, DisjointOrEdgeSharingPolygonsDoNotOverlap) {
  EXPECT_TRUE(clip_convex(square(0.0, 0.0, 1.0), square(2.0, 0.0, 1.0)).empty());
  // Two triangles of a square, sharing its diagonal only.
  const std::vector<Vec2> lower = {Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.0, 1.0)};
  const std::vector<Vec2> upper = {Vec2(1.0, 0.0), Vec2(1.0, 1.0), Vec2(0.0, 1.0)};
  EXPECT_TRUE(clip_convex(lower, upper).empty());
  EXPECT_TRUE(clip_convex(upper, lower).empty());
  // Squares sharing a corner only; degenerate input.
  EXPECT_TRUE(clip_convex(square(0.0, 0.0, 1.0), square(1.0, 1.0, 1.0)).empty());
  EXPECT_TRUE(clip_convex({Vec2(0, 0), Vec2(1, 0)}, square(0.0, 0.0, 1.0)).empty());
  EXPECT_TRUE(clip_convex({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}, square(0.0, 0.0, 3.0)).empty());
}

TEST(MortarClip, FarFromTheOriginAreasStayAccurate) {
  // A hexagon from a triangle and its point reflection about their common centroid.
  const Vec2 far(1e6, -3e6);
  const Real h = 1e-3;
  const std::vector<Vec2> up = {far + Vec2(0, 2 * h), far + Vec2(-std::sqrt(3.0) * h, -h),
                                far + Vec2(std::sqrt(3.0) * h, -h)};
  const std::vector<Vec2> down = {far + Vec2(0, -2 * h), far + Vec2(std::sqrt(3.0) * h, h),
                                  far + Vec2(-std::sqrt(3.0) * h, h)};
  // The hexagram's core: a regular hexagon of circumradius 2h / sqrt(3) (area 2 sqrt(3) h^2).
  const std::vector<Vec2> overlap = clip_convex(up, down);
  EXPECT_EQ(overlap.size(), 6u);
  EXPECT_NEAR(polygon_area(overlap), 2.0 * std::sqrt(3.0) * h * h, 1e-6 * h * h);
}

// ---------------------------------------------------------------------------------------------
// The locator

TEST(MortarLocator, RayFromAboveHitsTheRightFace) {
  const Index k = 5;
  const Surface s = flat_square(k);
  mesh::TetMesh m;  // only the fields the locator reads
  m.nodes = s.nodes;
  m.faces = s.triangles;
  const SurfaceLocator locator(m, s.all());
  for (const Vec2& xy : {Vec2(0.31, 0.55), Vec2(0.05, 0.93), Vec2(0.77, 0.12), Vec2(0.97, 0.99)}) {
    const Vec3 point(xy.x(), xy.y(), 0.0);
    const std::optional<RayHit> hit = locator.ray_hit(point + Vec3(0, 0, 0.5), Vec3(0, 0, -1), 1.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->face, flat_square_face(k, xy.x(), xy.y()));
    EXPECT_NEAR(hit->distance, 0.5, 1e-15);
    for (Real l : hit->barycentric)
      EXPECT_GT(l, 0.0);
    expect_on_triangle(vertices(s, hit->face), hit->barycentric, point);
  }
}

TEST(MortarLocator, RaysThatMissFindNothing) {
  const Surface s = flat_square(5);
  const SurfaceLocator locator(s.nodes, s.triangles, s.all());
  const Vec3 down(0, 0, -1);
  EXPECT_FALSE(locator.ray_hit(Vec3(1.5, 0.5, 0.5), down, 1.0));   // beside the square
  EXPECT_FALSE(locator.ray_hit(Vec3(0.5, 0.5, 0.5), down, 0.4));   // too far
  EXPECT_FALSE(locator.ray_hit(Vec3(0.5, 0.5, -0.5), down, 0.4));  // too far behind
  EXPECT_FALSE(locator.ray_hit(Vec3(1.0 + 1e-3, 0.5, 0.5), down, 1.0));
  EXPECT_FALSE(locator.ray_hit(Vec3(-0.5, 0.5, 0.1), Vec3(1, 0, 0), 10.0));  // parallel
  const std::vector<Index> none;
  EXPECT_FALSE(SurfaceLocator(s.nodes, s.triangles, none).ray_hit(Vec3(0.5, 0.5, 0.5), down, 1));
}

TEST(MortarLocator, TheNearestHitWinsEvenBehindTheOrigin) {
  // Two copies of the square, at z = 0 and z = 0.2; the ray starts at z = 0.15 going down.
  Surface s = flat_square(4);
  const Index n_nodes = s.nodes.cols(), n_faces = s.triangles.cols();
  s.nodes.conservativeResize(3, 2 * n_nodes);
  s.nodes.rightCols(n_nodes) = s.nodes.leftCols(n_nodes).colwise() + Vec3(0, 0, 0.2);
  s.triangles.conservativeResize(3, 2 * n_faces);
  s.triangles.rightCols(n_faces) = s.triangles.leftCols(n_faces).array() + n_nodes;
  const SurfaceLocator locator(s.nodes, s.triangles, s.all());
  const Vec3 origin(0.4, 0.7, 0.15);
  const std::optional<RayHit> hit = locator.ray_hit(origin, Vec3(0, 0, -1), 1.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->face, n_faces + flat_square_face(4, 0.4, 0.7));
  EXPECT_NEAR(hit->distance, -0.05, 1e-15);
  // Behind only: the lower copy is out of reach.
  const std::optional<RayHit> short_hit = locator.ray_hit(origin, Vec3(0, 0, -1), 0.1);
  ASSERT_TRUE(short_hit.has_value());
  EXPECT_EQ(short_hit->face, hit->face);
  // A locator of the lower copy only finds that one.
  const std::optional<RayHit> lower = SurfaceLocator(s.nodes, s.triangles, flat_square(4).all())
                                          .ray_hit(origin, Vec3(0, 0, -1), 1.0);
  ASSERT_TRUE(lower.has_value());
  EXPECT_EQ(lower->face, flat_square_face(4, 0.4, 0.7));
  EXPECT_NEAR(lower->distance, 0.15, 1e-15);
}

TEST(MortarLocator, RaysThroughEdgesAndVerticesHitANeighbour) {
  const Index k = 5;
  const Surface s = flat_square(k);
  const SurfaceLocator locator(s.nodes, s.triangles, s.all());
  // On a grid line, on a diagonal, at an interior vertex, on the boundary, at a corner.
  for (const Vec2& xy : {Vec2(0.4, 0.5), Vec2(0.5, 0.1), Vec2(0.3, 0.3), Vec2(0.4, 0.4),
                         Vec2(1.0, 0.5), Vec2(0.0, 0.0), Vec2(1.0, 1.0)}) {
    const Vec3 point(xy.x(), xy.y(), 0.0);
    const std::optional<RayHit> hit = locator.ray_hit(point + Vec3(0, 0, 0.25), Vec3(0, 0, -1), 1);
    ASSERT_TRUE(hit.has_value()) << xy.transpose();
    expect_on_triangle(vertices(s, hit->face), hit->barycentric, point);
    // One of the faces that hold the point: a face of a grid square next to it.
    const Vec3 c = centroid(vertices(s, hit->face));
    EXPECT_LE((c.head<2>() - xy).cwiseAbs().maxCoeff(), 1.0 / static_cast<Real>(k));
  }
}

TEST(MortarLocator, ANearMissThroughACrackStillHits) {
  const Index k = 5;
  const Surface s = flat_square(k);
  const SurfaceLocator locator(s.nodes, s.triangles, s.all());
  const std::optional<RayHit> hit =
      locator.ray_hit(Vec3(1.0 + 1e-9, 0.5, 0.5), Vec3(0, 0, -1), 1.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->face, flat_square_face(k, 1.0 - 1e-9, 0.5));
  expect_on_triangle(vertices(s, hit->face), hit->barycentric, Vec3(1.0, 0.5, 0.0));
  for (Real l : hit->barycentric) {
    EXPECT_GE(l, 0.0);
    EXPECT_LE(l, 1.0);
  }
}

TEST(MortarLocator, RaysAlongTheRadiusHitTheSphereCapOnAFace) {
  const Surface cap = sphere_cap(6, 1.0);
  const SurfaceLocator locator(cap.nodes, cap.triangles, cap.all());
  for (Index i = 0; i < 50; ++i) {
    const Vec3 radial = Vec3(1.4 * halton(i, 2) - 0.7, 1.4 * halton(i, 3) - 0.7, 1.0).normalized();
    const Vec3 origin = 2.0 * radial;
    const std::optional<RayHit> hit = locator.ray_hit(origin, -radial, 2.0);
    ASSERT_TRUE(hit.has_value()) << i;
    const Vec3 p = origin - hit->distance * radial;
    expect_on_triangle(vertices(cap, hit->face), hit->barycentric, p);
    // On a chord of the sphere: inside it, not deeper than the sag of a coarse face.
    EXPECT_LE(p.norm(), 1.0 + 1e-12);
    EXPECT_GE(p.norm(), 0.97);
    EXPECT_NEAR(hit->distance, 2.0 - p.norm(), 1e-12);
  }
}

TEST(MortarLocator, FacesNearABoxAreThoseOfBruteForce) {
  const Surface cap = sphere_cap(9, 2.0);
  const SurfaceLocator locator(cap.nodes, cap.triangles, cap.all());
  for (Index i = 0; i < 40; ++i) {
    const Vec3 center(3.0 * halton(i, 2) - 1.5, 3.0 * halton(i, 3) - 1.5, 1.0 + halton(i, 5));
    const Vec3 half = Vec3(halton(i, 7), halton(i, 11), halton(i, 13)) * 0.4;
    const Vec3 lo = center - half, hi = center + half;
    const std::vector<Index> near = locator.faces_near(lo, hi);
    EXPECT_TRUE(std::is_sorted(near.begin(), near.end()));
    EXPECT_EQ(std::adjacent_find(near.begin(), near.end()), near.end());
    std::vector<Index> brute;
    for (Index f = 0; f < cap.triangles.cols(); ++f) {
      const Triangle3 x = vertices(cap, f);
      const Vec3 flo = x[0].cwiseMin(x[1]).cwiseMin(x[2]), fhi = x[0].cwiseMax(x[1]).cwiseMax(x[2]);
      if ((flo.array() <= hi.array()).all() && (fhi.array() >= lo.array()).all())
        brute.push_back(f);
    }
    EXPECT_EQ(near, brute) << i;
  }
}

TEST(MortarLocator, FiftyThousandFacesAreLocated) {
  const Index k = 158;  // 49928 triangles
  const Surface s = flat_square(k);
  const SurfaceLocator locator(s.nodes, s.triangles, s.all());
  for (Index i = 0; i < 2000; ++i) {
    const Vec3 point(halton(i, 2), halton(i, 3), 0.0);
    const std::optional<RayHit> hit =
        locator.ray_hit(point + Vec3(0, 0, 0.01), Vec3(0, 0, -1), 0.1);
    ASSERT_TRUE(hit.has_value()) << i;
    // The face holds the point (some points lie on grid lines: either neighbour).
    expect_on_triangle(vertices(s, hit->face), hit->barycentric, point);
  }
  // A box about one face finds its neighbours only.
  const std::vector<Index> near = locator.faces_near(Vec3(0.5, 0.5, -1), Vec3(0.501, 0.501, 1));
  EXPECT_GE(near.size(), 1u);
  EXPECT_LE(near.size(), 12u);
}

TEST(MortarLocator, BadInputIsRefused) {
  const Surface s = flat_square(2);
  EXPECT_THROW(SurfaceLocator(s.nodes, s.triangles, {0, 8}), Error);  // out of range
  EXPECT_THROW(SurfaceLocator(s.nodes, s.triangles, {1, 1}), Error);  // twice
  const SurfaceLocator locator(s.nodes, s.triangles, {0, 3});
  EXPECT_THROW(locator.triangle(2), Error);
  EXPECT_THROW(locator.ray_hit(Vec3(0.5, 0.5, 1), Vec3(0, 0, -2), 1.0), Error);
  EXPECT_THROW(mortar_overlaps(vertices(s, 0), Vec3(0, 0, 2), locator, 1.0), Error);
}

// ---------------------------------------------------------------------------------------------
// Mortar overlaps

TEST(MortarOverlaps, AFlatNonMatchingMasterCoversTheSlave) {
  const Surface master = flat_square(7);
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  const Vec3 n(0, 0, -1);  // the slave above, facing down (clockwise seen from above)
  const Triangle3 slave = {Vec3(0.13, 0.21, 1e-3), Vec3(0.41, 0.92, 1e-3), Vec3(0.87, 0.34, 1e-3)};
  for (const Vec3& e : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, -0.7, 0.2)}) {
    const MortarSums sums = mortar_sums(slave, n, locator, 1e-2, e);
    expect_covered(sums, slave, n, 1e-3, e);
    EXPECT_GT(sums.n_overlaps, 10u);
  }
  // Slightly below the master (an initial overlap) it is covered too.
  Triangle3 below = slave;
  for (Vec3& x : below)
    x.z() = -2e-3;
  expect_covered(mortar_sums(below, n, locator, 1e-2, Vec3(1, 2, 3)), below, n, -2e-3,
                 Vec3(1, 2, 3));
  // Beyond max_distance, in either direction, nothing.
  for (Real z : {0.05, -0.05}) {
    Triangle3 far = slave;
    for (Vec3& x : far)
      x.z() = z;
    EXPECT_TRUE(mortar_overlaps(far, n, locator, 1e-2).empty());
  }
}

TEST(MortarOverlaps, MasterFacesBeyondMaxDistanceAreSkipped) {
  // A master inclined under a horizontal slave: along n = -z the distance from the slave to it
  // runs from 0.051 to -0.049 across the slave; max_distance 0.02 keeps the middle only.
  const Surface master = grid_surface(6, [](Real u, Real v) { return Vec3(u, v, 0.5 * u); });
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  const Vec3 n(0, 0, -1);
  const Triangle3 slave = {Vec3(0.4, 0.3, 0.251), Vec3(0.5, 0.7, 0.251), Vec3(0.6, 0.35, 0.251)};
  const Real max_distance = 0.02;
  const std::vector<MortarOverlap> overlaps = mortar_overlaps(slave, n, locator, max_distance);
  Real area = 0.0;
  for (const MortarOverlap& o : overlaps) {
    // The mean slave and master points of the overlap are the points at its centroid.
    const Triangle3& m = locator.triangle(o.master_face);
    Vec3 slave_mean = Vec3::Zero(), master_mean = Vec3::Zero();
    for (size_t i = 0; i < 3; ++i) {
      slave_mean += o.slave_integrals[i] * slave[i] / o.area;
      master_mean += o.master_integrals[i] * m[i] / o.area;
    }
    EXPECT_NEAR((master_mean - slave_mean).cross(n).norm(), 0.0, 1e-14);  // on a line along n
    EXPECT_LE(std::abs((master_mean - slave_mean).dot(n)), max_distance);
    area += o.area;
  }
  EXPECT_FALSE(overlaps.empty());
  EXPECT_LT(area, 0.9 * triangle_area(slave));
  // Within reach, the slave is covered (the master's interpolant of x at the master points).
  expect_covered(mortar_sums(slave, n, locator, 0.06, Vec3(1, 0, 0)), slave, n, 0.0, Vec3(1, 0, 0));
}

TEST(MortarOverlaps, ATiltedSlaveIsMeasuredOnItself) {
  const Surface master = flat_square(6);
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  const Vec3 n(0, 0, -1);
  // Not parallel to the master: the slave's area exceeds its projection's.
  const Triangle3 slave = {Vec3(0.13, 0.21, 1e-3), Vec3(0.41, 0.92, 9e-3), Vec3(0.87, 0.34, 4e-3)};
  const Real area = triangle_area(slave);
  const MortarSums sums = mortar_sums(slave, n, locator, 2e-2, Vec3(1, 0, 0));
  EXPECT_NEAR(sums.area, area, kExact * area);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(sums.slave_integrals[i], area / 3.0, kExact * area);
  // f = x does not change along n: the master's interpolant integrates to the slave's integral.
  EXPECT_NEAR(sums.master_f, area * centroid(slave).x(), kExact * area);
  EXPECT_NEAR(sums.slave_f, area * centroid(slave).x(), kExact * area);
}

TEST(MortarOverlaps, ASlavePartlyBesideTheMasterKeepsItsCoveredPart) {
  const Surface master = flat_square(5);
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  // Its part over [0, 1]^2 is the square [0.5, 1]^2 (its hypotenuse passes through (1, 1)).
  const Triangle3 slave = {Vec3(0.5, 0.5, 1e-3), Vec3(0.5, 1.5, 1e-3), Vec3(1.5, 0.5, 1e-3)};
  const MortarSums sums = mortar_sums(slave, Vec3(0, 0, -1), locator, 1e-2, Vec3(1, 0, 0));
  EXPECT_NEAR(sums.area, 0.25, kExact);
  EXPECT_NEAR(sums.master_f, 0.25 * 0.75, kExact);  // integral of x over [0.5, 1]^2
  EXPECT_NEAR(sums.slave_f, 0.25 * 0.75, kExact);
}

TEST(MortarOverlaps, MasterFacesAlongTheNormalAreSkipped) {
  // The flat master plus a vertical triangle under the slave: seen edge-on, it adds nothing.
  Surface master = flat_square(4);
  const Index n_nodes = master.nodes.cols(), n_faces = master.triangles.cols();
  master.nodes.conservativeResize(3, n_nodes + 3);
  master.nodes.rightCols(3) << 0.5, 0.5, 0.5, 0.3, 0.6, 0.45, -5e-3, -5e-3, 5e-3;
  master.triangles.conservativeResize(3, n_faces + 1);
  master.triangles.col(n_faces) << n_nodes, n_nodes + 1, n_nodes + 2;
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  const Triangle3 slave = {Vec3(0.2, 0.2, 1e-3), Vec3(0.45, 0.8, 1e-3), Vec3(0.8, 0.3, 1e-3)};
  const Vec3 n(0, 0, -1);
  for (const MortarOverlap& o : mortar_overlaps(slave, n, locator, 1e-2))
    EXPECT_NE(o.master_face, n_faces);
  expect_covered(mortar_sums(slave, n, locator, 1e-2, Vec3(1, 1, 0)), slave, n, 1e-3,
                 Vec3(1, 1, 0));
  // A slave seen edge-on has no overlaps.
  const Triangle3 edge_on = {Vec3(0.2, 0.5, 0.0), Vec3(0.8, 0.5, 0.0), Vec3(0.5, 0.5, 0.01)};
  EXPECT_TRUE(mortar_overlaps(edge_on, n, locator, 1e-2).empty());
}

TEST(MortarOverlaps, ARotatedConfigurationGivesTheSameIntegrals) {
  const Mat3 rotation = Eigen::AngleAxisd(0.9, Vec3(1, -2, 3).normalized()).toRotationMatrix();
  Surface master = flat_square(7);
  master.nodes = (rotation * master.nodes).eval();
  master.nodes.colwise() += Vec3(3.0, -2.0, 5.0);
  const SurfaceLocator locator(master.nodes, master.triangles, master.all());
  const Vec3 n = rotation * Vec3(0, 0, -1);
  Triangle3 slave = {Vec3(0.13, 0.21, 1e-3), Vec3(0.41, 0.92, 1e-3), Vec3(0.87, 0.34, 1e-3)};
  for (Vec3& x : slave)
    x = rotation * x + Vec3(3.0, -2.0, 5.0);
  for (const Vec3& e : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0.3, -0.7, 0.2)})
    expect_covered(mortar_sums(slave, n, locator, 1e-2, e), slave, n, 1e-3, e);
  // The areas are those of the unrotated configuration, overlap by overlap.
  const Surface flat = flat_square(7);
  const SurfaceLocator flat_locator(flat.nodes, flat.triangles, flat.all());
  const Triangle3 flat_slave = {Vec3(0.13, 0.21, 1e-3), Vec3(0.41, 0.92, 1e-3),
                                Vec3(0.87, 0.34, 1e-3)};
  const std::vector<MortarOverlap> a = mortar_overlaps(slave, n, locator, 1e-2);
  const std::vector<MortarOverlap> b =
      mortar_overlaps(flat_slave, Vec3(0, 0, -1), flat_locator, 1e-2);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].master_face, b[i].master_face);
    EXPECT_NEAR(a[i].area, b[i].area, 1e-13);
    for (size_t j = 0; j < 3; ++j) {
      EXPECT_NEAR(a[i].master_integrals[j], b[i].master_integrals[j], 1e-13);
      EXPECT_NEAR(a[i].slave_integrals[j], b[i].slave_integrals[j], 1e-13);
    }
  }
}

TEST(MortarOverlaps, ACurvedMasterCoversTheSlaveOnce) {
  // The sphere cap sags up to ~0.02 below the sphere between its nodes; the slave floats above.
  const Surface cap = sphere_cap(8, 1.0);
  const SurfaceLocator locator(cap.nodes, cap.triangles, cap.all());
  const Vec3 n(0, 0, -1);
  const Triangle3 slave = {Vec3(-0.21, -0.17, 1.01), Vec3(0.05, 0.26, 1.01),
                           Vec3(0.24, -0.12, 1.01)};
  // x and y do not change along n: the master's interpolant of them is exact on its faces.
  for (const Vec3& e : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.6, -0.8, 0.0)}) {
    const MortarSums sums = mortar_sums(slave, n, locator, 0.2, e);
    expect_covered(sums, slave, n, 0.0, e);
    EXPECT_GT(sums.n_overlaps, 3u);
  }
}
