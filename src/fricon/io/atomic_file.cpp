#include "fricon/io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::io {

namespace {

// The system's reason for the last failed call, or `fallback` when it left none.
std::string reason(const char* fallback) {
  return errno != 0 ? std::strerror(errno) : fallback;
}

}  // namespace

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec)
      throw OutputError(
          fmt::format("cannot create folder {}: {}", path.parent_path().string(), ec.message()));
  }
  fs::path tmp = path;
  tmp += ".tmp";
  try {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw OutputError(
          fmt::format("cannot open {} for writing: {}", tmp.string(), reason("failed")));
    errno = 0;  // a failed write(2) of the stream leaves its reason here
    write(out);
    if (!out.fail()) out.close();  // the last buffer reaches the disk here: a full disk fails now
    if (out.fail())
      throw OutputError(
          fmt::format("writing {} failed: {}", tmp.string(), reason("the disk may be full")));
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw OutputError(fmt::format("cannot rename {} to {}: {}", tmp.string(), path.string(), why));
  }
}

}  // namespace fricon::io
