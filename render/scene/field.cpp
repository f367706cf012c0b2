// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "scene/field.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace dda::render {
namespace {

constexpr FieldInfo kFields[] = {
    {Field::None, "none", "", "blocks", "", 1, false},
    {Field::SigmaXX, "sigma_xx", "σxx", "normal stress σxx", "MPa", 1e-6, true},
    {Field::SigmaYY, "sigma_yy", "σyy", "normal stress σyy", "MPa", 1e-6, true},
    {Field::TauXY, "tau_xy", "τxy", "shear stress τxy", "MPa", 1e-6, true},
    {Field::SigmaMajor, "sigma_1", "σ1", "major principal stress σ1", "MPa", 1e-6, true},
    {Field::VonMises, "von_mises", "σvM", "von Mises stress", "MPa", 1e-6, false},
    {Field::Velocity, "velocity", "|v|", "velocity magnitude", "m/s", 1, false},
    {Field::Displacement, "displacement", "|u|", "displacement magnitude", "m", 1, false},
};

}  // namespace

const FieldInfo& field_info(Field f) {
  for (const FieldInfo& i : kFields)
    if (i.field == f) return i;
  DDA_ASSERT(false, "unknown field enum value");
}

std::span<const FieldInfo> all_fields() { return kFields; }

Field parse_field(std::string_view key) {
  for (const FieldInfo& i : kFields)
    if (key == i.key) return i.field;
  std::string known;
  for (const FieldInfo& i : kFields) known += (known.empty() ? "" : ", ") + std::string(i.key);
  throw Error(msg("unknown field '", key, "' (known fields: ", known, ")"));
}

double field_value(const Scene& scene, std::size_t b, Field f) {
  const Vec3& s = scene.stress[b];
  switch (f) {
    case Field::None:
      return 0;
    case Field::SigmaXX:
      return s.x();
    case Field::SigmaYY:
      return s.y();
    case Field::TauXY:
      return s.z();
    case Field::SigmaMajor: {
      const double c = (s.x() + s.y()) / 2, r = std::hypot((s.x() - s.y()) / 2, s.z());
      return c + r;
    }
    case Field::VonMises:
      return std::sqrt(std::max(0.0, s.x() * s.x() - s.x() * s.y() + s.y() * s.y() + 3 * s.z() * s.z()));
    case Field::Velocity:
      return scene.velocity[b].norm();
    case Field::Displacement:
      return scene.displacement[b].norm();
  }
  return 0;
}

ColorMap default_colormap(Field f) { return field_info(f).is_signed ? ColorMap::CoolWarm : ColorMap::Viridis; }

}  // namespace dda::render
