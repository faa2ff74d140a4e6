#pragma once
// io: frictional contact problems in Siconos' own text format (".dat", as its
// frictionContact_printInFile and globalFrictionContact_printInFile write them):
//   local   dimension, n_contacts, W (a NumericsMatrix), q, mu
//   global  dimension, n_contacts, M, H, q, b, mu   (M v = H r + q, u = H^T v + b)
// with the matrices dense (storage 0, column-major) or sparse-block (storage 1), optionally
// followed by one flag 0 or 1 (written by Siconos before 2010; docs/dual-format.md). Which of the
// two it is, the file says only by how its tokens add up: both readings are tried to the end of
// the file, and exactly one must fit. A global problem is reduced to local form,
// W = H^T M^-1 H and q_local = H^T M^-1 q + b.

#include <filesystem>

#include "fricon/qp/local_problem.hpp"

namespace fricon::io {

/// Reads the problem. Throws InputError naming the file and what is wrong, with the line of the
/// token at fault: not 3D, a storage that is not dense or sparse-block, a sparse-block structure
/// that contradicts the sizes, a token that is not the integer or finite number expected, a file
/// that ends early or has tokens left over, sizes that fit neither a local nor a global problem
/// (then why not, for each) or both, M not positive definite.
qp::LocalProblem read_siconos_dat(const std::filesystem::path& path);

}  // namespace fricon::io
