#pragma once
// core: the exception types of fricon and the CHECK/ASSERT macros.
//
// - InputError: the user's input is wrong (file, key, value, mesh). The app exits with code 1.
// - NumericalError: a computation failed for a mathematical reason on valid input (K not positive
//   definite, an unstable multiplier space). The app exits with code 1: the input defines an
//   ill-posed problem.
// - OutputError: a result file or folder could not be written (not a folder, not writable, disk
//   full). The app exits with code 4.
// - Error: anything else fricon raises on purpose; other exceptions are internal errors (code 3).
// Non-convergence is not an exception: it is a termination value in a solver's report.

#include <sstream>
#include <stdexcept>
#include <string>

namespace fricon {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public Error {
 public:
  using Error::Error;
};

class NumericalError : public Error {
 public:
  using Error::Error;
};

/// A result file or folder could not be written or an earlier run's results could not be
/// removed (the message names the path and the system's reason).
class OutputError : public Error {
 public:
  using Error::Error;
};

/// The user asked the run to stop (Ctrl-C) at a point where there is no iterate to return yet.
class Interrupted : public Error {
 public:
  using Error::Error;
};

namespace detail {
[[noreturn]] void throw_check_failure(const char* condition, const char* file, int line,
                                      const std::string& message);
}  // namespace detail

}  // namespace fricon

/// Always-on invariant check at module boundaries: throws fricon::Error naming the condition,
/// the source location and the streamed message, e.g. FRICON_CHECK(n > 0, "n = " << n).
#define FRICON_CHECK(cond, msg)                                                                 \
  do {                                                                                          \
    if (!(cond)) {                                                                              \
      std::ostringstream fricon_check_os_;                                                      \
      fricon_check_os_ << msg;                                                                  \
      ::fricon::detail::throw_check_failure(#cond, __FILE__, __LINE__, fricon_check_os_.str()); \
    }                                                                                           \
  } while (false)

/// Debug-only invariant check, free in release builds; may sit in hot loops.
#ifndef NDEBUG
#define FRICON_ASSERT(cond, msg) FRICON_CHECK(cond, msg)
#else
#define FRICON_ASSERT(cond, msg) \
  do {                           \
  } while (false)
#endif
