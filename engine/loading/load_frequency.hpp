// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The highest frequency of a model's dynamic loads: what the wave model sizes
// its elements by (world/wave_model.hpp) and what a rule for the time step
// can read.
//
// A load sends a wave whose stress (or particle velocity) follows the load's
// force, or the velocity of a prescribed motion. So each dynamic input is
// read as that "wave signal": a pressure or a force as it is, a prescribed
// displacement differentiated once, a velocity as it is, an acceleration
// integrated once (a ground-motion record). Its highest frequency of
// interest is the frequency below which kEnergyShare of the signal's energy
// lies, ∫₀^f |S(f')|² df' = kEnergyShare·∫₀^∞ |S|² df (Parseval: the whole
// is ½∫s(t)² dt), with S the exact Fourier transform of the piecewise-linear
// signal, less the value it ends at (what a load holds once it has risen is
// static: a history holds its last value after its end). One sine period at
// f₀ gives 2.2·f₀, half a period 2.36·f₀; a constant (a load switched on
// once and held, gravity) is not dynamic and gives none, a ramp to a held
// value what its ramp sends.
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace dda {

struct WorldState;

// What the samples of an input are (what its wave signal is made from).
enum class SignalKind { Force, Displacement, Velocity, Acceleration };

// One input as (t, value) samples, piecewise linear between them; `what`
// names it in the run log ("pressure 0", "the function of point load 2").
struct LoadSignal {
  std::vector<std::pair<double, double>> samples;
  SignalKind kind = SignalKind::Force;
  std::string what;
};

inline constexpr double kEnergyShare = 0.99;

// The signal's highest frequency of interest (Hz, above); 0 for a constant.
double signal_frequency(const LoadSignal& signal);

struct LoadFrequency {
  double frequency = 0;  // Hz; 0: no dynamic load
  std::string source;    // what set it: the load, or "max_frequency (stated)"
};

// The highest frequency of the model's dynamic loads: the largest over its
// loads' histories (pressures, point loads, prescribed motions, incident
// waves) and `script_signals` (inputs the engine does not hold, sampled by
// the caller: Lua functions), or the user's statement, controls'
// max_frequency, when it is positive. The one place this is decided.
LoadFrequency dynamic_load_frequency(const WorldState& w, std::span<const LoadSignal> script_signals = {});

}  // namespace dda
