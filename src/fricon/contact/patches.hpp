#pragma once
// contact: the coarse partition T_H of the contact surface that carries the multipliers
// (theory.md §2.3): a list of patches, each a set of surface triangles with one multiplier triple
// (lambda_n, lambda_t1, lambda_t2). make_patches is the factory: one PatchKind per way of
// partitioning, each implemented in a file of its own (chessboard.cpp, the paper's).

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
  /// Each elementary entity of the contact tag in the mesh file is one patch.
  Mesh,
  /// Built by fricon from the surface triangles.
  Agglomerate,
};

/// Patch p is the list of surface-face positions (indices into ContactSurface::faces).
struct Patches {
  std::vector<std::vector<Index>> faces;
  VectorXd area;                                    ///< |R_p| [m^2]
  Eigen::Matrix<Real, 3, Eigen::Dynamic> centroid;  ///< [m]
  Index size() const { return static_cast<Index>(faces.size()); }
};

/// The partition of `surface` of the given kind. `where` names the problem's key in messages
/// ("file:line:col"). Throws InputError when the surface does not admit the partition (e.g. a
/// chessboard on a surface that is not a grid of an even number of squares).
Patches make_patches(PatchKind kind, const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const std::string& where);

/// The paper's chessboard (chessboard.cpp): 2 x 2 squares of the structured grid of the surface
/// (each the union of the eight triangles around a node of odd grid indices). The surface must be
/// a rectangle of grid squares with an even count in each tangential direction.
Patches chessboard_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const std::string& where);

}  // namespace fricon::contact

FRICON_ENUM_NAMES(fricon::contact::PatchKind, "contact.patches",
                  {contact::PatchKind::Chessboard, "chessboard"},
                  {contact::PatchKind::Mesh, "mesh"},
                  {contact::PatchKind::Agglomerate, "agglomerate"});
