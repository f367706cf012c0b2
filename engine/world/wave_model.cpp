// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/wave_model.hpp"

#include <algorithm>
#include <cmath>

#include "block/mesh.hpp"
#include "core/error.hpp"
#include "world/world_state.hpp"

namespace dda {

WaveScheme wave_scheme() { return {MeshMass::Lumped, Integrator::Newmark}; }

double wave_element_size(const RockMaterial& rock, double frequency) {
  return s_wave_speed(rock) / (kElementsPerWavelength * frequency);
}

namespace {

double longest_edge(const Blocks& blocks, BlockId b) {
  const auto v = blocks.outline(b);
  double l = 0;
  for (std::size_t k = 0; k < v.size(); ++k) l = std::max(l, (v[(k + 1) % v.size()] - v[k]).norm());
  return l;
}

// A block whose mesh size the engine chooses: first-order, no mesh size of
// its rock's, and the controls' mesh_size automatic (−1).
bool automatic(const WorldState& w, BlockId b) {
  return !w.blocks.is_element(b) && w.rocks[w.blocks.material[b]].mesh_size <= 0 && w.controls.mesh_size < 0;
}

bool any_automatic(const WorldState& w) {
  for (std::size_t b = 0; b < w.blocks.count(); ++b)
    if (automatic(w, static_cast<BlockId>(b))) return true;
  return false;
}

std::string figure(double v) { return msg(std::round(v * 1000) / 1000); }

// The longest side of the box around every block: how far a wave can travel
// in the model.
double model_extent(const Blocks& blocks) {
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (std::size_t b = 0; b < blocks.count(); ++b)
    for (const Vec2& v : blocks.outline(static_cast<BlockId>(b))) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  return blocks.count() > 0 ? (hi - lo).maxCoeff() : 0.0;
}

// Whether first-order blocks carry a wave wrongly at element size `size`:
// where a block is larger than the size, and where the model spans a shear
// wavelength or more, whatever the blocks' size: a wave then travels through
// a chain of blocks, and a first-order block sends a wrong-sign lobe ahead of
// it (its strain modes' inertia; at stiff joints the lobe's height does not
// shrink with the block, docs/block_mass.md), where lumped-mass elements send
// none. A model shorter than the wavelength moves as a body (a block sliding
// on its base under an earthquake).
bool first_order_misleads(double block_edge, double size, double extent) {
  return block_edge > size * (1 + 1e-9) || extent >= kElementsPerWavelength * size;
}

// Per block, the mesh size that resolves `frequency` (0: none), budget aside:
// every automatic block where first-order blocks would mislead (a block
// within the size into the few elements of its outline).
std::vector<double> resolving_meshes(const WorldState& w, double frequency) {
  const std::size_t n = w.blocks.count();
  std::vector<double> size(n, 0.0);
  if (!(frequency > 0)) return size;
  const double extent = model_extent(w.blocks);
  bool needed = false;
  for (std::size_t b = 0; b < n; ++b) {
    const BlockId id = static_cast<BlockId>(b);
    if (!automatic(w, id)) continue;
    size[b] = wave_element_size(w.rocks[w.blocks.material[b]], frequency);
    needed = needed || first_order_misleads(longest_edge(w.blocks, id), size[b], extent);
  }
  if (!needed) size.assign(n, 0.0);
  return size;
}

double mesh_elements(const WorldState& w, const std::vector<double>& size) {
  double elements = 0;
  for (std::size_t b = 0; b < size.size(); ++b)
    if (size[b] > 0)
      elements += std::max(1.0, estimated_mesh_elements(w.blocks.outline(static_cast<BlockId>(b)), size[b]));
  return elements;
}

}  // namespace

bool moves_as_bodies(const WorldState& w, double frequency) {
  if (!(frequency > 0) || w.blocks.count() == 0) return false;
  const double extent = model_extent(w.blocks);
  for (std::size_t b = 0; b < w.blocks.count(); ++b) {
    const BlockId id = static_cast<BlockId>(b);
    if (w.blocks.is_element(id)) return false;
    const double size = wave_element_size(w.rocks[w.blocks.material[b]], frequency);
    if (first_order_misleads(longest_edge(w.blocks, id), size, extent)) return false;
  }
  return true;
}

std::vector<double> meshes_for_waves(const WorldState& w, double frequency) {
  std::vector<double> size = resolving_meshes(w, frequency);
  if (mesh_elements(w, size) > kWaveMeshElementBudget) size.assign(size.size(), 0.0);
  return size;
}

WaveModel choose_wave_model(const WorldState& w, const LoadFrequency& load) {
  WaveModel m;
  m.decided = true;
  m.frequency = load.frequency;
  m.source = load.source;
  const Controls& c = w.controls;
  if (!(load.frequency > 0)) {
    m.notes.push_back("no dynamic load: the blocks and the time scheme as the controls say");
    return m;
  }
  const double f = load.frequency;
  const std::vector<double> resolving = resolving_meshes(w, f);
  const double elements = mesh_elements(w, resolving);
  const bool over_budget = elements > kWaveMeshElementBudget;
  const std::vector<double> size = meshes_for_waves(w, f);
  double smallest = 0, largest_block = 0;
  bool meshed_by_hand = false;
  for (std::size_t b = 0; b < size.size(); ++b) {
    if (size[b] > 0) {
      ++m.meshed_blocks;
      smallest = smallest > 0 ? std::min(smallest, size[b]) : size[b];
    }
    meshed_by_hand = meshed_by_hand || w.blocks.is_element(static_cast<BlockId>(b));
    largest_block = std::max(largest_block, longest_edge(w.blocks, static_cast<BlockId>(b)));
  }
  m.active = m.meshed_blocks > 0 || meshed_by_hand;
  m.element_size = smallest;
  double h_min = 0;  // the element size the load needs, over the rocks in use
  for (std::size_t b = 0; b < w.blocks.count(); ++b) {
    const double h = wave_element_size(w.rocks[w.blocks.material[b]], f);
    h_min = h_min > 0 ? std::min(h_min, h) : h;
  }
  const double extent = model_extent(w.blocks);
  const std::string head =
      msg("dynamic loads up to ", figure(f), " Hz (", load.source, ", ", kEnergyShare * 100, " % of its energy below)");
  if (m.meshed_blocks > 0)
    m.notes.push_back(msg(head, ": the shortest shear wave resolved by ", kElementsPerWavelength,
                          " elements needs elements of ", figure(smallest), " m; ", m.meshed_blocks,
                          " first-order blocks meshed (docs/waves.md)"));
  else if (over_budget)
    m.notes.push_back(msg(head, ": first-order blocks kept (a mesh that resolves it would take ",
                          std::llround(elements), " elements)"));
  else if (meshed_by_hand)
    m.notes.push_back(msg(head, ": the blocks meshed as the script says"));
  else if (!any_automatic(w))
    m.notes.push_back(msg(head, ": first-order blocks kept, as mesh_size says"));
  else
    m.notes.push_back(msg(head, ": every block (the largest edge ", figure(largest_block), " m) is within the ",
                          figure(h_min), " m that resolves it and the model (", figure(extent),
                          " m across) within a shear wavelength; first-order blocks kept"));
  if (m.active && c.mesh_mass == MeshMass::Auto && c.integrator == Integrator::Auto)
    m.notes.push_back(
        "the elements' mass lumped at their corners and Newmark's average acceleration: no "
        "wrong-sign lobe ahead of a pulse (docs/waves.md)");

  if (over_budget) {
    double h = 0;  // the finest resolving size
    for (const double r : resolving)
      if (r > 0) h = h > 0 ? std::min(h, r) : r;
    m.warnings.push_back(
        msg("the dynamic load of ", figure(f), " Hz needs elements of ", figure(h), " m, about ",
            std::llround(elements), " elements here, more than the ", kWaveMeshElementBudget,
            " the engine makes by itself: the blocks stay first-order, and a first-order block sends a wrong-sign lobe "
            "of 2-16 % of the amplitude ahead of each pulse (docs/waves.md, \"The precursor\"); mesh_size = ",
            figure(h),
            " meshes them anyway, max_frequency = F (Hz) sizes the elements for the highest frequency "
            "of interest"));
  }

  // Choices by hand that carry a precursor or under-resolve the load.
  if (c.mesh_size == 0 && first_order_misleads(largest_block, h_min, extent))
    m.warnings.push_back(msg("mesh_size = 0 keeps first-order blocks (the largest edge ", figure(largest_block),
                             " m) under a dynamic load of ", figure(f), " Hz, which needs elements of ", figure(h_min),
                             " m: first-order blocks send a wrong-sign lobe of 2-16 % (Shi's scheme) "
                             "to 4-23 % (newmark) of the amplitude ahead of each pulse (docs/waves.md, \"The "
                             "precursor\"); leave mesh_size out to mesh them"));
  for (std::size_t r = 0; r < w.rocks.size(); ++r) {
    const double hand = w.rocks[r].mesh_size > 0 ? w.rocks[r].mesh_size : c.mesh_size;
    const double need = wave_element_size(w.rocks[r], f);
    bool used = false;
    for (std::size_t b = 0; b < w.blocks.count(); ++b) used = used || w.blocks.material[b] == static_cast<int>(r);
    if (used && hand > need * (1 + 1e-9))
      m.warnings.push_back(msg(
          "mesh_size = ", hand, " m (rock material ", r, ") under-resolves the dynamic load of ", figure(f),
          " Hz: ", figure(s_wave_speed(w.rocks[r]) / (f * hand)), " elements per shear wavelength where ",
          kElementsPerWavelength,
          " keep the first peak of a pulse within 2 % (docs/waves.md, \"Element size\"); mesh_size = ", figure(need),
          " or less, or leave it out"));
  }
  if (m.active && c.mesh_mass == MeshMass::Consistent)
    m.warnings.push_back(
        "mesh_mass = \"consistent\" under a dynamic load: its short waves run faster than the "
        "rock's waves, a wrong-sign lobe of up to 9 % of the amplitude ahead of a pulse at 0.2 m "
        "elements, 3 % at 0.05 m (docs/waves.md, \"The precursor\"); leave mesh_mass out for the "
        "lumped mass");
  if (m.active && c.integrator == Integrator::Shi)
    m.warnings.push_back(msg("integrator = \"shi\" under a dynamic load of ", figure(f),
                             " Hz: Shi's scheme damps a wave of angular frequency w by about exp(-w^2 dt t / 4), "
                             "5-11 % of Model 1's first peak at 1000-1500 Hz and dt = 2e-6 s (docs/waves.md); "
                             "leave integrator out for Newmark's average acceleration"));
  return m;
}

Integrator effective_integrator(const WorldState& w) {
  const Integrator i = w.controls.integrator;
  if (i != Integrator::Auto) return i;
  return w.wave.active ? wave_scheme().integrator : Integrator::Shi;
}

MeshMass effective_mesh_mass(const WorldState& w) {
  const MeshMass m = w.controls.mesh_mass;
  if (m != MeshMass::Auto) return m;
  return w.wave.active ? wave_scheme().mass : MeshMass::Consistent;
}

}  // namespace dda
