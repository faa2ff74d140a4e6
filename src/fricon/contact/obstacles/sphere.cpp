// contact: the rigid ball obstacle (theory.md §2.11): distance |x - c| - r, normal (x - c)/|x - c|.
#include <array>
#include <cmath>
#include <vector>

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
  ObstacleSurface picture(const Vec3&, Real) const override {
    // Latitude-longitude triangles, kRings rings of kSectors, closed by the two poles.
    constexpr Index kRings = 24, kSectors = 48;
    constexpr Real kPi = 3.14159265358979323846;
    ObstacleSurface s;
    s.points.resize(3, 2 + (kRings - 1) * kSectors);
    s.points.col(0) = center_ + radius_ * Vec3::UnitZ();
    s.points.col(1) = center_ - radius_ * Vec3::UnitZ();
    for (Index i = 1; i < kRings; ++i)
      for (Index j = 0; j < kSectors; ++j) {
        const Real theta = kPi * static_cast<Real>(i) / kRings;
        const Real phi = 2.0 * kPi * static_cast<Real>(j) / kSectors;
        s.points.col(2 + (i - 1) * kSectors + j) =
            center_ + radius_ * Vec3(std::sin(theta) * std::cos(phi),
                                     std::sin(theta) * std::sin(phi), std::cos(theta));
      }
    const auto at = [](Index ring, Index j) { return 2 + (ring - 1) * kSectors + j % kSectors; };
    std::vector<std::array<Index, 3>> t;
    for (Index j = 0; j < kSectors; ++j) {
      t.push_back({0, at(1, j), at(1, j + 1)});
      t.push_back({1, at(kRings - 1, j + 1), at(kRings - 1, j)});
      for (Index i = 1; i + 1 < kRings; ++i) {
        t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
    s.triangles.resize(3, static_cast<Index>(t.size()));
    for (size_t k = 0; k < t.size(); ++k)
      s.triangles.col(static_cast<Index>(k)) << t[k][0], t[k][1], t[k][2];
    return s;
  }
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
