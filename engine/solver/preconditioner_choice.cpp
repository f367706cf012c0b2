// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/preconditioner_choice.hpp"

#include "solver/multigrid.hpp"
#include "solver/pcg.hpp"

namespace dda {

Preconditioning choose_preconditioning(Preconditioning requested, const SystemTraits& traits) {
  if (requested != Preconditioning::Auto) return requested;
  if (traits.blocks < kMultigridMinBlocks) return Preconditioning::BlockJacobi;
  if (!traits.last_kind || *traits.last_kind == Preconditioning::Auto) return Preconditioning::BlockJacobi;
  if (*traits.last_kind == Preconditioning::BlockJacobi)
    return traits.last_cg_per_solve > kToMultigrid ? Preconditioning::Multigrid : Preconditioning::BlockJacobi;
  return traits.last_cg_per_solve < kToBlockJacobi ? Preconditioning::BlockJacobi : Preconditioning::Multigrid;
}

std::unique_ptr<Preconditioner> make_preconditioner(Preconditioning kind) {
  switch (kind) {
    case Preconditioning::Auto:
    case Preconditioning::BlockJacobi:
      return std::make_unique<BlockJacobi>();
    case Preconditioning::Multigrid:
      return std::make_unique<Multigrid>();
  }
  return std::make_unique<BlockJacobi>();
}

}  // namespace dda
