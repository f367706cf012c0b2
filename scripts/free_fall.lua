-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- free_fall.lua: one block falling freely under gravity.
--
-- Models:  a 1 m x 1 m block released from rest, gravity g = 9.81 m/s^2, no
--          contacts. DDA's time integration is exact for a constant
--          acceleration, so the drop must equal 1/2 g t^2 to round-off.
-- Run:     build/dda run scripts/free_fall.lua [--set t_end=1.0] [--set dt=0.01] [--out out]
-- Writes:  out/free_fall.csv (step, time, uy, vy of the block's centre), and
--          prints the drop beside 1/2 g t^2 as it goes.

local dda = require "dda"

local g = dda.param("g", 9.81)          -- m/s^2
local t_end = dda.param("t_end", 1.0)   -- s
local dt = dda.param("dt", 0.01)        -- s, the upper step time g1

-- m and centre are globals: `dda console` can reach them after the run.
m = dda.model{ plane = "stress", gravity = {0, -g}, g1 = dt, g2 = 0.5 }
local rock = m:rock{ density = 2500, E = 1e9, nu = 0.25 }
m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1}, rock = rock }

centre = m:monitor{ name = "free_fall", at = {0.5, 0.5}, fields = {"uy", "vy"} }

print(string.format("%10s %14s %14s %12s", "t (s)", "drop (m)", "1/2 g t^2 (m)", "rel. error"))
local worst = 0
local function report(model)
  local t = model:time()
  local drop = -centre:value("uy")
  local exact = 0.5 * g * t * t
  local err = math.abs(drop - exact) / exact
  worst = math.max(worst, err)
  print(string.format("%10.4f %14.8f %14.8f %12.3e", t, drop, exact, err))
end

m:run{ time = t_end, every = math.max(1, math.floor(t_end / dt / 10 + 0.5)), callback = report }
print(string.format("largest relative error against 1/2 g t^2: %.3e after %d steps", worst, m:steps()))
