-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- plate_bar.lua: the unjointed rock bar, the engine's default wave model against
-- the exact 2-D answer (Rayleigh-Lamb plate modes) and the 1-D one.
--
-- Models:  Model 1's bar without joints: one block 20 m x 1 m, rho = 2000
--          kg/m^3, E = 50 GPa, nu = 0 or 0.25, plane stress; one sine period of
--          5 MPa (compression first) at f on the left end, the right end fixed;
--          sigma_xx at (10.1, 0.5). Everything else is the engine's default
--          (docs/waves.md): the block meshed for the pulse, lumped mass, Newmark;
--          dt = 2e-6 s (--set dt=). --set sizes=0.2,0.1 runs given element
--          sizes instead (the convergence table).
--          References: the exact 2-D answer of a long strip 1 m high with a free
--          end (dda.exact_plate_bar: the symmetric Rayleigh-Lamb modes, Fourier
--          synthesis of the pulse, to 20 kHz), and the 1-D bar's
--          sigma = -p(t - x/c0), c0 = 5000 m/s (exact for nu = 0).
-- Run:     build/dda run scripts/waves/plate_bar.lua [--set nus=0,0.25] [--set freqs=500,1000,1500]
--                   [--set dt=2e-6] [--set sizes=auto] [--set check=true] [--set tolerance=2]
-- Writes:  out/plate_bar.csv: nu, f (Hz), element size (m), elements, dt, the first
--          compressive peak (MPa) ours / 2-D / 1-D, the differences (%), the
--          arrival of 1 % of the amplitude (ms) ours / 2-D, the largest tension
--          ahead of the peak (%); out/plate_bar_<nu>_<f>.png: ours and the two
--          references. With --set check=true: an error unless every first peak
--          is within `tolerance` % of the 2-D answer.

local dda = require "dda"

local E, rho, A, x, at_y = 50e9, 2000, 5e6, 10.1, 0.5
local dt = dda.param("dt", 2e-6)
local check = dda.param("check", false)
local tolerance = dda.param("tolerance", 2)
local function list(name, default)
  local out = {}
  for v in tostring(dda.param(name, default)):gmatch("[^,]+") do out[#out + 1] = v end
  return out
end
local nus, freqs, sizes = list("nus", "0,0.25"), list("freqs", "500,1000,1500"), list("sizes", "auto")

-- One sine period at f as a table (the engine's history; 400 points a period).
local function pulse(f)
  local t = {}
  for i = 0, 400 do t[#t + 1] = { i / (400 * f), A * math.sin(2 * math.pi * i / 400) } end
  return t
end

local function run(nu, f, size)
  local controls = { plane = "stress", g1 = dt, g2 = 0.01, gg = 1 }
  if size ~= "auto" then controls.mesh_size = tonumber(size) end
  local m = dda.model(controls)
  local rock = m:rock{ density = rho, E = E, nu = nu }
  m:add_block{ {0, 0}, {20, 0}, {20, 1}, {0, 1}, rock = rock }
  m:edges{ on_segment = {0, 0, 0, 1} }:pressure(pulse(f))
  m:edges{ on_segment = {20, 0, 20, 1} }:fix()
  local name = string.format("plate_bar_%g_%g_%s", nu, f, size)
  local centre = m:monitor{ name = name, at = {x, at_y}, fields = {"sxx"} }
  local t_end = x / 5000 + 1 / f + 0.3e-3
  local cpu = os.clock()
  m:run{ time = t_end }
  local r = { times = centre:times(), sxx = centre:series("sxx"), elements = #m:blocks(), cpu = os.clock() - cpu,
              steps = m:steps() }
  m:close()
  return r
end

-- The first compressive peak (refined by a parabola), the arrival of 1 % of
-- the amplitude, the largest tension before the peak.
local function first_peak(times, sxx, t_window)
  local bi, best = nil, 0
  for i = 1, #times do if times[i] <= t_window and sxx[i] < best then best, bi = sxx[i], i end end
  local v, t = sxx[bi], times[bi]
  if bi > 1 and bi < #times then
    local y0, y1, y2 = sxx[bi - 1], sxx[bi], sxx[bi + 1]
    local den = y0 - 2 * y1 + y2
    if den ~= 0 then
      local d = 0.5 * (y0 - y2) / den
      if math.abs(d) <= 1 then v, t = y1 - 0.25 * (y0 - y2) * d, t + d * (times[bi + 1] - times[bi]) end
    end
  end
  local arrival, lobe = nil, 0
  for i = 1, #times do
    if not arrival and sxx[i] < -0.01 * A then arrival = times[i] end
    if times[i] < t then lobe = math.max(lobe, sxx[i]) end
  end
  return v, t, arrival, lobe
end

local rows, failures = {}, {}
for _, nu_text in ipairs(nus) do
  local nu = tonumber(nu_text)
  for _, f_text in ipairs(freqs) do
    local f = tonumber(f_text)
    local t_window = x / 5000 + 0.5 / f  -- the first (compressive) half of the pulse at the centre
    local refs = nil
    for _, size in ipairs(sizes) do
      local r = run(nu, f, size)
      if not refs then
        -- The references at the run's own times.
        local two = dda.exact_plate_bar{ load = pulse(f), x = x, y = 0, times = r.times, E = E, nu = nu, density = rho,
                                         height = 1, ["end"] = "free" }
        local one = {}
        for i, t in ipairs(r.times) do
          local s = t - x / 5000
          one[i] = (s > 0 and s < 1 / f) and -A * math.sin(2 * math.pi * f * s) or 0
        end
        refs = { two = two, one = one, t = r.times }
      end
      local ours, t_ours, arr_ours, lobe = first_peak(r.times, r.sxx, t_window)
      local two, _, arr_two = first_peak(refs.t, refs.two, t_window)
      local one = first_peak(refs.t, refs.one, t_window)
      local d2, d1 = 100 * (ours - two) / math.abs(two), 100 * (ours - one) / math.abs(one)
      local h = size == "auto" and "auto" or size
      -- no arrival: a bar left as one first-order block (beyond the wave
      -- model's budget) carries its mean stress only
      arr_ours = arr_ours or 0 / 0
      rows[#rows + 1] = string.format("%g,%g,%s,%d,%g,%.4f,%.4f,%.4f,%+.2f,%+.2f,%.4f,%.4f,%.2f,%.1f", nu, f, h,
                                      r.elements, dt, ours / 1e6, two / 1e6, one / 1e6, d2, d1, arr_ours * 1e3,
                                      arr_two * 1e3, 100 * lobe / A, r.cpu)
      print(string.format("nu = %-4g f = %4g Hz %-5s (%5d elements): first peak %.4f MPa, 2-D %.4f (%+.2f %%), 1-D %.4f "
                          .. "(%+.2f %%); arrival %.4f ms, 2-D %.4f; tension ahead %.2f %%; %.1f s", nu, f, h,
                          r.elements, ours / 1e6, two / 1e6, d2, one / 1e6, d1, arr_ours * 1e3, arr_two * 1e3,
                          100 * lobe / A, r.cpu))
      if math.abs(d2) > tolerance then
        failures[#failures + 1] = string.format("nu = %g, %g Hz, %s: %+.2f %%", nu, f, h, d2)
      end
      if dda.has_render then
        dda.plot{ file = string.format("plate_bar_%g_%g_%s.png", nu, f, h),
                  series = { { name = "ours", x = r.times, y = r.sxx },
                             { name = "exact 2-D (plate modes)", x = refs.t, y = refs.two },
                             { name = "exact 1-D", x = refs.t, y = refs.one } },
                  title = string.format("unjointed bar, nu = %g, %g Hz: sigma_xx at (10.1, 0.5)", nu, f),
                  x_label = "time", x_unit = "ms", x_scale = 1e3, y_label = "sxx", y_unit = "MPa", y_scale = 1e-6,
                  width = 1000, height = 500 }
      end
    end
  end
end
local out = assert(io.open(dda.output("plate_bar.csv"), "w"))
out:write("nu,f,size,elements,dt,peak,peak_2d,peak_1d,diff_2d_percent,diff_1d_percent,arrival_ms,arrival_2d_ms,"
          .. "tension_ahead_percent,cpu_s\n", table.concat(rows, "\n"), "\n")
assert(out:close())
if check and #failures > 0 then
  error("first peak off the exact 2-D answer by more than " .. tolerance .. " %: " .. table.concat(failures, "; "), 0)
end
