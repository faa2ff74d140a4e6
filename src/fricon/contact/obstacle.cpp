#include "fricon/contact/obstacle.hpp"

#include <fmt/format.h>

namespace fricon::contact {

std::string describe(const Obstacle& obstacle, const Vec3& displacement) {
  std::string text(obstacle.kind());
  const char* separator = ": ";
  for (const ObstacleParameter& p : obstacle.parameters()) {
    std::string value;
    if (p.value.size() == 1) {
      value = fmt::format("{:.6g}", p.value.front());
    } else {
      for (size_t i = 0; i < p.value.size(); ++i)
        value += fmt::format("{}{:.6g}", i == 0 ? "(" : ", ", p.value[i] + 0.0);  // no "-0"
      value += ")";
    }
    text += fmt::format("{}{} {}", separator, p.name, value);
    separator = ", ";
  }
  if (!displacement.isZero(0.0))
    text += fmt::format("; moved by ({:.6g}, {:.6g}, {:.6g}) m", displacement(0) + 0.0,
                        displacement(1) + 0.0, displacement(2) + 0.0);
  return text;
}

}  // namespace fricon::contact
