// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A free-field column (UDEC's and FLAC's free-field boundary, for vertically
// incident waves): the 1-D response of the ground beside a model's vertical
// side, computed on its own and fed to the side through dashpots and the
// column's stresses, so that the side neither reflects nor distorts the
// incoming motion.
//
// The column runs from the bottom to the top of the side, with a node at the
// height of each end point of the side's edges; each segment between two
// nodes has the density ρ, shear modulus G and constrained modulus
// M = λ + 2G of the block whose side edge spans it (of the plane mode). Per
// unit area of the side: each segment's consistent mass (the inertia of the
// blocks beside it: lumped masses left the model's top 3 % off the column's
// in the free-field test, consistent ones 0.1 %), shear springs G/h for the
// horizontal motion u (S waves), axial springs M/h for the vertical motion w
// (P waves).
// Its base is a quiet base on the half-space (impedances ρC_S, ρC_P) with the
// same incident wave as the model's: force ρC·(2·v_in − v). Stepped with the
// model's time scheme (block/time_scheme.hpp) and Δt, so that column and
// model share their integration error. The stresses it hands to the side:
// τxy = G·∂u/∂y and σxx = λ·∂w/∂y of the segment (dynamic only: the column
// carries no gravity; a side under gravity needs its static support besides).
#include <vector>

#include "block/time_scheme.hpp"
#include "loading/history.hpp"

namespace dda {

class FreeFieldColumn {
 public:
  struct Segment {
    double height;                        // of the segment (m)
    double density, shear_modulus, lame;  // ρ, G, λ
    template <class Archive>
    void fields(Archive& ar) {
      ar(height, density, shear_modulus, lame);
    }
  };
  // Segments from the bottom (at y0) up; base impedances ρC_S, ρC_P of the
  // half-space and the incident wave's particle velocity (vx: S, vy: P).
  FreeFieldColumn(double y0, std::vector<Segment> segments, double base_zs, double base_zp, History incident_vx,
                  History incident_vy);

  // The trial state at t_end = t + dt (scheme.dt) from the committed one;
  // commit() keeps it (after the model's step is accepted).
  void advance(double t_end, const TimeScheme& scheme);

  // Checkpoints (core/archive.hpp): a column is read into a default one.
  FreeFieldColumn() = default;
  template <class Archive>
  void fields(Archive& ar) {
    ar(y_, k_shear_, k_axial_, segments_, zs_, zp_, vx_in_, vy_in_, state_, trial_);
    if constexpr (Archive::reading) check_loaded(ar.what());
  }
  void commit();

  // At node i (0 at the bottom), trial state: velocity (vx, vy).
  double node_height(int i) const { return y_[i]; }
  int nodes() const { return static_cast<int>(y_.size()); }
  double vx(int i) const { return trial_.vu[i]; }
  double vy(int i) const { return trial_.vw[i]; }
  // Stresses of segment s (between nodes s and s + 1), trial state.
  double shear_stress(int s) const;    // τxy
  double lateral_stress(int s) const;  // σxx
  // The segment containing height y (clamped to the column).
  int segment_at(double y) const;
  int node_at(double y) const;  // the nearest node

 private:
  struct State {
    std::vector<double> u, vu, w, vw;  // displacements and velocities of the nodes
    template <class Archive>
    void fields(Archive& ar) {
      ar(u, vu, w, vw);
    }
  };
  // Read from a checkpoint: a node more than segments, every list sized for
  // them (throws dda::Error naming `what`).
  void check_loaded(const std::string& what) const;
  // One direction: springs k per segment, base impedance z, input v_in.
  void advance_component(const std::vector<double>& k, double z, double v_in, const TimeScheme& scheme,
                         const std::vector<double>& u, const std::vector<double>& v, std::vector<double>& u1,
                         std::vector<double>& v1) const;

  std::vector<double> y_, k_shear_, k_axial_;
  std::vector<Segment> segments_;
  double zs_, zp_;
  History vx_in_, vy_in_;
  State state_, trial_;
};

}  // namespace dda
