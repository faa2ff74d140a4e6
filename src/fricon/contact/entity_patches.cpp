// contact: the mesh file's partition, one patch per elementary entity of the contact tag
// (theory.md §2.3).
#include <map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fricon/contact/patches.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {
// Entity of boundary triangle f, or -1 when the mesh records none.
int entity_of(const mesh::TetMesh& mesh, Index f) {
  const auto k = static_cast<size_t>(f);
  return k < mesh.face_entity.size() ? mesh.face_entity[k] : -1;
}
}  // namespace

Patches entity_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                       const std::string& where) {
  std::map<int, std::vector<Index>> by_entity;  // ordered: patches in increasing entity order
  for (size_t k = 0; k < surface.faces.size(); ++k) {
    const int entity = entity_of(mesh, surface.faces[k]);
    if (entity < 0)
      throw InputError(fmt::format(
          "{} = \"mesh\": the mesh has no elementary entities for the contact "
          "tag '{}' (triangle {} of it has none), so it defines no partition; use \"agglomerate\" "
          "or draw the partition in Gmsh (one surface per patch)",
          where, surface.tag, surface.faces[k]));
    by_entity[entity].push_back(static_cast<Index>(k));
  }
  std::vector<std::vector<Index>> faces;
  faces.reserve(by_entity.size());
  for (auto& [entity, list] : by_entity)
    faces.push_back(std::move(list));
  return finish_patches(mesh, surface, std::move(faces));
}

}  // namespace fricon::contact
