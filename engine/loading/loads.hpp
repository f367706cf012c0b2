// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Loads on the blocks (the paper's point loads, FHI and SHI): what a model
// holds, and their terms in each step. Histories are evaluated at the end of
// the step, t + Δt; loads act at material points that move with their block.
#include <vector>

#include "assembly/block_terms.hpp"
#include "block/blocks.hpp"
#include "block/remeshing.hpp"
#include "loading/history.hpp"
#include "loading/load_frequency.hpp"

namespace dda {

class Loads {
 public:
  // A point load fixed to the material point `point` of block b (checked by
  // the caller).
  int add_point_load(BlockId b, const Vec2& point, const Vec2& force);
  void set_point_load(int id, const Vec2& force);  // also drops a force history
  // FHI: the point load's force becomes direction × magnitude(t).
  void set_point_load_history(int id, const Vec2& direction, History magnitude);
  // SHI: a pressure (Pa) on edges, normal to each edge and pushing into its
  // block, integrated exactly along the edge (its current length and normal).
  int add_pressure_load(const Blocks& blocks, const std::vector<EdgeRef>& edges, double pressure);
  void set_pressure(int id, double pressure);
  void set_pressure_history(int id, History pressure);
  // No point load and no pressure.
  bool empty() const { return point_loads_.empty() && pressure_loads_.empty(); }
  std::size_t point_load_count() const { return point_loads_.size(); }
  std::size_t pressure_count() const { return pressure_loads_.size(); }

  // The step: forces at t_end into the right-hand side, serially in a fixed
  // order (few next to the blocks).
  void add_terms(double t_end, const Blocks& blocks, BlockTerms& terms);
  // The accepted step's displacement d moves the load points with their
  // blocks (before the blocks themselves move).
  void move_points(const Blocks& blocks, const VecX& d);
  // The work (J/m) of the point loads and of the pressures on the accepted
  // step displacement d (before move_points): trapezoidal between the forces
  // the step before applied and those this step applied (those at t_end).
  struct Work {
    double point = 0, pressure = 0;
  };
  Work step_work(const Blocks& blocks, const VecX& d) const;

  // The loads that follow a history, as wave signals (load_frequency.hpp).
  std::vector<LoadSignal> dynamic_signals() const;
  // After first-order blocks were meshed in place: point loads go to the
  // element under them, pressures onto the edges that now stand where
  // theirs stood (ids unchanged).
  void remesh(const Remeshing& r);
  // The edges of pressure load `id` (as they are now).
  const std::vector<EdgeRef>& pressure_edges(int id) const { return pressure_loads_.at(id).edges; }
  BlockId point_load_block(int id) const { return point_loads_.at(id).block; }

  // What a checkpoint holds (core/archive.hpp): every load with its history.
  template <class Archive>
  void fields(Archive& ar) {
    ar(point_loads_, point_load_histories_, pressure_loads_);
  }
  // Read from a checkpoint: every block, edge and load in range (core/load_check.hpp).
  void check_loaded(const LoadCheck& check, const Blocks& blocks) const;

 private:
  struct PointLoad {
    BlockId block;
    Vec2 point;
    Vec2 force;
    Vec2 force_before = Vec2::Zero();  // applied in the step before (for its work)
    bool applied = false;              // by a step yet
    template <class Archive>
    void fields(Archive& ar) {
      ar(block, point, force, force_before, applied);
    }
  };
  struct PointLoadHistory {
    int load;
    Vec2 direction;
    History magnitude;
    template <class Archive>
    void fields(Archive& ar) {
      ar(load, direction, magnitude);
    }
  };
  struct PressureLoad {
    std::vector<EdgeRef> edges;
    double pressure;
    History history;
    bool from_history;
    double pressure_before = 0;  // applied in the step before (for its work)
    bool applied = false;        // by a step yet
    template <class Archive>
    void fields(Archive& ar) {
      ar(edges, pressure, history, from_history, pressure_before, applied);
    }
  };
  std::vector<PointLoad> point_loads_;
  std::vector<PointLoadHistory> point_load_histories_;
  std::vector<PressureLoad> pressure_loads_;
};

}  // namespace dda
