#pragma once
// io: frictional contact problems of other codes in FCLIB's HDF5 format (Debian libfclib-dev):
// local problems (W, q, mu) as they are, global problems (M, H, f, w, mu) reduced to local form
// W = H^T M^-1 H, q = H^T M^-1 f + w (M factored by a sparse Cholesky); and the solution of a
// local problem written in FCLIB's layout, with FCLIB's own merit function.

#include <filesystem>

#include "fricon/qp/local_problem.hpp"

namespace fricon::io {

/// Whether the file starts with HDF5's signature.
bool is_hdf5_file(const std::filesystem::path& path);

/// Reads an FCLIB file: its local problem, or its global problem reduced to local form, with its
/// solution r when the file has one. Throws InputError naming the file when it is not FCLIB, is
/// not 3D, has equality constraints (V, R or G), or M is not positive definite.
qp::LocalProblem read_fclib(const std::filesystem::path& path);

/// FCLIB's merit (fclib_merit_local, MERIT_1) of the reactions r and velocities u = W r + q.
double fclib_merit(const qp::LocalProblem& problem, const VectorXd& r, const VectorXd& u);

/// Writes the local problem and its solution (r, u) as an FCLIB file (atomically: a failed write
/// leaves no file). Throws Error when HDF5 cannot write it.
void write_fclib_solution(const std::filesystem::path& path, const qp::LocalProblem& problem,
                          const VectorXd& r, const VectorXd& u);

}  // namespace fricon::io
