#pragma once
// driver: the model example of [HL09] (theory.md §7.1-7.2) and the paper's Tables 1 and 2
// (theory.md §7.3-7.4), so that `fricon paper` can print our numbers beside theirs.

#include <vector>

#include "fricon/driver/problem.hpp"

namespace fricon::driver {

/// The paper's brick for mesh parameter n (3n x n x n cubes) and friction parameter `param`,
/// with the paper's tolerances (outer 1e-4, QP 1e-6).
Problem paper_problem(Index n, Real param);

/// One row of the paper's Tables 1 and 2 (values as printed there).
struct PaperRow {
  Index n;
  Real param;
  Index n_p, n_d;
  int it;
  long n_mult;
  double time_s;    ///< on 2007 hardware
  Real wn_pos_l2;   ///< ||w_hn^+||_0
  Real wn_pos_inf;  ///< ||w_hn^+||_inf
};

/// Table 1 (param = 6e4, n = 4..16).
const std::vector<PaperRow>& paper_table1();
/// Table 2 (n = 16, param = 2e4, 6e4, 3e5).
const std::vector<PaperRow>& paper_table2();

}  // namespace fricon::driver
