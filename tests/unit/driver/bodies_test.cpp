// The rigid-motion check per connected body (issue 23, defect 8): on a mesh of several bodies that
// share no node, a body that its own [[dirichlet]] conditions do not hold is refused before
// assembly, by a message that names it (index, region, bounding box), the entries on it and the
// rigid motions left free; bodies that are all held give a model that keeps its bodies
// (Model::bodies) and a K that factorizes.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "fricon/core/error.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/io/problem_file.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/brick.hpp"

namespace fricon::driver {
namespace {

// Bricks side by side along x, 2 m apart: brick i is [2 i + ..., 2 i + 1] x [0, 1] x [0, 1] (its
// tags and region prefixed "a_", "b_", "c_").
std::shared_ptr<const mesh::TetMesh> bricks(int n) {
  std::vector<mesh::TetMesh> parts;
  std::vector<std::string> prefixes;
  for (int i = 0; i < n; ++i) {
    mesh::TetMesh m = mesh::make_brick({Vec3(1, 1, 1), {2, 2, 2}});
    m.nodes.colwise() += Vec3(2.0 * i, 0, 0);
    parts.push_back(std::move(m));
    prefixes.push_back(std::string(1, static_cast<char>('a' + i)) + "_");
  }
  return std::make_shared<const mesh::TetMesh>(mesh::disjoint_union(parts, prefixes));
}

// A problem on `n` bricks with the [[dirichlet]] entries `dirichlet` (TOML text).
Problem problem_on(int n, const std::string& dirichlet) {
  io::ReadOptions options;
  options.code.mesh = bricks(n);
  return io::parse_problem(R"(
[mesh]
kind = "arrays"
[material]
young = 2.0e11
poisson = 0.3
)" + dirichlet + R"(
[[traction]]
boundary = "b_x1"
value = [0.0, 0.0, -1.0e7]
)",
                           "t.toml", options);
}

constexpr const char* kClampA = "[[dirichlet]]\nboundary = \"a_x0\"\ncomponents = \"xyz\"\n";
constexpr const char* kClampB = "[[dirichlet]]\nboundary = \"b_x0\"\ncomponents = \"xyz\"\n";
constexpr const char* kRollerB = "[[dirichlet]]\nboundary = \"b_z0\"\ncomponents = \"z\"\n";

// The message of the InputError that assemble_model throws for `problem` (empty if none).
std::string assembly_error(const Problem& problem) {
  try {
    PhaseTimes times;
    (void)assemble_model(problem, times);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "no InputError";
  for (const auto& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST(DirichletPerBody, AFreeBodyNextToAClampedOneIsNamed) {
  expect_contains(assembly_error(problem_on(2, kClampA)),
                  {"t.toml:", ": dirichlet: the mesh has 2 separate bodies",
                   "body 1 (region \"b_body\", 27 nodes in [2, 3] x [0, 1] x [0, 1] m) is not held",
                   "no [[dirichlet]] entry fixes any of its nodes", "6 rigid motion(s) of it free",
                   "stiffness matrix would be singular", "contact alone does not hold a body"});
}

TEST(DirichletPerBody, ABodyOnARollerIsNamedWithItsEntriesAndLooseAxes) {
  expect_contains(assembly_error(problem_on(2, std::string(kClampA) + kRollerB)),
                  {"body 1 (region \"b_body\"",
                   "the [[dirichlet]] entries on it, dirichlet[1] (\"b_z0\"), leave 3 rigid "
                   "motion(s) of it free (no x or y component is fixed on it)"});
}

TEST(DirichletPerBody, TheFirstFreeBodyIsDescribedAndTheOthersListed) {
  const std::string message = assembly_error(problem_on(3, kClampB));
  expect_contains(message, {"3 separate bodies (0 to 2", "body 0 (region \"a_body\"",
                            "[0, 1] x [0, 1] x [0, 1] m", "; body 2 is not held either"});
  EXPECT_EQ(message.find("dirichlet[0]"), std::string::npos) << message;  // b_x0 is on body 1
}

TEST(DirichletPerBody, BodiesThatAreAllHeldGiveAModelWithItsBodiesAndAFactor) {
  const Problem problem = problem_on(2, std::string(kClampA) + kClampB);
  PhaseTimes times;
  Model model = assemble_model(problem, times);
  ASSERT_EQ(model.bodies.n_bodies(), 2);
  EXPECT_EQ(model.bodies.nodes[0].size() + model.bodies.nodes[1].size(),
            static_cast<size_t>(model.mesh.n_nodes()));
  EXPECT_NO_THROW(factorize_model(model, {}, times));
  EXPECT_NO_THROW((void)make_dofs(problem, model.mesh));  // the bodies found again
}

// One body: the message of a single body, as before (tests/bad_input/89, 90).
TEST(DirichletPerBody, OneBodyKeepsTheMessageOfTheWholeBody) {
  io::ReadOptions options;
  options.code.mesh = bricks(1);
  const Problem problem = io::parse_problem(R"(
[mesh]
kind = "arrays"
[material]
young = 2.0e11
poisson = 0.3
[[dirichlet]]
boundary = "a_z0"
components = "z"
)",
                                            "t.toml", options);
  const std::string message = assembly_error(problem);
  expect_contains(
      message, {"3 rigid motion(s) of the body free", "(no x or y component is fixed anywhere)"});
  EXPECT_EQ(message.find("separate bodies"), std::string::npos) << message;
}

}  // namespace
}  // namespace fricon::driver
