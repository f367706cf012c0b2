-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig7_fixed_free.lua: the paper's Fig. 7, Fixed vs Free right end.
--
-- Models:  Model 1 (bars.lua), half sine (compression), 5 MPa, 1000 Hz on the left
--          end; g0 = 50 E; joints phi = 40 deg, c = sigma_t = 8 MPa; right end
--          Fixed (fixed points at the ends of its edges) or Free. Recorded at the
--          centre: sxx and vx. Definitions as wave.lua: incident = extreme before
--          t_split (~4.25 ms), reflected = largest magnitude after it, signed.
--          The incident compression has sxx < 0 and vx > 0.
-- Run:     build/dda run scripts/paper/fig7_fixed_free.lua [--set t_end=7e-3]
--                   [--set check=true] [--out out]
-- Writes:  out/fig7_fixed.csv, out/fig7_free.csv (step, time, sxx, vx),
--          out/fig7_numbers.csv, out/fig7_sxx.png, out/fig7_vx.png.
--          check=true: error unless Fixed keeps the sign of the reflected stress,
--          Free inverts it, both within 10 % of 4.45 MPa.

local dda = require "dda"
local wave = require "wave"

local t_end = dda.param("t_end", 7e-3)
local fig = wave.figure("fig7", "Fig. 7: Fixed vs Free right end, Model 1, g0 = 50E, half sine")

local out = {}
for _, bc in ipairs{ "fixed", "free" } do
  local r = wave.run{ tag = "fig7_" .. bc, g0 = 50, load = "half", right = bc, t_end = t_end }
  local s_in = wave.incident(r, "comp")
  local v_in = wave.peak(r.t, r.vx, 0, r.t_split, 0)
  local s_re, v_re = wave.reflected(r, "sxx"), wave.reflected(r, "vx")
  fig:row(bc .. " incident sxx", nil, s_in / 1e6, "MPa", r.T_over_dt)
  fig:row(bc .. " reflected sxx (signed)", bc == "fixed" and -4.45 or 4.45, s_re / 1e6, "MPa", r.T_over_dt)
  fig:row(bc .. " incident vx", nil, v_in, "m/s", r.T_over_dt)
  fig:row(bc .. " reflected vx (signed)", bc == "fixed" and -0.424 or 0.424, v_re, "m/s", r.T_over_dt)
  out[bc] = { r = r, s_in = s_in, s_re = s_re, v_in = v_in, v_re = v_re }
end
local fx, fr = out.fixed, out.free
local function within(v) return math.abs(math.abs(v) / 4.45e6 - 1) <= 0.10 end
fig:target("Fixed keeps the sign of the reflected stress, |amp| within 10% of 4.45 MPa",
           fx.s_re * fx.s_in > 0 and within(fx.s_re), string.format("%.3f MPa", fx.s_re / 1e6))
fig:target("Free inverts the reflected stress, |amp| within 10% of 4.45 MPa",
           fr.s_re * fr.s_in < 0 and within(fr.s_re), string.format("%.3f MPa", fr.s_re / 1e6))
fig:target("velocity: Fixed inverts, Free keeps the sign",
           fx.v_re * fx.v_in < 0 and fr.v_re * fr.v_in > 0,
           string.format("fixed %.3f, free %.3f m/s", fx.v_re, fr.v_re))
fig:plot("fig7_sxx.png", { fx.r, fr.r }, { "Fixed", "Free" }, "sxx", "Fig. 7: sxx at the centre, Fixed vs Free")
fig:plot("fig7_vx.png", { fx.r, fr.r }, { "Fixed", "Free" }, "vx", "Fig. 7: vx at the centre, Fixed vs Free")
return fig:finish()
