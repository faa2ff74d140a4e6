#pragma once
// contact: the rigid obstacle of a meshed surface (theory.md §2.11), contact.obstacle kind
// "surface": a rigid surface of the mesh file (mesh::RigidSurface), its triangles oriented so that
// their right-hand normals point outside, towards the body. closest(x) is the exact nearest point
// of the triangles (a bounding volume hierarchy finds it), the distance signed by the
// angle-weighted pseudo-normal of the nearest face, edge or vertex (J. A. Baerentzen and H. Aanaes,
// Signed distance computation using the angle weighted pseudonormal, IEEE TVCG 11(3), 2005), so
// that points near an edge or a vertex get the right side too.

#include <string>
#include <utility>

#include "fricon/contact/obstacle.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// The rigid obstacle bounded by `surface` (its points [m] and triangles, as read from the mesh
/// file), kind "surface".
///
/// The triangles are first made consistently oriented over each connected component (triangles
/// joined by shared edges), by flipping them edge by edge from the component's first triangle.
/// Then each component's outside is chosen: a closed component (every edge in two triangles)
/// faces out of the volume it encloses (its signed volume made positive); an open one faces the
/// side on which most of `body_points` lie ([m], one column per point: the contact surface's
/// nodes), each point counting for the component its nearest point lies on, by the sign of its
/// distance; without such points or when they are as many on each side, the file's orientation
/// of the component's first triangle is kept. An open surface's distance beyond its rim is that to
/// its boundary edges, signed by the side of their triangles.
///
/// closest(x) gives the distance of x to the nearest point p of the triangles, positive outside
/// (on the side of the pseudo-normal of the face, edge or vertex p lies on), and as normal the unit
/// vector from p towards x times that sign (the face normal when p lies inside a triangle, and the
/// normal of p's triangle when x is on the surface, within 1e-12 of the surface's size).
/// parameters(): "triangles" (their count) and "bounding_box" (xmin, ymin, zmin, xmax, ymax, zmax
/// [m] at rest), neither moved by the obstacle's displacement.
///
/// Throws InputError naming `where` (the problem file's key, for the message) and the surface's
/// name if the surface has no triangle, a point index out of range, a non-finite coordinate, a
/// triangle of zero area, an edge in three or more triangles or a vertex where two fans of
/// triangles meet (non-manifold), or a component that cannot be oriented (a Moebius strip).
ObstaclePtr make_meshed_surface(const mesh::RigidSurface& surface,
                                const Eigen::Matrix<Real, 3, Eigen::Dynamic>& body_points,
                                const std::string& where);

/// The rigid surface's triangles with their outside orientation, for output (3 x n points [m],
/// 3 x m triangles, indices into the points, counter-clockwise seen from outside) of an obstacle
/// made by make_meshed_surface; empty matrices for an obstacle of another kind.
std::pair<Eigen::Matrix<Real, 3, Eigen::Dynamic>, Eigen::Matrix<Index, 3, Eigen::Dynamic>>
oriented_triangles(const Obstacle& obstacle);

}  // namespace fricon::contact
