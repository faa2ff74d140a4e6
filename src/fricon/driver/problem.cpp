#include "fricon/driver/problem.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::driver {

std::span<const std::string_view> mesh_parameters(MeshKind kind) {
  static constexpr std::string_view kBrick[] = {"size", "cells", "order"};
  static constexpr std::string_view kGmsh[] = {"file", "size_factor", "unit", "order"};
  switch (kind) {
    case MeshKind::Brick:
      return kBrick;
    case MeshKind::Gmsh:
      return kGmsh;
    case MeshKind::Arrays:
      return {};
  }
  return {};
}

std::span<const std::string_view> obstacle_parameters(ObstacleKind kind) {
  static constexpr std::string_view kPlane[] = {"point", "normal", "displacement", "path"};
  static constexpr std::string_view kBody[] = {"boundary"};
  static constexpr std::string_view kSphere[] = {"center", "radius", "displacement", "path"};
  static constexpr std::string_view kCylinder[] = {"point", "axis", "radius", "displacement",
                                                   "path"};
  static constexpr std::string_view kSurface[] = {"boundary", "displacement", "path"};
  switch (kind) {
    case ObstacleKind::Plane:
      return kPlane;
    case ObstacleKind::Body:
      return kBody;
    case ObstacleKind::Sphere:
      return kSphere;
    case ObstacleKind::Cylinder:
      return kCylinder;
    case ObstacleKind::Surface:
      return kSurface;
  }
  return {};
}

Vec3 obstacle_displacement(const ObstacleOptions& o, int k, int steps) {
  if (k <= 0 || o.path.empty()) return o.displacement;
  const auto step = static_cast<std::size_t>(k - 1);
  // One factor per step, or one per component and step (3 steps values, the obstacle table's
  // check).
  if (o.path.size() == static_cast<std::size_t>(steps)) return o.path.at(step) * o.displacement;
  return o.displacement.cwiseProduct(
      Vec3(o.path.at(3 * step), o.path.at(3 * step + 1), o.path.at(3 * step + 2)));
}

Real metres_per(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Metre:
      return 1.0;
    case LengthUnit::Centimetre:
      return 1e-2;
    case LengthUnit::Millimetre:
      return 1e-3;
  }
  throw Error("metres_per: invalid length unit");
}

std::string Problem::where(std::string_view key) const {
  // "traction[1].value[2]" -> "traction[1].value" -> "traction[1]" -> "traction".
  while (!key.empty()) {
    if (const std::string* origin = positions.find(key)) return *origin;
    const auto cut = key.find_last_of(".[");
    if (cut == std::string_view::npos) break;
    key = key.substr(0, cut);
  }
  return source;
}

void Problem::fail(std::string_view key, std::string_view what) const {
  throw InputError(fmt::format("{}: {}: {}", where(key), key, what));
}

std::string Problem::contact_key(std::size_t i) const {
  return contact.size() == 1 && !given_as_array("contact") ? std::string("contact")
                                                           : fmt::format("contact[{}]", i);
}

bool Problem::given_as_array(std::string_view key) const {
  return positions.contains(fmt::format("{}[0]", key));
}

Problem scaled_loads(const Problem& problem, const std::vector<Real>& factors, Real rest) {
  Problem p = problem;
  std::size_t i = 0;  // the next load with a path, in path_loads order
  const auto factor = [&](const std::vector<Real>& path) {
    return path.empty() ? rest : factors.at(i++);
  };
  for (TractionOptions& t : p.traction)
    t.value *= factor(t.path);
  for (DirichletOptions& d : p.dirichlet)
    d.value *= factor(d.path);
  p.volume_force *= factor(p.loading.volume_force_path);
  return p;
}

Problem at_step(const Problem& problem, int k) {
  return scaled_loads(problem, step_factors(path_loads(problem), k), 1.0);
}

std::vector<Real> step_factors(const std::vector<PathLoad>& loads, int k) {
  std::vector<Real> a;
  for (const PathLoad& load : loads)
    a.push_back((*load.factors)[static_cast<std::size_t>(k - 1)]);
  return a;
}

std::vector<PathLoad> path_loads(const Problem& problem) {
  std::vector<PathLoad> loads;
  for (std::size_t i = 0; i < problem.traction.size(); ++i)
    if (!problem.traction[i].path.empty())
      loads.push_back({fmt::format("traction[{}]", i), &problem.traction[i].path,
                       problem.traction[i].boundary});
  for (std::size_t i = 0; i < problem.dirichlet.size(); ++i)
    if (!problem.dirichlet[i].path.empty())
      loads.push_back({fmt::format("dirichlet[{}]", i), &problem.dirichlet[i].path,
                       problem.dirichlet[i].boundary});
  if (!problem.loading.volume_force_path.empty())
    loads.push_back({"volume_force", &problem.loading.volume_force_path, {}});
  return loads;
}

}  // namespace fricon::driver
