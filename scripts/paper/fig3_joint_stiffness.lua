-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig3_joint_stiffness.lua: the paper's Fig. 3, joint (contact spring) stiffness.
--
-- Models:  Model 1 (bars.lua), one full sine period (compression first), 5 MPa,
--          1000 Hz, on the left end; right end Fixed; joints phi = 40 deg,
--          c = sigma_t = 8 MPa; g0 = 1, 5, 10, 20, 50 x E. Controls and definitions
--          as wave.lua: wave speed = 10.1 m / (t of the first tensile peak at the
--          centre - 0.75 ms, the input's tensile peak); attenuation = 1 - first
--          tensile peak / 5 MPa. T/dt = 1 ms / mean step.
-- Run:     build/dda run scripts/paper/fig3_joint_stiffness.lua [--set cases=1,5,10,20,50]
--                   [--set t_end=4e-3] [--set check=true] [--out out]
-- Writes:  out/fig3_g0_<k>E.csv (step, time, sxx, vx at the centre) per g0,
--          out/fig3_numbers.csv (figure,quantity,paper,ours,unit), out/fig3.png (with
--          the exact 1-D joint physics for g0 = E and 20E, wave.exact).
--          check=true: error when a target fails (g0 = 20E: speed within 1 % of
--          5000 m/s, attenuation < 4 %; g0 = E: speed within 3 % of 4082 m/s).

local dda = require "dda"
local wave = require "wave"

local cases = tostring(dda.param("cases", "1,5,10,20,50"))
local t_end = dda.param("t_end", 4e-3)
local fig = wave.figure("fig3", "Fig. 3: joint stiffness g0, Model 1, full sine 5 MPa 1000 Hz")
local paper = { [1] = { 4081.63, 6.12 }, [20] = { 4999.994, 2.18 } }

local runs, labels = {}, {}
local exacts, exact_labels = {}, {}
for k in cases:gmatch("[^,]+") do
  local g = tonumber(k)
  local r = wave.run{ tag = "fig3_g0_" .. k .. "E", g0 = g, load = "full", t_end = t_end }
  local v, t, c = wave.incident(r, "tens")
  local att = 100 * (1 - v / wave.A)
  local p = paper[g] or {}
  fig:row(string.format("g0=%sE first tensile peak", k), ({ [1] = 4.694, [20] = 4.891 })[g], v / 1e6, "MPa", r.T_over_dt)
  fig:row(string.format("g0=%sE wave speed", k), p[1], c, "m/s", r.T_over_dt)
  fig:row(string.format("g0=%sE attenuation", k), p[2], att, "%", r.T_over_dt)
  if g == 20 then
    fig:target("g0=20E speed within 1% of 5000 m/s", math.abs(c / 5000 - 1) <= 0.01, string.format("%.1f m/s", c))
    fig:target("g0=20E attenuation below 4%", att < 4, string.format("%.2f %%", att))
  elseif g == 1 then
    fig:target("g0=E speed within 3% of 4082 m/s", math.abs(c / 4082 - 1) <= 0.03, string.format("%.1f m/s", c))
  end
  runs[#runs + 1] = r; labels[#labels + 1] = "g0 = " .. k .. "E"
  local ex = wave.exact{ g0 = g, load = "full", t_end = t_end }
  local xv, _, xc = wave.incident(ex, "tens")
  fig:exact_value(string.format("g0=%sE first tensile peak", k), xv / 1e6)
  fig:exact_value(string.format("g0=%sE wave speed", k), xc)
  fig:exact_value(string.format("g0=%sE attenuation", k), 100 * (1 - xv / wave.A))
  if g == 1 or g == 20 then exacts[#exacts + 1] = ex; exact_labels[#exact_labels + 1] = "g0 = " .. k .. "E, exact" end
end
for i, ex in ipairs(exacts) do runs[#runs + 1] = ex; labels[#labels + 1] = exact_labels[i] end
fig:plot("fig3.png", runs, labels)
return fig:finish()
