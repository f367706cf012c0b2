// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The per-block quantities a frame can be coloured by.
//
//   key            shown as   unit on the bar  value (SI)
//   none           —          —                blocks drawn in one grey
//   sigma_xx       σxx        MPa              normal stress in x (Pa, tension +)
//   sigma_yy       σyy        MPa              normal stress in y
//   tau_xy         τxy        MPa              shear stress
//   sigma_1        σ1         MPa              major principal stress: the
//                                              algebraically largest (most
//                                              tensile) in-plane principal stress
//   von_mises      σvM        MPa              sqrt(σxx² − σxx·σyy + σyy² + 3τxy²)
//                                              (in-plane stresses; σzz taken as 0)
//   velocity       |v|        m/s              speed of the block centroid
//   displacement   |u|        m                centroid displacement since the start
//
// Stresses, being constant over a DDA block (first order), colour the block
// uniformly; velocity and displacement are taken at the centroid.
#include <span>
#include <string_view>

#include "raster/colormap.hpp"
#include "scene/scene.hpp"

namespace dda::render {

enum class Field { None, SigmaXX, SigmaYY, TauXY, SigmaMajor, VonMises, Velocity, Displacement };

struct FieldInfo {
  Field field;
  const char* key;          // name in scripts and file names: "sigma_yy"
  const char* label;        // UTF-8, drawn on frames: "σyy"
  const char* description;  // "normal stress σyy"
  const char* unit;         // unit shown on the colour bar: "MPa"
  double display_scale;     // SI value × display_scale = shown value (1e-6 for Pa → MPa)
  bool is_signed;           // signed → diverging map, symmetric automatic range
};

const FieldInfo& field_info(Field f);
std::span<const FieldInfo> all_fields();
// Accepts the keys above; throws dda::Error listing them otherwise.
Field parse_field(std::string_view key);

// The field's value for block b, in SI units.
double field_value(const Scene& scene, std::size_t b, Field f);

// Default colour map: CoolWarm for signed fields, Viridis for magnitudes.
ColorMap default_colormap(Field f);

}  // namespace dda::render
