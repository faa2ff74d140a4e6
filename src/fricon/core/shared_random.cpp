#include "fricon/core/shared_random.hpp"

namespace fricon {

std::mutex& shared_random_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace fricon
