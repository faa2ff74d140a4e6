// contact: the rigid ball obstacle (theory.md §2.11): distance |x - c| - r, normal (x - c)/|x - c|.
#include "fricon/contact/obstacle.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

class Sphere final : public Obstacle {
 public:
  Sphere(const Vec3& center, Real radius) : center_(center), radius_(radius) {}
  Proximity closest(const Vec3& x) const override {
    const Vec3 r = x - center_;
    const Real distance = r.norm();
    // At the centre every direction is nearest; any one will do.
    const Vec3 normal = distance > 0.0 ? Vec3(r / distance) : Vec3::UnitZ();
    return {distance - radius_, normal};
  }
  std::string_view kind() const override { return "sphere"; }
  std::vector<ObstacleParameter> parameters() const override {
    return {{"center", {center_(0), center_(1), center_(2)}, true}, {"radius", {radius_}, false}};
  }

 private:
  Vec3 center_;
  Real radius_;
};

}  // namespace

ObstaclePtr make_sphere(const Vec3& center, Real radius) {
  FRICON_CHECK(radius > 0.0, "make_sphere: radius " << radius);
  return std::make_shared<Sphere>(center, radius);
}

}  // namespace fricon::contact
