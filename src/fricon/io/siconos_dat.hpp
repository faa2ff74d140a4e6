#pragma once
// io: frictional contact problems in Siconos' own text format (".dat", as its
// frictionContact_printInFile and globalFrictionContact_printInFile write them):
//   local   dimension, n_contacts, W (a NumericsMatrix), q, mu
//   global  dimension, n_contacts, M, H, q, b, mu   (M v = H r + q, u = H^T v + b)
// with the matrices dense (storage 0, column-major) or sparse-block (storage 1). A global problem
// is reduced to local form, W = H^T M^-1 H and q_local = H^T M^-1 q + b.

#include <filesystem>

#include "fricon/qp/local_problem.hpp"

namespace fricon::io {

/// Reads the problem. Throws InputError naming the file and what is wrong (not 3D, a storage
/// that is not dense or sparse-block, a truncated file, M not positive definite).
qp::LocalProblem read_siconos_dat(const std::filesystem::path& path);

}  // namespace fricon::io
