-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_geometry.lua: the geometry of the paper's Section 4 blasting model.
--
-- Models:  a square jointed rock mass (100 m by default; the paper's Models 1-3
--          are 120, 100 and 80 m) with two joint sets at 45 and 135 deg, 2 m
--          spacing, and an 8 m x 4 m blasting chamber at its centre (the
--          origin is the detonation centre). Rock: density 2650 kg/m^3,
--          E = 74 GPa, nu = 0.2; joints: phi = 25 deg, c = 2 MPa, no tensile
--          strength. Reports block counts, the chamber wall, and which blocks
--          hold the monitor points MP1 (0, 8), MP2 (-6, 5) and MP3 (near the
--          top boundary above the centre). No run.
-- Run:     build/dda run scripts/paper/blast_geometry.lua [--set size=120] [--set check_step=false]
-- Writes:  out/blast_geometry.csv: size, blocks, area, chamber_edges,
--          chamber_wall_length, boundary_edges, and the monitor points' blocks.

local dda = require "dda"
local docs_output = require "docs_output"

local size = dda.param("size", 100)         -- m, side of the square model
local spacing = dda.param("spacing", 2)     -- m
-- One time step validates the model (no overlapping blocks); --set check_step=false skips it.
local check_step = dda.param("check_step", true)
local h = size / 2

-- contact_law = "shi": the paper's DDA contact law (docs/contacts.md), as every paper script.
local m = dda.model{ plane = "strain", g0 = 100e9, g1 = 1e-5, g2 = 0.005, gg = 1, contact_law = "shi" }
local rock = m:rock{ density = 2650, E = 74e9, nu = 0.2 }
local joint = m:joint{ friction = 25, cohesion = 2e6, tension = 0 }

m:domain{ box = {-h, -h, h, h}, rock = rock, joint = joint }
local chamber = m:hole{ box = {-4, -2, 4, 2}, joint = joint }
m:joint_set{ dip = 45, spacing = spacing, joint = joint }
m:joint_set{ dip = 135, spacing = spacing, joint = joint }
local blocks, info = m:generate()

local wall = chamber:edges()
local outer = m:edges{ boundary = "domain" }
local points = { MP1 = {0, 8}, MP2 = {-6, 5}, MP3 = {0, h - 1} }
print(string.format("blast model %g m x %g m: %d blocks (%d slivers merged), area %.3f m^2", size, size, #blocks,
                    info.slivers_merged, blocks:area()))
print(string.format("chamber wall: %d edges, %.3f m (8 m x 4 m: 24 m); outer boundary: %d edges, %.3f m",
                    #wall, wall:length(), #outer, outer:length()))
local ids = {}
for _, name in ipairs{"MP1", "MP2", "MP3"} do
  local p = points[name]
  local b = m:block_at(p[1], p[2])
  ids[name] = b and b:id() or -1
  print(string.format("%s at (%g, %g): block %d", name, p[1], p[2], ids[name]))
end
if check_step then m:step(1) end   -- validates the model: no overlapping blocks

local out = assert(io.open(dda.output("blast_geometry.csv"), "w"))
out:write("size,blocks,area,chamber_edges,chamber_wall_length,boundary_edges,mp1_block,mp2_block,mp3_block\n")
out:write(string.format("%g,%d,%.9g,%d,%.9g,%d,%d,%d,%d\n", size, #blocks, blocks:area(), #wall, wall:length(),
                        #outer, ids.MP1, ids.MP2, ids.MP3))
docs_output.close(out, dda.output("blast_geometry.csv"))
print("written to " .. dda.output("blast_geometry.csv"))
