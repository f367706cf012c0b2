-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- make_checkpoint_seeds.lua: the seed corpus of dda_fuzz_checkpoint, real
-- checkpoints of small models that hold every kind of state.
--
-- Writes:  OUT/first_order.ckpt  a blast in small: cohesive joints, a pressure
--                                pulse, a point load driven by a Lua function (saved
--                                as its last value), viscous boundaries, fixed
--                                points, a target driven by an acceleration history,
--                                monitors; a few steps in
--          OUT/meshed.ckpt       a meshed block dropped on a fixed base (Newmark)
--          OUT/cholmod.ckpt      a brick wall on the CHOLMOD factor (quasi-static)
--          OUT/multigrid.ckpt    the wall under PCG with the multigrid preconditioner
--          OUT/earthquake.ckpt   a column of blocks on a compliant base carrying the
--                                recorded earthquake of data/, with free-field sides
-- Run:     build/dda run fuzz/make_checkpoint_seeds.lua --out SEED_FOLDER
local dda = require "dda"
local here = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"

local function save(m, name)
  print(m:save(name .. ".ckpt"))
  m:close()
end

-- First order: 4 x 2 blocks of 1 m.
do
  local m = dda.model{ gravity = {0, -9.81}, g0 = 6e11, g1 = 1e-5 }
  local rock = m:rock{ density = 2600, E = 30e9, nu = 0.25 }
  local joint = m:joint{ friction = 35, cohesion = 0.5e6, tension = 0.2e6 }
  m:domain{ box = {0, 0, 4, 2}, rock = rock, joint = joint }
  m:joint_set{ dip = 0, spacing = 1, joint = joint }
  m:joint_set{ dip = 90, spacing = 1, joint = joint }
  m:generate()
  m:edges{ on_segment = {0, 0, 0, 2} }:pressure{ {0, 0}, {1e-4, 5e6}, {2e-4, 0} }
  m:edges{ on_segment = {4, 0, 4, 2} }:viscous_boundary{}
  m:point_load{ at = {2.5, 1.5}, force = function(t) return 1e4 * t, 0 end }
  m:fix({0.5, 0.05})
  m:target{ at = {1.5, 0.05}, direction = {1, 0}, acceleration = { {0, 0}, {1e-3, 1} } }
  m:monitor{ at = {3.5, 0.5}, name = "probe", fields = {"ux", "sxx"} }
  m:step(4)
  save(m, "first_order")
end

-- Meshed: a 1 m x 0.5 m block of elements of 0.25 m on a fixed base.
do
  local m = dda.model{ gravity = {0, -9.81}, g1 = 1e-3, integrator = "newmark" }
  local base = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  local meshed = m:rock{ density = 2600, E = 5e9, nu = 0.25, mesh_size = 0.25 }
  m:add_block{ {-1, -1}, {2, -1}, {2, 0}, {-1, 0}, rock = base }:fix()
  m:add_block{ {0, 0.001}, {1, 0.001}, {1, 0.501}, {0, 0.501}, rock = meshed }
  m:step(4)
  save(m, "meshed")
end

-- A brick wall of `n` columns and 2n rows, quasi-static, on the factor or on
-- multigrid (its hierarchy needs more than 24 blocks to have two levels).
local function wall(n, controls)
  local m = dda.model(controls)
  local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  m:add_block{ {-1, -1}, {n + 1, -1}, {n + 1, 0}, {-1, 0}, rock = rock }:fix()
  for row = 0, 2 * n - 1 do
    local y = row * 0.5
    local x0 = row % 2 == 0 and 0 or -0.5
    for c = 0, n do
      local a, b = math.max(0, x0 + c), math.min(n, x0 + c + 1)
      if b > a then m:add_block{ {a, y}, {b, y}, {b, y + 0.5}, {a, y + 0.5}, rock = rock } end
    end
  end
  m:step(3)
  return m
end
save(wall(3, { gravity = {0, -9.81}, g1 = 1e-3, g2 = 0.001, gg = 0, solver = "cholmod" }), "cholmod")
save(wall(5, { gravity = {0, -9.81}, g1 = 1e-3, g2 = 0.001, gg = 0, solver = "pcg", preconditioner = "multigrid" }),
     "multigrid")

-- Earthquake: the record of data/ (its first 0.5 s) coming in through a
-- compliant base under a column of four blocks, free-field sides.
do
  local record = dda.ground_motion{ file = here .. "../data/imperial_valley_1979_el_centro_array7_S50W.dat" }
  local velocity = {}
  for i = 1, 26 do velocity[i] = record.velocity[i] end
  local m = dda.model{ plane = "strain", gravity = {0, -9.81}, g1 = 2.5e-4 }
  local rock = m:rock{ density = 2600, E = 10e9, nu = 0.25 }
  local bedrock = m:rock{ density = 2600, E = 18.7e9, nu = 0.25 }
  m:domain{ box = {0, 0, 2, 8}, rock = rock }
  m:joint_set{ dip = 0, spacing = 2 }
  m:generate()
  local base = m:edges{ on_segment = {0, 0, 2, 0} }:viscous_boundary{ rock = bedrock, vx = velocity }
  m:edges{ on_segment = {0, 0, 0, 8} }:free_field{ base = base }
  m:edges{ on_segment = {2, 0, 2, 8} }:free_field{ base = base }
  m:step(4)
  save(m, "earthquake")
end
