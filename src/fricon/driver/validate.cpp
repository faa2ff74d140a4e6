// driver: validate(Problem), the one place where the values of a problem are checked.
#include "fricon/driver/problem.hpp"

namespace fricon::driver {

void validate(const Problem&) {}

}  // namespace fricon::driver
