-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- jointed_slope.lua: a jointed rock slope settling and sliding under gravity.
--
-- Models:  a 20 m high slope (face at 60 deg, 10 m of ground in front of its
--          toe at 2 m, 14 m of crest behind it), cut by two joint sets at
--          25 deg and 110 deg (spacing 3 m): 77 blocks; phi = 35 deg, no
--          cohesion or tension; the bottom edges fixed; gravity switched on at
--          once. The bedding dips out of the face at 25 deg, so wedges on the
--          face slide and tip past the corners of the blocks below: contacts
--          must follow vertices past the ends of edges
--          (docs/contact_transfer.md).
-- Run:     build/dda run scripts/jointed_slope.lua [--set t_end=5] [--set dt=1e-3] [--set law=shi]
-- Writes:  prints, every 0.1 s, the largest block displacement, how many
--          blocks moved more than 0.1 m, the deepest closed-contact penetration
--          and the step count; returns the same at the end as results
--          (result.csv). Blocks that roll off the far end of the ground fall
--          on without end (there is nothing below them).

local dda = require "dda"

local t_end = dda.param("t_end", 5)
local dt = dda.param("dt", 1e-3)
local law = dda.param("law", nil)  -- nil: the engine's default contact law ("holding"); --set law=shi for Shi's

m = dda.model{ plane = "strain", gravity = {0, -9.81}, g1 = dt, g2 = dda.param("g2", 0.005), contact_law = law }
local rock = m:rock{ density = 2600, E = 10e9, nu = 0.25 }
local joint = m:joint{ friction = dda.param("phi", 35) }

local H, toe_x = 20, 24
local face_run = H / math.tan(math.rad(60))
local W = toe_x + face_run + 14
m:domain{ polygon = { {0, 0}, {W, 0}, {W, H + 2}, {toe_x + face_run, H + 2}, {toe_x, 2}, {0, 2} }, rock = rock,
          joint = joint }
m:joint_set{ dip = 25, spacing = dda.param("spacing", 3), origin = {toe_x, 2}, joint = joint }
m:joint_set{ dip = 110, spacing = dda.param("spacing", 3), origin = {toe_x, 2}, joint = joint }
local generated = m:generate{ min_area = dda.param("min_area", 0.5) }
local blocks = {}
for _, id in ipairs(generated:ids()) do blocks[#blocks + 1] = m:block(id) end
m:edges{ on_segment = {0, 0, W, 0} }:fix()
print(string.format("%d blocks", #blocks))

local start = {}
for i = 1, #blocks do start[i] = { blocks[i]:centroid() } end
-- The largest block motion (blocks that roll off the far end of the ground
-- fall on without end), and how many blocks moved more than 0.1 m.
local function largest_motion()
  local largest, moved = 0, 0
  for i = 1, #blocks do
    local x, y = blocks[i]:centroid()
    local d = math.sqrt((x - start[i][1]) ^ 2 + (y - start[i][2]) ^ 2)
    largest = math.max(largest, d)
    if d > 0.1 then moved = moved + 1 end
  end
  return largest, moved
end
local function deepest()
  local d = 0
  for _, c in ipairs(m:contacts()) do
    if c.state ~= "open" then d = math.max(d, c.penetration) end
  end
  return d
end

local clock0 = os.clock()
m:run{ time = t_end, every = math.max(1, math.floor(0.1 / dt + 0.5)), callback = function(model)
  local largest, moved = largest_motion()
  print(string.format("t = %5.2f s  steps %6d  largest block motion %8.4f m  moved > 0.1 m: %2d  deepest penetration %9.3e m",
                      model:time(), model:steps(), largest, moved, deepest()))
end }
local largest, moved = largest_motion()
local result = { blocks = #blocks, t = m:time(), steps = m:steps(), step_cuts = m:totals().step_cuts,
                 largest_motion = largest, moved = moved, deepest = deepest(), cpu_s = os.clock() - clock0 }
print(string.format("done: t = %.3f s, %d steps (%d cuts), largest block motion %.4f m, %d blocks moved > 0.1 m, "
                    .. "deepest penetration %.3e m, cpu %.1f s", result.t, result.steps, result.step_cuts,
                    result.largest_motion, result.moved, result.deepest, result.cpu_s))
return result
