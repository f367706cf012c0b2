-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig5_joint_strength.lua: the paper's Fig. 5 and Table 1, joint strength.
--
-- Models:  Models 1 and 2 (bars.lua), half sine (compression), 5 MPa, 1000 Hz on
--          the left end; right end Fixed; g0 = E; Table 1 levels
--          1: phi = 40 deg, c = 8, sigma_t = 8 MPa; 2: 40 deg, 2, 2 MPa;
--          3: 40 deg, 2, 0 MPa. Definitions as wave.lua: the "first peak" is the
--          incident compressive peak at the centre, the "second peak" the reflected
--          one (the Fixed right end returns the pulse as compression), both as
--          magnitudes in MPa.
-- Run:     build/dda run scripts/paper/fig5_joint_strength.lua [--set models=1,2]
--                   [--set levels=1,2,3] [--set t_end=8e-3] [--out out]
-- Writes:  out/fig5_model<M>_level<L>.csv (step, time, sxx, vx at the centre),
--          out/fig5_numbers.csv, out/fig5_model<M>.png.

local dda = require "dda"
local wave = require "wave"

local models = tostring(dda.param("models", "1,2"))
local levels = tostring(dda.param("levels", "1,2,3"))
local t_end = dda.param("t_end", 8e-3)
local fig = wave.figure("fig5", "Fig. 5: joint strength (Table 1), half sine 5 MPa 1000 Hz, g0 = E")
local table1 = { { 40, 8e6, 8e6 }, { 40, 2e6, 2e6 }, { 40, 2e6, 0 } }
local paper = { [2] = { [1] = { 4.43, 3.58 }, [3] = { 3.29, 1.76 } } }

for mk in models:gmatch("[^,]+") do
  local model = tonumber(mk)
  local runs, labels = {}, {}
  for lk in levels:gmatch("[^,]+") do
    local lv = tonumber(lk)
    local s = table1[lv]
    local r = wave.run{ tag = string.format("fig5_model%d_level%d", model, lv), model = model, g0 = 1,
                        load = "half", phi = s[1], c = s[2], tension = s[3], t_end = t_end }
    local v1 = wave.incident(r, "comp")
    local v2 = wave.peak(r.t, r.sxx, r.t_split, 1e9, -1)
    local p = (paper[model] or {})[lv] or {}
    fig:row(string.format("Model %d level %d first peak", model, lv), p[1], -v1 / 1e6, "MPa", r.T_over_dt)
    fig:row(string.format("Model %d level %d second peak", model, lv), p[2], -v2 / 1e6, "MPa", r.T_over_dt)
    runs[#runs + 1] = r; labels[#labels + 1] = "level " .. lk
  end
  fig:plot(string.format("fig5_model%d.png", model), runs, labels, "sxx",
           string.format("Fig. 5: Model %d, joint strength levels", model))
end
return fig:finish()
