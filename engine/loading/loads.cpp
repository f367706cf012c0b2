// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "loading/loads.hpp"

#include <cmath>

#include "block/displacement.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"

namespace dda {

int Loads::add_point_load(BlockId b, const Vec2& point, const Vec2& force) {
  if (!point.allFinite()) throw Error(msg("point load on block ", b, ": point is not finite"));
  if (!force.allFinite()) throw Error(msg("point load on block ", b, ": force is not finite"));
  point_loads_.push_back({b, point, force});
  return static_cast<int>(point_loads_.size()) - 1;
}

void Loads::set_point_load(int id, const Vec2& force) {
  if (id < 0 || id >= static_cast<int>(point_loads_.size())) throw Error(msg("no point load ", id));
  if (!force.allFinite()) throw Error(msg("point load ", id, ": force is not finite"));
  point_loads_[id].force = force;
  // A fixed force replaces any force history the load had.
  std::erase_if(point_load_histories_, [&](const PointLoadHistory& h) { return h.load == id; });
}

void Loads::set_point_load_history(int id, const Vec2& direction, History magnitude) {
  if (id < 0 || id >= static_cast<int>(point_loads_.size())) throw Error(msg("no point load ", id));
  if (!direction.allFinite() || direction.norm() == 0)
    throw Error(msg("point load ", id, ": direction must be a non-zero vector"));
  for (PointLoadHistory& h : point_load_histories_)
    if (h.load == id) {
      h = {id, direction, std::move(magnitude)};
      return;
    }
  point_load_histories_.push_back({id, direction, std::move(magnitude)});
}

int Loads::add_pressure_load(const Blocks& blocks, const std::vector<EdgeRef>& edges, double pressure) {
  const std::string what = msg("pressure load ", pressure_loads_.size());
  check_edges(blocks, edges, what);
  if (!std::isfinite(pressure)) throw Error(msg(what, ": pressure is not finite"));
  pressure_loads_.push_back({edges, pressure, History(), false});
  return static_cast<int>(pressure_loads_.size()) - 1;
}

void Loads::set_pressure(int id, double pressure) {
  if (id < 0 || id >= static_cast<int>(pressure_loads_.size())) throw Error(msg("no pressure load ", id));
  if (!std::isfinite(pressure)) throw Error(msg("pressure load ", id, ": pressure is not finite"));
  pressure_loads_[id].pressure = pressure;
  pressure_loads_[id].from_history = false;
}

void Loads::set_pressure_history(int id, History pressure) {
  if (id < 0 || id >= static_cast<int>(pressure_loads_.size())) throw Error(msg("no pressure load ", id));
  pressure_loads_[id].history = std::move(pressure);
  pressure_loads_[id].from_history = true;
}

std::vector<LoadSignal> Loads::dynamic_signals() const {
  std::vector<LoadSignal> signals;
  for (const PointLoadHistory& h : point_load_histories_)
    signals.push_back({h.magnitude.points(), SignalKind::Force, msg("point load ", h.load)});
  for (std::size_t i = 0; i < pressure_loads_.size(); ++i)
    if (pressure_loads_[i].from_history)
      signals.push_back({pressure_loads_[i].history.points(), SignalKind::Force, msg("pressure load ", i)});
  return signals;
}

void Loads::remesh(const Remeshing& r) {
  for (PointLoad& p : point_loads_) p.block = r.element_at(p.block, p.point);
  for (PressureLoad& p : pressure_loads_) p.edges = r.edges(p.edges);
}

void Loads::add_terms(double t_end, const Blocks& blocks, BlockTerms& terms) {
  auto add_force = [&](BlockId b, const Vec2& at, const Vec2& force) {
    terms.f[b] += displacement_matrix(at, blocks.centroid[b]).transpose() * force;
  };
  for (const PointLoadHistory& h : point_load_histories_)
    point_loads_[h.load].force = h.direction * h.magnitude.value(t_end);
  for (const PointLoad& p : point_loads_) add_force(p.block, p.point, p.force);

  // SHI: ∫ Tᵀ(−p n) dl over a straight edge is l·Tᵀ(midpoint)·(−p n).
  for (PressureLoad& load : pressure_loads_) {
    if (load.from_history) load.pressure = load.history.value(t_end);
    for (const EdgeRef& e : load.edges) {
      const BlockPolygons polys = blocks.polygons();
      const Vec2& a = polys.vertex(e.block, e.edge);
      const Vec2& b = polys.vertex(e.block, e.edge + 1);
      const Vec2 outward((b - a).y(), -(b - a).x());  // length l, outward for a counter-clockwise outline
      add_force(e.block, 0.5 * (a + b), -load.pressure * outward);
    }
  }
}

void Loads::move_points(const Blocks& blocks, const VecX& d) {
  for (PointLoad& p : point_loads_) {
    p.point += point_displacement(p.point, blocks.centroid[p.block], d.segment<6>(6 * p.block));
    p.force_before = p.force;
    p.applied = true;
  }
  for (PressureLoad& load : pressure_loads_) {
    load.pressure_before = load.pressure;
    load.applied = true;
  }
}

Loads::Work Loads::step_work(const Blocks& blocks, const VecX& d) const {
  Work w;
  for (const PointLoad& p : point_loads_) {
    const Vec2 before = p.applied ? p.force_before : p.force;
    w.point +=
        0.5 *
        (before + p.force).dot(displacement_matrix(p.point, blocks.centroid[p.block]) * d.segment<6>(6 * p.block));
  }
  const BlockPolygons polys = blocks.polygons();
  for (const PressureLoad& load : pressure_loads_) {
    const double mean = 0.5 * ((load.applied ? load.pressure_before : load.pressure) + load.pressure);
    for (const EdgeRef& e : load.edges) {
      const Vec2& a = polys.vertex(e.block, e.edge);
      const Vec2& b = polys.vertex(e.block, e.edge + 1);
      const Vec2 outward((b - a).y(), -(b - a).x());
      w.pressure +=
          -mean * outward.dot(displacement_matrix(0.5 * (a + b), blocks.centroid[e.block]) * d.segment<6>(6 * e.block));
    }
  }
  return w;
}

void Loads::check_loaded(const LoadCheck& check, const Blocks& blocks) const {
  for (std::size_t i = 0; i < point_loads_.size(); ++i) {
    const PointLoad& l = point_loads_[i];
    check.index(l.block, blocks.count(), "blocks", "point load ", i, "'s block");
    check.finite(l.point, "point load ", i, "'s point");
  }
  for (std::size_t i = 0; i < point_load_histories_.size(); ++i)
    check.index(point_load_histories_[i].load, point_loads_.size(), "point loads", "force history ", i, "'s load");
  for (std::size_t i = 0; i < pressure_loads_.size(); ++i) try {
      check_edges(blocks, pressure_loads_[i].edges, msg("pressure ", i));
    } catch (const Error& e) {
      check.fail(e.what());
    }
}

}  // namespace dda
