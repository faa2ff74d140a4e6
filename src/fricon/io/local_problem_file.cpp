#include "fricon/io/local_problem_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/fclib_file.hpp"
#include "fricon/io/siconos_dat.hpp"

namespace fricon::io {

qp::LocalProblem read_local_problem(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot open the problem file: {}", path.string(), std::strerror(errno)));
  std::string first;
  std::getline(in, first);
  in.close();
  if (is_hdf5_file(path)) return read_fclib(path);
  if (first.rfind(kDualMagic, 0) == 0) {
    const qp::DualProblem d = read_dual(path);
    qp::LocalProblem p;
    p.W = d.Q.sparseView();
    p.q = -d.h;
    p.threshold = d.radius;
    p.source = path.string();
    return p;
  }
  // Siconos' text format starts with the dimension (3) and the number of contacts.
  if (first.find_first_not_of(" \t\r0123456789") == std::string::npos && !first.empty())
    return read_siconos_dat(path);
  throw InputError(fmt::format(
      "{}: unknown format: fricon reads FCLIB files (HDF5), Siconos .dat files and its own dual "
      "files (\"{}\")",
      path.string(), kDualMagic));
}

}  // namespace fricon::io
