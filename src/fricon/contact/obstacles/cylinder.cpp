// contact: the rigid infinite cylinder obstacle (theory.md §2.11): distance |x_perp| - r, with
// x_perp the part of x - p normal to the axis, and normal x_perp / |x_perp|.
#include <array>
#include <cmath>
#include <vector>

#include "fricon/contact/obstacle.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

class Cylinder final : public Obstacle {
 public:
  Cylinder(const Vec3& point, const Vec3& axis, Real radius)
      : point_(point), axis_(axis), radius_(radius) {}
  Proximity closest(const Vec3& x) const override {
    const Vec3 r = x - point_;
    const Vec3 across = r - r.dot(axis_) * axis_;
    const Real distance = across.norm();
    // On the axis every direction normal to it is nearest; any one will do.
    const Vec3 normal = distance > 0.0 ? Vec3(across / distance) : axis_.unitOrthogonal();
    return {distance - radius_, normal};
  }
  std::string_view kind() const override { return "cylinder"; }
  ObstacleSurface picture(const Vec3& centre, Real extent) const override {
    // Its mantle over the length 2 extent around centre's projection on the axis, kSectors
    // around.
    constexpr Index kSectors = 64;
    constexpr Real kPi = 3.14159265358979323846;
    const Vec3 middle = point_ + (centre - point_).dot(axis_) * axis_;
    const Vec3 e1 = axis_.unitOrthogonal(), e2 = axis_.cross(e1);
    ObstacleSurface s;
    s.points.resize(3, 2 * kSectors);
    for (Index j = 0; j < kSectors; ++j) {
      const Real phi = 2.0 * kPi * static_cast<Real>(j) / kSectors;
      const Vec3 r = radius_ * (std::cos(phi) * e1 + std::sin(phi) * e2);
      s.points.col(j) = middle - extent * axis_ + r;
      s.points.col(kSectors + j) = middle + extent * axis_ + r;
    }
    s.triangles.resize(3, 2 * kSectors);
    for (Index j = 0; j < kSectors; ++j) {
      const Index k = (j + 1) % kSectors;
      s.triangles.col(2 * j) << j, k, kSectors + k;
      s.triangles.col(2 * j + 1) << j, kSectors + k, kSectors + j;
    }
    return s;
  }
  std::vector<ObstacleParameter> parameters() const override {
    return {{"point", {point_(0), point_(1), point_(2)}, true},
            {"axis", {axis_(0), axis_(1), axis_(2)}, false},
            {"radius", {radius_}, false}};
  }

 private:
  Vec3 point_, axis_;
  Real radius_;
};

}  // namespace

ObstaclePtr make_cylinder(const Vec3& point, const Vec3& axis, Real radius) {
  FRICON_CHECK(radius > 0.0, "make_cylinder: radius " << radius);
  FRICON_CHECK(axis.stableNorm() > 0.0, "make_cylinder: a zero axis");
  return std::make_shared<Cylinder>(point, axis.stableNormalized(), radius);
}

}  // namespace fricon::contact
