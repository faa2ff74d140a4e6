#include "fricon/contact/patches.hpp"

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::contact {

Patches make_patches(PatchKind kind, const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const std::string& where) {
  switch (kind) {
    case PatchKind::Chessboard:
      return chessboard_patches(mesh, surface, where);
    case PatchKind::Mesh:
    case PatchKind::Agglomerate:
      break;
  }
  throw InputError(
      fmt::format("{}: contact.patches: invalid partition kind {}", where, static_cast<int>(kind)));
}

}  // namespace fricon::contact
