-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- earthquake_slope.lua: a jointed rock slope shaken by a recorded earthquake.
--
-- Models:  a 20 m high rock slope (on 4 m of rock in front of its toe) with
--          two benches: 10 m faces at 70 deg and a 6 m bench between them,
--          cut by two joint sets: bedding dipping 30 deg out of the slope
--          (spacing 3 m) and a steep cross set dipping 75 deg into it
--          (spacing 4 m); blocks under 1 m^2 merged into a neighbour. Rock:
--          density 2600 kg/m^3, E = 10 GPa, nu = 0.25. Joints: phi = 40 deg
--          (the bedding yields at g tan(40 - 30) = 0.18 g), no cohesion or
--          tension. Under gravity for 1 s, then shaken horizontally by the
--          1979 Imperial Valley record, El Centro Array #7, S50W (data/;
--          baseline-corrected, times --set scale), through the bottom edges of
--          the lowest blocks, in one of two ways (docs/seismic.md):
--            base = "rigid":     they follow the record's displacement
--                                (stiff springs);
--            base = "compliant": they are a quiet base (dashpots of a bedrock
--                                of Vs = 1200 m/s) through which the record
--                                comes in as an upgoing S wave (half the
--                                record: it is taken as an outcrop motion).
--          Both hold the base vertically; the sides are free. Shi's scheme
--          (gg = 1), steps of at most 0.25 ms (at 2 ms the open-close
--          iteration does not settle), g0 = 1e11 N/m, g2 = 0.005.
--          Both bases run the record to its end (docs/seismic.md, Section 4).
--          If the engine cannot complete a step, the run stops there, says so
--          (naming the contact), and still writes its outputs.
-- Run:     build/dda run scripts/earthquake_slope.lua [--set base=rigid|compliant]
--                   [--set t_end=12] [--set scale=1] [--set frames=0.1] [--set phi=40]
--                   [--set law=shi] (the contact law; the engine's default when not set)
--          Both bases, one after the other:
--            for b in rigid compliant; do build/dda run scripts/earthquake_slope.lua --set base=$b --out out/slope_$b; done
-- Writes:  out/slope_crest.csv, out/slope_face.csv, out/slope_toe.csv: time,
--          ux, uy, vx, vy of three points of the slope face, every step;
--          out/slope_ground.csv: time and the ground's (a base block's) ux, vx;
--          out/slope_permanent.csv: block, centroid x, y, ux, uy and rotation
--          (deg) of every block from the end of the settling to the end, less
--          the ground's ux, and whether it slid (> 5 cm) or toppled (> 5 deg);
--          out/slope_frames/velocity_*.png: frames of velocity magnitude on the
--          blocks where they are (displacements drawn true to scale: blocks
--          slide decimetres, and a magnification would draw them metres apart
--          and overlapping), one colour scale for the whole film (0 to 1.5 m/s
--          times `scale`: the record's PGV is 1.13 m/s), every 0.1 s of
--          shaking (with the renderer); prints the run time (CPU) and a
--          summary, also written as results (result.csv).

local dda = require "dda"

local base_kind = dda.param("base", "rigid")
local t_end = dda.param("t_end", 12)          -- s of shaking after the settling
local scale = dda.param("scale", 1)           -- factor on the record
local frames = dda.param("frames", 0.1)       -- s between frames (0: none)
local settle = dda.param("settle", 1.0)       -- s under gravity before the shaking
local dt = dda.param("dt", 2.5e-4)            -- s, the largest step
assert(base_kind == "rigid" or base_kind == "compliant",
       "--set base=rigid or base=compliant (got " .. tostring(base_kind) .. ")")

-- The record, resampled to the step and baseline-corrected; it starts after
-- the settling: its histories are shifted by `settle` (a history holds its
-- last value after its end: the velocity is brought to zero one step after).
local here = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"   -- the folder of this script
local record = dda.ground_motion{ file = here .. "../data/imperial_valley_1979_el_centro_array7_S50W.dat", dt = dt,
                                  scale = scale }
local function shifted(series, factor)
  local out = { {0, 0} }
  for _, p in ipairs(series) do out[#out + 1] = { p[1] + settle, factor * p[2] } end
  if series == record.velocity then out[#out + 1] = { out[#out][1] + record.dt, 0 } end
  return out
end
print(string.format("record: %s, %.1f s, PGA %.2f m/s^2 at %.2f s, PGV %.3f m/s, PGD %.3f m",
                    record.source, record.duration, record.pga.value, record.pga.time, record.pgv.value,
                    record.pgd.value))

m = dda.model{ plane = "strain", gravity = {0, -9.81}, g1 = dt, g2 = dda.param("g2", 0.005), gg = 1,
                 g0 = dda.param("g0", 1e11), open_close_limit = dda.param("open_close_limit", 30),
                 contact_law = dda.param("law", nil) }  -- nil: the engine's default ("holding")
local rock = m:rock{ density = 2600, E = 10e9, nu = 0.25 }
local bedrock = m:rock{ density = 2600, E = 2 * 1.25 * 2600 * 1200^2, nu = 0.25 }  -- Vs = 1200 m/s
local joint = m:joint{ friction = dda.param("phi", 40) }   -- deg; the bedding (30 deg) yields at g tan(phi - 30)

-- The slope: ground at y = 24 on the left, two 10 m faces at 70 deg down
-- to the lower ground at y = 4 on the right, a 6 m bench between them.
local run70 = 10 / math.tan(math.rad(70))
local x1 = 30                       -- top of the upper face
local x2 = x1 + run70               -- its foot
local x3 = x2 + 6                   -- top of the lower face
local x4 = x3 + run70               -- the toe
local W = x4 + 20
m:domain{ polygon = { {0, 0}, {W, 0}, {W, 4}, {x4, 4}, {x3, 14}, {x2, 14}, {x1, 24}, {0, 24} }, rock = rock,
          joint = joint }
m:joint_set{ dip = -30, spacing = dda.param("bedding", 3), origin = {x1, 24}, joint = joint }  -- out of the slope
m:joint_set{ dip = 75, spacing = dda.param("cross", 4), origin = {x1, 24}, joint = joint }     -- into it
local generated = m:generate{ min_area = dda.param("min_area", 1.0) }
local blocks = {}
for _, id in ipairs(generated:ids()) do blocks[#blocks + 1] = m:block(id) end
print(string.format("%d rock blocks, %.1f m wide", #blocks, W))

-- The shaking, on the bottom edges of the lowest blocks. Rigid: targets at
-- their ends follow the ground displacement along x. Compliant: the edges
-- are a quiet base carrying the upgoing wave (half the outcrop record).
-- Both hold the base in y.
local bottom = m:edges{ on_segment = {0, 0, W, 0} }
local ground
if base_kind == "rigid" then
  ground = bottom:target{ displacement = shifted(record.displacement, 1), direction = {1, 0} }
else
  bottom:viscous_boundary{ rock = bedrock, vx = shifted(record.velocity, 0.5) }
end
bottom:target{ displacement = 0, direction = {0, 1} }
local ground_point = m:monitor{ name = "slope_ground", at = {W - 1, 0.1}, fields = {"ux", "vx"} }

local crest = m:monitor{ name = "slope_crest", at = {x1 - 0.5, 23.5}, fields = {"ux", "uy", "vx", "vy"} }
local face = m:monitor{ name = "slope_face", at = {x3 - 0.5, 13.5}, fields = {"ux", "uy", "vx", "vy"} }
local toe = m:monitor{ name = "slope_toe", at = {x4 - 1, 3.5}, fields = {"ux", "uy", "vx", "vy"} }

-- Each block's starting centroid and the direction of its first edge, for
-- the permanent displacement and rotation.
local start = {}
local function edge_angle(b)
  local v = b:vertices()
  return math.atan(v[2][2] - v[1][2], v[2][1] - v[1][1])
end
for i = 1, #blocks do
  local b = blocks[i]
  local x, y = b:centroid()
  start[i] = { x = x, y = y, angle = edge_angle(b) }
end

local clock0 = os.clock()
m:run{ time = settle }
-- Displacements from here on are the earthquake's, not the settling's.
local settled = {}
for i = 1, #blocks do
  local x, y = blocks[i]:centroid()
  settled[i] = { x = x, y = y, angle = edge_angle(blocks[i]) }
end
local film   -- kept: the sequence lives as long as this handle
if frames > 0 and dda.has_render then
  film = m:frames{ folder = "slope_frames", every_time = frames, field = "velocity", magnify = 1,
            range = { 0, 1.5 * scale }, on_error = "continue",
            monitors = false }
end
-- A run that stops early (a step the engine cannot complete) still writes
-- what it has and says where it stopped.
local finished, why = pcall(m.run, m, { time = settle + t_end, every = 500, callback = function(model)
  print(string.format("t = %6.2f s  ground ux = %7.3f m  crest ux = %7.3f m", model:time(), ground_point:value("ux"),
                      crest:value("ux")))
end })
if not finished then print("the run stopped at t = " .. m:time() .. " s: " .. tostring(why)) end
local seconds = os.clock() - clock0
if film then film:flush() end

-- The permanent displacement field: each block against the ground beneath.
local ground_ux = ground_point:value("ux")
local out = assert(io.open(dda.output("slope_permanent.csv"), "w"))
out:write("block,x,y,ux,uy,rotation_deg,state\n")
local slid, toppled, largest = 0, 0, 0
for i = 1, #blocks do
  local x, y = blocks[i]:centroid()
  local ux, uy = x - settled[i].x - ground_ux, y - settled[i].y
  local turn = math.deg(edge_angle(blocks[i]) - settled[i].angle)
  turn = (turn + 180) % 360 - 180
  local state = "held"
  if math.abs(turn) > 5 then
    state, toppled = "toppled", toppled + 1
  elseif math.sqrt(ux * ux + uy * uy) > 0.05 then
    state, slid = "slid", slid + 1
  end
  largest = math.max(largest, math.sqrt(ux * ux + uy * uy))
  out:write(string.format("%d,%.4f,%.4f,%.6g,%.6g,%.4g,%s\n", blocks[i]:id(), start[i].x, start[i].y, ux, uy, turn,
                          state))
end
out:close()

local steps = m:steps()
print(string.format("%s base: %d steps, %.1f s of CPU time (%.2f ms a step); %d blocks slid (> 5 cm), %d toppled "
                    .. "(> 5 deg); largest permanent displacement %.3f m; crest ux %.3f m against the ground",
                    base_kind, steps, seconds, 1000 * seconds / steps, slid, toppled, largest,
                    crest:value("ux") - ground_ux))
dda.result{ base = base_kind, finished = finished, t_reached = m:time(), steps = steps, cpu_seconds = seconds, blocks = #blocks, slid = slid, toppled = toppled,
            largest_displacement = largest, crest_ux = crest:value("ux") - ground_ux }
