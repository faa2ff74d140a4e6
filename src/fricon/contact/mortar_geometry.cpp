#include "fricon/contact/mortar_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

// A clipped polygon whose area is at most this fraction of the smaller input's is degenerate: a
// point, a shared edge, or a sliver made of rounding errors (they are ~1e-16 relative).
constexpr Real kDegenerateAreaTolerance = 1e-12;
// Consecutive vertices of a clipped polygon closer than this fraction of the clip window's
// diameter are one vertex (Sutherland-Hodgman repeats a vertex that lies on a clipping edge).
constexpr Real kMergeTolerance = 1e-14;
// A barycentric coordinate >= -kInsideTolerance is inside: a line through an edge shared by two
// triangles is in at least one of them despite rounding.
constexpr Real kInsideTolerance = 1e-9;
// A line that misses every triangle but passes this close to one, relative to its diameter,
// still hits it (cracks of a surface whose shared vertices differ by rounding).
constexpr Real kNearMissTolerance = 1e-6;
// A line with |direction . unit normal| below this never hits the triangle: the intersection
// would be ill-conditioned (and beyond any reasonable max_distance).
constexpr Real kRayParallelTolerance = 1e-12;
// A triangle with |n . unit normal| below this is seen edge-on along n: its projection is a
// sliver and the slave measure 1 / |n . normal| blows up, so mortar_overlaps skips it.
constexpr Real kProjectionParallelTolerance = 1e-3;
// Directions (the ray's, the contact normal) are unit vectors to this tolerance.
constexpr Real kUnitTolerance = 1e-9;
// The bounding box of a triangle is padded by this fraction of its diameter, so that boxes that
// touch are found despite rounding, and a ray's near miss (kNearMissTolerance) is in the box.
constexpr Real kBoxPadding = kNearMissTolerance;
// The grid has at most this many cells per triangle (plus one): the cell size grows beyond the
// mean diameter when a surface's bounding box is mostly empty (a sphere, a few far-apart parts).
constexpr Real kMaxCellsPerTriangle = 8.0;

Real cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// ---------------------------------------------------------------------------------------------
// Clipping

// The polygon running counter-clockwise (reversed if its signed area is negative).
std::vector<Vec2> counter_clockwise(std::vector<Vec2> polygon) {
  if (polygon_area(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

// The part of `polygon` on the left of the directed line a -> b (Sutherland-Hodgman step).
std::vector<Vec2> clip_by_half_plane(const std::vector<Vec2>& polygon, const Vec2& a,
                                     const Vec2& b) {
  std::vector<Vec2> out;
  const Vec2 edge = b - a;
  auto side = [&](const Vec2& p) { return cross2(edge, p - a); };  // > 0: left, inside
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& prev = polygon[(i + polygon.size() - 1) % polygon.size()];
    const Vec2& cur = polygon[i];
    const Real s_prev = side(prev), s_cur = side(cur);
    const bool prev_inside = s_prev >= 0.0, cur_inside = s_cur >= 0.0;
    if (cur_inside != prev_inside) out.push_back(prev + (s_prev / (s_prev - s_cur)) * (cur - prev));
    if (cur_inside) out.push_back(cur);
  }
  return out;
}

// The polygon without consecutive vertices closer than `tolerance` (the last and first too).
std::vector<Vec2> without_repeated_vertices(const std::vector<Vec2>& polygon, Real tolerance) {
  std::vector<Vec2> out;
  for (const Vec2& p : polygon)
    if (out.empty() || (p - out.back()).norm() > tolerance) out.push_back(p);
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tolerance)
    out.pop_back();
  return out;
}

// Diameter [m] of the bounding box of the polygon.
Real box_diameter(const std::vector<Vec2>& polygon) {
  Vec2 lo = polygon.front(), hi = polygon.front();
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// ---------------------------------------------------------------------------------------------
// Triangles

Real longest_edge(const Triangle3& x) {
  return std::max({(x[1] - x[0]).norm(), (x[2] - x[1]).norm(), (x[0] - x[2]).norm()});
}

// Barycentric coordinates of the closest point of triangle (a, b, c) to p (Ericson, Real-Time
// Collision Detection, §5.1.5: the Voronoi regions of the vertices, the edges and the face).
std::array<Real, 3> closest_point_barycentric(const Vec3& a, const Vec3& b, const Vec3& c,
                                              const Vec3& p) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const Real v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const Real w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const Real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const Real denom = 1.0 / (va + vb + vc);
  const Real v = vb * denom, w = vc * denom;
  return {1.0 - v - w, v, w};
}

Vec3 point_at(const Triangle3& x, const std::array<Real, 3>& lambda) {
  return lambda[0] * x[0] + lambda[1] * x[1] + lambda[2] * x[2];
}

// Where the line origin + t * direction crosses the plane of a triangle: t and the barycentric
// coordinates of the crossing (exact for a point of the plane), or nothing when the line is
// (nearly) parallel to the plane or the triangle is degenerate.
struct PlaneCrossing {
  Real t;
  std::array<Real, 3> lambda;
};

std::optional<PlaneCrossing> plane_crossing(const Triangle3& x, const Vec3& origin,
                                            const Vec3& direction) {
  const Vec3 m = (x[1] - x[0]).cross(x[2] - x[0]);  // normal, |m| = twice the area
  const Real m2 = m.squaredNorm();
  const Real along = direction.dot(m);
  if (!(m2 > 0.0) || std::abs(along) < kRayParallelTolerance * std::sqrt(m2)) return std::nullopt;
  const Real t = (x[0] - origin).dot(m) / along;
  const Vec3 p = origin + t * direction;
  // lambda_i = signed area of the sub-triangle opposite vertex i / area.
  const Real l0 = m.dot((x[1] - p).cross(x[2] - p)) / m2;
  const Real l1 = m.dot((x[2] - p).cross(x[0] - p)) / m2;
  return PlaneCrossing{t, {l0, l1, 1.0 - l0 - l1}};
}

// ---------------------------------------------------------------------------------------------
// Projection on the plane orthogonal to n

// An orthonormal basis (t1, t2) of the plane orthogonal to the unit vector n, and the point the
// projected coordinates are measured from (near the slave: it keeps them small and accurate).
struct Projection {
  Vec3 origin, t1, t2;
  Vec2 operator()(const Vec3& x) const { return {(x - origin).dot(t1), (x - origin).dot(t2)}; }
};

Projection projection_along(const Vec3& n, const Vec3& origin) {
  // t1: the coordinate axis least aligned with n, made orthogonal to n.
  Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Vec3 t1 = (Vec3::Unit(axis) - n(axis) * n).normalized();
  return {origin, t1, n.cross(t1)};
}

using Triangle2 = std::array<Vec2, 3>;

// Barycentric coordinates of p in the (non-degenerate) plane triangle x.
std::array<Real, 3> barycentric_2d(const Triangle2& x, const Vec2& p) {
  const Real twice_area = cross2(x[1] - x[0], x[2] - x[0]);
  const Real l0 = cross2(x[1] - p, x[2] - p) / twice_area;
  const Real l1 = cross2(x[2] - p, x[0] - p) / twice_area;
  return {l0, l1, 1.0 - l0 - l1};
}

// Unit normal of a triangle (zero for a degenerate one).
Vec3 unit_normal(const Triangle3& x) {
  const Vec3 m = (x[1] - x[0]).cross(x[2] - x[0]);
  const Real norm = m.norm();
  return norm > 0.0 ? Vec3(m / norm) : Vec3::Zero();
}

// The fan triangulation of a convex polygon from its first vertex: area [m^2] (in the plane of
// the projection) and centroid of each sub-triangle.
struct FanPiece {
  Real area;
  Vec2 centroid;
  std::array<Vec2, 3> corners;
};

// The weights of the corners at a point of the 3-point triangle rule of degree 2.
constexpr Real kNearWeight = 2.0 / 3.0, kFarWeight = 1.0 / 6.0;

std::vector<FanPiece> fan(const std::vector<Vec2>& polygon) {
  std::vector<FanPiece> pieces;
  for (size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Vec2& a = polygon[0];
    const Vec2& b = polygon[k];
    const Vec2& c = polygon[k + 1];
    pieces.push_back({0.5 * cross2(b - a, c - a), (a + b + c) / 3.0, {a, b, c}});
  }
  return pieces;
}

Vec2 fan_centroid(const std::vector<FanPiece>& pieces) {
  Real area = 0.0;
  Vec2 moment = Vec2::Zero();
  for (const FanPiece& piece : pieces) {
    area += piece.area;
    moment += piece.area * piece.centroid;
  }
  return moment / area;
}

void check_unit(const Vec3& v, const char* what) {
  FRICON_CHECK(v.allFinite() && std::abs(v.norm() - 1.0) <= kUnitTolerance,
               what << " must be a unit vector, has norm " << v.norm());
}

}  // namespace

// -----------------------------------------------------------------------------------------------
// Clipping

Real polygon_area(const std::vector<Vec2>& polygon) {
  if (polygon.size() < 3) return 0.0;
  // Measured from the first vertex: no loss of accuracy far from the origin.
  Real twice_area = 0.0;
  for (size_t k = 1; k + 1 < polygon.size(); ++k)
    twice_area += cross2(polygon[k] - polygon[0], polygon[k + 1] - polygon[0]);
  return 0.5 * twice_area;
}

std::vector<Vec2> clip_convex(const std::vector<Vec2>& subject, const std::vector<Vec2>& clip) {
  // 1. Degenerate inputs have no overlap.
  const Real subject_area = std::abs(polygon_area(subject));
  const Real clip_area = std::abs(polygon_area(clip));
  if (!(subject_area > 0.0) || !(clip_area > 0.0)) return {};
  // 2. Both counter-clockwise: the inside of each edge of the window is on its left.
  std::vector<Vec2> result = counter_clockwise(subject);
  const std::vector<Vec2> window = counter_clockwise(clip);
  // 3. Sutherland-Hodgman: the subject cut by each edge of the window in turn.
  for (size_t i = 0; i < window.size() && result.size() >= 3; ++i)
    result = clip_by_half_plane(result, window[i], window[(i + 1) % window.size()]);
  // 4. Clean up, and drop degenerate intersections.
  result = without_repeated_vertices(result, kMergeTolerance * box_diameter(window));
  if (result.size() < 3 ||
      polygon_area(result) <= kDegenerateAreaTolerance * std::min(subject_area, clip_area))
    return {};
  return result;
}

// -----------------------------------------------------------------------------------------------
// SurfaceLocator

SurfaceLocator::SurfaceLocator(const mesh::TetMesh& mesh, std::vector<Index> faces)
    : SurfaceLocator(mesh.nodes, mesh.faces, std::move(faces)) {}

SurfaceLocator::SurfaceLocator(const Eigen::Matrix<Real, 3, Eigen::Dynamic>& nodes,
                               const Eigen::Matrix<Index, 3, Eigen::Dynamic>& triangles,
                               std::vector<Index> faces)
    : faces_(std::move(faces)) {
  // 1. The triangles: coordinates, padded boxes, diameters, and the slot of each.
  slot_of_face_.assign(static_cast<size_t>(triangles.cols()), -1);
  const Index n_slots = static_cast<Index>(faces_.size());
  Real diameter_sum = 0.0;
  for (Index s = 0; s < n_slots; ++s) {
    const Index f = faces_[static_cast<size_t>(s)];
    FRICON_CHECK(f >= 0 && f < triangles.cols(),
                 "face " << f << " out of range (" << triangles.cols() << " triangles)");
    FRICON_CHECK(slot_of_face_[static_cast<size_t>(f)] < 0, "face " << f << " listed twice");
    slot_of_face_[static_cast<size_t>(f)] = s;
    Triangle3 x;
    for (int v = 0; v < 3; ++v) {
      const Index node = triangles(v, f);
      FRICON_CHECK(node >= 0 && node < nodes.cols(),
                   "face " << f << ": node " << node << " out of range");
      x[static_cast<size_t>(v)] = nodes.col(node);
      FRICON_CHECK(x[static_cast<size_t>(v)].allFinite(),
                   "face " << f << ": node " << node << " has a non-finite coordinate");
    }
    const Real diameter = longest_edge(x);
    const Vec3 pad = Vec3::Constant(kBoxPadding * diameter);
    boxes_.push_back(
        {x[0].cwiseMin(x[1]).cwiseMin(x[2]) - pad, x[0].cwiseMax(x[1]).cwiseMax(x[2]) + pad});
    triangles_.push_back(x);
    diameters_.push_back(diameter);
    diameter_sum += diameter;
  }
  if (n_slots == 0) {
    grid_box_ = {Vec3::Zero(), Vec3::Zero()};
    bucket_start_.assign(2, 0);
    return;
  }

  // 2. The grid: the union of the boxes in cubic cells of about the mean diameter, coarsened
  // while it would have more than kMaxCellsPerTriangle cells per triangle.
  grid_box_ = boxes_.front();
  for (const Box& box : boxes_) {
    grid_box_.lo = grid_box_.lo.cwiseMin(box.lo);
    grid_box_.hi = grid_box_.hi.cwiseMax(box.hi);
  }
  const Vec3 extent = grid_box_.hi - grid_box_.lo;
  cell_size_ = diameter_sum / static_cast<Real>(n_slots);
  if (!(cell_size_ > 0.0)) cell_size_ = std::max(extent.maxCoeff(), Real(1));  // all points
  const Real max_cells = kMaxCellsPerTriangle * static_cast<Real>(n_slots) + 1.0;
  for (;;) {
    Real total = 1.0;
    for (int a = 0; a < 3; ++a)
      total *= std::max(Real(1), std::ceil(extent(a) / cell_size_));
    if (total <= max_cells) break;
    cell_size_ *= std::max(std::cbrt(total / max_cells), Real(1.01));
  }
  for (int a = 0; a < 3; ++a)
    n_cells_[static_cast<size_t>(a)] =
        std::max(Index(1), static_cast<Index>(std::ceil(extent(a) / cell_size_)));

  // 3. The buckets (compressed): each slot in every cell its box meets, counted then filled.
  const Index n_total = n_cells_[0] * n_cells_[1] * n_cells_[2];
  auto for_each_cell = [&](const Box& box, auto&& visit) {
    const Index i0 = cell_coordinate(box.lo.x(), 0), i1 = cell_coordinate(box.hi.x(), 0);
    const Index j0 = cell_coordinate(box.lo.y(), 1), j1 = cell_coordinate(box.hi.y(), 1);
    const Index k0 = cell_coordinate(box.lo.z(), 2), k1 = cell_coordinate(box.hi.z(), 2);
    for (Index k = k0; k <= k1; ++k)
      for (Index j = j0; j <= j1; ++j)
        for (Index i = i0; i <= i1; ++i)
          visit(i + n_cells_[0] * (j + n_cells_[1] * k));
  };
  bucket_start_.assign(static_cast<size_t>(n_total + 1), 0);
  for (const Box& box : boxes_)
    for_each_cell(box, [&](Index c) { ++bucket_start_[static_cast<size_t>(c + 1)]; });
  for (Index c = 0; c < n_total; ++c)
    bucket_start_[static_cast<size_t>(c + 1)] += bucket_start_[static_cast<size_t>(c)];
  bucket_slots_.resize(static_cast<size_t>(bucket_start_.back()));
  std::vector<Index> fill(bucket_start_.begin(), bucket_start_.end() - 1);
  for (Index s = 0; s < n_slots; ++s)
    for_each_cell(boxes_[static_cast<size_t>(s)], [&](Index c) {
      bucket_slots_[static_cast<size_t>(fill[static_cast<size_t>(c)]++)] = s;
    });
}

Index SurfaceLocator::slot_of(Index face) const {
  if (face < 0 || face >= static_cast<Index>(slot_of_face_.size())) return -1;
  return slot_of_face_[static_cast<size_t>(face)];
}

const Triangle3& SurfaceLocator::triangle(Index face) const {
  const Index s = slot_of(face);
  FRICON_CHECK(s >= 0, "face " << face << " is not in the locator");
  return triangles_[static_cast<size_t>(s)];
}

Index SurfaceLocator::cell_coordinate(Real x, int a) const {
  const Real cell = std::floor((x - grid_box_.lo(a)) / cell_size_);
  const Index last = n_cells_[static_cast<size_t>(a)] - 1;
  if (!(cell > 0.0)) return 0;  // below the grid, or NaN
  if (cell >= static_cast<Real>(last)) return last;
  return static_cast<Index>(cell);
}

void SurfaceLocator::collect_slots(const Vec3& lo, const Vec3& hi,
                                   std::vector<Index>& slots) const {
  const Index i0 = cell_coordinate(lo.x(), 0), i1 = cell_coordinate(hi.x(), 0);
  const Index j0 = cell_coordinate(lo.y(), 1), j1 = cell_coordinate(hi.y(), 1);
  const Index k0 = cell_coordinate(lo.z(), 2), k1 = cell_coordinate(hi.z(), 2);
  for (Index k = k0; k <= k1; ++k)
    for (Index j = j0; j <= j1; ++j)
      for (Index i = i0; i <= i1; ++i) {
        const Index c = i + n_cells_[0] * (j + n_cells_[1] * k);
        slots.insert(slots.end(), bucket_slots_.begin() + bucket_start_[static_cast<size_t>(c)],
                     bucket_slots_.begin() + bucket_start_[static_cast<size_t>(c + 1)]);
      }
}

std::vector<Index> SurfaceLocator::faces_near(const Vec3& lo, const Vec3& hi) const {
  std::vector<Index> near;
  if (faces_.empty() || (lo.array() > grid_box_.hi.array()).any() ||
      (hi.array() < grid_box_.lo.array()).any())
    return near;
  // 1. The slots of the buckets of the cells the box meets, each once.
  std::vector<Index> slots;
  collect_slots(lo, hi, slots);
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  // 2. Those whose own box meets the box.
  for (Index s : slots) {
    const Box& box = boxes_[static_cast<size_t>(s)];
    if ((box.lo.array() <= hi.array()).all() && (box.hi.array() >= lo.array()).all())
      near.push_back(faces_[static_cast<size_t>(s)]);
  }
  std::sort(near.begin(), near.end());
  return near;
}

std::optional<RayHit> SurfaceLocator::ray_hit(const Vec3& origin, const Vec3& direction,
                                              Real max_distance) const {
  check_unit(direction, "the ray's direction");
  FRICON_CHECK(origin.allFinite(), "the ray's origin is not finite");
  FRICON_CHECK(max_distance >= 0.0 && std::isfinite(max_distance),
               "max_distance = " << max_distance);
  if (faces_.empty()) return std::nullopt;

  // 1. The part [t0, t1] of the segment t in [-max_distance, max_distance] inside the grid's box
  // (slab by slab).
  Real t0 = -max_distance, t1 = max_distance;
  for (int a = 0; a < 3; ++a) {
    if (direction(a) == 0.0) {
      if (origin(a) < grid_box_.lo(a) || origin(a) > grid_box_.hi(a)) return std::nullopt;
      continue;
    }
    Real ta = (grid_box_.lo(a) - origin(a)) / direction(a);
    Real tb = (grid_box_.hi(a) - origin(a)) / direction(a);
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return std::nullopt;

  // 2. The candidates: the buckets met by pieces of the segment no longer than a cell (the box of
  // each piece spans at most two cells per axis), each slot once.
  std::vector<Index> slots;
  const Index n_pieces = std::max(Index(1), static_cast<Index>(std::ceil((t1 - t0) / cell_size_)));
  for (Index k = 0; k < n_pieces; ++k) {
    const Real ta = t0 + (t1 - t0) * static_cast<Real>(k) / static_cast<Real>(n_pieces);
    const Real tb = t0 + (t1 - t0) * static_cast<Real>(k + 1) / static_cast<Real>(n_pieces);
    const Vec3 a = origin + ta * direction, b = origin + tb * direction;
    collect_slots(a.cwiseMin(b), a.cwiseMax(b), slots);
  }
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());

  // 3. The crossing with the smallest |t| inside a triangle; failing that, the nearest miss.
  std::optional<RayHit> inside, near_miss;
  Real near_miss_gap = std::numeric_limits<Real>::infinity();
  for (Index s : slots) {
    const Triangle3& x = triangles_[static_cast<size_t>(s)];
    const std::optional<PlaneCrossing> crossing = plane_crossing(x, origin, direction);
    if (!crossing || std::abs(crossing->t) > max_distance) continue;
    const Index face = faces_[static_cast<size_t>(s)];
    const std::array<Real, 3>& l = crossing->lambda;
    if (std::min({l[0], l[1], l[2]}) >= -kInsideTolerance) {
      if (!inside || std::abs(crossing->t) < std::abs(inside->distance))
        inside = RayHit{face, l, crossing->t};
      continue;
    }
    if (inside) continue;  // a near miss matters only when nothing is hit
    const Vec3 p = origin + crossing->t * direction;
    const std::array<Real, 3> closest = closest_point_barycentric(x[0], x[1], x[2], p);
    const Real gap = (point_at(x, closest) - p).norm();
    if (gap < kNearMissTolerance * diameters_[static_cast<size_t>(s)] && gap < near_miss_gap) {
      near_miss_gap = gap;
      near_miss = RayHit{face, closest, crossing->t};
    }
  }
  return inside ? inside : near_miss;
}

// -----------------------------------------------------------------------------------------------
// Mortar overlaps

std::vector<MortarOverlap> mortar_overlaps(const Triangle3& slave, const Vec3& n,
                                           const SurfaceLocator& master, Real max_distance) {
  check_unit(n, "the contact normal n");
  FRICON_CHECK(max_distance >= 0.0 && std::isfinite(max_distance),
               "max_distance = " << max_distance);
  std::vector<MortarOverlap> overlaps;

  // 1. The slave seen along n: its measure factor 1 / |n . normal| and its projection, in
  // coordinates centred on its centroid.
  const Real slave_cosine = std::abs(n.dot(unit_normal(slave)));
  if (slave_cosine < kProjectionParallelTolerance) return overlaps;
  const Real slave_measure = 1.0 / slave_cosine;  // slave area per projected area
  const Projection project = projection_along(n, (slave[0] + slave[1] + slave[2]) / 3.0);
  const Triangle2 slave_2d = {project(slave[0]), project(slave[1]), project(slave[2])};
  const std::vector<Vec2> slave_polygon(slave_2d.begin(), slave_2d.end());

  // 2. The candidates: master triangles near the box of the slave swept along n over
  // [-max_distance, max_distance] (a master point within max_distance along n of a slave point
  // lies in that prism, hence in its box: the slave's box widened by max_distance |n_a| on axis a).
  const Vec3 sweep = max_distance * n.cwiseAbs();
  const Vec3 lo = slave[0].cwiseMin(slave[1]).cwiseMin(slave[2]) - sweep;
  const Vec3 hi = slave[0].cwiseMax(slave[1]).cwiseMax(slave[2]) + sweep;
  for (Index face : master.faces_near(lo, hi)) {
    const Triangle3& x = master.triangle(face);
    // 3. The overlap of the projections (master triangles seen edge-on are skipped).
    if (std::abs(n.dot(unit_normal(x))) < kProjectionParallelTolerance) continue;
    const Triangle2 master_2d = {project(x[0]), project(x[1]), project(x[2])};
    const std::vector<Vec2> overlap =
        clip_convex(slave_polygon, std::vector<Vec2>(master_2d.begin(), master_2d.end()));
    if (overlap.empty()) continue;
    const std::vector<FanPiece> pieces = fan(overlap);

    // 4. The distance along n at the overlap's centroid, from the slave point to the master one.
    const Vec2 centroid = fan_centroid(pieces);
    const Vec3 slave_point = point_at(slave, barycentric_2d(slave_2d, centroid));
    const Vec3 master_point = point_at(x, barycentric_2d(master_2d, centroid));
    const Real distance = (master_point - slave_point).dot(n);
    if (std::abs(distance) > max_distance) continue;

    // 5. The integrals: on each sub-triangle, its slave area times the shape functions at its
    // centroid (exact: both triangles' shape functions are affine in the projected coordinates).
    MortarOverlap result;
    result.master_face = face;
    for (const FanPiece& piece : pieces) {
      const Real area = piece.area * slave_measure;
      const std::array<Real, 3> ls = barycentric_2d(slave_2d, piece.centroid);
      const std::array<Real, 3> lm = barycentric_2d(master_2d, piece.centroid);
      result.area += area;
      for (size_t i = 0; i < 3; ++i) {
        result.slave_integrals[i] += area * ls[i];
        result.master_integrals[i] += area * lm[i];
      }
      // The 3-point rule of degree 2 on the sub-triangle, at (2/3, 1/6, 1/6) and its
      // permutations, weights a third of the area.
      for (size_t i = 0; i < 3; ++i) {
        const Vec2 point = kNearWeight * piece.corners[i] +
                           kFarWeight * (piece.corners[(i + 1) % 3] + piece.corners[(i + 2) % 3]);
        result.points.push_back(
            {area / 3.0, barycentric_2d(slave_2d, point), barycentric_2d(master_2d, point)});
      }
    }
    overlaps.push_back(result);
  }
  return overlaps;
}

}  // namespace fricon::contact
