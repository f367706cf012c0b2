-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- bars.lua: the paper's jointed rock bars (Figs. 2 and 9), as a module the
-- paper scripts share.
--
-- Models:  Models 1-6 of Sections 2-3: bars L = 20 m long, H = 1 m high, two
--          joint sets at 0.2 m spacing (measured perpendicular to the joints).
--            1: horizontal and vertical sets
--            2: horizontal set and a set inclined at 60 deg
--            3: horizontal set and a set inclined at 30 deg
--            4: Model 1 with the five blocks of the right-end column merged
--               into three of height 1/3 m
--            5: Model 1 with the right end inclined at 60 deg (incidence 30 deg)
--            6: Model 1 with the right end inclined at 30 deg (incidence 60 deg)
--          For Models 5 and 6 the inclined end face passes through (20, 0.5),
--          so the bar is 20 m long along its axis and x = 10 m stays its centre.
--          The paper's "joint spacing/block size l = 0.2 m" with "minimum height
--          of the blocks 0.2 m" reads as 0.2 m perpendicular to each set, the
--          default here; opts.inclined_spacing = "horizontal" spaces the inclined
--          set 0.2 m along the bar instead (perpendicular spacing 0.2 sin(dip)).
-- Use:     local bars = require "bars"          -- from a script in scripts/paper/
--          local bars = require "paper.bars"    -- from a script in scripts/
--          local blocks = bars.build(m, 1, rock, joint [, {inclined_spacing = "horizontal"}])
--          local left, right = bars.left_end(m), bars.right_end(m, 1)
-- Writes:  nothing.

local bars = {
  length = 20,        -- m
  height = 1,         -- m
  spacing = 0.2,      -- m
  centre = {10.1, 0.5},   -- a point inside the block just right of x = 10 m
  rock = { density = 2000, E = 50e9, nu = 0.25 },
  descriptions = {
    "horizontal + vertical joints",
    "horizontal + 60 deg joints",
    "horizontal + 30 deg joints",
    "Model 1, right-end column of 3 blocks (h = 1/3 m)",
    "Model 1, right end inclined at 60 deg (incidence 30 deg)",
    "Model 1, right end inclined at 30 deg (incidence 60 deg)",
  },
}

local L, H, l = bars.length, bars.height, bars.spacing

-- The right end's inclination (deg) for Models 5 and 6.
local end_angle = { [5] = 60, [6] = 30 }

-- Corners of the right end: bottom and top.
local function right_corners(number)
  local beta = end_angle[number]
  if not beta then return {L, 0}, {L, H} end
  local dx = (H / 2) / math.tan(math.rad(beta))
  return {L + dx, 0}, {L - dx, H}
end

-- Cuts model `number` (1-6) into blocks in model m; returns the BlockSet.
function bars.build(m, number, rock, joint, opts)
  assert(bars.descriptions[number], "bars.build: model number must be 1-6, got " .. tostring(number))
  opts = opts or {}
  local along = opts.inclined_spacing or "perpendicular"
  assert(along == "perpendicular" or along == "horizontal",
         "bars.build: inclined_spacing must be \"perpendicular\" or \"horizontal\"")
  local bottom, top = right_corners(number)
  m:domain{ {0, 0}, bottom, top, {0, H}, rock = rock }
  if number == 4 then
    -- Vertical set everywhere; horizontal joints stop at x = L - l, where the
    -- right-end column is split into three blocks instead of five.
    m:joint_set{ dip = 90, spacing = l, joint = joint }
    for k = 1, math.floor(H / l + 0.5) - 1 do
      m:joint_line{ from = {0, k * l}, to = {L - l, k * l}, joint = joint }
    end
    for k = 1, 2 do
      m:joint_line{ from = {L - l, k * H / 3}, to = {L, k * H / 3}, joint = joint }
    end
  else
    m:joint_set{ dip = 0, spacing = l, joint = joint }
    local dip = ({ 90, 60, 30, 90, 90, 90 })[number]
    local spacing = along == "horizontal" and l * math.sin(math.rad(dip)) or l
    m:joint_set{ dip = dip, spacing = spacing, joint = joint }
  end
  return m:generate()
end

-- The edges of the left (loaded) end.
function bars.left_end(m)
  return m:edges{ on_segment = {0, 0, 0, H} }
end

-- The edges of the right end (vertical, or inclined for Models 5 and 6).
function bars.right_end(m, number)
  local bottom, top = right_corners(number)
  return m:edges{ on_segment = {bottom[1], bottom[2], top[1], top[2]} }
end

return bars
