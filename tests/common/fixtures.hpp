#pragma once
// What the test executables share (library fricon_test_common, tests/CMakeLists.txt): the
// clamped brick in its forms (a dof map, the contact discretization on it, a driver::Problem),
// the gravity column, a temporary folder per test, the paths of the repository's files, and the
// message of an InputError.
//
// The brick is the paper's body (docs/theory.md §7): size 3 x 1 x 1 m by default, meshed by
// mesh::make_brick (5 tetrahedra per cube, boundary tags x0 ... z1), clamped on its end x0 and in
// contact with the rigid foundation through its bottom z0.
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fricon/contact/contact_surface.hpp"
#include "fricon/contact/patches.hpp"
#include "fricon/core/types.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::test {

// ------------------------------------------------------------------------------------------
// The clamped brick.

/// The dof map of `m` with every component (x, y, z) of the nodes on boundary `clamp` fixed (by
/// default "x0", the brick's clamped end), and also the single components `extra`, given as
/// (node, component) pairs with component 0, 1 or 2.
fe::DofMap clamped_dofs(const mesh::TetMesh& m, const std::string& clamp = "x0",
                        const std::vector<std::array<Index, 2>>& extra = {});

/// The brick clamped at x0 with its contact surface z0, and what the contact tests build on it.
struct ClampedBrick {
  mesh::TetMesh mesh;
  fe::DofMap dofs{0};               ///< clamped_dofs(mesh): x0 clamped
  contact::ContactSurface surface;  ///< make_contact_surface on "z0"
  contact::Patches patches;         ///< the paper's chessboard; empty without one
  SparseMatrix B;                   ///< assemble_b on the chessboard; empty without one
};

/// Whether clamped_brick builds the chessboard patches and their B (the chessboard needs an even
/// number of cells along x and y).
enum class Chessboard { Yes, No };

/// The brick of edge lengths `size` [m] with `cells` cubes per direction, clamped at x0, its
/// contact surface z0 (whose where-string in messages is "test"), and, by default, the paper's
/// chessboard patches and B.
ClampedBrick clamped_brick(const std::array<Index, 3>& cells,
                           Chessboard chessboard = Chessboard::Yes,
                           const Vec3& size = Vec3(3.0, 1.0, 1.0));

/// The paper's brick for mesh parameter n (3n x n x n cubes, n even), with its chessboard.
ClampedBrick paper_brick(Index n);

/// A driver::Problem of the brick with every section a valid run needs and nothing more: the
/// default mesh ([mesh] defaults: 3 x 1 x 1 m, 12 x 4 x 4 cells) and material, clamped at x0,
/// pulled at x1 by the traction (1e7, 0, 2e7) Pa, and, with `with_contact`, a [contact] section
/// of default options (contact on z0).
driver::Problem clamped_problem(bool with_contact = true);

/// Lists the triangles of boundary `tag` of `m` again under a new tag `second`, on the same Gmsh
/// entities (as a mesh file that puts a face in two physical groups).
void add_second_tag(mesh::TetMesh& m, const std::string& tag, const std::string& second);

// ------------------------------------------------------------------------------------------
// The gravity column.

/// The column's weight per volume b0 [N/m^3] and its height H [m]: the foundation carries a
/// uniform pressure b0 H / 2.
inline constexpr Real kColumnWeight = 7.8e4;
inline constexpr Real kColumnHeight = 2.0;

/// A column (0,1) x (0,1) x (0,H) m (4 x 4 x 8 cells, E = 1e9 Pa, nu = 0.3) clamped on top (z1),
/// on rollers at its four sides, under its own weight (0, 0, -b0), resting on the foundation at
/// z = 0 ([contact] of default options), QP tolerance 1e-12. The solution depends on z only and
/// u_z vanishes at both ends, so each end carries half the weight: a uniform contact pressure
/// b0 H / 2 and no tangential displacement.
driver::Problem gravity_column();

// ------------------------------------------------------------------------------------------
// Files.

/// A fresh folder for the running test, removed with its contents at the end of the object's
/// life: <system temporary folder>/fricon_<test suite>_<test>_<process id>, so that tests that
/// CTest runs at the same time never share one.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Writes `text` byte for byte to the file `name` in the folder; returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const;

 private:
  std::filesystem::path path_;
};

/// A GoogleTest fixture that gives each of its tests a fresh folder, dir_.
class TempDirTest : public ::testing::Test {
 protected:
  /// The message of the InputError that `read` throws on the file `name` of dir_ holding
  /// `text`, or "" when it throws none; any other exception goes through.
  std::string read_error(const std::string& name, const std::string& text,
                         const std::function<void(const std::filesystem::path&)>& read) const;

  const TempDir dir_;
};

/// A file or folder of this repository, by its path relative to the top (e.g.
/// "examples/paper-brick.toml").
std::filesystem::path source_path(const std::string& relative);

/// A folder of the third-party data beside the repository (../shared/data/<name>), which may be
/// absent: tests that need it skip (GTEST_SKIP) without it.
std::filesystem::path shared_data(const std::string& name);

// ------------------------------------------------------------------------------------------
// Errors.

/// The message of the InputError that `f` throws, or "" when it throws none; any other exception
/// goes through.
std::string input_error_of(const std::function<void()>& f);

/// Runs `f`, which must throw InputError whose message contains every one of `parts` (a failure
/// of the current test otherwise).
void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& parts);

}  // namespace fricon::test
