-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- geometry_models.lua: builds the geometry of the paper's rock bars, Models 1-6.
--
-- Models:  the six jointed rock bars of Sections 2 and 3 (see bars.lua): cuts
--          each into blocks, checks the blocks tile the bar (total area 20 m^2)
--          and that the model can take one time step (no overlaps), and
--          reports block counts and the number of edges on each end. No wave
--          is run here; the figure scripts do that.
-- Run:     build/dda run scripts/paper/geometry_models.lua [--set models=1,4] [--set check_step=false]
-- Writes:  out/paper_geometry.csv: model, blocks, area (m^2), left_edges,
--          right_edges, right_length (m), smallest block area (m^2).

local dda = require "dda"
local bars = require "bars"

local wanted = tostring(dda.param("models", "1,2,3,4,5,6"))
local check_step = dda.param("check_step", true)

local out = assert(io.open(dda.output("paper_geometry.csv"), "w"))
out:write("model,blocks,area,left_edges,right_edges,right_length,smallest_block\n")

print(string.format("%-6s %-58s %7s %9s %6s %6s", "model", "description", "blocks", "area", "left", "right"))
for number in wanted:gmatch("%d+") do
  number = tonumber(number)
  -- contact_law = "shi": the paper's DDA contact law (docs/contacts.md), as every paper script.
  local m = dda.model{ plane = "stress", g0 = 20 * bars.rock.E, g1 = 2e-6, g2 = 0.005, gg = 1, contact_law = "shi" }
  local rock = m:rock(bars.rock)
  local joint = m:joint{ friction = 40, cohesion = 8e6, tension = 8e6 }
  local blocks = bars.build(m, number, rock, joint)
  local left, right = bars.left_end(m), bars.right_end(m, number)
  local smallest = math.huge
  for i = 1, #blocks do smallest = math.min(smallest, blocks[i]:area()) end
  print(string.format("%-6d %-58s %7d %9.6f %6d %6d", number, bars.descriptions[number], #blocks, blocks:area(),
                      #left, #right))
  out:write(string.format("%d,%d,%.9g,%d,%d,%.9g,%.9g\n", number, #blocks, blocks:area(), #left, #right,
                          right:length(), smallest))
  out:flush()
  assert(math.abs(blocks:area() - bars.length * bars.height) < 1e-9, "blocks do not tile the bar")
  if check_step then m:step(1) end   -- validates the model: no overlapping blocks
  m:close()
end
out:close()
print("written to " .. dda.output("paper_geometry.csv"))
