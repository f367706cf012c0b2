-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_joint_offset.lua: how much the PPV at MP1 of the paper's blast model
-- (Section 4, Fig. 14b) depends on where the joint pattern lies.
--
-- Models:  the 100 m blast model of blast_model.lua (2 m joints at 45 and 135
--          deg, the 8 m x 4 m chamber, Fixed outer boundary), with both joint
--          sets shifted along x by an offset d from the detonation centre.
--          The paper does not say where its joints lie. The pattern repeats
--          every 2 m * sqrt(2) = 2.83 m of shift along x and is mirrored about
--          the chamber's axis by d -> 2.83 - d, so the offsets k * 2.83 / n
--          (k = 0 .. n-1) sample every placement. For each: DHI and SHI,
--          12 ms, PPV (max |vy|) at MP1 (8 m above the detonation centre).
-- Run:     build/dda run scripts/paper/blast_joint_offset.lua [--set n=8]
--            [--set t_end=0.012] [--set spacing=2] [--out out]
--          --set check=true: an error unless the mirrored placements (d and
--            2.83 - d) give the same PPV within 1 % (the model is symmetric
--            about x = 0 but for the joint pattern; a bias of the engine
--            towards one side, or a cutting that is not mirror-exact, fails it).
-- Writes:  blast_joint_offset.csv: offset_m, blocks, ppv_dhi_m_s,
--          t_peak_dhi_s, ppv_shi_m_s, t_peak_shi_s; prints the table with the
--          mean, smallest and largest PPV against the field's 0.95 m/s.

local dda = require "dda"
local docs_output = require "docs_output"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local blast_model = require "blast_model"

local n = dda.param("n", 8)
local t_end = dda.param("t_end", 0.012)
local spacing = dda.param("spacing", 2)
local check = dda.param("check", false)
local period = spacing * math.sqrt(2)
local FIELD_PPV = 0.95  -- m/s at MP1, paper Fig. 14b

local function run(offset, load)
  local M = blast_model.build{ size = 100, spacing = spacing, joint_origin = {offset, 0},
                               min_area = 0.01 * spacing * spacing }
  blast_model.load(M, load)
  M.outer:fix()
  local mon = M.m:monitor{ at = {0, 8}, fields = {"vy"}, csv = false }
  M.m:run{ time = t_end }
  local vy, t_peak = mon:peak("vy")
  return math.abs(vy), t_peak, #M.blocks
end

local rows = {}
print(string.format("PPV at MP1, 100 m model, %g m joints shifted by d along x (one period: %.3f m), %g ms",
                    spacing, period, 1e3 * t_end))
print("   d (m)  blocks  DHI (m/s)  SHI (m/s)")
for k = 0, n - 1 do
  local d = k * period / n
  local dhi, t_dhi, blocks = run(d, "dhi")
  local shi, t_shi = run(d, "shi")
  rows[#rows + 1] = { d = d, blocks = blocks, dhi = dhi, t_dhi = t_dhi, shi = shi, t_shi = t_shi }
  print(string.format("  %6.3f  %6d  %9.4f  %9.4f", d, blocks, dhi, shi))
end

local offset_csv = dda.output("blast_joint_offset.csv")
local f = assert(io.open(offset_csv, "w"))
f:write("offset_m,blocks,ppv_dhi_m_s,t_peak_dhi_s,ppv_shi_m_s,t_peak_shi_s\n")
for _, r in ipairs(rows) do
  f:write(string.format("%.6g,%d,%.6g,%.6g,%.6g,%.6g\n", r.d, r.blocks, r.dhi, r.t_dhi, r.shi, r.t_shi))
end
docs_output.close(f, offset_csv)

local function stats(key)
  local sum, lo, hi = 0, math.huge, -math.huge
  for _, r in ipairs(rows) do sum, lo, hi = sum + r[key], math.min(lo, r[key]), math.max(hi, r[key]) end
  return sum / #rows, lo, hi
end
for _, key in ipairs{ "dhi", "shi" } do
  local mean, lo, hi = stats(key)
  print(string.format("%s: mean %.4f m/s (%+.0f %% against the field's %.2f), range %.4f .. %.4f", key:upper(), mean,
                      100 * (mean / FIELD_PPV - 1), FIELD_PPV, lo, hi))
end

if check then
  -- d and period - d are mirror images about x = 0: the same PPV at MP1 (on the axis).
  for k = 1, n - 1 do
    local a, b = rows[k + 1], rows[n - k + 1]
    for _, key in ipairs{ "dhi", "shi" } do
      if math.abs(a[key] - b[key]) > 0.01 * math.max(a[key], b[key]) then
        error(string.format("mirrored joint placements d = %.3f and %.3f m give %s PPVs %.4f and %.4f m/s (more than 1 %% apart)",
                            a.d, b.d, key:upper(), a[key], b[key]))
      end
    end
  end
  print("check: mirrored placements agree within 1 %")
end
