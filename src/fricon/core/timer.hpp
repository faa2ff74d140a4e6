#pragma once
// core: wall-clock timing of named phases (read, mesh, assembly, factorize, contact, qp, ...).

#include <chrono>
#include <map>
#include <string>

namespace fricon {

/// Accumulated wall time [s] and call count per named phase, in insertion-independent order.
struct PhaseTimes {
  struct Entry {
    double seconds = 0.0;
    int calls = 0;
  };
  std::map<std::string, Entry> phases;

  void add(const std::string& name, double seconds) {
    auto& e = phases[name];
    e.seconds += seconds;
    e.calls += 1;
  }
  double seconds(const std::string& name) const {
    auto it = phases.find(name);
    return it == phases.end() ? 0.0 : it->second.seconds;
  }
};

/// Wall-clock stopwatch started at construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  /// Seconds since construction or the last restart().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Adds the lifetime of the scope to `times` under `name`.
class ScopedPhase {
 public:
  ScopedPhase(PhaseTimes& times, std::string name) : times_(times), name_(std::move(name)) {}
  ~ScopedPhase() { times_.add(name_, watch_.seconds()); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimes& times_;
  std::string name_;
  Stopwatch watch_;
};

}  // namespace fricon
