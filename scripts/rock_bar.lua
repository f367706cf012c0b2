-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- rock_bar.lua: a stress wave through the paper's jointed rock bar, Model 1.
--
-- Models:  a 20 m x 1 m bar cut by a horizontal and a vertical joint set, both
--          at 0.2 m spacing (500 blocks of 0.2 m x 0.2 m; scripts/paper/bars.lua,
--          the bars of every paper script and benchmark). Rock: density 2000
--          kg/m^3, E = 50 GPa, nu = 0.25 (bar wave speed sqrt(E/rho) = 5000 m/s,
--          plane stress). Joints: phi = 40 deg, c = 8 MPa, tensile strength 8 MPa.
--          Controls as the paper's Section 2: g0 = 20 E (or --set g0=1 for E),
--          g1 = 2e-6 s, g2 = 0.005, gg = 1. A half-sine pressure pulse of 5 MPa at
--          1000 Hz pushes on the left end; the right end is held by fixed points
--          at the corners of its edges. sigma_xx is recorded at the bar centre.
--          The pulse reaches the centre after about 10 m / 5000 m/s = 2 ms.
--          The pressure acts on the left-end edges, normal to them and pushing
--          into the blocks (the engine's SHI load).
-- Run:     build/dda run scripts/rock_bar.lua [--set t_end=3e-3] [--set g0=20]
--                   [--set frequency=1000] [--set frame_every=15] [--set movie=rock_bar.mp4] [--out out]
-- Writes:  out/rock_bar_centre.csv: step, time, sxx (Pa, tension positive),
--          vx (m/s) at (10.1, 0.5), the centre of the block right of x = 10 m,
--          one row per step; prints the peak compression and its arrival time.
--          out/rock_bar_frames/sigma_xx_00000.png, ...: a frame of sigma_xx every
--          15 steps (30 us: 101 frames), colours fixed to +-5 MPa (when built with the
--          renderer); out/rock_bar.mp4, a 30 frames/s movie of them (3.4 s) when
--          ffmpeg is on the PATH (--set movie= for none). out/result.csv: the
--          peak compression (Pa) and its time (s), a row of dda sweep's table.

local dda = require "dda"
local bars = require "paper.bars"

local E = 50e9                                   -- Pa
local g0 = dda.param("g0", 20) * E               -- contact spring, in multiples of E
local t_end = dda.param("t_end", 3e-3)           -- s
local frequency = dda.param("frequency", 1000)   -- Hz
local amplitude = dda.param("amplitude", 5e6)    -- Pa

-- m, centre and left_pressure are globals so that `dda console scripts/rock_bar.lua`
-- can inspect and drive them after the script has run.
m = dda.model{ plane = "stress", g0 = g0, g1 = 2e-6, g2 = 0.005, gg = 1 }
local rock = m:rock(bars.rock)                   -- density 2000, E = 50 GPa, nu = 0.25
local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6 }
local blocks = bars.build(m, 1, rock, joint)     -- horizontal and vertical joints
print(string.format("rock bar Model 1: %d blocks, g0 = %g E, dt <= %g s", #blocks, g0 / E, 2e-6))

-- Loads and boundaries.
local half_period = 0.5 / frequency
local left = bars.left_end(m)
left_pressure = left:pressure(function(t)
  if t < half_period then return amplitude * math.sin(2 * math.pi * frequency * t) end
  return 0
end)
bars.right_end(m, 1):fix()

centre = m:monitor{ name = "rock_bar_centre", at = bars.centre, fields = {"sxx", "vx"} }

-- Frames of sigma_xx every `frame_every` steps (0: none), when the renderer is
-- built, and a movie of them when ffmpeg is on the PATH (a warning otherwise).
local frame_every = dda.param("frame_every", 15)
local movie = tostring(dda.param("movie", "rock_bar.mp4"))
if dda.has_render and frame_every > 0 then
  m:frames{ folder = "rock_bar_frames", every = frame_every, field = "sigma_xx", width = 1600, height = 200,
            range = {-amplitude, amplitude}, title = "rock bar Model 1: sigma_xx",
            movie = movie ~= "" and movie or nil }
end

m:run{ time = t_end }

local totals = m:totals()
print(string.format("%d steps to t = %.4g s (%.0f steps/s, %d step cuts)", m:steps(), m:time(),
                    totals.steps_per_second, totals.step_cuts))
if centre:count() > 0 then
  local sxx, t_peak = centre:min("sxx")   -- compression is negative
  print(string.format("peak compression at the centre: %.4g MPa at t = %.4g ms", -sxx / 1e6, t_peak * 1e3))
  print("history written to " .. centre:file())
  return { peak_compression = -sxx, t_peak = t_peak }   -- DIR/result.csv; dda sweep's columns
end
