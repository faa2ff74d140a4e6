#pragma once
// driver: the rigid obstacle of a contact pair, made once from its [contact.obstacle] table
// (theory.md §2.11): the one place that knows which kinds exist.

#include <string>

#include "fricon/contact/obstacle.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::driver {

/// The obstacle of kind plane, sphere, cylinder or surface (a rigid `o`, is_rigid) at rest.
/// A surface is the rigid surface of `mesh` tagged o.boundary, its outside the side of the
/// contact surface `contact_boundary`. Throws InputError naming `where_boundary` (the position of
/// obstacle.boundary) when the tag is no rigid surface of the mesh: it does not exist, or an
/// elastic body carries it.
contact::ObstaclePtr make_obstacle(const ObstacleOptions& o, const mesh::TetMesh& mesh,
                                   const std::string& contact_boundary,
                                   const std::string& where_boundary);

}  // namespace fricon::driver
