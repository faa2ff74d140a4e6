#pragma once
// Shared by the size-scan benchmarks: run one measurement in a child process, so that the peak
// resident memory it reports is that of one problem size alone, and a size that runs out of
// memory fails on its own row instead of ending the scan.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <optional>
#include <type_traits>

namespace fricon::bench {

/// Peak resident memory of this process so far [MiB] (ru_maxrss is in KiB on Linux).
inline double peak_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

/// Runs `measure()` in a forked child and returns the Row it produced (a trivially copyable
/// struct sent back through a pipe), or nothing if the child failed, was killed or exited with
/// a non-zero status.
template <class Measure>
auto run_in_child(Measure measure) -> std::optional<decltype(measure())> {
  using Row = decltype(measure());
  static_assert(std::is_trivially_copyable_v<Row>);
  std::fflush(stdout);  // the child must not inherit (and print again) buffered output
  int fd[2];
  if (pipe(fd) != 0) return std::nullopt;
  const pid_t pid = fork();
  if (pid < 0) return std::nullopt;
  if (pid == 0) {
    close(fd[0]);
    const Row r = measure();
    _exit(write(fd[1], &r, sizeof r) == static_cast<ssize_t>(sizeof r) ? 0 : 3);
  }
  close(fd[1]);
  Row r;
  const bool ok = read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!ok || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return r;
}

}  // namespace fricon::bench
