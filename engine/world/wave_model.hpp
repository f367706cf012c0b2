// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The wave model: how a model with dynamic loads is meshed and stepped when
// its controls leave it to the engine (docs/waves.md).
//
// Before the first step the engine finds the highest frequency f of the
// model's dynamic loads (loading/load_frequency.hpp) and, per rock, the
// element size that resolves the shortest wave of interest, the shear wave
// at f: h = C_S / (kElementsPerWavelength·f). Where a first-order block of
// an automatic mesh size (controls' mesh_size −1, no mesh_size of its rock)
// is larger than that (an edge longer than h), every such block is meshed in
// place (blocks larger than h at h, smaller ones into one cell), and the
// model is stepped with the wave scheme: the elements' mass and the time
// integrator that carry a pulse without a wrong-sign lobe ahead of it
// (wave_scheme, the one place that names them). A model whose blocks all
// resolve the load as they are (a slope under an earthquake), or that has
// no dynamic load, keeps its first-order blocks and Shi's scheme. What a
// user sets by hand (mesh_size, mesh_mass, integrator) is kept; a choice
// that carries a precursor or under-resolves the load gets a warning naming
// the figure.
#include <string>
#include <vector>

#include "block/time_scheme.hpp"
#include "core/material.hpp"
#include "loading/load_frequency.hpp"

namespace dda {

struct WorldState;

// The elements' mass and the time integrator of the wave model. Lumped
// (a third of each element's mass at its corners): its short waves lag
// instead of running ahead; Newmark's average acceleration: second order,
// no numerical damping of the pulse. Measured in docs/waves.md; a later
// time stepping that carries waves and contacts in one scheme replaces
// this function.
struct WaveScheme {
  MeshMass mass = MeshMass::Lumped;
  Integrator integrator = Integrator::Newmark;
};
WaveScheme wave_scheme();

// Elements per shear wavelength at the load's highest frequency (docs/waves.md,
// "Element size": the first peak of the 2-D bar within 2 % at 500 and
// 1000 Hz).
inline constexpr double kElementsPerWavelength = 12;

// The most elements the wave model makes by itself. A mesh for the load
// larger than this costs far more than a user who set nothing expects (the
// README's job, 8000 elements, takes half a minute on 2 cores; a slope of
// 105 blocks hit by a 2 ms pulse would take about 85 000 elements and hours):
// the blocks then stay first-order, with a warning naming the mesh and the
// controls that make it (mesh_size, max_frequency).
inline constexpr double kWaveMeshElementBudget = 20000;

// The element size (m) that resolves frequency f (Hz) in `rock`.
double wave_element_size(const RockMaterial& rock, double frequency);

struct WaveModel {
  bool decided = false;  // (before the first step)
  // The blocks were meshed for the load and are stepped with wave_scheme()
  // where mesh_mass and integrator are "auto".
  bool active = false;
  double frequency = 0;               // Hz: the highest of the dynamic loads (0: none)
  std::string source;                 // the load that set it
  double element_size = 0;            // m: the smallest rock's (0 when not active)
  int meshed_blocks = 0;              // first-order blocks meshed in place
  std::vector<std::string> notes;     // what was decided, for the run log
  std::vector<std::string> warnings;  // choices by hand that carry a precursor or under-resolve the load
  template <class Archive>
  void fields(Archive& ar) {
    ar(decided, active, frequency, source, element_size, meshed_blocks, notes, warnings);
  }
};

// Whether the model moves as bodies under dynamic loads up to `frequency`
// (Hz): no block is meshed, and none would mislead as a first-order block
// (each within the element size that resolves the load, the model within a
// shear wavelength; first_order_misleads in wave_model.cpp). The loads' waves
// then cross every block quasi-statically, and the time step need follow
// only the loads and gravity (world/time_step_rule.hpp).
bool moves_as_bodies(const WorldState& w, double frequency);

// The decision for the model as it stands before its first step (the blocks
// to mesh: meshes_for_waves).
WaveModel choose_wave_model(const WorldState& w, const LoadFrequency& load);
// Per block, the size of the mesh the wave model gives it (0: none; none
// at all where the mesh would exceed kWaveMeshElementBudget).
std::vector<double> meshes_for_waves(const WorldState& w, double frequency);

// The integrator and the elements' mass a step uses: the controls', or,
// where they say "auto", the wave scheme's while the wave model is active
// and Shi's scheme and the consistent mass otherwise.
Integrator effective_integrator(const WorldState& w);
MeshMass effective_mesh_mass(const WorldState& w);

}  // namespace dda
