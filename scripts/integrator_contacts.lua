-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- integrator_contacts.lua: the time integrators on contacts that settle, hold
-- and slide at a quasi-static step: the measurements behind the engine's
-- default integrator (docs/time_integration.md, "The default, measured").
--
-- Models:  (1) a 0.5 m block on a 30 deg incline (scripts/incline.lua's model:
--          rock 2600 kg/m^3, E = 5 GPa, nu = 0.25, gravity, dt = 1e-3 s,
--          g2 = 0.01), friction 20 deg (it slides: a = g (sin 30 - cos 30
--          tan 20)) and 35 deg (friction holds it), 0.5 s;
--          (2) a stack of six 1 m blocks on a fixed 4 m base, every other one
--          offset 0.3 m, friction 30 deg, 2 s: the top block's largest speed
--          after 1 s (at rest, it is the contact springs' ringing).
--          Each under shi, newmark and generalized-alpha at rho_inf = 0.9,
--          0.8, 0.6, 0.5, 0.3.
-- Run:     build/dda run scripts/integrator_contacts.lua [--set schemes=shi,newmark,0.8]
--          [--set law=shi] (a number is generalized-alpha's rho_inf; law: the
--          contact law, the engine's default when not set)
-- Writes:  nothing; prints one line per model and scheme (slip against the
--          closed form, Δt cuts, open-close iterations; a run the engine cannot
--          finish is reported with its error).

local dda = require "dda"

local g = 9.81
local wanted = tostring(dda.param("schemes", "shi,newmark,0.9,0.8,0.6,0.5,0.3"))
local law = dda.param("law", nil)  -- nil: the engine's default contact law ("holding")

local function model(scheme, rho)
  return dda.model{ plane = "stress", gravity = {0, -g}, g1 = 1e-3, g2 = 0.01, integrator = scheme, rho_inf = rho,
                    contact_law = law }
end

-- The distance slid down the incline in 0.5 s and the closed form.
local function incline(scheme, rho, phi)
  local m = model(scheme, rho)
  local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  local joint = m:joint{ friction = phi }
  local a = math.rad(30)
  local s, n = {math.cos(a), math.sin(a)}, {-math.sin(a), math.cos(a)}
  m:add_block{ {0, 0}, {0, -1}, {4 * s[1], -1}, {4 * s[1], 4 * s[2]}, rock = rock, joint = joint }:fix()
  local function at(d, h) return {d * s[1] + h * n[1], d * s[2] + h * n[2]} end
  m:add_block{ at(3, 1e-6), at(3.5, 1e-6), at(3.5, 0.500001), at(3, 0.500001), rock = rock, joint = joint }
  local c = m:monitor{ at = at(3.25, 0.25), fields = {"ux", "uy"}, csv = false }
  m:run{ time = 0.5 }
  local slid = -(c:value("ux") * s[1] + c:value("uy") * s[2])
  local acc = phi < 30 and g * (math.sin(a) - math.cos(a) * math.tan(math.rad(phi))) or 0
  local t, tot = m:time(), m:totals()
  return slid, 0.5 * acc * t * t, tot.step_cuts, tot.open_close_iterations
end

-- The top block's largest speed after 1 s of a 2 s run.
local function stack(scheme, rho)
  local m = model(scheme, rho)
  local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  local joint = m:joint{ friction = 30 }
  m:add_block{ {-2, -1}, {2, -1}, {2, 0}, {-2, 0}, rock = rock, joint = joint }:fix()
  local nb = 6
  for i = 0, nb - 1 do
    local y0, off = i + (i + 1) * 1e-6, (i % 2 == 0) and 0 or 0.3
    m:add_block{ {-0.5 + off, y0}, {0.5 + off, y0}, {0.5 + off, y0 + 1}, {-0.5 + off, y0 + 1}, rock = rock,
                 joint = joint }
  end
  local mon = m:monitor{ at = {0.3 * ((nb - 1) % 2), nb - 0.5}, fields = {"vx", "vy"}, csv = false }
  local fastest = 0
  m:run{ time = 2.0, callback = function(model)
    if model:time() > 1.0 then
      fastest = math.max(fastest, math.abs(mon:value("vx")), math.abs(mon:value("vy")))
    end
  end }
  local tot = m:totals()
  return fastest, tot.step_cuts, tot.open_close_iterations
end

for k in wanted:gmatch("[^,]+") do
  local rho = tonumber(k)
  local scheme = rho and "generalized_alpha" or k
  local name = rho and string.format("generalized_alpha(%g)", rho) or k
  local ok, slid, exact, cuts, oc = pcall(incline, scheme, rho, 20)
  if ok then
    print(string.format("%-24s incline, phi 20: slid %.6f m, 1/2 a t^2 %.6f m (%+.2f %%), cuts %d, open-close %d", name,
                        slid, exact, 100 * (slid / exact - 1), cuts, oc))
  else print(string.format("%-24s incline, phi 20: %s", name, tostring(slid))) end
  ok, slid, exact, cuts, oc = pcall(incline, scheme, rho, 35)
  if ok then
    print(string.format("%-24s incline, phi 35 (holds): slid %.3g m, cuts %d, open-close %d", name, slid, cuts, oc))
  else print(string.format("%-24s incline, phi 35: %s", name, tostring(slid))) end
  local fastest
  ok, fastest, cuts, oc = pcall(stack, scheme, rho)
  if ok then
    print(string.format("%-24s stack of 6: top block's largest speed after 1 s %.3g m/s, cuts %d, open-close %d", name,
                        fastest, cuts, oc))
  else print(string.format("%-24s stack of 6: %s", name, tostring(fastest))) end
end
