// driver::partial_load: the parts of f that the ranks of a distributed run assemble from their own
// tetrahedra sum to the f of the whole mesh, for every kind of load (tractions, a volume force,
// the coupling to prescribed displacements), however the tetrahedra are split.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "fricon/driver/model.hpp"
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
  Problem problem = io::parse_problem(kProblem, "partial_load_test.toml");
  Model model;
  Loads() {
    PhaseTimes times;
    model = assemble_loads(problem, times);
  }
  // The sum of the parts over the split of the tetrahedra by part_of(t) in [0, n_parts).
  template <class PartOf>
  VectorXd sum_of_parts(int n_parts, PartOf part_of) const {
    std::vector<std::vector<Index>> parts(static_cast<size_t>(n_parts));
    for (Index t = 0; t < model.mesh.n_tets(); ++t)
      parts[static_cast<size_t>(part_of(t))].push_back(t);
    VectorXd sum = VectorXd::Zero(model.dofs.n_free());
    for (const auto& p : parts)
      sum += partial_load(problem, model, p);
    return sum;
  }
};

TEST(PartialLoad, AllTetrahedraGiveTheWholeLoad) {
  const Loads l;
  std::vector<Index> all(static_cast<size_t>(l.model.mesh.n_tets()));
  std::iota(all.begin(), all.end(), Index{0});
  const VectorXd f = partial_load(l.problem, l.model, all);
  EXPECT_LT((f - l.model.f).norm(), kRoundoff * l.model.f.norm());
}

TEST(PartialLoad, PartsOfAnySplitSumToTheWholeLoad) {
  const Loads l;
  const Index n = l.model.mesh.n_tets();
  const VectorXd interleaved = l.sum_of_parts(3, [](Index t) { return static_cast<int>(t % 3); });
  const VectorXd blocks = l.sum_of_parts(2, [n](Index t) { return t < n / 2 ? 0 : 1; });
  EXPECT_LT((interleaved - l.model.f).norm(), kRoundoff * l.model.f.norm());
  EXPECT_LT((blocks - l.model.f).norm(), kRoundoff * l.model.f.norm());
}

TEST(PartialLoad, NoTetrahedraGiveNoLoad) {
  const Loads l;
  EXPECT_EQ(partial_load(l.problem, l.model, {}).norm(), 0.0);
}

}  // namespace
}  // namespace fricon::driver
