#include "fricon/feti/preconditioner.hpp"

namespace fricon::feti {

std::unique_ptr<const Preconditioner> make_preconditioner(FetiPreconditioner kind,
                                                          const FetiOperator& F) {
  switch (kind) {
    case FetiPreconditioner::Lumped:
      return make_lumped_preconditioner(F);
    case FetiPreconditioner::None:
      break;
  }
  return nullptr;
}

}  // namespace fricon::feti
