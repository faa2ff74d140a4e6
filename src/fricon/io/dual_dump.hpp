#pragma once
// io: the dual problem of one Tresca step as a plain text file ("fricon dual v1"), so that other
// solvers (Siconos, FCLIB tools, Python) can be run on exactly the QP that fricon solves:
//
//   minimise 1/2 l^T Q l - l^T h  over  l_n,i >= 0,  ||(l_t1,i, l_t2,i)|| <= radius_i,
//
// unknowns ordered (n, t1, t2) per patch. The layout, the units and the mapping to the FCLIB /
// Siconos "local" formulation are documented in docs/dual-format.md. In short:
//
//   # fricon dual v1                 magic line (line 1, exactly)
//   source <text>                    where the problem came from (\\, \n, \r escaped)
//   patches <m>
//   patch_data <m> 5                 then m rows: h_n h_t1 h_t2 radius area
//   Q <3m> <3m>                      then 3m rows of 3m numbers (full, row-major)
//   end
//
// Lines starting with '#' and blank lines are comments everywhere after line 1. Numbers are
// written in the shortest form that reads back to the same double, so a round trip is exact.

#include <filesystem>
#include <string>

#include "fricon/qp/dual_problem.hpp"

namespace fricon::io {

/// The magic first line of a dual file.
inline constexpr const char* kDualMagic = "# fricon dual v1";

/// Writes `dual` to `path` atomically (see atomic_file.hpp). Throws fricon::Error if the sizes
/// are inconsistent (Q not 3m x 3m, h not 3m, patch_area not m, with m = radius.size() >= 1) or
/// a value is not finite, and when the file cannot be written.
void write_dual(const std::filesystem::path& path, const qp::DualProblem& dual);

/// Reads a "fricon dual v1" file. Throws fricon::InputError naming the file and the line
/// ("file:line: ...") on malformed input: wrong magic line, missing or misspelt keyword, wrong
/// counts, a token that is not a finite number, a negative radius, a non-positive area, a Q
/// that is not symmetric (|Q_ij - Q_ji| > 1e-8 max|Q|) or has a non-positive diagonal entry,
/// or text after `end`. Positive definiteness is not checked.
qp::DualProblem read_dual(const std::filesystem::path& path);

}  // namespace fricon::io
