-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- bench.lua: time one benchmark scene and append a row to a CSV table.
--
-- Models:  one scene of scenes.lua: --set scene=wall --set n=40 | scene=blast
--          --set h=2 | scene=blast_meshed --set mesh=0.25 --set radius=12 (radius 0:
--          every block meshed) | scene=bar; --set threads=1|2; --set steps=10 timed steps
--          after --set warmup=2 untimed ones (another warmup names the row
--          blast(0.5)@2500: timed after 2500 steps); --set pre=block_jacobi|multigrid
--          forces a preconditioner (default: the scene's, auto); --set
--          mesh_pre=block_factor|node_jacobi the meshed blocks' (mesh_preconditioner); --set
--          predict=false starts open-close iterations from the last step's
--          contact states (predict_states = false); --set patch=0 re-solves
--          over all rows only (patch_hops = 0), --set patch=N
--          patches of N couplings; --set solver=pcg|cholmod forces the linear
--          solver (default: auto) and names the row wall(40)[cholmod];
--          --set gg=1 makes a wall dynamic (row wall(40)gg1);
--          --set integrator=newmark|generalized_alpha (default: the scene's, shi).
--          --set law=shi|holding: the contact law (default: the scene's; the walls take the
--          engine's default); --set stages=true also prints each stage's ms per step
--          (scripts/bench/thread_scaling.sh reads it).
-- Run:     build/dda run scripts/bench/bench.lua --set scene=wall --set n=20 --set threads=2 [--set csv=FILE]
--          (scripts/bench/run.sh runs the whole table, one process per row so
--          that each row's peak memory is its own).
-- Writes:  prints one table row; with --set csv=FILE appends it to FILE with the
--          columns scene,threads,blocks,contacts,steps,ms_per_step,block_steps_per_s,
--          oc_per_step,cg_per_step,cuts,detect_share,assemble_share,solve_share,
--          update_share,other_share,peak_rss_mb,patch_per_step (CG iterations
--          confined to a re-solve's patch, PcgSettings::patch_hops; cg_per_step
--          counts those over all rows),cpu_ms_per_step (the process's CPU time
--          over the timed steps, all threads: on a shared machine it moves far
--          less than the elapsed ms_per_step).

local dda = require "dda"
package.path = package.path .. ";" .. (debug.getinfo(1, "S").source:match("@?(.*/)") or "./") .. "?.lua"
local scenes = require "scenes"

local scene = dda.param("scene", "wall")
local threads = dda.param("threads", 1)
local steps = dda.param("steps", 10)
local warmup = dda.param("warmup", 2)
local csv = dda.param("csv", "")
local pre = dda.param("pre", "")  -- preconditioner; "" keeps the scene's (auto)
local mesh_pre = dda.param("mesh_pre", "")  -- mesh_preconditioner; "" keeps the default
local integrator = dda.param("integrator", "")
local predict = dda.param("predict", true)  -- false: open-close iterations start from the last step's states
local patch = dda.param("patch", -1)  -- re-solve patch hops; -1 keeps the engine's default
local solver = dda.param("solver", "")  -- "pcg" or "cholmod"; "" keeps the automatic choice
local gg = dda.param("gg", -1)  -- the dynamic parameter; -1 keeps the scene's
local stages = dda.param("stages", false)  -- true: also print each stage's ms per step
local law = dda.param("law", "")  -- contact_law; "" keeps the scene's (the engine's default for walls)

local m, name
if scene == "wall" then
  local n = dda.param("n", 10)
  m, name = scenes.wall(n, threads), string.format("wall(%d)", n)
elseif scene == "blast" then
  local h = dda.param("h", 2)
  m, name = scenes.blast(h, threads), string.format("blast(%g)", h)
elseif scene == "blast_meshed" then
  local mesh, radius = dda.param("mesh", 0.25), dda.param("radius", 12)
  m, name = scenes.blast_meshed(mesh, radius, threads), string.format("blast_meshed(%g/%g)", mesh, radius)
elseif scene == "bar" then
  m, name = scenes.bar(threads), "bar"
else
  error("unknown scene '" .. tostring(scene) .. "' (wall, blast, blast_meshed, bar)")
end

if gg >= 0 then
  m:controls{ gg = gg }
  name = string.format("%sgg%g", name, gg)
end
if warmup ~= 2 then name = string.format("%s@%d", name, warmup) end
if solver ~= "" then
  m:controls{ solver = solver }
  name = string.format("%s[%s]", name, solver)
end
if law ~= "" then
  m:controls{ contact_law = law }
  name = string.format("%s{%s}", name, law)
end
if pre ~= "" then m:controls{ preconditioner = pre } end
if mesh_pre ~= "" then m:controls{ mesh_preconditioner = mesh_pre } end
m:controls{ predict_states = predict }
if integrator ~= "" then m:controls{ integrator = integrator } end
if patch >= 0 then m:controls{ patch_hops = patch } end
m:step(warmup)
local cpu_start = os.clock()
local sum = { t_detect = 0, t_predict = 0, t_assemble = 0, t_solve = 0, t_check = 0, t_control = 0, t_update = 0,
              t_total = 0,
              open_close_iterations = 0, cg_iterations = 0, patch_iterations = 0, step_cuts = 0,
              factorisations = 0 }
for _ = 1, steps do
  m:step(1)
  local s = m:stats()
  for k in pairs(sum) do sum[k] = sum[k] + s[k] end
end
local cpu_ms = 1e3 * (os.clock() - cpu_start) / steps
local contacts = m:stats().contacts
local blocks = #m:blocks{}

local function peak_rss_mb()
  local f = io.open("/proc/self/status", "r")
  if not f then return 0 end
  for line in f:lines() do
    local kb = line:match("^VmHWM:%s+(%d+)")
    if kb then f:close() return tonumber(kb) / 1024 end
  end
  f:close()
  return 0
end

local total = sum.t_total
local ms = 1e3 * total / steps
local function share(x) return total > 0 and x / total or 0 end
local other = total - sum.t_detect - sum.t_assemble - sum.t_solve - sum.t_check - sum.t_update
local row = string.format("%s,%d,%d,%d,%d,%.3f,%.0f,%.2f,%.1f,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.1f,%.1f,%.3f",
  name, threads, blocks, contacts, steps, ms, blocks * steps / total, sum.open_close_iterations / steps,
  sum.cg_iterations / steps, sum.step_cuts, share(sum.t_detect), share(sum.t_assemble),
  share(sum.t_solve + sum.t_check), share(sum.t_update), share(other), peak_rss_mb(), sum.patch_iterations / steps,
  cpu_ms)
print(string.format("%-10s threads %d  blocks %6d  contacts %7d  %9.2f ms/step (CPU %.2f)  %9.0f block-steps/s  oc %.2f  cg %.1f (+%.1f on patches)  cuts %d  %s (%.2f factorisations/step)",
  name, threads, blocks, contacts, ms, cpu_ms, blocks * steps / total, sum.open_close_iterations / steps,
  sum.cg_iterations / steps, sum.patch_iterations / steps, sum.step_cuts, m:stats().solver,
  sum.factorisations / steps))
if stages then
  local line = { "stages ms/step:" }
  for _, k in ipairs{ "detect", "predict", "assemble", "solve", "check", "control", "update", "total" } do
    line[#line + 1] = string.format("%s %.4f", k, 1e3 * sum["t_" .. k] / steps)
  end
  print(table.concat(line, " "))
end
if csv ~= "" then
  local f = assert(io.open(csv, "a"))
  f:write(row, "\n")
  f:close()
end
