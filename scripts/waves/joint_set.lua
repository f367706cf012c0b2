-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- joint_set.lua: a P wave across N parallel joints, the engine's default wave
-- model against the exact transmission coefficient |T_N| (transfer matrices).
--
-- Models:  a bar 0.1 m high (rho = 2000 kg/m^3, E = 50 GPa, nu = 0: the
--          plane-stress strip is then the 1-D rod the reference assumes, c = 5000
--          m/s, Z = rho c), cut across by N vertical joints `spacing` apart, each
--          with its own normal stiffness kn (m:joint{kn = }, which the mesh keeps).
--          A compliant left end (edges:viscous_boundary{vx = }) sends in a Ricker
--          pulse of particle velocity peaking at f = 1000 Hz; the right end
--          absorbs (edges:viscous_boundary{}). Monitor A (0.5 m from the left end)
--          records the incident pulse before the joints' first reflection comes
--          back; monitor B (0.5 m past the last joint) the whole transmitted wave,
--          the run going on until its tail is under 1e-4 of its peak. The
--          engine's |T|(f) is |V_B(f)| / |V_A(f)|, the exact Fourier transforms
--          of the piecewise-linear records (1-D propagation without loss keeps
--          |V| from A to B). A case is named at f = 1000 Hz (lambda = 5 m):
--          N, spacing/lambda, kn/(omega Z/2).
--          Everything else is the engine's default (docs/waves.md): it meshes the
--          blocks for the pulse (99 % of its energy below 1942 Hz: elements of
--          0.152 m), lumps the mass, steps with Newmark. dt = 1e-5 s (100 steps a
--          period at 1000 Hz) is pinned (--set dt=; 0: the default rule): the
--          default steps at 2.5e-7 s here, for the same |T| within 0.03 % at 30
--          times the cost.
--          Reference: dda.exact_joint_set (engine/reference/joint_set.hpp),
--          the transfer-matrix |T_N| of Cai & Zhao (2000).
-- Run:     build/dda run scripts/waves/joint_set.lua [--set counts=1,2,3,5,10]
--                   [--set spacings=0.05,0.25,1] [--set stiffnesses=0.5,2,20]
--                   [--set cases=N:s:k,...] [--set dt=1e-5] [--set mesh_size=-1] [--set check=true]
--                   [--set tolerance=2] [--set max_sensitivity=20] [--set figure=joint_set.png]
-- Writes:  out/joint_set.csv: N, spacing/lambda, kn/(omega Z/2), |T| ours, exact,
--          the difference (%), d ln|T| / d ln c (below), checked or not,
--          elements, steps, the record's length, its cut tail, CPU s; the same
--          table on stdout (markdown); out/<figure> (when built with the
--          renderer): |T| over frequency, ours and exact, for the cases of the
--          sweep the figure shows. With --set check=true: an error unless every
--          case is within `tolerance` % of the exact |T|, but for those where
--          |T| is too sensitive to the wave speed to be checked at this mesh,
--          |d ln|T| / d ln c| > max_sensitivity (20: a 0.1 % error in the wave
--          speed, about what the elements and the step carry at 1000 Hz, moves
--          |T| by over 2 %), or too small to stand above the record's cut tail,
--          |T| < min_transmission (1e-3); those are listed on stdout.

local dda = require "dda"

local E, rho = 50e9, 2000
local c = math.sqrt(E / rho)
local Z = rho * c
local f_ref = 1000                       -- Hz: the frequency a case is named at
local lambda = c / f_ref
local height = 0.1                       -- m
local dt = dda.param("dt", 1e-5)
local mesh_size = dda.param("mesh_size", -1)   -- m: elements of this size instead of the engine's (-1)
local check = dda.param("check", false)
local tolerance = dda.param("tolerance", 2)
local figure = tostring(dda.param("figure", "joint_set.png"))
local t_cap = dda.param("t_cap", 0.6)    -- s: the longest record
-- The check holds where a 0.1 % error in the wave speed moves |T| by at most
-- 2 %, |d ln|T| / d ln c| <= 20 (see sensitivity below), and where the
-- transmitted wave stands above what the record leaves out (its tail under
-- 1e-4 of its peak): |T| >= 1e-3.
local max_sensitivity = dda.param("max_sensitivity", 20)
local min_transmission = dda.param("min_transmission", 1e-3)

local function list(name, default)
  local out = {}
  for v in tostring(dda.param(name, default)):gmatch("[^,]+") do out[#out + 1] = v end
  return out
end

-- The cases: --set cases=N:s:k,... or every count x spacing x stiffness (one
-- joint has no spacing: once per stiffness).
local cases = {}
if dda.param("cases", "") ~= "" then
  for _, text in ipairs(list("cases", "")) do
    local n, s, k = text:match("^([^:]+):([^:]+):([^:]+)$")
    assert(n, "cases: N:spacing/lambda:kn/(omega Z/2), got " .. text)
    cases[#cases + 1] = { n = math.tointeger(tonumber(n)), s = tonumber(s), k = tonumber(k) }
  end
else
  for _, n in ipairs(list("counts", "1,2,3,5,10")) do
    for i, s in ipairs(list("spacings", "0.05,0.25,1")) do
      for _, k in ipairs(list("stiffnesses", "0.5,2,20")) do
        if tonumber(n) > 1 or i == 1 then
          cases[#cases + 1] = { n = math.tointeger(tonumber(n)), s = tonumber(s), k = tonumber(k) }
        end
      end
    end
  end
end

-- The incident particle velocity: a Ricker pulse peaking at f_ref, 2.6 / f_ref long.
local pulse_length, amplitude = 2.6 / f_ref, 0.1
local pulse = {}
for i = 0, 400 do
  local t = i * pulse_length / 400
  local a = (math.pi * f_ref * (t - pulse_length / 2)) ^ 2
  pulse[#pulse + 1] = { t, amplitude * (1 - 2 * a) * math.exp(-a) }
end

-- |F(f)| of a piecewise-linear record up to t_last, exact: on a piece
-- g(t) = a + slope (t - t0), the integral of g e^{-iwt} is
-- [g e^{-iwt} i/w] + slope/w^2 [e^{-iwt}] between its ends.
local function spectrum(times, v, f, t_last)
  local w, re, im = 2 * math.pi * f, 0, 0
  for i = 2, #times do
    local t0, t1 = times[i - 1], times[i]
    if t1 > t_last then break end
    local a, b = v[i - 1], v[i]
    local slope = (b - a) / (t1 - t0)
    local c0, s0, c1, s1 = math.cos(w * t0), math.sin(w * t0), math.cos(w * t1), math.sin(w * t1)
    re = re + (b * s1 - a * s0) / w + slope * (c1 - c0) / (w * w)
    im = im + (b * c1 - a * c0) / w - slope * (s1 - s0) / (w * w)
  end
  return math.sqrt(re * re + im * im)
end

local function run(case)
  local s = case.s * lambda
  local kn = case.k * math.pi * f_ref * Z    -- k x (omega Z / 2)
  local x_a = 0.5
  local x_first = x_a + c * pulse_length / 2 + 0.5  -- the pulse has passed A before its reflection returns
  local x_last = x_first + (case.n - 1) * s
  local x_b = x_last + 0.5
  local length = x_b + 0.5
  local m = dda.model{ plane = "stress", g1 = dt, mesh_size = mesh_size }
  local rock = m:rock{ density = rho, E = E, nu = 0 }
  local joint = m:joint{ friction = 40, cohesion = 1e12, tension = 1e12, kn = kn }   -- no slip, no opening
  m:domain{ box = {0, 0, length, height}, rock = rock }
  for k = 0, case.n - 1 do
    local x = x_first + k * s
    m:joint_line{ from = {x, 0}, to = {x, height}, joint = joint }
  end
  m:generate()
  m:edges{ on_segment = {0, 0, 0, height} }:viscous_boundary{ vx = pulse }
  m:edges{ on_segment = {length, 0, length, height} }:viscous_boundary{}
  local a = m:monitor{ at = {x_a, height / 2}, fields = {"vx"}, csv = false }
  local b = m:monitor{ at = {x_b, height / 2}, fields = {"vx"}, csv = false }
  -- Until B's tail (the last round trip between the outer joints, at least 2 ms)
  -- is under 1e-4 of its peak.
  local chunk = math.max(2e-3, 2 * (x_last - x_first) / c)
  local t = x_b / c + pulse_length + chunk
  local cpu = os.clock()
  while true do
    m:run{ time = t }
    local times, v = b:times(), b:series("vx")
    local peak, tail = 0, 0
    for i = 1, #times do
      peak = math.max(peak, math.abs(v[i]))
      if times[i] > t - chunk then tail = math.max(tail, math.abs(v[i])) end
    end
    case.tail = tail / peak
    if case.tail < 1e-4 or t >= t_cap then break end
    t = math.min(t + chunk, t_cap)
  end
  case.cpu, case.elements, case.steps, case.record = os.clock() - cpu, #m:blocks(), m:steps(), t
  case.a_times, case.a_v = a:times(), a:series("vx")
  case.b_times, case.b_v = b:times(), b:series("vx")
  case.a_window = (2 * x_first - x_a) / c       -- the first reflection reaches A
  case.spacing, case.kn = s, kn
  m:close()
end

-- The exact |T| in a rock of wave speed c (1 + stretch), Z kept.
local function exact_transmission(case, f, stretch)
  local speed = c * (1 + (stretch or 0))
  return (dda.exact_joint_set{ count = case.n, spacing = case.spacing, kn = case.kn, E = Z * speed,
                               density = Z / speed, frequency = f })
end

local function transmission(case, f)
  local ours = spectrum(case.b_times, case.b_v, f, math.huge) / spectrum(case.a_times, case.a_v, f, case.a_window)
  return ours, exact_transmission(case, f)
end

-- How much |T| moves with the rock's wave speed: d ln|T| / d ln c. The
-- engine carries the waves a little slower than the rock (0.07 % at 1000 Hz
-- here: the elements and Newmark's step): where this is large, a joint set's
-- resonances move and |T| with them.
local function sensitivity(case, f)
  local d = 1e-4
  return (math.log(exact_transmission(case, f, d)) - math.log(exact_transmission(case, f, -d))) / (2 * d)
end

local function digits(t) return t >= 0.01 and string.format("%.4f", t) or string.format("%.3g", t) end

local rows, failures, unchecked = {}, {}, {}
print("| N | spacing/λ | k_n/(ωZ/2) | |T| engine | |T| exact | difference | d ln|T|/d ln c | elements | record (ms) |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for _, case in ipairs(cases) do
  run(case)
  case.ours, case.exact = transmission(case, f_ref)
  case.diff = 100 * (case.ours - case.exact) / case.exact
  case.sensitivity = sensitivity(case, f_ref)
  local checked = math.abs(case.sensitivity) <= max_sensitivity and case.exact >= min_transmission
  local name = string.format("N = %d, spacing %g lambda, kn %g (omega Z/2): %+.2f %%", case.n, case.s, case.k, case.diff)
  if not checked then
    unchecked[#unchecked + 1] = string.format("%s (|T| = %.2g, d ln|T|/d ln c = %.0f)", name, case.exact,
                                              case.sensitivity)
  elseif math.abs(case.diff) > tolerance then
    failures[#failures + 1] = name
  end
  print(string.format("| %d | %g | %g | %s | %s | %+.2f %%%s | %.1f | %d | %.0f |", case.n, case.s, case.k,
                      digits(case.ours), digits(case.exact), case.diff, checked and "" or " (not checked)", case.sensitivity,
                      case.elements, case.record * 1e3))
  rows[#rows + 1] = string.format("%d,%g,%g,%.6g,%.6g,%.3f,%.3f,%s,%d,%d,%.4f,%.2e,%.1f", case.n, case.s, case.k,
                                  case.ours, case.exact, case.diff, case.sensitivity, tostring(checked),
                                  case.elements, case.steps, case.record, case.tail, case.cpu)
end
local out = assert(io.open(dda.output("joint_set.csv"), "w"))
out:write("N,spacing_over_lambda,kn_over_omegaZ2,T_ours,T_exact,diff_percent,dlnT_dlnc,checked,elements,steps,record_s,tail,cpu_s\n",
          table.concat(rows, "\n"), "\n")
assert(out:close())

-- The figure: |T| from 300 to 2000 Hz (where the pulse carries at least a
-- tenth of its peak), ours and exact, for the cases it shows that were run.
local shown = { "1:0.05:0.5", "3:0.25:2", "10:0.05:2", "10:1:20", "3:1:0.5" }
if dda.has_render and figure ~= "" then
  local palette = { {31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {148, 103, 189}, {255, 127, 14} }
  local series = {}
  for _, case in ipairs(cases) do
    local key = string.format("%d:%g:%g", case.n, case.s, case.k)
    for i, want in ipairs(shown) do
      if key == want then
        local fs, ours, exact = {}, {}, {}
        for j = 0, 170 do
          local f = 300 + 10 * j
          fs[#fs + 1] = f
          ours[#ours + 1], exact[#exact + 1] = transmission(case, f)
        end
        local name = string.format("engine: N = %d, s = %g λ, k_n = %g ωZ/2", case.n, case.s, case.k)
        series[#series + 1] = { name = name, x = fs, y = ours, color = palette[i], width = 5 }
        series[#series + 1] = { name = "", x = fs, y = exact, color = {0, 0, 0}, width = 1 }
      end
    end
  end
  if #series > 0 then
    series[#series].name = "exact (transfer matrices)"   -- one legend entry for the black lines
    dda.plot{ file = figure, series = series, title = "P wave across N joints: |T| (case named at 1000 Hz)",
              x_label = "frequency", x_unit = "Hz", y_label = "|T|", width = 1000, height = 700,
              y_range = {-0.4, 1.05}, legend = "bottom_left" }
  end
end

if #unchecked > 0 then
  print("not checked (|T| too sensitive to the wave speed, or too small): " .. table.concat(unchecked, "; "))
end
if check and #failures > 0 then
  error("|T| off the exact transfer-matrix answer by more than " .. tolerance .. " %: " .. table.concat(failures, "; "),
        0)
end
