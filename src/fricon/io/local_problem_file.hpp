#pragma once
// io: a local frictional contact problem from a file of any format fricon reads, told apart by
// its first bytes: FCLIB (HDF5: local, or global reduced to local; fclib_file.hpp), Siconos' text
// format (.dat; siconos_dat.hpp) or fricon's own dual dump ("# fricon dual v1": a Tresca problem,
// dual_dump.hpp).

#include <filesystem>

#include "fricon/qp/local_problem.hpp"

namespace fricon::io {

/// Reads the problem. Throws InputError naming the file for an unknown or malformed format.
qp::LocalProblem read_local_problem(const std::filesystem::path& path);

}  // namespace fricon::io
