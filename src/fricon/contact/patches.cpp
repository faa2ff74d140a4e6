#include "fricon/contact/patches.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "fricon/contact/surface_integrals.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

Patches make_patches(PatchKind kind, const mesh::TetMesh& mesh, const ContactSurface& surface,
                     Real patch_size, const std::string& where) {
  switch (kind) {
    case PatchKind::Chessboard:
      return chessboard_patches(mesh, surface, where);
    case PatchKind::Mesh:
      return entity_patches(mesh, surface, where);
    case PatchKind::Agglomerate:
      return agglomerate_patches(mesh, surface, patch_size, where);
  }
  throw InputError(fmt::format("{}: invalid partition kind {}", where, static_cast<int>(kind)));
}

Vec3 face_centroid(const mesh::TetMesh& mesh, Index f) {
  Vec3 centroid = Vec3::Zero();
  for (int v = 0; v < 3; ++v)
    centroid += mesh.nodes.col(mesh.faces(v, f)) / 3.0;
  return centroid;
}

Patches finish_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                       std::vector<std::vector<Index>> faces) {
  Patches p;
  p.faces = std::move(faces);
  p.area = VectorXd::Zero(p.size());
  p.centroid = Eigen::Matrix<Real, 3, Eigen::Dynamic>::Zero(3, p.size());
  for (Index q = 0; q < p.size(); ++q) {
    FRICON_CHECK(!p.faces[static_cast<size_t>(q)].empty(), "patch " << q << " has no triangle");
    for (Index k : p.faces[static_cast<size_t>(q)]) {
      const Index f = surface.faces[static_cast<size_t>(k)];
      // The triangle's area as B's rows integrate it (curved at order 2, theory.md §2.12).
      const Real area = face_integrals(mesh, surface, k).shape.sum();
      p.area(q) += area;
      p.centroid.col(q) += area * face_centroid(mesh, f);
    }
    p.centroid.col(q) /= p.area(q);
  }
  return p;
}

Real patch_diameter(const mesh::TetMesh& mesh, const ContactSurface& surface,
                    const Patches& patches, Index p) {
  std::vector<Index> nodes;
  for (Index k : patches.faces[static_cast<size_t>(p)])
    for (int v = 0; v < 3; ++v)
      nodes.push_back(mesh.faces(v, surface.faces[static_cast<size_t>(k)]));
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  Real diameter = 0.0;
  for (size_t a = 0; a < nodes.size(); ++a)
    for (size_t b = a + 1; b < nodes.size(); ++b)
      diameter = std::max(diameter, (mesh.nodes.col(nodes[a]) - mesh.nodes.col(nodes[b])).norm());
  return diameter;
}

}  // namespace fricon::contact
