#include "solver/preconditioner_choice.hpp"

#include "core/error.hpp"
#include "world/world.hpp"

namespace dda {

Preconditioning choose_preconditioning(Preconditioning requested, const SystemTraits& /*traits*/) {
  if (requested != Preconditioning::Auto) return requested;
  return Preconditioning::BlockJacobi;
}

std::unique_ptr<Preconditioner> make_preconditioner(Preconditioning kind) {
  switch (kind) {
    case Preconditioning::Auto:
    case Preconditioning::BlockJacobi: return std::make_unique<BlockJacobi>();
    case Preconditioning::Multigrid: throw Error("controls: the multigrid preconditioner is not available in this build");
  }
  return std::make_unique<BlockJacobi>();
}

}  // namespace dda
