#include "fricon/mesh/brick.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::mesh {

namespace {

// Each side of the box is cut into blocks of kBlockCells x kBlockCells grid cells, each block one
// face entity (the paper's chessboard of patches, theory.md §7.2).
constexpr Index kBlockCells = 2;

Index blocks_along(Index cells) {
  return (cells + kBlockCells - 1) / kBlockCells;
}

// Entity numbers: 1, 2, ... block by block, side by side in the order x0, x1, y0, y1, z0, z1.
void assign_block_entities(const BrickSpec& spec, TetMesh& mesh) {
  std::array<int, 6> first_entity{};
  int next = 1;
  for (int side = 0; side < 6; ++side) {
    const int d = side / 2;
    first_entity[side] = next;
    next += static_cast<int>(blocks_along(spec.cells[(d + 1) % 3]) *
                             blocks_along(spec.cells[(d + 2) % 3]));
  }
  mesh.face_entity.assign(static_cast<size_t>(mesh.n_faces()), -1);
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    const int side = mesh.face_tag[f];
    const int d = side / 2;
    const Vec3 centroid = (mesh.nodes.col(mesh.faces(0, f)) + mesh.nodes.col(mesh.faces(1, f)) +
                           mesh.nodes.col(mesh.faces(2, f))) /
                          3.0;
    auto block = [&](int axis) {
      const Real h = spec.size[axis] / static_cast<Real>(spec.cells[axis]);
      const Index cell = std::clamp(static_cast<Index>(std::floor(centroid[axis] / h)), Index{0},
                                    spec.cells[axis] - 1);
      return cell / kBlockCells;
    };
    const int p = (d + 1) % 3, q = (d + 2) % 3;
    mesh.face_entity[f] =
        first_entity[side] + static_cast<int>(block(p) + blocks_along(spec.cells[p]) * block(q));
  }
}

}  // namespace

TetMesh make_brick(const BrickSpec& spec) {
  for (int d = 0; d < 3; ++d) {
    if (!(spec.size[d] > 0.0) || !std::isfinite(spec.size[d]))
      throw InputError(
          fmt::format("brick: size[{}] = {} must be a positive length", d, spec.size[d]));
    if (spec.cells[d] < 1)
      throw InputError(fmt::format("brick: cells[{}] = {} must be at least 1", d, spec.cells[d]));
  }
  const auto [nx, ny, nz] = spec.cells;
  TetMesh mesh;
  mesh.nodes.resize(3, (nx + 1) * (ny + 1) * (nz + 1));
  for (Index k = 0; k <= nz; ++k)
    for (Index j = 0; j <= ny; ++j)
      for (Index i = 0; i <= nx; ++i)
        mesh.nodes.col(brick_node(spec, i, j, k)) =
            Vec3(spec.size[0] * static_cast<Real>(i) / static_cast<Real>(nx),
                 spec.size[1] * static_cast<Real>(j) / static_cast<Real>(ny),
                 spec.size[2] * static_cast<Real>(k) / static_cast<Real>(nz));

  mesh.tets.resize(4, 5 * nx * ny * nz);
  Index t = 0;
  auto add_tet = [&](std::array<Index, 4> v) {
    const Real volume = signed_volume(mesh.nodes.col(v[0]), mesh.nodes.col(v[1]),
                                      mesh.nodes.col(v[2]), mesh.nodes.col(v[3]));
    if (volume < 0) std::swap(v[2], v[3]);
    for (int a = 0; a < 4; ++a)
      mesh.tets(a, t) = v[a];
    ++t;
  };
  for (Index k = 0; k < nz; ++k)
    for (Index j = 0; j < ny; ++j)
      for (Index i = 0; i < nx; ++i) {
        // Cube vertices by local offsets (a, b, c) in {0,1}^3, split by global parity.
        auto vertex = [&](int a, int b, int c) { return brick_node(spec, i + a, j + b, k + c); };
        auto parity = [&](int a, int b, int c) { return (i + a + j + b + k + c) % 2; };
        std::array<Index, 4> central{};
        int n_central = 0;
        for (int c = 0; c < 2; ++c)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              if (parity(a, b, c) == 0) {
                central[n_central++] = vertex(a, b, c);
              } else {
                add_tet({vertex(a, b, c), vertex(1 - a, b, c), vertex(a, 1 - b, c),
                         vertex(a, b, 1 - c)});
              }
            }
        add_tet(central);
      }

  // Boundary faces: the faces of exactly one tetrahedron, tagged by the box side they lie on.
  mesh.tag_names = {"x0", "x1", "y0", "y1", "z0", "z1"};
  mesh.faces = boundary_faces_of(mesh);
  mesh.face_tag.assign(static_cast<size_t>(mesh.n_faces()), -1);
  const std::array<Index, 3> n_cells{nx, ny, nz};
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    for (int d = 0; d < 3 && mesh.face_tag[f] < 0; ++d) {
      for (int side = 0; side < 2; ++side) {
        const Real plane = side == 0 ? 0.0 : spec.size[d];
        const Real tol = 1e-9 * spec.size[d] / static_cast<Real>(n_cells[d]);
        bool on_plane = true;
        for (int v = 0; v < 3; ++v)
          on_plane = on_plane && std::abs(mesh.nodes(d, mesh.faces(v, f)) - plane) < tol;
        if (on_plane) {
          mesh.face_tag[f] = 2 * d + side;
          break;
        }
      }
    }
    FRICON_CHECK(mesh.face_tag[f] >= 0, "brick boundary face " << f << " lies on no side");
  }
  assign_block_entities(spec, mesh);
  return mesh;
}

}  // namespace fricon::mesh
