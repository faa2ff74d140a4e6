#pragma once
// contact: the coarse partition T_H of the contact surface that carries the multipliers
// (theory.md §2.3): a list of patches, each a set of surface triangles with one multiplier triple
// (lambda_n, lambda_t1, lambda_t2). make_patches is the factory: one PatchKind per way of
// partitioning, each implemented in a file of its own (chessboard.cpp, the paper's;
// entity_patches.cpp, the mesh file's; agglomerate.cpp, fricon's own on any triangulation).

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::contact {

/// How the contact surface is partitioned into multiplier patches ([contact] patches).
enum class PatchKind {
  /// The paper's: 2 x 2 squares of the structured grid of a rectangular surface.
  Chessboard,
  /// The mesh file's: one patch per elementary entity (Gmsh surface) of the contact tag.
  Mesh,
  /// fricon's: stars of well separated surface vertices, grown over the triangles.
  Agglomerate,
};

/// Patch p is the list of surface-face positions (indices into ContactSurface::faces).
struct Patches {
  std::vector<std::vector<Index>> faces;
  VectorXd area;                                    ///< |R_p| [m^2]
  Eigen::Matrix<Real, 3, Eigen::Dynamic> centroid;  ///< [m]
  Index size() const { return static_cast<Index>(faces.size()); }
};

/// The partition of `surface` of the given kind. `patch_size` [m] is the target patch diameter
/// of PatchKind::Agglomerate (0: the finest stable one, see agglomerate_patches); the other kinds
/// ignore it. `where` starts messages: the position and name of the key ("file:line:col:
/// contact.patches"). Throws InputError when the surface does not admit the partition (e.g. a
/// chessboard on a surface that is not a grid of an even number of squares, or "mesh" on a surface
/// without elementary entities).
Patches make_patches(PatchKind kind, const mesh::TetMesh& mesh, const ContactSurface& surface,
                     Real patch_size, const std::string& where);

/// The paper's chessboard (chessboard.cpp): 2 x 2 squares of the structured grid of the surface
/// (each the union of the eight triangles around a node of odd grid indices). The surface must be
/// a rectangle of grid squares with an even count in each tangential direction.
Patches chessboard_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const std::string& where);

/// The mesh file's partition (entity_patches.cpp): the surface triangles with the same
/// TetMesh::face_entity form one patch, patches in increasing entity order, each triangle's
/// surface-face positions in increasing order. A patch need not be edge-connected (an entity may
/// be drawn in several pieces); stability is checked later, on B. Throws InputError naming `where`
/// if some triangle of the surface has no entity (face_entity empty or -1).
Patches entity_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                       const std::string& where);

/// fricon's partition of any triangulated surface (agglomerate.cpp), deterministic:
///  1. seeds: a greedy independent set of surface vertices (no two joined by a surface edge),
///     tried in the order: fewest components fixed by Dirichlet conditions, interior before
///     boundary vertices, then by (t2, t1) coordinates lexicographically; with patch_size > 0 a
///     seed must moreover be at least patch_size / sqrt(2) [m] (Euclidean) from every earlier one;
///  2. each seed's star (its triangles) is a patch;
///  3. the other triangles are grown into the patches across edges, nearest first, each joining
///     the patch next to it whose star centroid is nearest to its own centroid (a triangle that
///     no growth across edges reaches joins the nearest patch it shares a vertex with, else
///     starts one: only then is a patch not edge-connected).
/// On a structured grid with an even number of squares each way and patch_size = 0 the seeds are
/// the nodes of odd grid indices and the result is the chessboard (in another order). Patches are
/// edge-connected on an edge-connected manifold surface; with patch_size > 0 their mean diameter
/// is about patch_size (never below the finest partition's, that of the stars). Expects
/// patch_size >= 0 (finite); `where` names the key in messages.
Patches agglomerate_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                            Real patch_size, const std::string& where);

/// The patches of the given face lists (surface-face positions), with their areas and
/// area-weighted centroids: the step every kind ends with. Expects non-empty lists.
Patches finish_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                       std::vector<std::vector<Index>> faces);

/// Centroid [m] of boundary triangle f of the mesh.
Vec3 face_centroid(const mesh::TetMesh& mesh, Index f);

/// Largest distance [m] between two vertices of patch p: its diameter.
Real patch_diameter(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches, Index p);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::PatchKind, "contact.patches",
                  {contact::PatchKind::Chessboard, "chessboard"},
                  {contact::PatchKind::Mesh, "mesh"},
                  {contact::PatchKind::Agglomerate, "agglomerate"});
