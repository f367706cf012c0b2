-- joint_set.lua: a P wave across N parallel joints, the engine against the
-- exact transmission coefficient |T_N| (transfer matrices; Cai & Zhao 2000,
-- Zhu et al. 2011).
--
-- Models:  a 1-D bar (nu = 0, plane stress: c = sqrt(E/rho) = 5000 m/s, Z = rho c
--          = 1e7 Pa s/m), one row of rock 0.15 m high, crossed by N joints of
--          normal stiffness kn every s m. At f = 1000 Hz (lambda = 5 m) the
--          spacing is s = xi lambda and kn = K omega Z / 2 (|T_1| = [1 + 1/K^2]^(-1/2)).
--          A P wave comes in through the left end, a viscous boundary carrying an
--          incident velocity (a sine of 1000 Hz in a Gaussian window, 0.1 m/s) and
--          absorbing what comes back; the right end is a viscous boundary too.
--          sigma_xx is recorded 1 m beyond the last joint and in the same bar
--          without joints; |T_N| = the ratio of their spectra at f, each record
--          run until the bar holds under 1e-6 of the energy the wave brought in.
--          Everything else is the engine's default (docs/waves.md): the bar is
--          meshed for the wave (elements of 0.12 m), lumped mass, Newmark,
--          dt = 1e-5 s (--set dt=).
-- Run:     build/dda run scripts/waves/joint_set.lua [--set counts=1,2,...,10]
--                   [--set spacings=0.05,0.2,1] [--set stiffnesses=0.5,2,20]
--                   [--set check=true] [--set tolerance=2] [--set write_docs=true]
-- Writes:  out/joint_set.csv: N, spacing/lambda, K, |T_N| exact, ours, difference
--          (%); out/joint_set.png: |T_N| against N, exact (a broad line, one colour
--          per spacing and K) and ours (a thin black line over it); with --set write_docs=true the two into
--          docs/ (docs/waves_joint_set.csv, docs/figures/waves_joint_set.png).
--          With --set check=true: an error unless every |T_N| is within
--          `tolerance` % of the exact one (or 0.002 where |T_N| < 0.1: a stop band's
--          decay, far below the wave's amplitude).

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "../paper/?.lua"
local docs_output = require "docs_output"

local E, rho, f = 50e9, 2000, 1000
local c = math.sqrt(E / rho)
local Z, lambda, omega = rho * c, c / f, 2 * math.pi * f
local height = 0.15
local dt = dda.param("dt", 1e-5)
local check = dda.param("check", false)
local tolerance = dda.param("tolerance", 2)
local write_docs = dda.param("write_docs", false)

local function list(name, default)
  local out = {}
  for v in tostring(dda.param(name, default)):gmatch("[^,]+") do out[#out + 1] = tonumber(v) end
  return out
end
local counts = list("counts", "1,2,3,4,5,6,7,8,9,10")
local spacings = list("spacings", "0.05,0.2,1")
local stiffnesses = list("stiffnesses", "0.5,2,20")

-- The incident particle velocity: a 1000 Hz sine in a Gaussian window
-- centred at 1.5 ms (width 0.5 ms: its spectrum covers about 0.4-1.6 kHz).
local incident = {}
for i = 0, 300 do
  local t = i * 1e-5
  incident[#incident + 1] = { t, 0.1 * math.sin(omega * (t - 1.5e-3)) * math.exp(-((t - 1.5e-3) / 5e-4) ^ 2) }
end

-- One bar of `length`: joints at x0 + k s (k = 0 .. n - 1; none for n = 0),
-- receivers at `at` (x). Returns each receiver's record and the element count.
local function record(n, s, kn, length, at)
  local m = dda.model{ plane = "stress", g1 = dt, g2 = 0.01, gg = 1 }
  local rock = m:rock{ density = rho, E = E, nu = 0 }
  local joint = m:joint{ friction = 40, cohesion = 1e9, tension = 1e9, kn = kn }
  local x0 = 1.5 * lambda
  local cuts = { 0 }
  for k = 0, n - 1 do cuts[#cuts + 1] = x0 + k * s end
  cuts[#cuts + 1] = length
  for i = 1, #cuts - 1 do
    m:add_block{ {cuts[i], 0}, {cuts[i + 1], 0}, {cuts[i + 1], height}, {cuts[i], height}, rock = rock, joint = joint }
  end
  m:edges{ on_segment = {0, 0, 0, height} }:viscous_boundary{ vx = incident }
  m:edges{ on_segment = {length, 0, length, height} }:viscous_boundary()
  local probes = {}
  for i, x in ipairs(at) do
    probes[i] = m:monitor{ name = string.format("joint_set_%d_%d", n, i), at = {x, height / 2}, fields = {"sxx"},
                           csv = false }
  end
  -- Until the wave has passed and the bar holds under 1e-6 of the most it held.
  m:run{ time = 3.5e-3 }
  local most = 0
  for _ = 1, 1000 do
    local e = m:energy()
    local held = e.kinetic + e.strain + e.contact
    most = math.max(most, held)
    if m:time() > (length + lambda) / c + 3e-3 and held < 1e-6 * most then break end
    m:run{ time = m:time() + 1e-3 }
  end
  local out = {}
  for i, p in ipairs(probes) do out[i] = { p:times(), p:series("sxx") } end
  local elements = #m:blocks()
  m:close()
  return out, elements
end

-- |Σ σ(t)·exp(−iωt)·Δt| over a record.
local function spectrum(rec)
  local times, series = rec[1], rec[2]
  local re, im = 0, 0
  for i = 2, #times do
    local h = times[i] - times[i - 1]
    re = re + series[i] * math.cos(omega * times[i]) * h
    im = im - series[i] * math.sin(omega * times[i]) * h
  end
  return math.sqrt(re * re + im * im)
end

local rows, failures, cases = {}, {}, {}
for _, xi in ipairs(spacings) do
  local s = xi * lambda
  local length = 1.5 * lambda + (counts[#counts] - 1) * s + 1 + 1.5 * lambda
  -- The receivers (1 m beyond the last joint of each count) in the bar without joints.
  local at = {}
  for i, n in ipairs(counts) do at[i] = 1.5 * lambda + (n - 1) * s + 1 end
  local free = record(0, s, 1, length, at)
  for _, K in ipairs(stiffnesses) do
    local kn = K * omega * Z / 2
    local case = { xi = xi, K = K, n = {}, ours = {}, exact = {} }
    cases[#cases + 1] = case
    for i, n in ipairs(counts) do
      local jointed, elements = record(n, s, kn, length, { at[i] })
      local ours = spectrum(jointed[1]) / spectrum(free[i])
      local exact = dda.exact_joint_set{ count = n, spacing = s, kn = kn, E = E, density = rho, frequency = f }
      local diff = 100 * (ours - exact) / exact
      rows[#rows + 1] = string.format("%d,%g,%g,%.5f,%.5f,%.2f,%d", n, xi, K, exact, ours, diff, elements)
      print(string.format("N = %2d  s/lambda = %-5g K = %-4g |T| exact %.4f ours %.4f (%+.2f %%), %d elements", n, xi,
                          K, exact, ours, diff, elements))
      case.n[#case.n + 1], case.ours[#case.ours + 1], case.exact[#case.exact + 1] = n, ours, exact
      local ok = (exact < 0.1 and math.abs(ours - exact) <= 0.002) or math.abs(diff) <= tolerance
      if not ok then failures[#failures + 1] = string.format("N = %d, s/lambda = %g, K = %g: %+.2f %%", n, xi, K, diff) end
    end
  end
end

-- The table and the plot (and, with write_docs, their copies in docs/).
local here = debug.getinfo(1, "S").source:gsub("^@", ""):match("^(.*)/[^/]*$") or "."
local csv = "N,spacing_over_lambda,K,exact,ours,difference_percent,elements\n" .. table.concat(rows, "\n") .. "\n"
docs_output.write(dda.output("joint_set.csv"), csv)
local plot = nil
if dda.has_render then
  local series = {}
  local palette = { {31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189},
                    {140, 86, 75}, {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207} }
  for i, cs in ipairs(cases) do
    local colour = palette[(i - 1) % #palette + 1]
    series[#series + 1] = { name = string.format("s/lambda = %g, K = %g", cs.xi, cs.K), x = cs.n, y = cs.exact,
                            color = colour, width = 4 }
    series[#series + 1] = { name = "", x = cs.n, y = cs.ours, color = { 0, 0, 0 }, width = 1 }
  end
  plot = dda.plot{ file = "joint_set.png", series = series,
                   title = "|T_N| across N joints at 1000 Hz: exact (colour), the engine (black)",
                   x_label = "N (joints)", y_label = "|T_N|", width = 1000, height = 600 }
end
if write_docs then
  local docs = here .. "/../../docs"
  docs_output.write(docs .. "/waves_joint_set.csv", csv)
  if plot then
    local i = assert(io.open(plot, "rb")); local data = i:read("a"); i:close()
    docs_output.write(docs .. "/figures/waves_joint_set.png", data)
  end
end
if check and #failures > 0 then
  error("|T_N| off the exact value by more than " .. tolerance .. " %: " .. table.concat(failures, "; "), 0)
end
