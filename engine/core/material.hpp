// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Rock (block) and joint (contact) materials, and the controls of a run.
#include <string>

#include "core/types.hpp"

namespace dda {

enum class PlaneMode { Stress, Strain };

struct RockMaterial {
  double density = 2600;  // kg/m³
  double youngs = 5e9;    // Pa
  double poisson = 0.25;  // -
  // Element size (m) of the mesh of blocks of this rock (block/mesh.hpp);
  // 0: the controls' mesh_size.
  double mesh_size = 0;
  template <class Archive>
  void fields(Archive& ar) {
    ar(density, youngs, poisson, mesh_size);
  }
};

// Mohr-Coulomb joint. Cohesion and tensile strength act only while a contact
// is intact; once it fails in tension or shear they are lost for good.
struct JointMaterial {
  double friction_deg = 30;     // friction angle φ, degrees (radians inside the engine)
  double cohesion = 0;          // Pa
  double tensile_strength = 0;  // Pa
  // Joint stiffness (Pa/m) as UDEC users give it; 0: from the contact
  // springs g0 and shear_ratio·g0 (the paper's Eq. 4: k_n = 2·g0/l). Given,
  // the springs of a contact standing for a length L of joint are k_n·L and
  // k_s·L (ContactParameters::springs); k_s = 0 with k_n given:
  // shear_ratio·k_n.
  double normal_stiffness = 0;
  double shear_stiffness = 0;
  template <class Archive>
  void fields(Archive& ar) {
    ar(friction_deg, cohesion, tensile_strength, normal_stiffness, shear_stiffness);
  }
};

// Throw dda::Error naming the material ("rock material 2") and the parameter
// when a value is NaN, non-positive where it must be positive, or out of
// range. Cheap when the values are good (the step checks every material).
void validate(const RockMaterial& m, int index);
void validate(const JointMaterial& m, int index);

// Elastic matrix E (3×3) mapping (εx, εy, γxy) to (σx, σy, τxy).
Mat3 elastic_matrix(const RockMaterial& m, PlaneMode mode);

// P- and S-wave speeds of the rock (used for step-time estimates and the
// viscous boundary): C_P = sqrt((K + 4G/3)/ρ), C_S = sqrt(G/ρ).
double p_wave_speed(const RockMaterial& m, PlaneMode mode);
double s_wave_speed(const RockMaterial& m);

}  // namespace dda
