// contact: the rigid plane obstacle (theory.md §2.11): the half-space (x - p) . n <= 0.
#include <fmt/format.h>

#include "fricon/contact/obstacle.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

class Plane final : public Obstacle {
 public:
  Plane(const Vec3& point, const Vec3& normal) : point_(point), normal_(normal) {}
  Proximity closest(const Vec3& x) const override { return {(x - point_).dot(normal_), normal_}; }
  std::string_view kind() const override { return "plane"; }
  std::vector<ObstacleParameter> parameters() const override {
    return {{"point", {point_(0), point_(1), point_(2)}, true},
            {"normal", {normal_(0), normal_(1), normal_(2)}, false}};
  }
  bool flat() const override { return true; }
  ObstacleSurface picture(const Vec3& centre, Real extent) const override {
    // The square of side 2 extent around centre's projection, in the plane's own tangents.
    const Vec3 middle = centre - (centre - point_).dot(normal_) * normal_;
    const Vec3 t1 = normal_.unitOrthogonal(), t2 = normal_.cross(t1);
    ObstacleSurface s;
    s.points.resize(3, 4);
    s.points << middle - extent * (t1 + t2), middle + extent * (t1 - t2),
        middle + extent * (t1 + t2), middle - extent * (t1 - t2);
    s.triangles.resize(3, 2);
    s.triangles << 0, 0, 1, 2, 2, 3;  // counter-clockwise about the normal: t1 x t2 = n
    return s;
  }

 private:
  Vec3 point_, normal_;
};

}  // namespace

ObstaclePtr make_plane(const Vec3& point, const Vec3& normal) {
  FRICON_CHECK(normal.stableNorm() > 0.0, "make_plane: a zero normal");
  return std::make_shared<Plane>(point, normal.stableNormalized());
}

}  // namespace fricon::contact
