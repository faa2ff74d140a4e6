// contact: the rigid infinite cylinder obstacle (theory.md §2.11): distance |x_perp| - r, with
// x_perp the part of x - p normal to the axis, and normal x_perp / |x_perp|.
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
