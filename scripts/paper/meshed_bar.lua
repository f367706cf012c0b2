-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- meshed_bar.lua: the paper's Model 1 bar with its blocks meshed (deformable
-- blocks, docs/meshed_blocks.md) against the exact jointed bar.
--
-- Models:  Model 1 (bars.lua, wave.lua: 0.2 m blocks, joints phi = 40 deg,
--          c = sigma_t = 8 MPa), one sine period of 5 MPa (compression first) at
--          `freq` (1500 Hz), right end fixed, `integrator` (newmark) at Δt = `dt`
--          (2e-6 s); each 0.2 m block meshed at each size of `sizes` (0.1, 0.05 m),
--          and, for comparison, the first-order blocks ("-"). The joints get the
--          paper's stiffness as their own, k_n = 2 g0 / 0.2 m with g0 = E (Eq. 4):
--          on a meshed block a contact stands for a share of the joint's length, so
--          the joint keeps its stiffness whatever the mesh (docs/meshed_blocks.md).
-- Measures: the first compressive and tensile peaks of sigma_xx at x = `at`
--          (10.1 m, the bar's centre; wave.lua's definitions) against the exact
--          jointed bar (jointed_bar_exact.lua, the same k_n).
-- Run:     build/dda run scripts/paper/meshed_bar.lua [--set sizes=0.1,0.05]
--                   [--set freq=1500] [--set at=10.1] [--set check=true]
-- Writes:  out/meshed_bar.csv (size, peak, MPa, exact, error) and prints the table.
--          check=true: error unless the compressive peak at the last size of
--          `sizes` lies within `tolerance` (3 %) of the exact one.

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local wave = require "wave"
local exact = require "jointed_bar_exact"

local sizes_text = tostring(dda.param("sizes", "0.1,0.05"))
local f = dda.param("freq", 1500)
local at = dda.param("at", 10.1)
local dt = dda.param("dt", 2e-6)
local integrator = dda.param("integrator", "newmark")
local nu = dda.param("nu", 0.25)
local first_order = dda.param("first_order", true)
local check = dda.param("check", false)
local tolerance = dda.param("tolerance", 0.03)

local sizes = {}
for k in sizes_text:gmatch("[^,]+") do sizes[#sizes + 1] = tonumber(k) end
assert(#sizes >= 1, "meshed_bar: sizes needs at least one mesh size")

local T = 1 / f
local t_end = at / 4000 + T + 3e-4  -- past the first tensile peak
local kn = 2 * wave.E / 0.2
local A = wave.A
local _, rec = exact.run{ length = 20, rho = 2000, E = wave.E, spacing = 0.2, kn = kn,
                          load = function(t) return (t > 0 and t < T) and -A * math.sin(2 * math.pi * f * t) or 0 end,
                          right = "fixed", receivers = {at}, t_end = t_end, h = 1e-7 }
local lo, hi = exact.peaks(rec[1])
local ex = { comp = lo / 1e6, tens = hi / 1e6 }

local rows, last = {}, nil
print(string.format("\n%g Hz, nu = %g, sigma_xx at x = %g m (MPa), %s at %g s; exact: comp %.4f, tens %.4f", f, nu,
                    at, integrator, dt, ex.comp, ex.tens))
print(string.format("  %-8s %10s %9s %10s %9s", "mesh", "comp", "error", "tens", "error"))
local runs = {}
if first_order then runs[#runs + 1] = false end
for _, h in ipairs(sizes) do runs[#runs + 1] = h end
for _, h in ipairs(runs) do
  local r = wave.run{ tag = string.format("meshed_bar_%gHz_%s", f, h and tostring(h) or "first_order"), g0 = 1,
                      load = "full", freq = f, t_end = t_end, integrator = integrator, dt = dt, at = {at, 0.5},
                      mesh_size = h or nil, kn = kn, nu = nu }
  local p = { comp = wave.incident(r, "comp") / 1e6, tens = wave.incident(r, "tens") / 1e6 }
  local e = { comp = (p.comp - ex.comp) / math.abs(ex.comp), tens = (p.tens - ex.tens) / math.abs(ex.tens) }
  local name = h and string.format("%g m", h) or "-"
  print(string.format("  %-8s %10.4f %8.2f%% %10.4f %8.2f%%", name, p.comp, 100 * e.comp, p.tens, 100 * e.tens))
  for _, k in ipairs{"comp", "tens"} do
    rows[#rows + 1] = string.format("%s,%s,%.6f,%.6f,%.6f", h and tostring(h) or "", k, p[k], ex[k], e[k])
  end
  if h then last = e end
end

local file = io.open(dda.out_dir() .. "/meshed_bar.csv", "w")
if file then
  file:write("size,peak,MPa,exact,error\n", table.concat(rows, "\n"), "\n")
  file:close()
end
if check and last and math.abs(last.comp) > tolerance then
  error(string.format("meshed_bar: compressive peak %.2f %% from the exact jointed bar (tolerance %.1f %%)",
                      100 * last.comp, 100 * tolerance), 0)
end
