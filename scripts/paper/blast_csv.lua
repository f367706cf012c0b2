-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_csv.lua: reading blast.lua's CSV files, shared by blast_summary.lua and
-- blast_meshed_summary.lua (no simulation).
--
--   local blast_csv = require "blast_csv"
--   local rows = blast_csv.read(path)      -- nil if no file; else rows keyed by the header
--   local t = blast_csv.column(rows, "time")
--   local e = blast_csv.reflected_energy(rows, 15e-3)

local M = {}

-- A CSV file as a list of rows, each a table keyed by the header's names
-- (numbers where a cell reads as one); nil when the file cannot be opened.
function M.read(path)
  local f = io.open(path, "r")
  if not f then return nil end
  local hdr, rows = nil, {}
  for line in f:lines() do
    local cells = {}
    for c in (line .. ","):gmatch("([^,]*),") do cells[#cells + 1] = c end
    if not hdr then hdr = cells else
      local r = {}
      for i, k in ipairs(hdr) do r[k] = tonumber(cells[i]) or cells[i] end
      rows[#rows + 1] = r
    end
  end
  f:close()
  return rows
end

function M.column(rows, k) local v = {} for i, r in ipairs(rows) do v[i] = r[k] end return v end

-- The integral of vx^2 + vy^2 over t >= t0 of a monitor history (rows with
-- time, vx, vy): the report's reflected energy (docs/validation.md, Section 4).
function M.reflected_energy(rows, t0)
  local e = 0
  for i = 2, #rows do
    if rows[i].time >= t0 then
      e = e + (rows[i].vx ^ 2 + rows[i].vy ^ 2) * (rows[i].time - rows[i - 1].time)
    end
  end
  return e
end

return M
