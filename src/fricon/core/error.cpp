#include "fricon/core/error.hpp"

namespace fricon::detail {

void throw_check_failure(const char* condition, const char* file, int line,
                         const std::string& message) {
  std::ostringstream os;
  os << "internal check failed: " << condition << " at " << file << ":" << line;
  if (!message.empty()) os << ": " << message;
  throw Error(os.str());
}

}  // namespace fricon::detail
