-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- meshed_cost.lua: the cost of meshed blocks against first-order blocks of
-- the same count (docs/meshed_blocks.md, "Cost"), as a whole process to time.
--
-- Models:  the paper's Model 1 bar (20 m x 1 m, rock of wave.lua, nu = 0.25,
--          joints phi = 40 deg, c = sigma_t = 8 MPa, k_n = 2 E / 0.2 m), loaded
--          at its left end by one sine period of 5 MPa at 1500 Hz, `newmark`,
--          dt = 2e-6 s, `steps` steps (300), one thread unless --threads says:
--            kind=first_order: square first-order blocks of side `block` (0.1 m:
--                              2000 blocks);
--            kind=meshed:      0.2 m blocks meshed at `mesh` (0.2 m: four
--                              triangles each, 2000 elements).
-- Run:     build/dda run scripts/bench/meshed_cost.lua --set kind=meshed [--set mesh=0.2]
--          [--set block=0.1] [--set steps=300]
-- Writes:  prints the blocks (elements), steps, contacts and CG iterations per step.

local dda = require "dda"
local kind = dda.param("kind", "meshed")
local steps = dda.param("steps", 300)
local block = dda.param("block", 0.1)
local mesh = dda.param("mesh", 0.2)
assert(kind == "meshed" or kind == "first_order", "meshed_cost: kind must be \"meshed\" or \"first_order\"")

local E, f = 50e9, 1500
local m = dda.model{ plane = "stress", g0 = E, g1 = 2e-6, g2 = 0.005, gg = 1, integrator = "newmark",
                     contact_law = "shi", mesh_size = 0, mesh_mass = "consistent", threads = 1 }
local spacing = kind == "meshed" and 0.2 or block
local rock = m:rock{ density = 2000, E = E, nu = 0.25, mesh_size = kind == "meshed" and mesh or nil }
local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6, kn = 2 * E / 0.2 }
m:domain{ {0, 0}, {20, 0}, {20, 1}, {0, 1}, rock = rock }
m:joint_set{ dip = 0, spacing = spacing, joint = joint }
m:joint_set{ dip = 90, spacing = spacing, joint = joint }
m:generate()
m:edges{ on_segment = {0, 0, 0, 1} }:pressure(function(t)
  return t < 1 / f and 5e6 * math.sin(2 * math.pi * f * t) or 0
end)
m:run{ steps = steps }
local totals = m:totals()
print(string.format("%s: %d blocks, %d steps, %d contacts, %.1f CG iterations per step", kind, m:block_count(),
                    m:steps(), m:contact_summary().total, (totals.cg_iterations or 0) / m:steps()))
