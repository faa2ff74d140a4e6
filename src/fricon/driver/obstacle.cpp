#include "fricon/driver/obstacle.hpp"

#include <fmt/format.h>

#include "fricon/contact/obstacles/meshed_surface.hpp"
#include "fricon/core/error.hpp"

namespace fricon::driver {

namespace {

// The rigid surface tagged `tag`, refused when it is a boundary of the elastic bodies or absent.
const mesh::RigidSurface& rigid_surface(const mesh::TetMesh& mesh, const std::string& tag,
                                        const std::string& where) {
  if (mesh.find_tag(tag) >= 0)
    throw InputError(fmt::format(
        "{}: '{}' is a boundary of an elastic body (its triangles are faces of tetrahedra), not a "
        "rigid surface: kind \"surface\" takes a surface that no simulated body carries (a "
        "surface-only physical group, or the surface of a volume left out of the physical "
        "groups); for contact with another elastic body use kind \"body\"",
        where, tag));
  const mesh::RigidSurface* surface = mesh.find_rigid_surface(tag);
  if (surface == nullptr) throw InputError(fmt::format("{}: {}", where, mesh.no_surface(tag)));
  return *surface;
}

}  // namespace

contact::ObstaclePtr make_obstacle(const ObstacleOptions& o, const mesh::TetMesh& mesh,
                                   const std::string& contact_boundary,
                                   const std::string& where_boundary) {
  switch (o.kind) {
    case ObstacleKind::Plane:
      return contact::make_plane(o.point, o.normal);
    case ObstacleKind::Sphere:
      return contact::make_sphere(o.center, o.radius);
    case ObstacleKind::Cylinder:
      return contact::make_cylinder(o.point, o.axis, o.radius);
    case ObstacleKind::Surface: {
      const std::vector<Index> nodes = mesh.nodes_with_tag(contact_boundary);
      Eigen::Matrix<Real, 3, Eigen::Dynamic> body(3, static_cast<Index>(nodes.size()));
      for (size_t k = 0; k < nodes.size(); ++k)
        body.col(static_cast<Index>(k)) = mesh.nodes.col(nodes[k]);
      return contact::make_meshed_surface(rigid_surface(mesh, o.boundary, where_boundary), body,
                                          where_boundary);
    }
    case ObstacleKind::Body:
      break;
  }
  throw Error("make_obstacle: kind body is no rigid obstacle");
}

}  // namespace fricon::driver
