// contact: the paper's chessboard partition of a rectangular contact surface (theory.md §2.3).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fricon/contact/patches.hpp"
#include "fricon/core/error.hpp"

namespace fricon::contact {

Patches chessboard_patches(const mesh::TetMesh& mesh, const ContactSurface& surface,
                           const std::string& where) {
  // Tangential coordinates of the triangles' corners, and the grid they lie on.
  std::vector<Real> c1, c2;
  for (Index f : surface.faces)
    for (int v = 0; v < 3; ++v) {
      c1.push_back(surface.t1.dot(mesh.nodes.col(mesh.faces(v, f))));
      c2.push_back(surface.t2.dot(mesh.nodes.col(mesh.faces(v, f))));
    }
  auto grid_lines = [](std::vector<Real> c) {
    std::sort(c.begin(), c.end());
    const Real tol = 1e-9 * (c.back() - c.front());
    std::vector<Real> lines{c.front()};
    for (Real v : c)
      if (v - lines.back() > tol) lines.push_back(v);
    return lines;
  };
  const auto lines1 = grid_lines(c1), lines2 = grid_lines(c2);
  const Index m1 = static_cast<Index>(lines1.size()) - 1,
              m2 = static_cast<Index>(lines2.size()) - 1;
  if (m1 < 2 || m2 < 2 || m1 % 2 != 0 || m2 % 2 != 0 ||
      surface.faces.size() != static_cast<size_t>(2 * m1 * m2))
    throw InputError(fmt::format(
        "{} = \"chessboard\" needs a rectangular contact surface of grid squares "
        "with an even number (>= 2) in each direction; '{}' has {} x {} grid intervals and {} "
        "triangles (on a brick: mesh.cells must be even along both edges of the contact face)",
        where, surface.tag, m1, m2, surface.faces.size()));
  const Real h1 = (lines1.back() - lines1.front()) / static_cast<Real>(m1);
  const Real h2 = (lines2.back() - lines2.front()) / static_cast<Real>(m2);
  const Index n1 = m1 / 2, n2 = m2 / 2;

  std::vector<std::vector<Index>> faces(static_cast<size_t>(n1 * n2));
  for (size_t k = 0; k < surface.faces.size(); ++k) {
    const Vec3 centroid = face_centroid(mesh, surface.faces[k]);
    const Index a = std::clamp<Index>(
        static_cast<Index>(std::floor((surface.t1.dot(centroid) - lines1.front()) / (2 * h1))), 0,
        n1 - 1);
    const Index b = std::clamp<Index>(
        static_cast<Index>(std::floor((surface.t2.dot(centroid) - lines2.front()) / (2 * h2))), 0,
        n2 - 1);
    faces[static_cast<size_t>(a + n1 * b)].push_back(static_cast<Index>(k));
  }
  return finish_patches(mesh, surface, std::move(faces));
}

}  // namespace fricon::contact
