-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- jointed_bar_exact_check.lua: the exact jointed-bar tool (jointed_bar_exact.lua)
-- against closed forms, and the exact numbers of the paper's Model 1.
--
-- Checks:  (1) no joints: the stress at x is the load delayed by x/c, to 1e-12
--              of the amplitude (the characteristics are exact);
--          (2) one joint, harmonic load: the transmitted amplitude, once steady,
--              is |T| = [1 + (omega Z / 2 k_n)^2]^(-1/2), to 2e-4 (the
--              step's linear interpolation of the sine at h = 1e-7 s);
--          (3) Model 1 (0.2 m joints, k_n = 2 g0 / 0.2 m with g0 = E, the
--              paper's Eq. 4), one sine period of 5 MPa at 500, 1000 and 1500 Hz,
--              sigma_xx at x = 10.1 m: prints the first compressive and tensile
--              peaks; at 1000 Hz they must be -4.901 and 4.965 MPa within
--              0.002 MPa (characteristics, written independently).
--              The record ends at 5.5 ms, before the fixed end's reflection
--              arrives (about 20 m / 4100 m/s + 9.9 m / 4100 m/s).
-- Run:     build/dda run scripts/paper/jointed_bar_exact_check.lua
-- Writes:  nothing; prints the Model 1 numbers; errors on a failed check.

package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local exact = require "jointed_bar_exact"

local rho, E = 2000, 50e9
local c, z = math.sqrt(E / rho), rho * math.sqrt(E / rho)
local function check(cond, what) if not cond then error("jointed_bar_exact_check: " .. what, 0) end end

-- (1) A bar without joints delays the load by x/c.
do
  local f, A = 1000, 5e6
  local load = function(t) return (t > 0 and t < 1 / f) and -A * math.sin(2 * math.pi * f * t) or 0 end
  local h = 1e-6
  local t, rec = exact.run{ length = 20, rho = rho, E = E, joints = {}, load = load, right = "absorbing",
                            receivers = {10}, t_end = 3.5e-3, h = h }
  local worst = 0
  for n = 1, #t do worst = math.max(worst, math.abs(rec[1][n] - load(t[n] - 10 / c))) end
  check(worst < 1e-12 * A, string.format("no joints: off the delayed load by %g Pa", worst))
  print(string.format("no joints: largest difference to the delayed load %.3g Pa", worst))
end

-- (2) One joint transmits a harmonic wave with |T|.
do
  local kn, f, A = 3e10, 1000, 1
  local omega = 2 * math.pi * f
  local load = function(t) return A * math.sin(omega * t) end
  local h = 1e-7
  local t, rec = exact.run{ length = 40, rho = rho, E = E, joints = {10}, kn = kn, load = load,
                            right = "absorbing", receivers = {20}, t_end = 8e-3, h = h }
  -- Steady once the joint's transient (time constant Z / 2 k_n) has passed: the
  -- last two periods (the reflection from the joint never reaches x = 20 m).
  local lo, hi = 0, 0
  for n = 1, #t do
    if t[n] > 6e-3 then lo, hi = math.min(lo, rec[1][n]), math.max(hi, rec[1][n]) end
  end
  local measured = (hi - lo) / 2 / A
  local want = 1 / math.sqrt(1 + (omega * z / (2 * kn)) ^ 2)
  print(string.format("one joint: |T| = %.6f, closed form %.6f", measured, want))
  check(math.abs(measured - want) < 2e-4, "one joint: |T| off the closed form")
end

-- (3) Model 1.
for _, f in ipairs{500, 1000, 1500} do
  local A, T = 5e6, 1 / f
  local load = function(t) return t < T and -A * math.sin(2 * math.pi * f * t) or 0 end
  local t, rec = exact.run{ length = 20, rho = rho, E = E, spacing = 0.2, kn = 2 * E / 0.2, load = load,
                            right = "fixed", receivers = {10.1}, t_end = 5.5e-3, h = 1e-7 }
  local lo, hi = exact.peaks(rec[1])
  print(string.format("Model 1, %4d Hz: compressive %.4f MPa, tensile %.4f MPa (attenuation %.2f %%)", f,
                      lo / 1e6, hi / 1e6, 100 * (1 - hi / A)))
  if f == 1000 then
    check(math.abs(lo / 1e6 + 4.901) < 0.002 and math.abs(hi / 1e6 - 4.965) < 0.002,
          "Model 1 at 1000 Hz: the peaks differ from -4.901 / 4.965 MPa")
  end
end
