#include "common/fixtures.hpp"

#include <unistd.h>

#include <fstream>

#include <gtest/gtest.h>

#include "fricon/contact/b_matrix.hpp"
#include "fricon/core/error.hpp"
#include "fricon/mesh/brick.hpp"

namespace fricon::test {

namespace fs = std::filesystem;

fe::DofMap clamped_dofs(const mesh::TetMesh& m, const std::string& clamp,
                        const std::vector<std::array<Index, 2>>& extra) {
  std::vector<bool> fixed(static_cast<size_t>(3 * m.n_nodes()), false);
  for (Index a : m.nodes_with_tag(clamp))
    for (int c = 0; c < 3; ++c)
      fixed[static_cast<size_t>(3 * a + c)] = true;
  for (const auto& [a, c] : extra)
    fixed[static_cast<size_t>(3 * a + c)] = true;
  return fe::DofMap(fixed);
}

ClampedBrick clamped_brick(const std::array<Index, 3>& cells, Chessboard chessboard,
                           const Vec3& size) {
  ClampedBrick b;
  b.mesh = mesh::make_brick({size, cells});
  b.dofs = clamped_dofs(b.mesh);
  b.surface = contact::make_contact_surface(b.mesh, b.dofs, "z0", "test");
  if (chessboard == Chessboard::Yes) {
    b.patches = contact::chessboard_patches(b.mesh, b.surface, "test");
    b.B = contact::assemble_b(b.mesh, b.dofs, b.surface, b.patches);
  }
  return b;
}

ClampedBrick paper_brick(Index n) {
  return clamped_brick({3 * n, n, n});
}

void add_second_tag(mesh::TetMesh& m, const std::string& tag, const std::string& second) {
  const std::vector<Index> faces = m.faces_with_tag(tag);
  const Index n = m.n_faces();
  m.faces.conservativeResize(3, n + static_cast<Index>(faces.size()));
  m.tag_names.push_back(second);
  for (size_t k = 0; k < faces.size(); ++k) {
    m.faces.col(n + static_cast<Index>(k)) = m.faces.col(faces[k]);
    m.face_tag.push_back(static_cast<int>(m.tag_names.size()) - 1);
    m.face_entity.push_back(m.face_entity[static_cast<size_t>(faces[k])]);
  }
}

driver::Problem clamped_problem(bool with_contact) {
  driver::Problem p;
  p.dirichlet.push_back({"x0", {true, true, true}});
  p.traction.push_back({"x1", Vec3(1e7, 0.0, 2e7)});
  if (with_contact) p.contact.emplace_back();
  return p;
}

driver::Problem gravity_column() {
  driver::Problem p;
  p.mesh.size = {1.0, 1.0, kColumnHeight};
  p.mesh.cells = {4, 4, 8};
  p.material.young = 1e9;
  p.material.poisson = 0.3;
  p.dirichlet = {{"z1", {true, true, true}},
                 {"x0", {true, false, false}},
                 {"x1", {true, false, false}},
                 {"y0", {false, true, false}},
                 {"y1", {false, true, false}}};
  p.volume_force = Vec3(0, 0, -kColumnWeight);
  p.contact = {driver::ContactOptions{}};
  p.solver.qp.rel_tolerance = 1e-12;
  return p;
}

TempDir::TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name =
      "fricon_" + (info ? std::string(info->test_suite_name()) + "_" + info->name() : "no_test") +
      "_" + std::to_string(::getpid());
  for (char& c : name)  // parameterized tests' names hold a '/'
    if (c == '/') c = '_';
  path_ = fs::temp_directory_path() / name;
  fs::remove_all(path_);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;  // a destructor must not throw
  fs::remove_all(path_, ignored);
}

fs::path TempDir::write(const std::string& name, const std::string& text) const {
  const fs::path p = path_ / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string TempDirTest::read_error(const std::string& name, const std::string& text,
                                    const std::function<void(const fs::path&)>& read) const {
  const fs::path p = dir_.write(name, text);
  return input_error_of([&] { read(p); });
}

fs::path source_path(const std::string& relative) {
  return fs::path(FRICON_SOURCE_DIR) / relative;
}

fs::path shared_data(const std::string& name) {
  return fs::path(FRICON_SHARED_DIR) / "data" / name;
}

std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  const std::string message = input_error_of(f);
  if (message.empty()) {
    ADD_FAILURE() << "no InputError thrown";
    return;
  }
  for (const auto& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

}  // namespace fricon::test
