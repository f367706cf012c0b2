-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- incline.lua: a block sliding down a 30 degree incline with Coulomb friction.
--
-- Models:  a fixed base whose top face is inclined at alpha = 30 deg and a
--          0.5 m x 0.5 m block resting on it; joint friction phi = 20 deg, no
--          cohesion; gravity 9.81 m/s^2 straight down. For alpha > phi the
--          block slides with a = g (sin alpha - cos alpha tan phi) =
--          1.81281 m/s^2, so it travels s = 1/2 a t^2 down the slope; with
--          phi >= alpha (e.g. --set phi=35) it stays put.
-- Run:     build/dda run scripts/incline.lua [--set t_end=1.0] [--set phi=20] [--set alpha=30]
--                [--set dt=1e-3] [--set law=shi]
-- Writes:  out/incline.csv (step, time, ux, uy, vx, vy of the block's centre),
--          and prints the distance slid beside 1/2 a t^2 as it goes.

local dda = require "dda"

local g = 9.81
local alpha = dda.param("alpha", 30)    -- slope angle, degrees
local phi = dda.param("phi", 20)        -- joint friction angle, degrees
local t_end = dda.param("t_end", 1.0)   -- s

-- m and centre are globals: `dda console` can reach them after the run.
-- law: nil leaves the engine's default contact law ("holding"); --set law=shi
-- runs Shi's, under which a block that must hold creeps at small dt.
m = dda.model{ plane = "stress", gravity = {0, -g}, g1 = dda.param("dt", 1e-3), g2 = 0.01,
               contact_law = dda.param("law", nil) }
local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
local joint = m:joint{ friction = phi }

-- The base: its top edge runs from (0, 0) up the slope to (L cos a, L sin a).
local a = math.rad(alpha)
local s, n = {math.cos(a), math.sin(a)}, {-math.sin(a), math.cos(a)}   -- along and normal to the slope
local L = 4
local base = m:add_block{ {0, 0}, {0, -1}, {L * s[1], -1}, {L * s[1], L * s[2]}, rock = rock, joint = joint }
base:fix()   -- fixed points at every vertex

-- The block: its bottom edge lies on the slope, 3 m up from the foot. (It
-- starts a micrometre above the slope: corners computed with cos and sin are
-- not exactly on the base's edge, and a rounding-level overlap is refused.)
local function on_slope(d, h) return {d * s[1] + h * n[1], d * s[2] + h * n[2]} end
local w, d0, gap = 0.5, 3.0, 1e-6
m:add_block{ on_slope(d0, gap), on_slope(d0 + w, gap), on_slope(d0 + w, gap + w), on_slope(d0, gap + w),
             rock = rock, joint = joint }
local c = on_slope(d0 + w / 2, gap + w / 2)
centre = m:monitor{ name = "incline", at = c, fields = {"ux", "uy", "vx", "vy"} }

local acc = alpha > phi and g * (math.sin(a) - math.cos(a) * math.tan(math.rad(phi))) or 0
print(string.format("alpha = %g deg, phi = %g deg: expected a = %.5f m/s^2", alpha, phi, acc))
print(string.format("%10s %14s %14s", "t (s)", "slid (m)", "1/2 a t^2 (m)"))

-- Distance slid down the slope (positive downhill).
local function slid() return -(centre:value("ux") * s[1] + centre:value("uy") * s[2]) end

m:run{ time = t_end, every = math.max(1, math.floor(t_end / 1e-3 / 10 + 0.5)), callback = function(model)
  local t = model:time()
  print(string.format("%10.4f %14.8f %14.8f", t, slid(), 0.5 * acc * t * t))
end }

local t = m:time()
local measured = 2 * slid() / (t * t)
print(string.format("after %d steps: a = 2 s / t^2 = %.5f m/s^2 (expected %.5f)", m:steps(), measured, acc))
