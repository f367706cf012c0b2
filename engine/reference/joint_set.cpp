// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "reference/joint_set.hpp"

#include <Eigen/Dense>

#include "core/error.hpp"

namespace dda::reference {

std::complex<double> joint_set_transmission(const JointSet& set, std::complex<double> omega) {
  using C = std::complex<double>;
  using M = Eigen::Matrix2cd;
  if (set.count < 1 || !(set.spacing > 0) || !(set.stiffness > 0) || !(set.impedance > 0) || !(set.wave_speed > 0))
    throw Error("joint set reference: N ≥ 1 and positive spacing, stiffness, impedance and wave speed");
  const C wz = omega * set.impedance, ks = omega / set.wave_speed * set.spacing;
  M joint, rock;
  joint << 1.0, 1.0 / set.stiffness, 0.0, 1.0;
  rock << std::cos(ks), std::sin(ks) / wz, -wz * std::sin(ks), std::cos(ks);
  M total = joint;
  for (int n = 1; n < set.count; ++n) total = joint * rock * total;
  // Left of the first joint u = e^{ikx} + R·e^{−ikx} (x = 0 at the joint):
  // (u, σ) = (1 + R, iωZ(1 − R)); right of the last: (T, iωZ·T).
  // total·(1 + R, iωZ(1 − R)) = (T, iωZ·T): two equations in R and T.
  const C i(0, 1), z = i * wz;
  // Columns: R, T; right-hand side from the incident wave.
  Eigen::Matrix2cd a;
  Eigen::Vector2cd rhs;
  a << total(0, 0) - total(0, 1) * z, -1.0, total(1, 0) - total(1, 1) * z, -z;
  rhs << -(total(0, 0) + total(0, 1) * z), -(total(1, 0) + total(1, 1) * z);
  const Eigen::Vector2cd rt = a.partialPivLu().solve(rhs);
  return rt[1];
}

}  // namespace dda::reference
