-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- bar_block_size.lua: the paper's Model 1 joints in bars of smaller blocks: how
-- far the blocks' own error (first peaks, and the wrong-sign precursor ahead of
-- a compressive pulse) falls as the blocks shrink, against the exact jointed bar.
--
-- Models:  Model 1's joints (bars.lua: horizontal and vertical sets every 0.2 m,
--          each joint a normal spring k_n = 2 g0 / 0.2 m, the paper's Eq. 4, as a
--          joint material's stiffness; g0 = E unless --set g0) in a bar of
--          blocks `size` m long: the vertical cuts between the 0.2 m joints are
--          near-rigid (k_n = 1e15 Pa/m: 0.05 % of a 0.05 m block's compliance).
--          rho = 2000 kg/m^3, E = 50 GPa, nu = 0.25, plane stress; one sine
--          period of 5 MPa (compression first) at 1000 Hz on the left end, right
--          end fixed; sigma_xx at x = 10.1 m; the `integrator` (newmark: no
--          numerical damping) at Δt = `dt` (2e-6 s).
-- Measures: per block size, the first compressive and tensile peaks (wave.lua's
--          definitions) beside the exact ones (wave.exact), and the precursor:
--          the largest tensile sigma_xx before the compressive peak, in % of the
--          5 MPa amplitude (the exact bar has none).
--          mesh=h: the blocks meshed at element size h (docs/meshed_blocks.md);
--          mesh_mass: the elements' mass (consistent, lumped or mixed: the
--          control mesh_mass); nu: the rock's Poisson's ratio (0.25); penalty=true: the joints
--          without their own k_n (each contact the penalty g0).
-- Run:     build/dda run scripts/paper/bar_block_size.lua [--set sizes=0.2,0.1,0.05]
--                   [--set g0=1] [--set dt=2e-6] [--set check=true] [--set mesh=0.05]
--                   [--set nu=0.25] [--set penalty=true] [--set max_precursor=2]
--                   [--set mesh_mass=lumped]
-- Writes:  out/bar_block_size.csv (size, blocks, comp, tens, exact comp, exact tens,
--          precursor %); prints the table. check=true: error unless the precursor
--          falls by at least half with each halving of the blocks, and at the
--          smallest size lies under 2 % of the amplitude with both peaks within 1 %
--          of the exact ones. max_precursor=p: error unless every run's precursor
--          lies under p %.

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local wave = require "wave"
local bars = require "bars"

local sizes_text = tostring(dda.param("sizes", "0.2,0.1,0.05"))
local g0 = dda.param("g0", 1)
local dt = dda.param("dt", 2e-6)
local integrator = dda.param("integrator", "newmark")
local check = dda.param("check", false)
-- mesh: the blocks meshed at this element size (m; docs/meshed_blocks.md), nil:
-- first-order blocks. The joints keep their own k_n whatever the mesh.
local mesh = dda.param("mesh", nil)
local mesh_mass = dda.param("mesh_mass", "consistent")
local nu = dda.param("nu", bars.rock.nu)
-- penalty=true: the joints without their own k_n, each contact's springs the
-- penalty g0 (the paper's Eq. 4 holds for first-order blocks only: on a meshed
-- block every node on a joint adds a contact, so the joint stiffens with the mesh).
local penalty = dda.param("penalty", false)
-- max_precursor (%): error unless every run's precursor lies under it (the
-- the target: 2 % of the amplitude at g0 <= 20E).
local max_precursor = dda.param("max_precursor", nil)
local E, A, f = wave.E, wave.A, 1000
local t_end = 3.6e-3  -- past the first tensile peak at the centre (about 3.2 ms)

local ex = wave.exact{ g0 = g0, load = "full", freq = f, t_end = t_end }
local ex_comp, ex_tens = wave.incident(ex, "comp"), wave.incident(ex, "tens")

local function run(size)
  local m = dda.model{ plane = "stress", g0 = g0 * E, g1 = dt, g2 = 0.005, gg = 1, integrator = integrator,
                       contact_law = "shi", mesh_mass = mesh_mass, mesh_size = 0 }
  local rock = m:rock{ density = bars.rock.density, E = bars.rock.E, nu = nu, mesh_size = mesh }
  local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6,
                        kn = (not penalty) and 2 * g0 * E / bars.spacing or nil }
  local weld = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6, kn = 1e15 }
  m:domain{ {0, 0}, {bars.length, 0}, {bars.length, bars.height}, {0, bars.height}, rock = rock }
  m:joint_set{ dip = 0, spacing = bars.spacing, joint = joint }
  m:joint_set{ dip = 90, spacing = bars.spacing, joint = joint }
  local cuts = math.floor(bars.spacing / size + 0.5)
  for j = 1, cuts - 1 do
    m:joint_set{ dip = 90, spacing = bars.spacing, joint = weld, origin = {j * bars.spacing / cuts, 0} }
  end
  local blocks = m:generate()
  local fn, dur, t_comp, t_tens = wave.load("full", f, A)
  bars.left_end(m):pressure(fn)
  bars.right_end(m, 1):fix()
  local mon = m:monitor{ at = bars.centre, fields = {"sxx"}, name = string.format("bar_block_size_%g", size) }
  m:run{ time = t_end }
  local r = { t = mon:times(), sxx = mon:series("sxx"), t_comp = t_comp, t_tens = t_tens,
              t_split = 20 / 4000 + dur / 2 }
  local comp, t_peak = wave.incident(r, "comp")
  local tens = wave.incident(r, "tens")
  local precursor = 0
  for i, t in ipairs(r.t) do
    if t < t_peak then precursor = math.max(precursor, r.sxx[i]) end
  end
  local n = #blocks
  m:close()
  return { size = size, blocks = n, comp = comp, tens = tens, precursor = 100 * precursor / A }
end

local rows, results = {}, {}
print(string.format("Model 1 joints (g0 = %gE%s), %s blocks, nu = %g, %s at dt = %g s, sigma_xx at x = 10.1 m (MPa); "
                    .. "exact %.4f / %.4f", g0, penalty and ", the penalty per contact" or ", k_n = 2 g0 / 0.2 m",
                    mesh and string.format("meshed at %g m (%s mass)", mesh, mesh_mass) or "first-order", nu,
                    integrator, dt,
                    ex_comp / 1e6, ex_tens / 1e6))
print(string.format("%8s %7s %10s %8s %10s %8s %12s", "size (m)", "blocks", "comp", "vs exact", "tens", "vs exact",
                    "precursor %"))
for k in sizes_text:gmatch("[^,]+") do
  local r = run(tonumber(k))
  results[#results + 1] = r
  local dc, dtn = 100 * (r.comp / ex_comp - 1), 100 * (r.tens / ex_tens - 1)
  print(string.format("%8g %7d %10.4f %7.2f%% %10.4f %7.2f%% %12.2f", r.size, r.blocks, r.comp / 1e6, dc,
                      r.tens / 1e6, dtn, r.precursor))
  rows[#rows + 1] = string.format("%g,%d,%.6f,%.6f,%.6f,%.6f,%.4f", r.size, r.blocks, r.comp / 1e6, r.tens / 1e6,
                                  ex_comp / 1e6, ex_tens / 1e6, r.precursor)
end
local file = io.open(dda.out_dir() .. "/bar_block_size.csv", "w")
if file then
  file:write("size,blocks,comp,tens,exact_comp,exact_tens,precursor_percent\n", table.concat(rows, "\n"), "\n")
  file:close()
end

if check then
  local failures = {}
  for i = 2, #results do
    if not (results[i].precursor <= 0.5 * results[i - 1].precursor) then
      failures[#failures + 1] = string.format("the precursor did not halve from %g m to %g m blocks (%.2f -> %.2f %%)",
                                              results[i - 1].size, results[i].size, results[i - 1].precursor,
                                              results[i].precursor)
    end
  end
  local last = results[#results]
  if last.precursor > 2 then
    failures[#failures + 1] = string.format("precursor %.2f %% over 2 %% at %g m blocks", last.precursor, last.size)
  end
  for _, p in ipairs{ { "compressive", last.comp, ex_comp }, { "tensile", last.tens, ex_tens } } do
    if math.abs(p[2] / p[3] - 1) > 0.01 then
      failures[#failures + 1] = string.format("%s peak %.4f MPa not within 1 %% of the exact %.4f at %g m blocks", p[1],
                                              p[2] / 1e6, p[3] / 1e6, last.size)
    end
  end
  if #failures > 0 then error("bar_block_size: " .. table.concat(failures, "; "), 0) end
end
if max_precursor then
  for _, r in ipairs(results) do
    if not (r.precursor <= max_precursor) then
      error(string.format("bar_block_size: precursor %.2f %% over %g %% at %g m blocks%s, g0 = %gE", r.precursor,
                          max_precursor, r.size, mesh and string.format(" meshed at %g m", mesh) or "", g0), 0)
    end
  end
end
