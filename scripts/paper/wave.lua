-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- wave.lua: shared runner and measurements for the paper's rock-bar figures
-- (Sections 2 and 3: scripts/paper/fig*.lua and validation_report.lua).
--
-- Models:  the bars of bars.lua (Models 1-6), rock rho = 2000 kg/m^3, E = 50 GPa,
--          nu = 0.25, plane stress (1-D bar speed sqrt(E/rho) = 5000 m/s), controls
--          g1 = 2e-6 s, gg = 1, g2 = 0.005, g0 given in multiples of E, Shi's time
--          integrator (the paper's: integrator = "shi" pinned, whatever the default).
--          Load: a pressure on the left-end edges (SHI, positive = compression
--          pushing into the bar), amplitude A (5 MPa), frequency f:
--            "half": p(t) = A sin(2 pi f t) for t < T/2, then 0 (compression only);
--            "full": p(t) = A sin(2 pi f t) for t < T, then 0 (compression first,
--                    then tension), T = 1/f.
--          Right end: "fixed" (fixed points at the edge ends), "free", "vbc"
--          (viscous boundary), "sbc" (spring boundary, p in multiples of E,
--          per_length = false: Eq. 21 p0; true: Eq. 22 p.l), or "sbc_incremental"
--          (the paper's SBC read as a spring on each step's displacement increment,
--          emulated with Lua point loads, explicit; for comparison, not an engine BC).
--          Monitor: sxx, vx at the bar centre (10.1, 0.5) (the block just right of
--          x = 10 m); optionally ux at (19.9, 0.5), the block at the right end.
-- Definitions used by every figure script:
--   input peak time     from the load function: compressive peak at T/4, tensile
--                       peak (full sine) at 3T/4;
--   peak at the centre  the extreme of sxx in the incident window (t < t_split),
--                       refined by a parabola through the extreme sample and its
--                       two neighbours; compression = min sxx, tension = max sxx;
--   wave speed          10.1 m / (t_peak_centre - t_peak_input), same peak;
--   attenuation         1 - |peak at the centre| / A;
--   reflected amplitude the sxx (or vx) of largest magnitude after t_split, signed;
--   t_split             20 m / c_guess + (load duration)/2, between the end of the
--                       incident pulse at the centre and the start of the reflection
--                       (c_guess = 5000 m/s, or 4000 m/s for g0 < 10 E);
--   absorbed share      1 - |reflected with the boundary| / |reflected with Fixed|;
--   T/dt                the wave period over the mean step of the run.
-- Use:     local wave = require "wave"; local r = wave.run{ tag = "fig3_g0_20", g0 = 20 }
-- Returns: r with the centre's series, the run's figures and its energy budget
--          (r.energy = m:energy() at the end).
-- Writes:  <out>/<tag>.csv (step, time, sxx, vx[, ux]) per run; fig:finish() writes
--          <out>/<figure>_numbers.csv (figure,quantity,paper,ours,unit) and the plots.

local dda = require "dda"
local bars = require "bars"

local wave = { E = 50e9, A = 5e6, x_centre = 10.1 }
local E = wave.E

-- The time integrator every wave.run without its own `integrator` uses: nil
-- (Shi's, the paper's), or { integrator = "newmark" | "generalized_alpha",
-- rho_inf = ..., suffix = "_newmark" } (validation_report.lua's second pass:
-- the suffix keeps that pass's monitors, numbers and plots apart), or
-- { default = true, suffix = "_default" [, dt = ...] [, nu = ...] }: the
-- engine's defaults for every choice the paper's runs pin (its third pass;
-- nu = 0 makes the bar the 1-D rod of the exact answer).
wave.scheme = nil
local function suffix() return wave.scheme and wave.scheme.suffix or "" end

-- The load history (a function of t) and its duration, input peak times.
function wave.load(kind, f, A)
  local T = 1 / f
  local dur = (kind == "full") and T or T / 2
  local fn = function(t)
    if t < dur then return A * math.sin(2 * math.pi * f * t) end
    return 0
  end
  return fn, dur, T / 4, 3 * T / 4
end

-- One bar run. opts: tag (monitor/CSV name), model (1), g0 (x E), load ("half"),
-- freq (1000), amp (5e6), phi (40), c (8e6), tension (8e6), right ("fixed"),
-- p (x E), per_length (true), t_end (s), end_monitor (false), integrator ("shi"),
-- rho_inf (generalized-α's spectral radius at infinity; the engine's default when nil),
-- dt (g1, 2e-6 s), at (the monitor point, bars.centre), mesh_size (m, the blocks
-- meshed; nil: first-order blocks), kn (the joints' stiffness, Pa/m; nil: from g0), nu (the
-- rock's Poisson's ratio; nil: bars.rock's 0.25).
function wave.run(o)
  local model = o.model or 1
  local freq, amp = o.freq or 1000, o.amp or wave.A
  local g0 = (o.g0 or 1) * E
  -- contact_law = "shi": the paper's DDA contact law, which its figures and
  -- docs/validation.md were made with (docs/contacts.md).
  -- mesh_size = 0: the paper's first-order blocks (the engine would mesh them
  -- for the pulse, docs/waves.md), unless the rock is given a mesh size; the
  -- consistent mass the meshed tables were measured with. wave.scheme =
  -- { default = true }: none of these pinned, the engine's defaults (the
  -- validation report's third pass).
  local scheme = o.integrator and o or wave.scheme or {}
  local controls = { plane = "stress", g0 = g0, g1 = o.dt or scheme.dt or 2e-6, g2 = 0.005, gg = 1 }
  if not scheme.default then
    controls.integrator = scheme.integrator or "shi"
    controls.rho_inf = scheme.rho_inf
    controls.contact_law = "shi"
    controls.mesh_size = 0
    controls.mesh_mass = o.mesh_mass or "consistent"
  end
  local m = dda.model(controls)
  -- mesh_size: blocks meshed (docs/meshed_blocks.md); kn: the joints' own stiffness (Pa/m).
  local rock = m:rock{ density = bars.rock.density, E = bars.rock.E, nu = o.nu or scheme.nu or bars.rock.nu,
                       mesh_size = o.mesh_size }
  local joint = m:joint{ friction = o.phi or 40, cohesion = o.c or 8e6, tension = o.tension or 8e6, kn = o.kn }
  local blocks = bars.build(m, model, rock, joint)
  local fn, dur, t_comp, t_tens = wave.load(o.load or "half", freq, amp)
  bars.left_end(m):pressure(fn)
  local right = o.right or "fixed"
  local re = bars.right_end(m, model)
  if right == "fixed" then re:fix()
  elseif right == "vbc" then re:viscous_boundary()
  elseif right == "sbc" then
    re:spring_boundary{ p = o.p * E, per_length = (o.per_length ~= false) }
  elseif right == "sbc_incremental" then
    -- The paper's SBC read as Shi's fixed point without the residual term: a spring
    -- p0 on each step's displacement increment, at each end of each edge (Eq. 21).
    -- Not an engine boundary: emulated here with point loads, explicitly (the force
    -- of a step is -p0 x the previous step's increment), for comparison only.
    local pts = {}
    for _, e in ipairs(re) do
      for _, at in ipairs{ e.from, e.to } do
        local pt = { fx = 0, fy = 0, ux = 0, uy = 0 }
        pt.mon = m:monitor{ at = at, block = e.block, fields = {"ux", "uy"}, csv = false }
        m:point_load{ at = at, block = e.block, force = function() return pt.fx, pt.fy end }
        pts[#pts + 1] = pt
      end
    end
    local k = o.p * E
    o.callback = function()
      for _, pt in ipairs(pts) do
        local ux, uy = pt.mon:value("ux"), pt.mon:value("uy")
        pt.fx, pt.fy = -k * (ux - pt.ux), -k * (uy - pt.uy)
        pt.ux, pt.uy = ux, uy
      end
    end
  elseif right ~= "free" then error("wave.run: unknown right end " .. tostring(right)) end
  local tag = o.tag .. suffix()
  local centre = m:monitor{ name = tag, at = o.at or bars.centre, fields = {"sxx", "vx"} }
  local endmon = nil
  if o.end_monitor then
    endmon = m:monitor{ name = tag .. "_end", at = {19.9, 0.5}, fields = {"ux"} }
  end
  m:run{ time = o.t_end, callback = o.callback }
  local c_guess = (o.g0 or 1) >= 10 and 5000 or 4000
  local r = {
    tag = o.tag, model = model, blocks = #blocks, steps = m:steps(), time = m:time(),
    dt = m:time() / math.max(m:steps(), 1), T = 1 / freq, dur = dur,
    t_comp = t_comp, t_tens = t_tens, cuts = m:totals().step_cuts,
    t = centre:times(), sxx = centre:series("sxx"), vx = centre:series("vx"),
    t_split = 20 / c_guess + dur / 2, file = centre:file(), monitor = centre, energy = m:energy(),
  }
  if endmon then r.ux_end = endmon:series("ux"); r.t_end_series = endmon:times() end
  r.T_over_dt = r.T / r.dt
  io.write(string.format("  %-28s %4d blocks %6d steps  T/dt = %.0f  cuts %d\n", tag, r.blocks,
                         r.steps, r.T_over_dt, r.cuts))
  m:close()
  return r
end

-- The exact 1-D answer for Model 1 (jointed_bar_exact.lua: joints every 0.2 m,
-- each a normal spring k_n = 2 g0 / 0.2 m, the paper's Eq. 4; the bar's speed
-- sqrt(E/rho)), at the centre, as a run table that wave.incident and
-- Figure:plot read. opts: g0 (x E, 1), load ("half"), freq (1000), amp,
-- right ("fixed", "free" or "absorbing"), t_end (s), h (the characteristics'
-- step, 2e-7 s: peaks to about 1e-4 of the amplitude).
function wave.exact(o)
  local exact = require "jointed_bar_exact"
  local freq, amp = o.freq or 1000, o.amp or wave.A
  local fn, dur, t_comp, t_tens = wave.load(o.load or "half", freq, amp)
  local t, rec = exact.run{ length = bars.length, rho = bars.rock.density, E = E, spacing = bars.spacing,
                            kn = 2 * (o.g0 or 1) * E / bars.spacing, load = function(tt) return -fn(tt) end,
                            right = o.right or "fixed", receivers = {wave.x_centre}, t_end = o.t_end,
                            h = o.h or 2e-7 }
  local c_guess = (o.g0 or 1) >= 10 and 5000 or 4000
  return { tag = "exact", t = t, sxx = rec[1], T = 1 / freq, dur = dur, t_comp = t_comp, t_tens = t_tens,
           t_split = 20 / c_guess + dur / 2 }
end

-- Extreme of vals in [t0, t1]: sign = -1 minimum, +1 maximum, 0 largest magnitude.
-- Returns the value and time, refined by a parabola through three samples.
function wave.peak(t, vals, t0, t1, sign)
  local best, bi = nil, nil
  for i = 1, #t do
    if t[i] >= t0 and t[i] <= t1 then
      local v = vals[i]
      local key = (sign == 0) and math.abs(v) or sign * v
      if best == nil or key > best then best, bi = key, i end
    end
  end
  if not bi then return 0, 0 end
  local v, tt = vals[bi], t[bi]
  if bi > 1 and bi < #t then
    local y0, y1, y2 = vals[bi - 1], vals[bi], vals[bi + 1]
    local h = t[bi + 1] - t[bi]
    local den = y0 - 2 * y1 + y2
    if den ~= 0 and math.abs(t[bi] - t[bi - 1] - h) < 1e-3 * h then
      local d = 0.5 * (y0 - y2) / den
      if math.abs(d) <= 1 then
        tt = t[bi] + d * h
        v = y1 - 0.25 * (y0 - y2) * d
      end
    end
  end
  return v, tt
end

-- Incident peak at the centre: "comp" or "tens"; returns value (Pa), time, speed.
function wave.incident(r, which)
  local sign = which == "tens" and 1 or -1
  local t_in = which == "tens" and r.t_tens or r.t_comp
  local v, t = wave.peak(r.t, r.sxx, t_in, r.t_split, sign)
  return v, t, wave.x_centre / (t - t_in)
end

-- Reflected amplitude (signed) of a field after t_split.
function wave.reflected(r, field)
  return (wave.peak(r.t, r[field or "sxx"], r.t_split, 1e9, 0))
end

-- A figure: rows of numbers, plots, checks.
local Figure = {}
Figure.__index = Figure

function wave.figure(name, title)
  local fig = setmetatable({ name = name, title = title, rows = {}, failures = {}, passes = {},
                             plots = {}, exact = {}, check = dda.param("check", false) }, Figure)
  io.write(string.format("%s: %s\n", name, title))
  return fig
end

-- paper may be nil (no number in the paper: a trend). note: free text for the report.
function Figure:row(quantity, paper, ours, unit, tdt, note)
  self.rows[#self.rows + 1] = { figure = self.name, quantity = quantity, paper = paper, ours = ours,
                                unit = unit or "", tdt = tdt, note = note }
  io.write(string.format("  %-52s paper %-10s ours %.6g %s\n", quantity,
                         paper and string.format("%.6g", paper) or "-", ours, unit or ""))
end

-- The exact 1-D joint physics' value of a row's quantity (wave.exact), for
-- the report's comparison of the schemes.
function Figure:exact_value(quantity, value)
  self.exact[quantity] = value
end

-- A target: cond true passes. Recorded; with --set check=true a failure raises at finish().
function Figure:target(name, cond, measured)
  local list = cond and self.passes or self.failures
  list[#list + 1] = name .. " (" .. measured .. ")"
  io.write(string.format("  target %-4s %s: %s\n", cond and "PASS" or "FAIL", name, measured))
end

-- A plot of sxx (MPa) at the centre against time (ms) for the given runs.
local palette = { {31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40},
                  {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127} }   -- 0-255
function Figure:plot(file, runs, labels, field, title)
  if not dda.has_render then return end
  field = field or "sxx"
  local series = {}
  for i, r in ipairs(runs) do
    local x, y = r.t, r[field]
    if field == "ux" then x, y = r.t_end_series, r.ux_end end
    series[#series + 1] = { name = labels[i], x = x, y = y, color = palette[(i - 1) % #palette + 1] }
  end
  local scale, unit, label = 1e-6, "MPa", "sxx at the centre"
  if field == "vx" then scale, unit, label = 1, "m/s", "vx at the centre" end
  if field == "ux" then scale, unit, label = 1e3, "mm", "ux at the right end" end
  file = file:gsub("%.png$", suffix() .. ".png")
  local path = dda.plot{ file = file, series = series, title = title or self.title, x_label = "time",
                         x_unit = "ms", x_scale = 1e3, y_label = label, y_unit = unit, y_scale = scale,
                         width = 1000, height = 500 }
  self.plots[#self.plots + 1] = path
end

local function csv_num(v)
  if v == nil then return "" end
  return string.format("%.6g", v)
end

function wave.csv_row(r)
  return string.format("%s,%s,%s,%s,%s", r.figure, r.quantity, csv_num(r.paper), csv_num(r.ours), r.unit)
end

function wave.write_rows(path, rows)
  local f = assert(io.open(path, "w"))
  f:write("figure,quantity,paper,ours,unit\n")
  for _, r in ipairs(rows) do f:write(wave.csv_row(r), "\n") end
  local ok, err = f:close()
  if not ok then error("cannot write " .. path .. ": " .. tostring(err), 2) end
end

-- Writes <out>/<name>_numbers.csv; raises when check=true and a target failed.
function Figure:finish()
  wave.write_rows(dda.output(self.name .. suffix() .. "_numbers.csv"), self.rows)
  if self.check and #self.failures > 0 then
    error(self.name .. ": targets not met: " .. table.concat(self.failures, "; "), 0)
  end
  return self
end

return wave
