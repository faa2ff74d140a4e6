#include "fricon/io/atomic_file.hpp"

#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::io {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec)
      throw Error(
          fmt::format("cannot create folder {}: {}", path.parent_path().string(), ec.message()));
  }
  fs::path tmp = path;
  tmp += ".tmp";
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(fmt::format("cannot open {} for writing", tmp.string()));
    write(out);
    out.flush();
    if (!out) throw Error(fmt::format("writing {} failed (disk full?)", tmp.string()));
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(
        fmt::format("cannot rename {} to {}: {}", tmp.string(), path.string(), ec.message()));
  }
}

}  // namespace fricon::io
