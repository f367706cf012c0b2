// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The ControlStep stage's vocabulary: why an attempt at a step is rejected.
// A rejected attempt is redone: with the same Δt after the automatic contact
// range widened (BeyondContactRange), otherwise with Δt cut by cut_factor.
namespace dda {

enum class Rejection {
  None,
  OpenCloseUnsettled,
  DisplacementTooLarge,
  PenetrationTooDeep,
  SolverNotConverged,
  BlockInverted,
  BeyondContactRange
};

inline const char* describe(Rejection r) {
  switch (r) {
    case Rejection::None:
      return "accepted";
    case Rejection::OpenCloseUnsettled:
      return "the open-close iteration did not settle";
    case Rejection::DisplacementTooLarge:
      return "a vertex moved more than the g2 bound in one step";
    case Rejection::PenetrationTooDeep:
      return "a contact penetrated deeper than the g2 bound";
    case Rejection::SolverNotConverged:
      return "the linear solver did not converge";
    case Rejection::BlockInverted:
      return "a block would turn inside out (its area would become zero or negative)";
    case Rejection::BeyondContactRange:
      return "a vertex moved more than the contact range allows in one step (range / 2.5)";
  }
  return "?";
}

}  // namespace dda
