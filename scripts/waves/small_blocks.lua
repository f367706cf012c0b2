-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- small_blocks.lua: the paper's Model 1 under a pulse slow enough that its
-- 0.2 m blocks are within the element size the load needs, with nothing
-- pinned but the step: the engine still meshes them (the bar spans many
-- shear wavelengths), each into the four elements of its outline, and the
-- pulse arrives without a wrong-sign lobe (docs/waves.md).
--
-- Models:  Model 1 (scripts/paper/bars.lua), half a sine of 5 MPa at 500 Hz on
--          the left end (99 % of its energy below 1183 Hz: elements of
--          0.223 m), right end fixed, g0 = E and 20E, nu = 0 (the strip is then
--          the 1-D rod of the exact answer), g1 = 2e-6 s.
-- Reference: the exact jointed 1-D bar (scripts/paper/jointed_bar_exact.lua,
--          each joint k_n = 2 g0 / 0.2 m, the paper's Eq. 4).
-- Run:     build/dda run scripts/waves/small_blocks.lua [--set check=true] [--out out]
-- Prints:  per g0 the compressive peak at the centre (10.1, 0.5), the exact
--          one, their difference, the largest tension ahead of the peak (% of
--          5 MPa). check=true: an error unless every peak is within 1 % of the
--          exact one and no tension ahead exceeds 1 % of the amplitude.

local here = debug.getinfo(1, "S").source:match("@?(.*/)") or "./"
package.path = package.path .. ";" .. here .. "../paper/?.lua"
local dda = require "dda"
local wave = require "wave"

local check = dda.param("check", false)
wave.scheme = { default = true, nu = 0, suffix = "_default" }
local failures = {}
for _, g0 in ipairs{ 1, 20 } do
  local r = wave.run{ tag = "small_blocks_g" .. g0, g0 = g0, load = "half", freq = 500, t_end = 3e-3 }
  local ex = wave.exact{ g0 = g0, load = "half", freq = 500, t_end = 3e-3 }
  local peak, t_peak = wave.peak(r.t, r.sxx, 0, r.t_split, -1)
  local exact = wave.peak(ex.t, ex.sxx, 0, ex.t_split, -1)
  local lobe = 0
  for i, v in ipairs(r.sxx) do if r.t[i] < t_peak then lobe = math.max(lobe, v) end end
  local off, ahead = 100 * (peak - exact) / math.abs(exact), 100 * lobe / wave.A
  print(string.format("g0 = %2dE: compressive peak %.4f MPa, exact %.4f (%+.2f %%); tension ahead %.2f %%",
                      g0, peak / 1e6, exact / 1e6, off, ahead))
  if math.abs(off) > 1 then failures[#failures + 1] = string.format("g0 = %dE: peak %+.2f %% from exact", g0, off) end
  if ahead > 1 then failures[#failures + 1] = string.format("g0 = %dE: tension ahead %.2f %%", g0, ahead) end
end
if check and #failures > 0 then error("small_blocks: " .. table.concat(failures, "; "), 0) end
