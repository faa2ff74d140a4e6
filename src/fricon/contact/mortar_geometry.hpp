#pragma once
// contact: the geometry of mortar (segment-to-segment) contact between two triangulated surfaces
// (theory.md §2.8): convex clipping in a plane, a bucket grid that finds the triangles of the
// master surface near a box or along a ray, and the exact integrals of the P1 shape functions of
// a slave triangle and of the master triangles over their overlaps, projected along the contact
// normal. Pure geometry: no dofs, no multipliers, no assembly.
//
// The master surface is read from node coordinates and triangles (the columns of TetMesh::nodes
// and TetMesh::faces, or of any other arrays with the same layout, e.g. deformed coordinates),
// and copied into the locator: it does not keep references to the arrays it was built from.

#include <array>
#include <optional>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// A slave triangle faces a master one when their outward normals make an angle above 90 degrees
/// by this cosine: n_slave . n_master < -kFacingCosine (the search of both sides, theory.md §2.8).
inline constexpr Real kFacingCosine = 1e-3;

/// A point or vector of a plane, in the coordinates of an orthonormal basis of that plane [m].
using Vec2 = Eigen::Matrix<Real, 2, 1>;

/// A triangle in space: its three vertices [m], in the order that defines its normal (the
/// right-hand rule) and its P1 shape functions (shape function i is 1 at x[i]).
using Triangle3 = std::array<Vec3, 3>;

/// Signed area [m^2] of the polygon with vertices `polygon` (the shoelace formula): positive when
/// they run counter-clockwise, 0 for fewer than three vertices.
Real polygon_area(const std::vector<Vec2>& polygon);

/// The intersection of two convex polygons [m] (Sutherland-Hodgman): `subject` clipped by the
/// half-planes of the edges of `clip`. Either may run clockwise or counter-clockwise; the result
/// runs counter-clockwise, without repeated vertices. Returns an empty polygon when the
/// intersection is degenerate: an input with fewer than three vertices or zero area, or an
/// intersection (a point, an edge shared by neighbours, a sliver) whose area is at most a relative
/// tolerance (1e-12) of the smaller input's area. The polygons must be convex; a non-convex
/// `clip` gives a wrong result, unchecked.
std::vector<Vec2> clip_convex(const std::vector<Vec2>& subject, const std::vector<Vec2>& clip);

/// A point of the master surface found by SurfaceLocator::ray_hit.
struct RayHit {
  Index face = -1;  ///< the triangle hit (an index into the triangles the locator was built from)
  /// Barycentric coordinates of the hit point in that triangle, in its vertex order; each at
  /// least -1e-9 (a hit on an edge may fall just outside), and within [0, 1] for a near miss.
  std::array<Real, 3> barycentric = {0.0, 0.0, 0.0};
  /// Signed distance t [m] along the ray to the hit point, origin + t * direction; negative when
  /// the hit lies behind the origin (e.g. a small initial overlap of two bodies).
  Real distance = 0.0;
};

/// A search structure over a fixed set of triangles, the master surface: a uniform grid of
/// buckets over their bounding boxes, with a cell size of about the mean triangle diameter, so
/// that the queries below visit only the triangles near the line or box asked about (50 000
/// triangles: built in about 50 ms, a ray query in about a microsecond). Immutable after
/// construction; its queries may run concurrently.
class SurfaceLocator {
 public:
  /// The locator of triangles `faces` (indices of columns of `triangles`, each at most once) of
  /// the surface with node coordinates `nodes` [m] (one column per node) and triangles
  /// `triangles` (three node indices per column). The coordinates of those triangles are copied.
  /// Throws Error if a face or node index is out of range, a face is listed twice, or a
  /// coordinate is not finite.
  SurfaceLocator(const Eigen::Matrix<Real, 3, Eigen::Dynamic>& nodes,
                 const Eigen::Matrix<Index, 3, Eigen::Dynamic>& triangles,
                 std::vector<Index> faces);

  /// The locator of the boundary triangles `faces` of `mesh` (columns of mesh.faces) in the
  /// mesh's reference configuration, mesh.nodes.
  SurfaceLocator(const mesh::TetMesh& mesh, std::vector<Index> faces);

  /// The first triangle on the line origin + t * direction (`direction` a unit vector, checked to
  /// 1e-9), t in [-max_distance, max_distance] [m]: among the triangles the line crosses at such
  /// t inside or on their boundary (barycentric coordinates all >= -1e-9), the one with the
  /// smallest |t|; a line through an edge or a vertex shared by several triangles gets any one of
  /// them. When the line crosses none of them, the triangle whose plane it crosses closest to the
  /// triangle itself, provided that this distance is below 1e-6 of the triangle's diameter (a
  /// line through a crack of a surface that is not watertight in floating point); its
  /// barycentric coordinates are those of the closest point of the triangle. Otherwise nothing.
  /// Triangles (nearly) parallel to the line (|direction . normal| < 1e-12) are never hit.
  std::optional<RayHit> ray_hit(const Vec3& origin, const Vec3& direction, Real max_distance) const;

  /// The triangles whose bounding box meets the box [lo, hi] [m] (componentwise lo <= hi), each
  /// once, in increasing order: the candidates of an overlap or proximity test. A triangle's box
  /// is padded by 1e-6 of its diameter, so that a triangle touching the box is not missed.
  std::vector<Index> faces_near(const Vec3& lo, const Vec3& hi) const;

  /// The triangles of the locator, in the order it was given them.
  const std::vector<Index>& faces() const { return faces_; }

  /// The vertices [m] of triangle `face` of the locator, in the order of its column of
  /// `triangles` (mesh.faces). Throws Error if the locator does not hold `face`.
  const Triangle3& triangle(Index face) const;

 private:
  struct Box {
    Vec3 lo, hi;
  };

  // The slot (position in faces_) of triangle `face`, or -1.
  Index slot_of(Index face) const;
  // Index of the grid cell of coordinate x along axis a, clamped to the grid.
  Index cell_coordinate(Real x, int a) const;
  // Appends the slots of the buckets of the cells that meet the box [lo, hi].
  void collect_slots(const Vec3& lo, const Vec3& hi, std::vector<Index>& slots) const;

  std::vector<Index> faces_;          // triangle of each slot
  std::vector<Triangle3> triangles_;  // vertices of each slot
  std::vector<Box> boxes_;            // padded bounding box of each slot
  std::vector<Real> diameters_;       // longest edge of each slot [m]
  std::vector<Index> slot_of_face_;   // slot of each triangle index, or -1
  Box grid_box_;                      // union of the boxes
  Real cell_size_ = 1.0;              // edge of the cubic cells [m]
  std::array<Index, 3> n_cells_ = {1, 1, 1};
  std::vector<Index> bucket_start_;  // cell c holds bucket_slots_[start[c], start[c + 1])
  std::vector<Index> bucket_slots_;
};

/// The overlap of a slave triangle with one master triangle, projected along the contact normal.
struct MortarOverlap {
  Index master_face = -1;  ///< the master triangle (as in SurfaceLocator::faces)
  /// Area [m^2] of the overlap measured on the slave triangle.
  Real area = 0.0;
  /// Integral [m^2] over the overlap (on the slave triangle) of the slave's shape function i.
  std::array<Real, 3> slave_integrals = {0.0, 0.0, 0.0};
  /// Integral [m^2] over the same overlap (same measure, on the slave triangle) of the master's
  /// shape function j (vertex order of SurfaceLocator::triangle(master_face)), evaluated at the
  /// point of the master triangle on the line through the slave point along the normal.
  std::array<Real, 3> master_integrals = {0.0, 0.0, 0.0};
  /// A quadrature of the overlap exact for polynomials of degree 2 in the projected coordinates
  /// (three points per sub-triangle of its fan): per point its weight [m^2] (measured on the
  /// slave triangle) and its barycentric coordinates on the slave and on the master triangle.
  /// The integrals of higher-order shape functions (6-node triangles) use it (theory.md §2.12).
  struct Point {
    Real weight = 0.0;
    std::array<Real, 3> slave = {0.0, 0.0, 0.0};
    std::array<Real, 3> master = {0.0, 0.0, 0.0};
  };
  std::vector<Point> points;
};

/// The mortar overlaps of triangle `slave` with the master surface `master`, projected along the
/// unit vector `n` (checked to 1e-9; the contact normal: the master lies along +n from the slave,
/// whose outward normal is roughly n). The slave and the candidate master triangles (those near
/// the box of the slave swept along n over [-max_distance, max_distance] [m]) are projected on
/// the plane orthogonal to n and intersected (clip_convex); all integrals are exact (the shape
/// functions of both triangles are affine on the plane: a fan of sub-triangles, each its area
/// times the value at its centroid; `points` a degree-2 rule on each). Skipped: master triangles
/// nearly parallel to n
/// (|n . normal| < 1e-3), degenerate overlaps, and master triangles whose distance along n from
/// the slave, (master point - slave point) . n at the overlap's centroid [m], lies outside
/// [-max_distance, max_distance]. Empty when the slave itself is nearly parallel to n. No master
/// triangle is skipped for its orientation: a triangle on the far side of a thin master within
/// max_distance is kept. For a slave covered once by the master, the areas add up to the slave's
/// area; for each overlap, the slave integrals and the master integrals each add up to its area.
/// Overlaps come in increasing master_face order.
std::vector<MortarOverlap> mortar_overlaps(const Triangle3& slave, const Vec3& n,
                                           const SurfaceLocator& master, Real max_distance);

}  // namespace fricon::contact
