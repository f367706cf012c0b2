-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- bar_time_step.lua: the paper's Model 1 bar with the second-order time
-- integrator: how far the paper's step (2e-6 s) is from the step's limit, and
-- how far that limit is from the exact jointed bar (the blocks' own error).
--
-- Models:  Model 1 (bars.lua, wave.lua: g0 = E, joints phi = 40 deg,
--          c = sigma_t = 8 MPa), one sine period of 5 MPa (compression first)
--          at each frequency, right end fixed; sigma_xx at x = `at` (10.1 m).
--          Each frequency runs with `integrator` (newmark) at each step of
--          `dts` (2e-6, 1e-6, 5e-7 s: halving), and with Shi's scheme at 2e-6 s.
-- Measures: the first compressive and tensile peaks (wave.lua's definitions);
--          the step's limit by Richardson extrapolation from the two smallest
--          steps (second order: limit = (4 p(dt/2) - p(dt)) / 3); the exact
--          peaks of the 1-D jointed bar (jointed_bar_exact.lua: k_n = 2 g0 / 0.2 m,
--          the paper's Eq. 4).
-- Run:     build/dda run scripts/paper/bar_time_step.lua [--set freqs=500,1000,1500]
--                   [--set dts=2e-6,1e-6,5e-7] [--set at=10.1] [--set check=true]
-- Writes:  out/bar_time_step.csv (frequency, peak, scheme, dt, MPa) and prints the
--          table. check=true: error unless every peak at the first step of `dts`
--          lies within `tolerance` (0.5 %) of the limit.

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local wave = require "wave"
local exact = require "jointed_bar_exact"

local freqs = tostring(dda.param("freqs", "500,1000,1500"))
local dts_text = tostring(dda.param("dts", "2e-6,1e-6,5e-7"))
local at = dda.param("at", 10.1)
local integrator = dda.param("integrator", "newmark")
local check = dda.param("check", false)
local tolerance = dda.param("tolerance", 0.005)

local dts = {}
for k in dts_text:gmatch("[^,]+") do dts[#dts + 1] = tonumber(k) end
assert(#dts >= 2, "bar_time_step: dts needs at least two steps, each half the one before")

local rows, failures = {}, {}
local function row(f, peak, scheme, dt, value)
  rows[#rows + 1] = string.format("%g,%s,%s,%s,%.6f", f, peak, scheme, dt and string.format("%g", dt) or "", value)
end

for k in freqs:gmatch("[^,]+") do
  local f = tonumber(k)
  local T = 1 / f
  local t_end = at / 4000 + T + 3e-4  -- past the first tensile peak (joints slow the wave to about 4100 m/s)
  local peaks = {}
  local function measure(r)
    local comp = wave.incident(r, "comp")
    local tens = wave.incident(r, "tens")
    return { comp = comp / 1e6, tens = tens / 1e6 }
  end
  for i, dt in ipairs(dts) do
    local r = wave.run{ tag = string.format("bar_%gHz_%s_%g", f, integrator, dt), g0 = 1, load = "full", freq = f,
                        t_end = t_end, integrator = integrator, dt = dt, at = {at, 0.5} }
    peaks[i] = measure(r)
    row(f, "comp", integrator, dt, peaks[i].comp)
    row(f, "tens", integrator, dt, peaks[i].tens)
  end
  local shi = measure(wave.run{ tag = string.format("bar_%gHz_shi", f), g0 = 1, load = "full", freq = f,
                                t_end = t_end, integrator = "shi", dt = dts[1], at = {at, 0.5} })
  local A = wave.A
  local _, rec = exact.run{ length = 20, rho = 2000, E = wave.E, spacing = 0.2, kn = 2 * wave.E / 0.2,
                            load = function(t) return (t > 0 and t < T) and -A * math.sin(2 * math.pi * f * t) or 0 end,
                            right = "fixed", receivers = {at}, t_end = t_end, h = 1e-7 }
  local lo, hi = exact.peaks(rec[1])
  local ex = { comp = lo / 1e6, tens = hi / 1e6 }
  print(string.format("\n%g Hz, sigma_xx at x = %g m (MPa):", f, at))
  print(string.format("  %-5s %10s %10s %10s %10s %12s %10s", "peak", "shi 2e-6", integrator .. " " .. dts[1],
                      "limit", "exact", "step error", "blocks"))
  for _, p in ipairs{"comp", "tens"} do
    local n = #dts
    local limit = (4 * peaks[n][p] - peaks[n - 1][p]) / 3
    local step_error = (peaks[1][p] - limit) / math.abs(limit)
    row(f, p, "limit", nil, limit)
    row(f, p, "exact", nil, ex[p])
    print(string.format("  %-5s %10.4f %10.4f %10.4f %10.4f %11.3f%% %9.2f%%", p, shi[p], peaks[1][p], limit, ex[p],
                        100 * step_error, 100 * (limit - ex[p]) / math.abs(ex[p])))
    if math.abs(step_error) > tolerance then
      failures[#failures + 1] = string.format("%g Hz %s peak at dt = %g: %.3f %% from the limit", f, p, dts[1],
                                              100 * step_error)
    end
  end
end

local out = dda.out_dir()
local file = io.open(out .. "/bar_time_step.csv", "w")
if file then
  file:write("frequency,peak,scheme,dt,MPa\n", table.concat(rows, "\n"), "\n")
  file:close()
end
if check and #failures > 0 then error("bar_time_step: " .. table.concat(failures, "; "), 0) end
