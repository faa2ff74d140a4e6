#include "fricon/io/local_problem_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/io/dual_dump.hpp"
#include "fricon/io/fclib_file.hpp"

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
  throw InputError(fmt::format(
      "{}: unknown format: fricon reads FCLIB files (HDF5) and its own dual files (\"{}\")",
      path.string(), kDualMagic));
}

}  // namespace fricon::io
