-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- scenes.lua: the benchmark scenes, as a module (no run).
--
-- Models:  wall(N)   quasi-static brick wall: N columns of 1 m x 0.5 m bricks,
--                    2N rows in running bond (half bricks at alternate row ends),
--                    on a 1 m thick base held by three fixed points; rho = 2600,
--                    E = 5 GPa, nu = 0.25, plane stress, friction 30 deg, no
--                    cohesion or tension, gravity, dt = 1e-3 s, g2 = 0.001,
--                    g0 = 50E, open-close limit 8. N = 10, 20, 40 give 211, 821
--                    and 3,241 blocks. Quasi-static as in Shi's static analysis:
--                    no velocity is carried into the next step (gg = 0).
--          blast(h)  the paper's Section 4 model (100 m square, sets at 45 and
--                    135 deg with spacing h, chamber, DHI load on the chamber wall,
--                    blocks under 0.01 h^2 merged into a neighbour).
--          blast_meshed(H, R)  blast(2), the paper's 2 m joints, with the blocks
--                    whose centroid lies within R m of the detonation centre meshed
--                    into elements of about H m (R = 0: every block), joints of their
--                    own stiffness 2*g0/2 m (as scripts/paper/blast.lua --set mesh=H
--                    --set mesh_radius=R); concave blocks at the chamber corners stay
--                    first-order (docs/meshed_blocks.md).
--          bar       the paper's rock bar Model 1 (scripts/paper/bars.lua: 500
--                    first-order blocks, g1 = 2e-6 s, g0 = 20E, a triangular
--                    pressure pulse at the left end, right end fixed).
--          These are the scenes; tests/scenes.hpp builds the same wall(n) in
--          C++ for the C++ tests and benchmarks (a test holds the two equal).
-- Run:     used by scripts/bench/bench.lua (build/dda run scripts/bench/bench.lua --set scene=wall --set n=20)
-- Writes:  nothing.

local dda = require "dda"
local scenes = {}

function scenes.wall(n, threads)
  local E = 5e9
  local m = dda.model{ plane = "stress", g0 = 50 * E, g1 = 1e-3, g2 = 0.001, gg = 0, open_close_limit = 8,
                       gravity = {0, -9.81}, threads = threads }
  local rock = m:rock{ density = 2600, E = E, nu = 0.25 }
  local joint = m:joint{ friction = 30, cohesion = 0, tension = 0 }
  local base = m:add_block{ {-1, -1}, {n + 1, -1}, {n + 1, 0}, {-1, 0}, rock = rock, joint = joint }
  m:fix(0, -0.5)
  m:fix(n / 2, -0.5)
  m:fix(n, -0.5)
  local function brick(x0, y0, w)
    m:add_block{ {x0, y0}, {x0 + w, y0}, {x0 + w, y0 + 0.5}, {x0, y0 + 0.5}, rock = rock, joint = joint }
  end
  for row = 0, 2 * n - 1 do
    local y = row * 0.5
    if row % 2 == 0 then
      for c = 0, n - 1 do brick(c, y, 1) end
    else
      brick(0, y, 0.5)
      for c = 0, n - 2 do brick(0.5 + c, y, 1) end
      brick(n - 0.5, y, 0.5)
    end
  end
  return m
end

-- The paper scripts' modules (blast_model, bars), beside this folder.
local function require_paper(name)
  package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "../paper/?.lua"
  return require(name)
end

function scenes.blast(h, threads)
  local blast_model = require_paper "blast_model"
  -- Slivers (where joints pass close to the chamber corners) are merged: crushed
  -- by the chamber-wall targets they would force tiny steps.
  local b = blast_model.build{ size = 100, spacing = h, controls = { threads = threads }, min_area = 0.01 * h * h }
  blast_model.load(b, "dhi")
  b.outer:fix()
  return b.m
end

function scenes.blast_meshed(mesh, radius, threads)
  local blast_model = require_paper "blast_model"
  local b = blast_model.build{ size = 100, spacing = 2, controls = { threads = threads }, mesh = mesh,
                               mesh_radius = radius, kn = 2 * blast_model.controls.g0 / 2 }
  blast_model.load(b, "dhi")
  b.outer:fix()
  return b.m
end

function scenes.bar(threads)
  local bars = require_paper "bars"
  -- mesh_size = 0: the benchmark's first-order blocks (the engine would mesh
  -- them for the pulse, docs/waves.md).
  local m = dda.model{ plane = "stress", g0 = 20 * bars.rock.E, g1 = 2e-6, g2 = 0.005, gg = 1, mesh_size = 0,
                       threads = threads }
  local rock = m:rock(bars.rock)
  local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6 }
  bars.build(m, 1, rock, joint)
  bars.left_end(m):pressure{ {0, 0}, {2.5e-4, 5e6}, {5e-4, 0} }
  bars.right_end(m, 1):fix()
  return m
end

return scenes
