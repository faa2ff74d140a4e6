#include "fricon/parallel/mpi/test_fault.hpp"

#include <algorithm>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/session.hpp"

namespace fricon::parallel {

namespace {

constexpr const char* kVariable = "FRICON_TEST_FAULT";

enum class FaultKind { BadAlloc, Numerical, Generic };

// FRICON_TEST_FAULT as read once per process; `active` is false without the variable.
struct Fault {
  bool active = false;
  std::string phase;
  int rank = -1;
  FaultKind kind = FaultKind::Generic;
  std::string message;  // what() of the exception thrown
  bool thrown = false;  // once per process
};

bool known_phase(std::string_view phase) {
  return std::find(std::begin(kFaultPhases), std::end(kFaultPhases), phase) !=
         std::end(kFaultPhases);
}

Fault read_fault() {
  Fault f;
  const char* value = std::getenv(kVariable);
  if (value == nullptr || *value == '\0') return f;
  const std::string v = value;
  const auto malformed = [&v] {
    return InputError(fmt::format(
        "{}={}: expected <phase>:<rank>:<kind> with a phase of a distributed run (model, share, "
        "partition, scatter, assembly, analysis, factorize, schur, setup, outer, solve, gather), "
        "a rank and a kind (bad_alloc, numerical, generic); this variable is for the tests only",
        kVariable, v));
  };
  const std::size_t a = v.find(':'), b = a == std::string::npos ? a : v.find(':', a + 1);
  if (b == std::string::npos) throw malformed();
  f.phase = v.substr(0, a);
  const std::string rank = v.substr(a + 1, b - a - 1), kind = v.substr(b + 1);
  char* end = nullptr;
  const long r = std::strtol(rank.c_str(), &end, 10);
  if (!known_phase(f.phase) || rank.empty() || *end != '\0' || r < 0) throw malformed();
  f.rank = static_cast<int>(r);
  if (kind == "bad_alloc")
    f.kind = FaultKind::BadAlloc;
  else if (kind == "numerical")
    f.kind = FaultKind::Numerical;
  else if (kind == "generic")
    f.kind = FaultKind::Generic;
  else
    throw malformed();
  f.message = fmt::format("injected fault {}={}", kVariable, v);
  f.active = true;
  return f;
}

Fault& fault() {
  static Fault f = read_fault();
  return f;
}

// A std::bad_alloc that says where it comes from.
class InjectedBadAlloc : public std::bad_alloc {
 public:
  explicit InjectedBadAlloc(const char* message) : message_(message) {}
  const char* what() const noexcept override { return message_; }

 private:
  const char* message_;  // Fault::message, which lives as long as the process
};

}  // namespace

void test_fault(std::string_view phase) {
  FRICON_ASSERT(known_phase(phase), "test_fault: unknown phase " << phase);
  Fault& f = fault();
  if (!f.active || f.thrown || phase != f.phase || world_rank() != f.rank) return;
  f.thrown = true;
  switch (f.kind) {
    case FaultKind::BadAlloc:
      throw InjectedBadAlloc(f.message.c_str());
    case FaultKind::Numerical:
      throw NumericalError(f.message);
    case FaultKind::Generic:
      throw std::runtime_error(f.message);
  }
}

}  // namespace fricon::parallel
