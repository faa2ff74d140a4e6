#include "fricon/feti/feti_options.hpp"

namespace fricon::feti {

// Apart from partition.cpp, so that the problem reader's checks need no METIS to link (the
// fuzzing build compiles the readers alone).
bool metis_available() {
#ifdef FRICON_HAVE_METIS
  return true;
#else
  return false;
#endif
}

}  // namespace fricon::feti
