-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig6_joint_direction.lua: the paper's Fig. 6, joint direction.
--
-- Models:  Models 1, 2, 3 (bars.lua: second set at 90, 60, 30 deg), half sine
--          (compression), 5 MPa, 1000 Hz on the left end; right end Fixed; g0 = E;
--          joints phi = 40 deg, c = sigma_t = 2 MPa. Definitions as wave.lua:
--          compressive peak at the centre, wave speed = 10.1 m / (t_peak - 0.25 ms),
--          attenuation = 1 - peak / 5 MPa. The paper gives only the trend: lower
--          inclination (Model 3) -> faster wave, much faster attenuation.
-- Run:     build/dda run scripts/paper/fig6_joint_direction.lua [--set models=1,2,3]
--                   [--set t_end=5e-3] [--out out]
-- Writes:  out/fig6_model<M>.csv, out/fig6_numbers.csv, out/fig6.png.

local dda = require "dda"
local wave = require "wave"

local models = tostring(dda.param("models", "1,2,3"))
local t_end = dda.param("t_end", 5e-3)
local fig = wave.figure("fig6", "Fig. 6: joint direction, Models 1-3, half sine 5 MPa 1000 Hz, g0 = E")

local runs, labels = {}, {}
for mk in models:gmatch("[^,]+") do
  local model = tonumber(mk)
  local r = wave.run{ tag = "fig6_model" .. mk, model = model, g0 = 1, load = "half", c = 2e6,
                      tension = 2e6, t_end = t_end }
  local v, t, c = wave.incident(r, "comp")
  fig:row("Model " .. mk .. " compressive peak", nil, -v / 1e6, "MPa", r.T_over_dt)
  fig:row("Model " .. mk .. " attenuation", nil, 100 * (1 + v / wave.A), "%", r.T_over_dt)
  fig:row("Model " .. mk .. " wave speed", nil, c, "m/s", r.T_over_dt)
  runs[#runs + 1] = r; labels[#labels + 1] = "Model " .. mk
end
fig:plot("fig6.png", runs, labels)
return fig:finish()
