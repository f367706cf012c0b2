-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- state_hashes.lua: the state hash of each benchmark scene after a fixed number of steps.
--
-- Models:  the scenes of scenes.lua (bar, blast(2), wall(10), wall(20) with gg = 1)
--          and the incline of scripts/incline.lua, each stepped a fixed count.
-- Run:     build/dda run scripts/bench/state_hashes.lua [--set threads=2] [--set only=bar]
--                [--set contact_law=shi]
--          Compare the output with bench/state_hashes.txt (contact_law
--          "holding", the default) or bench/state_hashes_shi.txt (contact_law=shi,
--          the engine's results before the holding law, bit for bit): a
--          refactoring that must not change results prints the same lines.
--          (tests script.state_hashes and script.state_hashes_shi compare them.)
-- Writes:  prints "scene steps hash" lines; nothing else.

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local scenes = require "scenes"

local threads = dda.param("threads", 2)
local only = dda.param("only", "")
local contact_law = dda.param("contact_law", "holding")  -- set on every scene, whatever the default (the blast pins "shi" itself)

local function incline()
  local g, alpha, phi = 9.81, math.rad(30), 20
  local m = dda.model{ plane = "stress", gravity = {0, -g}, g1 = 1e-3, g2 = 0.01, threads = threads }
  local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  local joint = m:joint{ friction = phi }
  local s, n = {math.cos(alpha), math.sin(alpha)}, {-math.sin(alpha), math.cos(alpha)}
  local base = m:add_block{ {0, 0}, {0, -1}, {4 * s[1], -1}, {4 * s[1], 4 * s[2]}, rock = rock, joint = joint }
  base:fix()
  local function at(d, h) return {d * s[1] + h * n[1], d * s[2] + h * n[2]} end
  m:add_block{ at(3, 1e-6), at(3.5, 1e-6), at(3.5, 0.500001), at(3, 0.500001), rock = rock, joint = joint }
  return m
end

local runs = {
  { "bar", 300, function() return scenes.bar(threads) end },
  { "blast(2)", 300, function() return scenes.blast(2, threads) end },
  { "wall(10)", 50, function() return scenes.wall(10, threads) end },
  { "wall(20)gg1", 30, function() local m = scenes.wall(20, threads); m:controls{ gg = 1 }; return m end },
  { "incline", 500, incline },
}
for _, r in ipairs(runs) do
  local name, steps, make = r[1], r[2], r[3]
  if only == "" or only == name then
    local m = make()
    m:controls{ contact_law = contact_law }
    m:step(steps)
    print(string.format("%-12s %5d %s", name, steps, m:hash()))
  end
end
