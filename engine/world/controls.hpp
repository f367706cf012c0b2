// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The controls of a World: what a script sets with dda.model{...} and
// m:controls{...}. They may change between steps and are checked at the
// start of each step.
//
// Every control is one row of the table control_specs() (controls.cpp): its
// name (the Lua name), its type, its check, its documentation and how the
// docs show its default (the value itself is the field's initializer below).
// The Lua layer reads, writes and checks controls through the table alone,
// the engine checks them through it (validate_controls), and the controls
// table of the Lua reference, docs/lua_api.md, is generated from it
// (controls_markdown_table; the test LuaApiReference.DocsAreTheBindingsOwn
// holds the two equal). Adding a control is its field here and its row there.
#include <span>
#include <string>

#include "block/time_scheme.hpp"
#include "contact/contact.hpp"
#include "core/material.hpp"
#include "core/types.hpp"
#include "solver/solver_settings.hpp"

namespace dda {

class ArchiveWriter;
class ArchiveReader;
struct Controls;
// A checkpoint's controls (core/archive.hpp): each by its name and type,
// through the table below, so a control added there needs nothing here.
void archive_controls(ArchiveWriter& ar, Controls& c);
void archive_controls(ArchiveReader& ar, Controls& c);

// The most worker threads a model (or --threads) may ask for: more than any
// machine has, and few enough that the thread pool can make them.
inline constexpr int kMaxThreads = 4096;
static_assert(kMaxThreads == 4096, "the threads control's rule says 4096");

struct Controls {
  PlaneMode plane = PlaneMode::Stress;
  double g0 = 0;                             // normal contact spring (N/m per unit thickness); 0 → 50 × largest E
  double g1 = 0;                             // upper step time (s); 0 → the default rule (world/time_step_rule.hpp)
  double g2 = 0.005;                         // largest step displacement / half the model height
  double gg = 1;                             // dynamic parameter: share of velocity carried into the next step
  Integrator integrator = Integrator::Auto;  // time integration (block/time_scheme.hpp; auto: world/wave_model.hpp)
  double rho_inf = 0.9;                      // generalized-α: spectral radius at high frequency
  double shear_ratio = 0.4;                  // shear spring = shear_ratio × g0 (Shi's 2/5)
  int open_close_limit = 6;                  // open-close iterations before Δt is cut and the step redone
  // Open-close hysteresis of gap decisions and intact joints, as a fraction
  // of half the model height: a closed contact opens once separated by more
  // than this, an open one closes once penetrated by more; an intact joint
  // fails once its shear force exceeds its strength by the shear spring
  // times this. Without it, contacts that carry next to no force (the
  // Poisson-loaded vertical joints of a wall) flip state on round-off and the
  // iteration never settles. (Under ContactLaw::Shi, friction decisions take
  // it too; under Holding those of contacts that are not intact joints have
  // their own band, in the step's units: contact/holding_law.hpp,
  // contact_slack.)
  double contact_tolerance = 1e-9;
  // The contact law (contact/contact_model.hpp, one file each): Holding,
  // in which friction holds (the default); Shi, the law of Shi (1988),
  // opt-in (a block that must hold on a slope creeps at small Δt;
  // the paper's scripts pin it to reproduce the paper's figures).
  ContactLaw contact_law = ContactLaw::Holding;
  // Kelvin–Voigt damping of the blocks' strains, σ = E(ε + β·ε̇): β in
  // seconds, a damping ratio βω/2 at angular frequency ω; 0: none (the
  // default). It keeps a block sliding at small Δt from chattering
  // (docs/friction_flutter.md).
  double strain_damping = 0;
  // Friction that lags the normal force: t_r in seconds, the friction's
  // normal force N_f following N as dN_f/dt = (N − N_f)/t_r; 0: none (the
  // default). It keeps a block sliding at small Δt from chattering without
  // damping waves (docs/friction_flutter.md).
  double friction_lag = 0;
  // The landing law (contact/landing.hpp): a contact that lands ends its
  // step as a rigid-body impact with this coefficient of restitution e,
  // 0 ≤ e ≤ 1; −1: off (the default), the penalty springs' bounce.
  double restitution = -1;
  double contact_range = 0;  // m; 0 → automatic (contact/contact_detection.hpp)
  // Element size (m) of the meshes of blocks added from now on whose rock
  // material gives none (block/mesh.hpp); 0: first-order blocks; −1: from
  // the dynamic loads (world/wave_model.hpp).
  double mesh_size = -1;
  // The mass of the meshes' elements (block/time_scheme.hpp).
  MeshMass mesh_mass = MeshMass::Auto;
  // The highest frequency (Hz) of the dynamic loads, when the user states
  // it; 0: found from the loads (loading/load_frequency.hpp).
  double max_frequency = 0;

  double fixed_point_factor = 100;  // fixed-point spring = factor × g0
  Vec2 gravity = Vec2::Zero();      // m/s²
  double cut_factor = 1.0 / 3.0;    // Δt multiplier when a step is redone
  int max_step_cuts = 20;           // cuts in one step before giving up (error)
  // Relative residuals: of the accepted solution; of the open-close solves
  // while contact states change; of the accepted solution in static analysis
  // (gg = 0). Where each applies: world/solve_regime.hpp.
  double cg_tolerance = 1e-10;
  double cg_open_close_tolerance = 1e-4;
  double cg_static_tolerance = 1e-6;
  bool predict_states = true;  // first guess of the contact states from the warm start (solve_regime.hpp)
  // The linear solver's own knobs (solver/solver_settings.hpp): the PCG's
  // preconditioner, block-Jacobi refresh tolerance and re-solve patches.
  SolverSettings solver;
  int cg_max_iterations = 0;  // 0 → 10 × unknowns + 100
  int threads = 0;            // 0 → every core

  template <class Archive>
  void fields(Archive& ar) {
    archive_controls(ar, *this);
  }
};

enum class ControlType { Number, Integer, Flag, Choice, Vector };
constexpr ControlType enum_last(ControlType) { return ControlType::Vector; }  // (core/archive.hpp)

// The values a number or integer control admits, and the words that say so
// ("must be zero or positive"): the same check and message from Lua and C++.
struct ControlRange {
  double min = -1e308, max = 1e308;
  bool min_open = false, max_open = false;  // min < v (else min ≤ v); v < max (else v ≤ max)
  const char* rule = "";
  bool min_is_off = false;  // min means "off", and the values between it and 0 are refused
  bool admits(double v) const {
    return (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max) && !(min_is_off && v > min && v < 0);
  }
};

struct ControlSpec {
  const char* name;  // in Lua and in the docs
  ControlType type;
  const char* doc;                       // the docs' "meaning" column (Markdown)
  const char* default_text;              // the docs' default column, or nullptr: the value as written by value_text
  ControlRange range;                    // Number, Integer
  std::span<const char* const> choices;  // Choice: the names, in the enum's order
  // Access to the field, by type (one is set).
  double& (*number)(Controls&);
  int& (*integer)(Controls&);
  bool& (*flag)(Controls&);
  Vec2& (*vector)(Controls&);
  int (*get_choice)(const Controls&);
  void (*set_choice)(Controls&, int);

  // The rule c breaks ("must be positive"), or nullptr when c's value passes.
  const char* violated(const Controls& c) const;
  // The value as Lua writes it: 0.4, 20, true, "stress", {0, -9.81}.
  std::string value_text(const Controls& c) const;
  // The choice named `name` (-1: none); the choices as "\"a\", \"b\" or \"c\"".
  int find_choice(std::string_view name) const;
  std::string choice_list() const;
};

// Every control, in the order Lua lists them.
std::span<const ControlSpec> control_specs();
const ControlSpec* find_control(std::string_view name);

// Throws dda::Error naming the first control out of its range.
void validate_controls(const Controls& c);

// The controls table of docs/lua_api.md (header, separator, one row each).
std::string controls_markdown_table();

}  // namespace dda
