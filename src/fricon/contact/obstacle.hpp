#pragma once
// contact: a rigid obstacle (theory.md §2.11), the value a contact pair without a master touches.
// The obstacle is its signed distance: closest(x) gives the distance of x to its surface
// (positive outside, where the body is) and the unit outward normal there, the distance's
// gradient. One implementation per file in contact/obstacles/ (plane, sphere, cylinder, meshed
// surface), chosen once where the problem is read; the discretization asks only closest().
// A rigid motion of the obstacle (a translation d) is not part of it: the obstacle moved by d has
// the distance closest(x - d) (closest_moved).

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::contact {

/// The nearest point of the obstacle's surface to a point x.
struct Proximity {
  Real distance = 0.0;  ///< signed distance [m]: > 0 outside the obstacle, < 0 inside it
  /// Unit outward normal of the obstacle at the nearest point, pointing from the obstacle
  /// towards x when x is outside (the gradient of the distance).
  Vec3 normal = Vec3::UnitZ();
};

/// One named parameter of an obstacle at rest, for reports and plots ("center", [x, y, z]).
struct ObstacleParameter {
  std::string name;
  std::vector<Real> value;  ///< [m] for points and radii, unit vectors as given (normalized)
  bool moves = false;       ///< a point, which the obstacle's displacement moves
};

/// A triangulated picture of an obstacle's surface, for output (ParaView).
struct ObstacleSurface {
  Eigen::Matrix<Real, 3, Eigen::Dynamic> points;      ///< [m]
  Eigen::Matrix<Index, 3, Eigen::Dynamic> triangles;  ///< counter-clockwise seen from outside
};

class Obstacle {
 public:
  virtual ~Obstacle() = default;
  /// The signed distance of x [m] to the obstacle at rest and its outward normal there.
  virtual Proximity closest(const Vec3& x) const = 0;
  /// The kind's name as the problem file writes it: "plane", "sphere", "cylinder", "surface".
  virtual std::string_view kind() const = 0;
  /// The obstacle's parameters at rest (points, directions, radius; a meshed surface its tag
  /// and triangle count).
  virtual std::vector<ObstacleParameter> parameters() const = 0;
  /// Whether the surface is flat: then its normal is the same everywhere and a patch has one
  /// frame.
  virtual bool flat() const { return false; }
  /// Its surface at rest as triangles: the whole of a bounded kind, and of an unbounded one (a
  /// plane, a cylinder) the part within about `extent` [m] of `centre` [m] (the contact
  /// surface's middle and size).
  virtual ObstacleSurface picture(const Vec3& centre, Real extent) const = 0;
};

using ObstaclePtr = std::shared_ptr<const Obstacle>;

/// The obstacle moved by the translation d [m]: closest(x - d).
inline Proximity closest_moved(const Obstacle& obstacle, const Vec3& x, const Vec3& d) {
  return obstacle.closest(x - d);
}

/// One line for summaries: the kind and its parameters at rest ("sphere: center (0, 0, 0.01),
/// radius 0.01"), then "; moved by (dx, dy, dz) m" when `displacement` is not zero.
std::string describe(const Obstacle& obstacle, const Vec3& displacement);

/// The half-space below the plane through `point` [m] with unit outward normal `normal` (pointing
/// towards the body; normalized here, non-zero).
ObstaclePtr make_plane(const Vec3& point, const Vec3& normal);
/// The ball of centre `center` [m] and radius `radius` [m] > 0; the body is outside it.
ObstaclePtr make_sphere(const Vec3& center, Real radius);
/// The infinite cylinder of axis through `point` [m] along `axis` (non-zero, normalized here)
/// and radius `radius` [m] > 0; the body is outside it.
ObstaclePtr make_cylinder(const Vec3& point, const Vec3& axis, Real radius);

}  // namespace fricon::contact
