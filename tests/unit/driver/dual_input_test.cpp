// driver: the good files of the dual-solve corpus (tests/dual_input, hand-made; their exit codes
// and messages are checked end to end by tests/regression/check_dual_input.py) solved to the
// reactions their .expect files give ("r: ..."), worked out by hand from each file's W and q.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/driver/local_solve.hpp"
#include "fricon/io/local_problem_file.hpp"

namespace fricon::driver {
namespace {

namespace fs = std::filesystem;

constexpr double kReactionTolerance = 1e-8;  // absolute, on reactions of order 1

// The reactions that NAME.expect gives, or none.
std::vector<double> expected_reactions(const fs::path& expect) {
  std::ifstream in(expect);
  std::string line;
  std::vector<double> r;
  while (std::getline(in, line))
    if (line.rfind("r:", 0) == 0) {
      std::istringstream numbers(line.substr(2));
      for (double x; numbers >> x;)
        r.push_back(x);
    }
  return r;
}

TEST(DualInputCorpus, GoodFilesSolveToTheirKnownReactions) {
  const fs::path corpus = test::source_path("tests/dual_input");
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(corpus)) {
    const fs::path& file = entry.path();
    if (file.extension() == ".expect" || file.extension() == ".md") continue;
    const std::vector<double> r = expected_reactions(fs::path(file).replace_extension(".expect"));
    if (r.empty()) continue;
    const qp::LocalProblem p = io::read_local_problem(file);
    const LocalSolution s = solve_local(p);
    ASSERT_TRUE(s.solved) << file << ": " << s.reason;
    ASSERT_EQ(s.r.size(), static_cast<Index>(r.size())) << file;
    for (size_t k = 0; k < r.size(); ++k)
      EXPECT_NEAR(s.r(static_cast<Index>(k)), r[k], kReactionTolerance) << file << ", entry " << k;
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

}  // namespace
}  // namespace fricon::driver
