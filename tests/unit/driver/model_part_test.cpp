// driver::model_part, the parts of the model that the ranks of a distributed run assemble from
// their own tetrahedra (each a model of its own, numbered within the part). Their f and K, mapped
// to the whole model and summed, are the whole model's, for every kind of load (tractions, a volume
// force, the coupling to prescribed displacements), however the tetrahedra are split.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "fricon/core/error.hpp"
#include "fricon/driver/model_part.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/io/problem_file.hpp"

namespace fricon::driver {
namespace {

constexpr double kRoundoff = 1e-13;  // relative: the same sums in another order

// A brick with every kind of load: tractions on two faces, gravity, and a prescribed
// displacement of one face (which couples into f through K).
constexpr const char* kProblem = R"(
volume_force = [0.0, 1.0e3, -7.8e4]
[mesh]
kind = "brick"
size = [3.0, 1.0, 1.0]
cells = [6, 3, 2]
[material]
model = "isotropic"
young = 2.0e11
poisson = 0.3
[[dirichlet]]
boundary = "x0"
components = "xyz"
[[dirichlet]]
boundary = "x1"
components = "z"
value = [0.0, 0.0, -1.0e-4]
[[traction]]
boundary = "z1"
value = [1.0e6, 0.0, -3.0e7]
[[traction]]
boundary = "y0"
value = [0.0, 2.0e6, 0.0]
)";

struct Loads {
  Problem problem = io::parse_problem(kProblem, "model_part_test.toml");
  Model model;
  Loads() {
    PhaseTimes times;
    model = assemble_model(problem, times);
  }
  // Tetrahedron t in part part_of(t) in [0, n_parts), as lists.
  template <class PartOf>
  std::vector<std::vector<Index>> split(int n_parts, PartOf part_of) const {
    std::vector<std::vector<Index>> parts(static_cast<size_t>(n_parts));
    for (Index t = 0; t < model.mesh.n_tets(); ++t)
      parts[static_cast<size_t>(part_of(t))].push_back(t);
    return parts;
  }
};

TEST(ModelPart, AllTetrahedraAreTheWholeModel) {
  const Loads l;
  std::vector<Index> all(static_cast<size_t>(l.model.mesh.n_tets()));
  std::iota(all.begin(), all.end(), Index{0});
  const ModelPart part = model_part(l.model, all);
  std::vector<Index> every_dof(static_cast<size_t>(l.model.dofs.n_free()));
  std::iota(every_dof.begin(), every_dof.end(), Index{0});
  EXPECT_EQ(part.global_dof, every_dof);
  const VectorXd f = load_vector(l.problem, part.model, Extent::Part);
  EXPECT_LT((f - l.model.f).norm(), kRoundoff * l.model.f.norm());
}

// A part may hold no triangle of a traction's boundary; the whole body may not.
TEST(ModelPart, APartWithoutATractionsTrianglesHasNoTraction) {
  const Loads l;
  Index inner = -1;  // a tetrahedron without boundary triangles (a cube's central one)
  for (Index t = 0; t < l.model.mesh.n_tets() && inner < 0; ++t) {
    const std::vector<bool> faces = mesh::faces_of(l.model.mesh, {t});
    if (std::none_of(faces.begin(), faces.end(), [](bool b) { return b; })) inner = t;
  }
  ASSERT_GE(inner, 0);
  const ModelPart part = model_part(l.model, {inner});
  ASSERT_EQ(part.model.mesh.n_faces(), 0);
  EXPECT_NO_THROW(load_vector(l.problem, part.model, Extent::Part));
  EXPECT_THROW(load_vector(l.problem, part.model, Extent::Whole), InputError);
}

// A part of the model on its own: its K and f, mapped by global_dof and summed over the parts,
// are the K and f of the whole model; each part holds only the nodes of its tetrahedra.
TEST(ModelPart, PartsOfAnySplitSumToTheWholeStiffnessAndLoad) {
  const Loads l;
  const Index n = l.model.mesh.n_tets();
  for (const auto& parts : {l.split(3, [](Index t) { return static_cast<int>(t % 3); }),
                            l.split(2, [n](Index t) { return t < n / 2 ? 0 : 1; })}) {
    std::vector<Eigen::Triplet<Real>> K_entries;
    VectorXd f = VectorXd::Zero(l.model.dofs.n_free());
    Index n_tets = 0;
    for (const auto& elements : parts) {
      const ModelPart part = model_part(l.model, elements);
      const std::vector<Index>& global = part.global_dof;
      ASSERT_TRUE(std::is_sorted(global.begin(), global.end()));
      ASSERT_EQ(static_cast<Index>(global.size()), part.model.dofs.n_free());
      EXPECT_LT(part.model.mesh.n_nodes(), l.model.mesh.n_nodes());
      n_tets += part.model.mesh.n_tets();
      const SparseMatrix K_part =
          fe::assemble_stiffness(part.model.mesh, part.model.materials, part.model.dofs);
      for (Index j = 0; j < K_part.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(K_part, j); it; ++it)
          K_entries.emplace_back(global[static_cast<size_t>(it.row())],
                                 global[static_cast<size_t>(j)], it.value());
      const VectorXd f_part = load_vector(l.problem, part.model, Extent::Part);
      for (size_t k = 0; k < global.size(); ++k)
        f(global[k]) += f_part(static_cast<Index>(k));
    }
    SparseMatrix K(l.model.K.rows(), l.model.K.cols());
    K.setFromTriplets(K_entries.begin(), K_entries.end());
    EXPECT_EQ(n_tets, n);
    EXPECT_LT((K - l.model.K).norm(), kRoundoff * l.model.K.norm());
    EXPECT_LT((f - l.model.f).norm(), kRoundoff * l.model.f.norm());
  }
}

}  // namespace
}  // namespace fricon::driver
