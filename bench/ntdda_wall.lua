-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- ntdda_wall.lua: this engine's half of bench/ntdda_side_by_side.sh: one wall,
-- CPU ms, open-close iterations and simulated ms per step after the untimed ones.
--
-- Models:  scripts/bench/scenes.lua's wall(n); --set gg=0|1 (quasi-static or
--          dynamic), --set solver=auto|pcg|cholmod, --set tol=default|ntdda|<number>
--          (ntdda: contact_tolerance set to ntdda's open-close tolerance,
--          2e-7 of w0 = half the model's larger side, where ours is a fraction of
--          half its height; a number: that contact_tolerance), --set law=shi|holding
--          (default "shi", ntdda's own contact law, under which contact_tolerance
--          acts; "holding" has bands of its own), --set threads,
--          --set steps=10 timed after
--          --set warmup=2.
-- Run:     build/dda run bench/ntdda_wall.lua --set n=20 --set gg=1
-- Writes:  one line: OURS cpu_ms_per_step X oc_per_step X sim_ms_per_step X cuts X
--          solver S settlement_um X wall_ms_per_step X cg_per_step X
--          factorisations_per_step X (CPU time of the process,
--          all threads, from os.clock; settlement: the bricks' mean centroid
--          displacement downwards over the whole run, µm; wall: the steps' own
--          elapsed time, m:stats().t_total).

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "../scripts/bench/?.lua"
local scenes = require "scenes"

local n = dda.param("n", 10)
local gg = dda.param("gg", 0)
local threads = dda.param("threads", 1)
local solver = dda.param("solver", "auto")
local tol = dda.param("tol", "default")
local steps = dda.param("steps", 10)
local warmup = dda.param("warmup", 2)

local m = scenes.wall(n, threads)
m:controls{ gg = gg, solver = solver, contact_law = dda.param("law", "shi") }
if tol == "ntdda" then
  -- The wall spans x from -1 to n + 1 and y from -1 to n: ntdda's w0 is (n + 2) / 2,
  -- half our model height (n + 1) / 2.
  m:controls{ contact_tolerance = 2e-7 * (n + 2) / (n + 1) }
elseif tonumber(tol) then
  m:controls{ contact_tolerance = tonumber(tol) }
elseif tol ~= "default" then
  error("tol must be 'default', 'ntdda' or a contact_tolerance (got '" .. tostring(tol) .. "')")
end
m:step(warmup)
local t_start, cpu_start = m:time(), os.clock()
local oc, cuts, wall, cg, factorisations = 0, 0, 0, 0, 0
for _ = 1, steps do
  m:step(1)
  local s = m:stats()
  oc, cuts, wall = oc + s.open_close_iterations, cuts + s.step_cuts, wall + s.t_total
  cg, factorisations = cg + s.cg_iterations, factorisations + s.factorisations
end
local cpu = os.clock() - cpu_start
-- The wall's settlement: the bricks' mean centroid displacement since the start.
local sum, count = 0, 0
for _, b in ipairs(m:blocks{ where = function(b) local _, y = b:centroid() return y > 0 end }) do
  local _, uy = b:displacement()
  sum, count = sum - uy, count + 1
end
print(string.format("OURS cpu_ms_per_step %.3f oc_per_step %.3f sim_ms_per_step %.6f cuts %d solver %s settlement_um %.4f wall_ms_per_step %.3f cg_per_step %.1f factorisations_per_step %.2f",
  1e3 * cpu / steps, oc / steps, 1e3 * (m:time() - t_start) / steps, cuts, m:stats().solver, 1e6 * sum / count,
  1e3 * wall / steps, cg / steps, factorisations / steps))
