#pragma once
// Which preconditioner a World's PCG uses, decided once per step.
#include <memory>

#include "solver/linear_solver.hpp"

namespace dda {

enum class Preconditioning;

// Facts about the system that decide Preconditioning::Auto.
struct SystemTraits {
  int blocks = 0;
  // Largest ratio, over blocks, of contact + elastic stiffness to the inertia
  // term 2m/Δt²: small for waves (inertia-dominated), large for quasi-static.
  double stiffness_to_inertia = 0;
};

// The kind to use for these traits (Auto resolved; others returned as given).
Preconditioning choose_preconditioning(Preconditioning requested, const SystemTraits& traits);
std::unique_ptr<Preconditioner> make_preconditioner(Preconditioning kind);

}  // namespace dda
