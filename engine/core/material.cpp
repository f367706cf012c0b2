// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "core/material.hpp"

#include <cmath>

#include "core/error.hpp"

namespace dda {

// `what()` names the material; called only to word an error.
template <typename What>
static void require_positive(double v, const What& what, const char* name) {
  if (!std::isfinite(v)) throw Error(msg(what(), ": ", name, " is not a finite number (", v, ")"));
  if (v <= 0) throw Error(msg(what(), ": ", name, " must be positive, got ", v));
}

void validate(const RockMaterial& m, int index) {
  const auto what = [index] { return msg("rock material ", index); };
  require_positive(m.density, what, "density");
  require_positive(m.youngs, what, "Young's modulus");
  if (!std::isfinite(m.poisson)) throw Error(msg(what(), ": Poisson's ratio is not a finite number"));
  if (m.poisson < 0 || m.poisson >= 0.5)
    throw Error(msg(what(), ": Poisson's ratio must lie in [0, 0.5), got ", m.poisson));
  if (!std::isfinite(m.mesh_size) || m.mesh_size < 0)
    throw Error(msg(what(), ": mesh size must be zero (first-order blocks) or positive, got ", m.mesh_size));
}

void validate(const JointMaterial& m, int index) {
  const auto what = [index] { return msg("joint material ", index); };
  if (!std::isfinite(m.friction_deg) || m.friction_deg < 0 || m.friction_deg >= 90)
    throw Error(msg(what(), ": friction angle must lie in [0, 90) degrees, got ", m.friction_deg));
  if (!std::isfinite(m.cohesion) || m.cohesion < 0)
    throw Error(msg(what(), ": cohesion must be zero or positive, got ", m.cohesion));
  if (!std::isfinite(m.tensile_strength) || m.tensile_strength < 0)
    throw Error(msg(what(), ": tensile strength must be zero or positive, got ", m.tensile_strength));
  if (!std::isfinite(m.normal_stiffness) || m.normal_stiffness < 0)
    throw Error(
        msg(what(), ": normal stiffness kn must be zero (from g0) or positive (Pa/m), got ", m.normal_stiffness));
  if (!std::isfinite(m.shear_stiffness) || m.shear_stiffness < 0)
    throw Error(
        msg(what(), ": shear stiffness ks must be zero (from kn or g0) or positive (Pa/m), got ", m.shear_stiffness));
  if (m.shear_stiffness > 0 && m.normal_stiffness == 0)
    throw Error(msg(what(), ": shear stiffness ks needs a normal stiffness kn (Pa/m) as well"));
}

Mat3 elastic_matrix(const RockMaterial& m, PlaneMode mode) {
  const double e = m.youngs, nu = m.poisson;
  Mat3 d = Mat3::Zero();
  if (mode == PlaneMode::Stress) {
    const double c = e / (1 - nu * nu);
    d << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  } else {
    const double c = e / ((1 + nu) * (1 - 2 * nu));
    d << c * (1 - nu), c * nu, 0, c * nu, c * (1 - nu), 0, 0, 0, c * (1 - 2 * nu) / 2;
  }
  return d;
}

double p_wave_speed(const RockMaterial& m, PlaneMode mode) {
  // Plane stress: the in-plane P modulus is E/(1-ν²); plane strain: K + 4G/3.
  const double e = m.youngs, nu = m.poisson;
  const double modulus = mode == PlaneMode::Stress ? e / (1 - nu * nu) : e * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  return std::sqrt(modulus / m.density);
}

double s_wave_speed(const RockMaterial& m) { return std::sqrt(m.youngs / (2 * (1 + m.poisson)) / m.density); }

}  // namespace dda
