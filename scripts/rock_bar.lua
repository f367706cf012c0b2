-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- rock_bar.lua: a stress wave through the paper's jointed rock bar, Model 1.
--
-- Models:  a 20 m x 1 m bar cut by a horizontal and a vertical joint set, both
--          at 0.2 m spacing (500 blocks of 0.2 m x 0.2 m; scripts/paper/bars.lua,
--          the bars of every paper script and benchmark). Rock: density 2000
--          kg/m^3, E = 50 GPa, nu = 0.25 (bar wave speed sqrt(E/rho) = 5000 m/s,
--          plane stress). Joints: phi = 40 deg, c = 8 MPa, tensile strength 8 MPa,
--          contact springs g0 = 20 E (or --set g0=1 for E). A half-sine pressure
--          pulse of 5 MPa at 1000 Hz pushes on the left end; the right end is held
--          by fixed points at the corners of its edges. sigma_xx is recorded at the
--          bar centre. The pulse reaches the centre after about 10 m / 5000 m/s = 2 ms.
--          The pressure acts on the left-end edges, normal to them and pushing
--          into the blocks (the engine's SHI load).
--          Everything else is the engine's default for a wave (docs/waves.md): it
--          finds the pulse's highest frequency (99 % of its energy below
--          2.4 kHz), meshes the blocks into elements that resolve its shortest
--          shear wave (0.1 m: 8000 elements), their mass lumped at their corners,
--          steps them with Newmark's average acceleration, and gives each joint
--          the stiffness its first-order blocks had (2 g0 / 0.2 m): no wrong-sign
--          lobe runs ahead of the pulse. dt = 2e-6 s (--set dt=), g2 = 0.005.
-- Run:     build/dda run scripts/rock_bar.lua [--set t_end=3e-3] [--set g0=20] [--set dt=2e-6]
--                   [--set frequency=1000] [--set frame_every=15] [--set movie=rock_bar.mp4]
--                   [--set check=true] [--out out]
-- Writes:  out/rock_bar_centre.csv: step, time, sxx (Pa, tension positive),
--          vx (m/s) at (10.1, 0.5), the element under that point, one row per
--          step; prints the peak compression and its arrival time, and the
--          largest tension ahead of the pulse (the precursor) at the centre and
--          in the frames. out/rock_bar_frames/sigma_xx_00000.png, ...: a frame of
--          sigma_xx every 15 steps (30 us: 101 frames), colours fixed to +-5 MPa
--          (when built with the renderer); out/rock_bar.mp4, a 30 frames/s movie
--          of them (3.4 s) when ffmpeg is on the PATH (--set movie= for none).
--          With --set check=true: an error unless the tension ahead of the pulse
--          stays under 1 % of its amplitude at the centre and in every frame, and
--          the arrival is within 2 % of the exact one (the 2-D bar's, from its
--          plate modes, with the joints' delay from the exact jointed 1-D bar).
--          out/result.csv: the peak compression (Pa) and its time (s), a row of
--          dda sweep's table.

local dda = require "dda"
local bars = require "paper.bars"

local E = 50e9                                   -- Pa
local g0 = dda.param("g0", 20) * E               -- contact spring, in multiples of E
local t_end = dda.param("t_end", 3e-3)           -- s
local frequency = dda.param("frequency", 1000)   -- Hz
local amplitude = dda.param("amplitude", 5e6)    -- Pa
local dt = dda.param("dt", 2e-6)                 -- s, the largest step
local check = dda.param("check", false)

-- m, centre and left_pressure are globals so that `dda console scripts/rock_bar.lua`
-- can inspect and drive them after the script has run.
m = dda.model{ plane = "stress", g0 = g0, g1 = dt, g2 = 0.005, gg = 1 }
local rock = m:rock(bars.rock)                   -- density 2000, E = 50 GPa, nu = 0.25
local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6 }
local blocks = bars.build(m, 1, rock, joint)     -- horizontal and vertical joints
print(string.format("rock bar Model 1: %d blocks, g0 = %g E, dt <= %g s", #blocks, g0 / E, dt))

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
local frame_every = dda.param("frame_every", math.max(1, math.floor(3e-5 / dt + 0.5)))
local movie = tostring(dda.param("movie", "rock_bar.mp4"))
if dda.has_render and frame_every > 0 then
  m:frames{ folder = "rock_bar_frames", every = frame_every, field = "sigma_xx", width = 1600, height = 200,
            range = {-amplitude, amplitude}, title = "rock bar Model 1: sigma_xx",
            movie = movie ~= "" and movie or nil }
end

-- The precursor in the frames: every 30 us (each frame), the largest tension
-- ahead of the pulse (beyond the furthest element compressed by 1 % of the
-- amplitude), until the pulse reaches the fixed end.
local frame_precursor = 0
local function precursor_in_frame()
  local front, tension = -math.huge, {}
  for _, b in ipairs(m:blocks()) do
    local x = b:centroid()
    local sxx = b:stress()
    if sxx < -0.01 * amplitude then front = math.max(front, x) end
    tension[#tension + 1] = { x, sxx }
  end
  if front < 0 or front > 19 then return end
  for _, p in ipairs(tension) do
    if p[1] > front then frame_precursor = math.max(frame_precursor, p[2]) end
  end
end
m:run{ time = t_end, every = math.max(1, math.floor(3e-5 / dt + 0.5)), callback = precursor_in_frame }

local totals = m:totals()
print(string.format("%d steps to t = %.4g s (%.0f steps/s, %d step cuts)", m:steps(), m:time(),
                    totals.steps_per_second, totals.step_cuts))
print(string.format("%d blocks stepped (the wave model's elements, docs/waves.md)", #m:blocks()))
if centre:count() > 0 then
  local sxx, t_peak = centre:min("sxx")   -- compression is negative
  print(string.format("peak compression at the centre: %.4g MPa at t = %.4g ms", -sxx / 1e6, t_peak * 1e3))
  -- The arrival (the first compression of 1 % of the amplitude) and the
  -- largest tension before the peak (a wrong-sign lobe ahead of the pulse).
  local times, series = centre:times(), centre:series("sxx")
  local function first_below(t, s, level)  -- linear between the samples
    for i = 2, #t do
      if s[i] < level then return t[i - 1] + (t[i] - t[i - 1]) * (level - s[i - 1]) / (s[i] - s[i - 1]) end
    end
  end
  local arrival, lobe = first_below(times, series, -0.01 * amplitude), 0
  for i, t in ipairs(times) do
    if t < t_peak then lobe = math.max(lobe, series[i]) end
  end
  print(string.format("arrival (1 %% of the amplitude) at t = %.4g ms; tension ahead of the pulse: %.2f %% of the " ..
                      "amplitude at the centre, %.2f %% in the frames", (arrival or 0) * 1e3, 100 * lobe / amplitude,
                      100 * frame_precursor / amplitude))
  print("history written to " .. centre:file())
  if check then
    if lobe > 0.01 * amplitude or frame_precursor > 0.01 * amplitude then
      error(string.format("a wrong-sign lobe ahead of the pulse: %.2f %% at the centre, %.2f %% in the frames " ..
                          "(at most 1 %%)", 100 * lobe / amplitude, 100 * frame_precursor / amplitude), 0)
    end
    -- The exact arrival: that of the 2-D bar without joints (its plate modes,
    -- dda.exact_plate_bar: its front runs ahead of the 1-D bar's, at up to
    -- the plane-stress P speed), plus the joints' delay from the exact
    -- jointed 1-D bar (method of characteristics, paper/jointed_bar_exact.lua;
    -- kn = 2 g0 / 0.2 m, the stiffness the first-order blocks gave the joints).
    local load = {}
    for i = 0, 200 do load[#load + 1] = { i * half_period / 200, amplitude * math.sin(math.pi * i / 200) } end
    local probe = {}
    for t = 1.8e-3, 2.2e-3, 1e-6 do probe[#probe + 1] = t end
    local plate = dda.exact_plate_bar{ load = load, x = bars.centre[1], y = 0, times = probe, E = E,
                                       nu = bars.rock.nu, density = bars.rock.density, height = 1 }
    local moc = require "paper.jointed_bar_exact"
    local function moc_arrival(joints)
      local t, rec = moc.run{ length = bars.length, rho = bars.rock.density, E = E, joints = joints,
                              spacing = bars.spacing, kn = 2 * g0 / bars.spacing, right = "fixed",
                              receivers = { bars.centre[1] }, t_end = 2.2e-3, h = 1e-7,
                              load = function(s) return s < half_period and -amplitude * math.sin(math.pi * s / half_period) or 0 end }
      return first_below(t, rec[1], -0.01 * amplitude)
    end
    local joint_delay = moc_arrival(nil) - moc_arrival({})
    local exact_arrival = first_below(probe, plate, -0.01 * amplitude) + joint_delay
    print(string.format("exact arrival %.4g ms (the 2-D bar %.4g ms, the joints' delay %.3g ms): ours %+.2f %%",
                        exact_arrival * 1e3, (exact_arrival - joint_delay) * 1e3, joint_delay * 1e3,
                        100 * ((arrival or 0) - exact_arrival) / exact_arrival))
    if not arrival or math.abs(arrival - exact_arrival) > 0.02 * exact_arrival then
      error(string.format("the arrival %.4g ms is off the exact %.4g ms by more than 2 %%", (arrival or 0) * 1e3,
                          exact_arrival * 1e3), 0)
    end
  end
  return { peak_compression = -sxx, t_peak = t_peak }   -- DIR/result.csv; dda sweep's columns
end
