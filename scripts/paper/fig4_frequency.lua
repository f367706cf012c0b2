-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig4_frequency.lua: the paper's Fig. 4, loading frequency.
--
-- Models:  Model 1 (bars.lua), one full sine period (compression first), 5 MPa,
--          at 500, 1000 and 1500 Hz on the left end; right end Fixed; g0 = E;
--          joints phi = 40 deg, c = sigma_t = 8 MPa. Definitions as wave.lua:
--          first tensile peak at the centre (input tensile peak at 3T/4);
--          attenuation = 1 - peak / 5 MPa; wave speed = 10.1 m / (t_centre - 3T/4).
-- Run:     build/dda run scripts/paper/fig4_frequency.lua [--set freqs=500,1000,1500]
--                   [--set t_end=5e-3] [--set check=true] [--out out]
-- Writes:  out/fig4_<f>Hz.csv (step, time, sxx, vx at the centre) per frequency,
--          out/fig4_numbers.csv, out/fig4.png (with the exact 1-D joint physics of
--          each frequency, wave.exact). check=true: error unless the attenuation
--          grows with the frequency.

local dda = require "dda"
local wave = require "wave"

local freqs = tostring(dda.param("freqs", "500,1000,1500"))
local t_end = dda.param("t_end", 5e-3)
local fig = wave.figure("fig4", "Fig. 4: frequency, Model 1, g0 = E, full sine 5 MPa")
local paper = { [500] = { 4.790, 4.20 }, [1000] = { 4.694, 6.12 }, [1500] = { 4.246, 15.08 } }

local runs, labels, atts = {}, {}, {}
local exacts, exact_labels = {}, {}
for k in freqs:gmatch("[^,]+") do
  local f = tonumber(k)
  local r = wave.run{ tag = "fig4_" .. k .. "Hz", g0 = 1, load = "full", freq = f, t_end = t_end }
  local v, t, c = wave.incident(r, "tens")
  local att = 100 * (1 - v / wave.A)
  local p = paper[f] or {}
  fig:row(k .. " Hz first tensile peak", p[1], v / 1e6, "MPa", r.T_over_dt)
  fig:row(k .. " Hz attenuation", p[2], att, "%", r.T_over_dt)
  fig:row(k .. " Hz wave speed", nil, c, "m/s", r.T_over_dt)
  runs[#runs + 1] = r; labels[#labels + 1] = k .. " Hz"; atts[#atts + 1] = { f, att }
  local ex = wave.exact{ g0 = 1, load = "full", freq = f, t_end = t_end }
  local xv, _, xc = wave.incident(ex, "tens")
  fig:exact_value(k .. " Hz first tensile peak", xv / 1e6)
  fig:exact_value(k .. " Hz attenuation", 100 * (1 - xv / wave.A))
  fig:exact_value(k .. " Hz wave speed", xc)
  exacts[#exacts + 1] = ex; exact_labels[#exact_labels + 1] = k .. " Hz, exact"
end
for i, ex in ipairs(exacts) do runs[#runs + 1] = ex; labels[#labels + 1] = exact_labels[i] end
if #atts >= 2 then
  local grows, txt = true, {}
  for i = 1, #atts do
    txt[#txt + 1] = string.format("%g Hz %.2f %%", atts[i][1], atts[i][2])
    if i > 1 and not (atts[i][2] > atts[i - 1][2]) then grows = false end
  end
  fig:target("attenuation grows with frequency", grows, table.concat(txt, ", "))
end
fig:plot("fig4.png", runs, labels)
return fig:finish()
