-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_corner_block.lua: why the chamber's four corner blocks must be meshed
-- too in the meshed Section 4 blast (docs/validation.md, "The paper's 2 m
-- joints with meshed blocks").
--
-- Models:  the blast model of blast_model.lua, 40 m (its boundary's first
--          reflection reaches MP1 after about 5 ms), 2 m joints, blocks meshed
--          at --set mesh (default 0.5 m) within 12 m of the centre, joints
--          k_n = 1e11 Pa/m, DHI on the chamber wall, Fixed boundary, Shi's
--          scheme, 2.2 ms (past MP1's peak), run twice:
--          "first-order corners" (the four blocks the chamber's corners cut,
--          concave, 3.94 m^2 each, kept first-order as before CGAL meshed
--          concave blocks) and "meshed corners".
--          Monitors in the upper-left corner block, whose wall edges are two
--          0.34 m stubs at the corner (-4, 2): "far" (-4.243, 4.1), 2.10 m from
--          the nearest wall point, and "side" (-5.5, 2.828), 1.71 m from it.
-- References: (1) the DHI itself: at 0.5 ms the wall has moved 0.5075 mm
--          (the integral of the triangular velocity, 0.5 x 2.03 m/s x 0.5 ms)
--          along its normal, so the chamber's corner point (-4, 2) by -0.5075
--          mm in x and +0.5075 mm in y (it belongs to both walls; a monitor
--          3 mm inside the rock reads it). (2) Causality: nothing moves before
--          the P wave from the wall can reach it, arrival >= distance / C_P,
--          C_P = 5570 m/s (plane strain).
--          Arrival: the first time |v| exceeds 1 % of the DHI's 2.03 m/s.
-- Run:     build/dda run scripts/paper/blast_corner_block.lua [--set mesh=0.5]
--          [--set check=true]
--          check=true: an error unless, with meshed corners, the corner point
--          moves as the DHI prescribes within 2 % in x and y and each monitor's
--          arrival is at least 0.9 x its travel time (the mesh's dispersion
--          lets a small precursor through), and, with first-order corners,
--          the corner point misses the DHI by more than 10 % (one constant
--          strain cannot follow the two walls' stubs) and the far monitor moves
--          before a third of its travel time (the block is a plug: its far side
--          moves with the wall).
-- Writes:  stdout, for both models: arrival, travel time, |v| at 0.5 ms (the
--          load's peak) and peak |v| to 1 ms at each monitor; the corner point's
--          displacement at 0.5 ms; the corner block's kinetic energy and
--          momentum at 0.5 ms; the PPV on the axis at y = 4, 6, 8 m.
--          corner_<first_order|meshed>_axis_y<4|6|8>.csv: vx, vy on the axis.

local dda = require "dda"
local blast_model = require "blast_model"

local mesh = dda.param("mesh", 0.5)
local check = dda.param("check", false)
if type(mesh) ~= "number" or not (mesh > 0) then error("--set mesh=" .. tostring(mesh) .. ": an element size in m, > 0") end

local rock = blast_model.rock
local lambda = rock.E * rock.nu / ((1 + rock.nu) * (1 - 2 * rock.nu))
local G = rock.E / (2 * (1 + rock.nu))
local cp = math.sqrt((lambda + 2 * G) / rock.density)   -- 5570 m/s
local v_wall = 2.03                                        -- m/s, the DHI's peak
local t_end = 2.2e-3     -- s: past the peak at MP1 (1.7-1.9 ms)

-- distance from a point to the chamber wall (the rectangle's outline)
local function wall_distance(p)
  local c = blast_model.chamber
  local dx = math.max(c[1] - p[1], 0, p[1] - c[3])
  local dy = math.max(c[2] - p[2], 0, p[2] - c[4])
  return math.sqrt(dx * dx + dy * dy)
end

local points = { { name = "far", at = { -4.243, 4.1 } }, { name = "side", at = { -5.5, 2.828 } } }
-- the upper-left corner block's outline (the 2 m joints through the centre
-- cut it): its kinetic energy and momentum, from monitors on a 0.1 m grid
-- inside it (each stands for 0.01 m^2)
local corner = { {-4, 2}, {-3.657, 2}, {-2.828, 2.828}, {-4.243, 4.243}, {-5.657, 2.828}, {-4.243, 1.414}, {-4, 1.657} }
local function inside(p, poly)
  local c = false
  local j = #poly
  for i = 1, #poly do
    local a, b = poly[i], poly[j]
    if (a[2] > p[2]) ~= (b[2] > p[2]) and p[1] < (b[1] - a[1]) * (p[2] - a[2]) / (b[2] - a[2]) + a[1] then c = not c end
    j = i
  end
  return c
end
local grid = {}
for x = -5.65, -2.8, 0.1 do
  for y = 1.45, 4.25, 0.1 do
    if inside({ x, y }, corner) then grid[#grid + 1] = { x, y } end
  end
end
-- the axis above the roof (MP1 at y = 8): PPV = max |vy|, and when
local axis = { 4, 6, 8 }

local function run(first_order_corners)
  local M = blast_model.build{ size = 40, mesh = mesh, mesh_radius = 12, kn = 2 * blast_model.controls.g0 / 2,
                               first_order_corners = first_order_corners, controls = { integrator = "shi" } }
  blast_model.load(M, "dhi")
  M.outer:fix()
  local mons = {}
  for i, p in ipairs(points) do
    mons[i] = M.m:monitor{ at = p.at, fields = { "vx", "vy" }, csv = false }
    if first_order_corners and mons[i]:block():area() < 1 then
      error(string.format("monitor %s lies in a block of %.3g m^2, not the first-order corner block", p.name,
                          mons[i]:block():area()))
    end
  end
  local grid_mons = {}
  for i, p in ipairs(grid) do grid_mons[i] = M.m:monitor{ at = p, fields = { "vx", "vy" }, csv = false } end
  local axis_mons = {}
  for i, y in ipairs(axis) do axis_mons[i] = M.m:monitor{ at = { 0, y }, fields = { "vx", "vy" }, name = string.format("corner_%s_axis_y%g", first_order_corners and "first_order" or "meshed", y) } end
  local at_corner = M.m:monitor{ at = { -4 + 0.003, 2 + 0.003 }, fields = { "ux", "uy" }, csv = false }
  M.m:run{ time = 0.5e-3 }
  local res = { axis = {}, ke = 0, px = 0, py = 0, corner_u = { at_corner:value("ux"), at_corner:value("uy") } }
  M.m:run{ time = t_end }
  -- kinetic energy (J per m of depth) and momentum (kg m/s per m) of the
  -- corner block at the load's peak, 0.5 ms
  local cell = 0.1 * 0.1 * rock.density
  for _, mon in ipairs(grid_mons) do
    local t, vx, vy = mon:times(), mon:series("vx"), mon:series("vy")
    local k = 1
    while t[k + 1] and t[k + 1] <= 0.5e-3 + 1e-12 do k = k + 1 end
    res.ke = res.ke + 0.5 * cell * (vx[k] ^ 2 + vy[k] ^ 2)
    res.px, res.py = res.px + cell * vx[k], res.py + cell * vy[k]
  end
  for i, y in ipairs(axis) do
    local v, t = axis_mons[i]:peak("vy")
    res.axis[i] = { y = y, ppv = math.abs(v), t = t }
  end
  for i, p in ipairs(points) do
    local t, vx, vy = mons[i]:times(), mons[i]:series("vx"), mons[i]:series("vy")
    local r = { name = p.name, travel = wall_distance(p.at) / cp, peak = 0 }
    for k = 1, #t do
      local s = math.sqrt(vx[k] ^ 2 + vy[k] ^ 2)
      if not r.arrival and s > 0.01 * v_wall then r.arrival = t[k] end
      if t[k] <= 0.5e-3 + 1e-12 then r.at_peak = s end
      if t[k] <= 1e-3 + 1e-12 then r.peak = math.max(r.peak, s) end
    end
    res[i] = r
  end
  M.m:close()
  return res
end

local results = { { label = "first-order corners", r = run(true) }, { label = "meshed corners", r = run(false) } }
print(string.format("corner block of the chamber (-4, 2), elements %g m within 12 m, DHI 2.03 m/s, C_P = %.0f m/s", mesh, cp))
print("| corners | monitor | travel time (ms) | arrival (ms) | |v| at 0.5 ms (m/s) | peak |v| to 1 ms (m/s) |")
print("|---|---|---:|---:|---:|---:|")
for _, set in ipairs(results) do
  for _, r in ipairs(set.r) do
    print(string.format("| %s | %s | %.3f | %s | %.3f | %.3f |", set.label, r.name, 1e3 * r.travel,
                        r.arrival and string.format("%.3f", 1e3 * r.arrival) or "none", r.at_peak, r.peak))
  end
end

local d_dhi = 0.5 * v_wall * 0.5e-3   -- m: the wall's displacement at 0.5 ms
for _, set in ipairs(results) do
  set.corner_err = math.max(math.abs(-set.r.corner_u[1] / d_dhi - 1), math.abs(set.r.corner_u[2] / d_dhi - 1))
  print(string.format("%s: corner point at 0.5 ms (%.4f, %.4f) mm, the DHI (%.4f, %.4f) mm: off by %.1f %%", set.label,
                      1e3 * set.r.corner_u[1], 1e3 * set.r.corner_u[2], -1e3 * d_dhi, 1e3 * d_dhi, 100 * set.corner_err))
end
print(string.format("upper-left corner block (%d grid points, %.2f m^2): at 0.5 ms", #grid, 0.01 * #grid))
for _, set in ipairs(results) do
  print(string.format("  %s: kinetic energy %.0f J/m, momentum (%.0f, %.0f) kg m/s per m", set.label, set.r.ke,
                      set.r.px, set.r.py))
end
print("| corners | PPV at y = 4 / 6 / 8 m on the axis (m/s) | at (ms) |")
print("|---|---|---|")
for _, set in ipairs(results) do
  local p, t = {}, {}
  for i, a in ipairs(set.r.axis) do p[i] = string.format("%.3f", a.ppv); t[i] = string.format("%.2f", 1e3 * a.t) end
  print(string.format("| %s | %s | %s |", set.label, table.concat(p, " / "), table.concat(t, " / ")))
end

if check then
  if results[2].corner_err > 0.02 then
    error(string.format("meshed corners: the corner point is %.1f %% off the DHI's motion (allowed 2 %%)", 100 * results[2].corner_err))
  end
  if results[1].corner_err < 0.10 then
    error(string.format("first-order corners: the corner point follows the DHI within %.1f %% (expected a miss over 10 %%)",
                        100 * results[1].corner_err))
  end
  for _, r in ipairs(results[2].r) do
    if not r.arrival or r.arrival < 0.9 * r.travel then
      error(string.format("meshed corners: %s moves at %s ms, before 0.9 x its travel time %.3f ms", r.name,
                          tostring(r.arrival and 1e3 * r.arrival), 1e3 * r.travel))
    end
  end
  local far = results[1].r[1]
  if not far.arrival or far.arrival > far.travel / 3 then
    error(string.format("first-order corners: the far point moves at %s ms, not before a third of its travel time " ..
                        "%.3f ms (no plug?)", tostring(far.arrival and 1e3 * far.arrival), 1e3 * far.travel))
  end
  print("check passed")
end
