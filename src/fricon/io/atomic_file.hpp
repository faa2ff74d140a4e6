#pragma once
// io: files are written atomically. The content goes to a temporary file beside the target,
// which is renamed over the target only once the writing succeeded, so an interrupted or failed
// run never leaves a file that looks complete.

#include <filesystem>
#include <functional>
#include <ostream>

namespace fricon::io {

/// Writes `path` through `write`, atomically: to "<path>.tmp" first, then renamed. Creates the
/// parent folder if needed. Throws fricon::OutputError naming the file and the system's reason
/// if anything fails (a folder that cannot be created, a file that cannot be opened, a full
/// disk); the temporary file is removed.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);

}  // namespace fricon::io
