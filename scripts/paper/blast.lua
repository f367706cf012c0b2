-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast.lua: the paper's Section 4 underground blast in a jointed rock mass
-- (Figs. 14-18), one parametrised script.
--
-- Models:  the square jointed rock mass of blast_model.lua (120, 100 or 80 m;
--          joint sets at 45 and 135 deg, 2 m spacing; rock 2650 kg/m^3,
--          E = 74 GPa, nu = 0.2, plane strain; joints phi = 25 deg, c = 2 MPa,
--          sigma_t = 0; g0 = 100e9 N/m, g1 = 1e-5 s, gg = 1, g2 = 0.005) with
--          the 8 m x 4 m blasting chamber.
--          Where the chamber is, and why: centred at the origin, which is the
--          detonation centre (chamber spans x = -4..4, y = -2..2). The paper's
--          2-D model is a square symmetric about the detonation centre, its
--          monitors are given relative to that centre (MP1 8 m above it, MP2
--          6 m left and 5 m above, MP3 above it near the upper boundary), and
--          the model-size study (120/100/80 m) only makes sense with the
--          chamber in the middle, equally far from every boundary.
--          Loads on the chamber wall (every edge of the hole):
--            load=shi: triangular pressure, 0 -> 30.23 MPa at 0.5 ms -> 0 at
--                      2.5 ms (paper's SHI), pushing into the rock;
--            load=dhi: triangular particle velocity, 0 -> 2.03 m/s at 0.5 ms
--                      -> 0 at 2.5 ms, normal to each wall into the rock
--                      (mean normal at the corners); the engine integrates it
--                      to a displacement (peak 2.54 mm) held afterwards.
--          Outer boundary: boundary=fixed (fixed points), vbc (viscous,
--          Eqs. 6-12) or sbc (springs p = E per unit length, Eq. 22).
--          Monitors: MP1 (0, 8), MP2 (-6, 5), MP3 (0, size/2 - 1) and a line
--          straight above the chamber at y = 4, 6, ..., size/2 - 2 (PPV
--          attenuation, Fig. 18; R = y from the detonation centre).
-- Run:     build/dda run scripts/paper/blast.lua [--set size=100|120|80]
--            [--set load=dhi|shi] [--set boundary=fixed|vbc|sbc]
--            [--set t_end=0.012] [--set frames=0.001] [--out out]
--          One command per figure (several models in turn):
--            --set figure=14a   DHI, Fixed, 12 ms, sizes 120/100/80
--            --set figure=14b   100 m, Fixed, 12 ms, DHI vs SHI (sigma_yy frames of
--                               the DHI run every 1 ms)
--          --set expect_ppv=0.95 [--set ppv_tolerance=0.15]: an error unless the
--          PPV at MP1 lies within the tolerance of the given value (single runs).
--          --set spacing=1: joints 1 m apart instead of the paper's 2 m (slivers
--          under 1 % of a block merged); output tags end in _h1
--            --set figure=15    100 m, DHI, 0.05 s, Fixed vs VBC vs SBC (Figs. 15-18)
--            --set figure=mesh  one run per element size of --set meshes=1,0.5,0.25
--                               (coarse to fine; with --set mesh_radius, t_end): the
--                               PPV convergence table, blast_mesh_convergence.csv;
--                               --set max_change=0.05: an error unless the two finest
--                               sizes' PPVs at MP1 differ by less than 5 %
--          --set check=true: a short test run (default t_end = 3 ms) that
--          raises an error unless the first arrival at MP1 matches the P-wave
--          travel time and no contact penetrates beyond the g2 bound. Arrival:
--          the first time |vy| at MP1 exceeds 1 % of its peak over the run; it
--          must lie between the travel time (at the plane-strain C_P = 5570 m/s)
--          from the roof (y = 2) to the lowest vertex of MP1's block (a
--          first-order block moves as a whole) and the travel time to MP1 at
--          the paper's C_P = 5284 m/s plus 0.25 ms (half the load's rise).
--          Penetration: every contact, every 5 steps, against g2 x half height.
--          --set contact_tolerance=X overrides the open-close hysteresis
--          (fraction of half the model height; engine default 1e-9).
--          --set mesh=H: blocks meshed into constant-strain triangles of about H m
--          (docs/meshed_blocks.md; default 0, first-order blocks); --set
--          mesh_radius=R: only the blocks whose centroid lies within R m of the
--          detonation centre (default 0: every block). Meshed models give their
--          joints the paper's stiffness per length, kn = 2*g0/spacing (1e11 Pa/m at
--          2 m), so that a joint keeps its stiffness whatever the mesh (--set
--          kn=K overrides it, Pa/m; kn=0 keeps the penalty g0 per contact). Tags
--          end in _m<H>[_r<R>]. docs/validation.md, Section 4 notes ("The paper's
--          2 m joints with meshed blocks"), has the convergence runs; the
--          0.05 s runs' Figs. 15-18: blast_meshed_summary.lua.
--          --set integrator=newmark|generalized_alpha: the time integrator
--          (default "shi", the paper's, pinned whatever the engine's default);
--          --set rho_inf=0.8: generalized-α's spectral radius at infinity.
-- Writes:  (under --out, <tag> = <load>_<boundary>_<size>)
--          blast_<tag>_MP1.csv, _MP2.csv, _MP3.csv  step,time,vx,vy,sxx,syy,ux,uy
--          blast_<tag>_line.csv   time and vy at each line monitor
--          blast_<tag>_ppv.csv    R, R/Q^(1/3), PPV (max |vy|), Eq. 23 for the line
--          blast_<tag>_vy_MP1.png y-velocity at MP1
--          blast_<tag>_frames/    sigma_yy frames every `frames` s (when > 0)
--          blast_runs.csv         one row per run appended: tag, blocks, steps,
--                                 wall time, PPVs at MP1/MP2/MP3, step cuts, elements
--                                 (each element of a meshed block), CG iterations, CPU s
--          result.csv             without figure=: ppv_mp1/2/3, t_peak_mp1, blocks,
--                                 steps, step_cuts, wall_s (a row of a dda sweep table)
--          with figure=...: fig<id>_*.png comparison plots; figure=mesh:
--                                 blast_mesh_convergence.csv (mesh_m, elements, steps,
--                                 cpu_s, ppv_mp1, change, ...) and the table on stdout.

local dda = require "dda"
local docs_output = require "docs_output"
local blast_model = require "blast_model"

local Q = blast_model.charge_kg                 -- kg TNT
local function eq23(sd) return 1.8 * sd ^ -2.5 end

local figure = tostring(dda.param("figure", ""))
local check = dda.param("check", false)
local P = {
  size = dda.param("size", 100),
  load = dda.param("load", "dhi"),
  boundary = dda.param("boundary", "fixed"),
  t_end = dda.param("t_end", check and 0.003 or 0.012),
  frames = dda.param("frames", 0),              -- s between sigma_yy frames, 0 = none
  line_step = dda.param("line_step", 2),        -- m between line monitors
  contact_tolerance = dda.param("contact_tolerance", 0),  -- 0 = engine default (1e-9)
  integrator = dda.param("integrator", "shi"),  -- the paper's scheme (docs/time_integration.md)
  rho_inf = dda.param("rho_inf", 0),            -- generalized-α's ρ∞ (0 = the engine's default)
  spacing = dda.param("spacing", 2),            -- m between joints (the paper: 2)
  expect_ppv = dda.param("expect_ppv", 0),      -- m/s: error unless the PPV at MP1 is within ppv_tolerance of it
  mesh = dda.param("mesh", 0),                  -- m: element size of meshed blocks (0 = first-order blocks)
  mesh_radius = dda.param("mesh_radius", 0),    -- m: mesh only blocks within it of the centre (0 = all)
  kn = dda.param("kn", -1),                     -- Pa/m: joints' own stiffness (-1: 2*g0/spacing when meshed)
  ppv_tolerance = dda.param("ppv_tolerance", 0.15),
}

-- Bad values stop here, with the name, rather than deep in a run (line_step
-- = 0 looped forever, t_end = 0 failed inside math.abs).
for _, k in ipairs{ "size", "t_end", "line_step", "spacing", "ppv_tolerance" } do
  if type(P[k]) ~= "number" or not (P[k] > 0) then
    error(string.format("--set %s=%s: must be a number > 0", k, tostring(P[k])))
  end
end
for _, k in ipairs{ "frames", "contact_tolerance", "expect_ppv", "mesh", "mesh_radius" } do
  if type(P[k]) ~= "number" or not (P[k] >= 0) then
    error(string.format("--set %s=%s: must be a number >= 0", k, tostring(P[k])))
  end
end

if type(P.kn) ~= "number" or not (P.kn >= 0 or P.kn == -1) then
  error(string.format("--set kn=%s: must be a number >= 0 (Pa/m; 0 = the penalty g0 per contact)", tostring(P.kn)))
end

local function ppv(mon, field)
  local v, t = mon:peak(field or "vy")
  return math.abs(v), t
end

-- first time |series| exceeds frac of its largest magnitude over the run
local function first_arrival(times, values, frac)
  local peak = 0
  for _, v in ipairs(values) do peak = math.max(peak, math.abs(v)) end
  for i, v in ipairs(values) do
    if math.abs(v) > frac * peak then return times[i], peak end
  end
  return nil, peak
end

local function run_case(cfg)
  local spacing = cfg.spacing or 2
  local tag = string.format("%s_%s_%g", cfg.load, cfg.boundary, cfg.size)
  if spacing ~= 2 then tag = tag .. string.format("_h%g", spacing) end
  local mesh = cfg.mesh or 0
  if mesh > 0 then
    tag = tag .. string.format("_m%g", mesh)
    if (cfg.mesh_radius or 0) > 0 then tag = tag .. string.format("_r%g", cfg.mesh_radius) end
  end
  -- the joints' own stiffness: a meshed block puts a contact at every node of
  -- a joint, so the penalty g0 per contact would stiffen the joint with the
  -- mesh; 2*g0/spacing is what a first-order block's two end contacts give a
  -- full joint of the paper's (Eq. 4 read backwards, docs/time_integration.md)
  local kn = cfg.kn or -1
  if kn < 0 then kn = mesh > 0 and 2 * blast_model.controls.g0 / spacing or 0 end
  if kn > 0 and mesh == 0 then tag = tag .. string.format("_kn%gG", kn / 1e9) end
  local controls = {}
  if (cfg.contact_tolerance or 0) > 0 then controls.contact_tolerance = cfg.contact_tolerance end
  controls.integrator = cfg.integrator or "shi"
  if (cfg.rho_inf or 0) > 0 then controls.rho_inf = cfg.rho_inf end
  -- finer joint sets cut slivers at the chamber corners: merge those under
  -- 1 % of a full block (as the benchmark scenes do)
  local M = blast_model.build{ size = cfg.size, spacing = spacing, controls = controls,
                              min_area = spacing ~= 2 and 0.01 * spacing * spacing or nil,
                              mesh = mesh, mesh_radius = cfg.mesh_radius, kn = kn > 0 and kn or nil }
  local m, h = M.m, M.h
  local elements = m:block_count()   -- blocks, each element of a meshed block counted
  local rock_blocks = M.rock_blocks  -- blocks cut by the joints, before meshing
  print(string.format("blast %s: %g m model, %d blocks (%d with elements), chamber wall %d edges (%.1f m), t_end = %g s",
                      tag, cfg.size, rock_blocks, elements, #M.wall, M.wall:length(), cfg.t_end))

  blast_model.load(M, cfg.load)

  -- outer boundary
  if cfg.boundary == "fixed" then M.outer:fix()
  elseif cfg.boundary == "vbc" then M.outer:viscous_boundary()
  elseif cfg.boundary == "sbc" then M.outer:spring_boundary{ p = blast_model.rock.E, per_length = true }
  else error("boundary must be fixed, vbc or sbc, got " .. tostring(cfg.boundary)) end

  local fields = { "vx", "vy", "sxx", "syy", "ux", "uy" }
  local mons = {}
  for _, mp in ipairs{ {"MP1", 0, 8}, {"MP2", -6, 5}, {"MP3", 0, h - 1} } do
    mons[mp[1]] = m:monitor{ at = {mp[2], mp[3]}, fields = fields, name = "blast_" .. tag .. "_" .. mp[1] }
  end
  -- the roof's middle, just inside the rock: the DHI prescribes 2.03 m/s there
  local roof = m:monitor{ at = {0, blast_model.chamber[4] + 1e-3}, fields = {"vy"}, csv = false }
  local line = {}
  local y = 4
  while y <= h - 2 + 1e-9 do
    line[#line + 1] = { y = y, mon = m:monitor{ at = {0, y}, fields = {"vy"}, csv = false } }
    y = y + cfg.line_step
  end

  if cfg.frames and cfg.frames > 0 and dda.has_render then
    m:frames{ folder = "blast_" .. tag .. "_frames", every_time = cfg.frames, field = "sigma_yy",
              on_error = "continue", colormap = "coolwarm", monitors = false }
  end

  local bound = m:controls().g2 * m:half_height()
  -- lowest point of MP1's block at the start: a first-order block moves as a
  -- whole, so MP1 can feel the wave once it reaches that point
  local mp1_ymin = math.huge
  for _, v in ipairs(mons.MP1:block():vertices()) do mp1_ymin = math.min(mp1_ymin, v[2]) end
  local max_pen, max_pen_t = 0, 0
  local callback = nil
  if cfg.check then
    callback = function(model)
      for _, c in ipairs(model:contacts{}) do
        if c.penetration > max_pen then max_pen, max_pen_t = c.penetration, model:time() end
      end
    end
  end
  local cpu0 = os.clock()
  if callback then m:run{ time = cfg.t_end, every = 5, callback = callback } else m:run{ time = cfg.t_end } end
  local cpu = os.clock() - cpu0   -- process CPU time of the run, all threads

  local tot = m:totals()
  local res = { tag = tag, blocks = rock_blocks, elements = elements, cpu = cpu, cg = tot.cg_iterations, steps = tot.steps, wall = tot.wall_seconds, cuts = tot.step_cuts,
                oc = tot.open_close_iterations, mons = mons, line = line, size = cfg.size, load = cfg.load,
                boundary = cfg.boundary }
  for name, mon in pairs(mons) do res[name] = ppv(mon) end
  res.t_peak_MP1 = select(2, ppv(mons.MP1))
  res.times = mons.MP1:times()
  res.vy = { MP1 = mons.MP1:series("vy"), MP2 = mons.MP2:series("vy"), MP3 = mons.MP3:series("vy") }
  res.syy = { MP1 = mons.MP1:series("syy"), MP2 = mons.MP2:series("syy") }
  res.uy_MP3 = mons.MP3:series("uy")
  print(string.format("  %d steps, %.1f s wall (%.1f ms/step), %.1f s CPU, %d step cuts, %d open-close iterations, " ..
                      "%.1f CG iterations a step", tot.steps, tot.wall_seconds, 1e3 * tot.wall_seconds / tot.steps, cpu,
                      tot.step_cuts, tot.open_close_iterations, tot.cg_iterations / tot.steps))
  print(string.format("  PPV (max |vy|): MP1 %.4f m/s at %.3f ms, MP2 %.4f, MP3 %.4f; MP3 final uy %.4g m",
                      res.MP1, 1e3 * res.t_peak_MP1, res.MP2, res.MP3, res.uy_MP3[#res.uy_MP3]))

  -- line monitors: history and PPV table
  local lt = line[1] and line[1].mon:times() or {}
  local line_csv = dda.output("blast_" .. tag .. "_line.csv")
  local f = assert(io.open(line_csv, "w"))
  local hdr = { "time" }
  local series = {}
  for i, l in ipairs(line) do hdr[#hdr + 1] = string.format("vy_y%g", l.y); series[i] = l.mon:series("vy") end
  f:write(table.concat(hdr, ","), "\n")
  for r = 1, #lt do
    local row = { string.format("%.9g", lt[r]) }
    for i = 1, #line do row[#row + 1] = string.format("%.6g", series[i][r]) end
    f:write(table.concat(row, ","), "\n")
  end
  docs_output.close(f, line_csv)
  local ppv_csv = dda.output("blast_" .. tag .. "_ppv.csv")
  f = assert(io.open(ppv_csv, "w"))
  f:write("R_m,scaled_distance,ppv_m_s,t_peak_s,eq23_m_s,ratio\n")
  res.ppv_line = {}
  for _, l in ipairs(line) do
    local v, t = ppv(l.mon)
    local sd = l.y / Q ^ (1 / 3)
    res.ppv_line[#res.ppv_line + 1] = { R = l.y, sd = sd, ppv = v, eq23 = eq23(sd) }
    f:write(string.format("%g,%.6g,%.6g,%.6g,%.6g,%.4g\n", l.y, sd, v, t, eq23(sd), v / eq23(sd)))
  end
  docs_output.close(f, ppv_csv)

  if dda.has_render then
    dda.plot{ file = "blast_" .. tag .. "_vy_MP1.png", title = "y-velocity at MP1 (" .. tag .. ")",
              series = { { monitor = mons.MP1, field = "vy", name = "MP1" } },
              x_label = "t", x_unit = "ms", x_scale = 1e3, y_label = "vy", y_unit = "m/s" }
  end

  -- one row per run
  local path = dda.output("blast_runs.csv")
  local exists = io.open(path, "r")
  if exists then exists:close() end
  f = assert(io.open(path, "a"))
  if not exists then
    f:write("tag,size,load,boundary,t_end,blocks,steps,wall_s,ms_per_step,step_cuts,open_close_iterations," ..
            "ppv_mp1,t_peak_mp1,ppv_mp2,ppv_mp3,uy_mp3_final,elements,cg_iterations,cpu_s\n")
  end
  f:write(string.format("%s,%g,%s,%s,%g,%d,%d,%.2f,%.2f,%d,%d,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%d,%.2f\n", tag, cfg.size,
                        cfg.load, cfg.boundary, cfg.t_end, rock_blocks, tot.steps, tot.wall_seconds,
                        1e3 * tot.wall_seconds / tot.steps, tot.step_cuts, tot.open_close_iterations, res.MP1,
                        res.t_peak_MP1, res.MP2, res.MP3, res.uy_MP3[#res.uy_MP3], elements, tot.cg_iterations,
                        res.cpu))
  docs_output.close(f, path)

  if cfg.check then
    -- (a) first arrival at MP1: |vy| first above 1 % of its peak over the run,
    -- against the P-wave travel time from the chamber roof (y = 2) to MP1 (y = 8)
    local rock = blast_model.rock
    local G = rock.E / (2 * (1 + rock.nu))
    local lambda = rock.E * rock.nu / ((1 + rock.nu) * (1 - 2 * rock.nu))
    -- plane-strain P-wave speed sqrt((lambda + 2G)/rho) = 5570 m/s; the paper's
    -- C_P = 5284.4 m/s is sqrt(E/rho) (the bar speed). The window below takes
    -- the faster one for the earliest and the slower one for the latest arrival.
    local cp = math.sqrt((lambda + 2 * G) / rock.density)
    local cbar = math.sqrt(rock.E / rock.density)
    local tp = (8 - 2) / cbar
    local ta, peak = first_arrival(res.times, res.vy.MP1, 0.01)
    res.t_early = (mp1_ymin - 2) / cp            -- wave at the bottom of MP1's block
    res.t_late = tp + 0.25e-3                     -- wave at MP1, plus half the load's rise time
    print(string.format("  check: MP1's block reaches down to y = %.3f m: earliest arrival %.4f ms; latest accepted %.4f ms",
                        mp1_ymin, 1e3 * res.t_early, 1e3 * res.t_late))
    print(string.format("  check: C_P = %.1f m/s (plane strain), %.1f m/s (paper, sqrt(E/rho)); travel time roof->MP1 %.4f / %.4f ms; first arrival (|vy| > 1 %% of peak %.4f m/s) %s ms",
                        cp, cbar, 1e3 * 6 / cp, 1e3 * tp, peak, ta and string.format("%.4f", 1e3 * ta) or "none"))
    print(string.format("  check: largest penetration %.4g m at %.4f ms; g2 bound %.4g m", max_pen, 1e3 * max_pen_t, bound))
    res.arrival, res.tp, res.max_pen, res.bound = ta, tp, max_pen, bound
    -- (c) the wall moves as the load says: vy at the roof's middle at its
    -- peak time (0.5 ms) against the DHI's 2.03 m/s (SHI: not prescribed)
    local rt, rv = roof:times(), roof:series("vy")
    for i = 1, #rt do
      if rt[i] <= 0.5e-3 + 1e-12 then res.roof_vy = rv[i] end
    end
    print(string.format("  check: vy at the roof's middle at 0.5 ms %.4f m/s (DHI: 2.03 m/s)", res.roof_vy))
    -- (d) a meshed MP1 reads the element under it, not its whole block
    res.mp1_area = mons.MP1:block():area()
    print(string.format("  check: MP1 reads a block of %.4g m^2 (element size %g m)", res.mp1_area, mesh))
  end
  m:close()
  return res
end

local function cfg_with(over)
  local c = { size = P.size, load = P.load, boundary = P.boundary, t_end = P.t_end, frames = P.frames,
              line_step = P.line_step, check = check, contact_tolerance = P.contact_tolerance,
              spacing = P.spacing, integrator = P.integrator, rho_inf = P.rho_inf,
              mesh = P.mesh, mesh_radius = P.mesh_radius, kn = P.kn }
  for k, v in pairs(over or {}) do c[k] = v end
  return c
end

local function plot_cmp(file, title, results, key, field, ylab, yunit, yscale)
  if not dda.has_render then return end
  local colors = { {30, 80, 200}, {215, 50, 30}, {30, 150, 50}, {120, 120, 120} }
  local s = {}
  for i, r in ipairs(results) do
    s[#s + 1] = { name = r.label, x = r.times, y = r[field][key] or r[field], color = colors[i] }
  end
  dda.plot{ file = file, title = title, series = s, x_label = "t", x_unit = "ms", x_scale = 1e3,
            y_label = ylab, y_unit = yunit, y_scale = yscale or 1 }
end

if figure == "" then
  local r = run_case(cfg_with())
  -- one case: its numbers for a dda sweep table (and <out>/result.csv)
  dda.result{ ppv_mp1 = r.MP1, ppv_mp2 = r.MP2, ppv_mp3 = r.MP3, t_peak_mp1 = r.t_peak_MP1, blocks = r.blocks,
              steps = r.steps, step_cuts = r.cuts, wall_s = r.wall }
  if P.expect_ppv > 0 then
    local diff = r.MP1 / P.expect_ppv - 1
    print(string.format("  PPV at MP1 %.4f m/s against %.4f m/s: %+.1f %% (allowed %.0f %%)", r.MP1, P.expect_ppv,
                        100 * diff, 100 * P.ppv_tolerance))
    if math.abs(diff) > P.ppv_tolerance then
      error(string.format("PPV at MP1 %.4f m/s is %+.1f %% from %.4f m/s (allowed %.0f %%)", r.MP1, 100 * diff,
                          P.expect_ppv, 100 * P.ppv_tolerance))
    end
  end
  if check then
    -- arrival window: from the P-wave travel time to the bottom of MP1's block
    -- (a first-order DDA block responds as a whole) to the travel time to MP1
    -- itself plus half the 0.5 ms rise of the load
    local ok_a = r.arrival and r.arrival >= r.t_early and r.arrival <= r.t_late
    local ok_p = r.max_pen <= r.bound
    if not ok_a then
      error(string.format("first arrival at MP1 %s s outside [%.4g, %.4g] s (P-wave travel time roof -> MP1 %.4g s)",
                          tostring(r.arrival), r.t_early, r.t_late, r.tp))
    end
    if not ok_p then
      error(string.format("contact penetration %.4g m beyond the g2 bound %.4g m", r.max_pen, r.bound))
    end
    if P.load == "dhi" and math.abs(r.roof_vy / 2.03 - 1) > 0.02 then
      error(string.format("vy at the roof's middle at 0.5 ms %.4f m/s, not the DHI's 2.03 m/s (within 2 %%)", r.roof_vy))
    end
    if P.mesh > 0 and r.mp1_area > P.mesh * P.mesh then
      error(string.format("MP1 reads a block of %.4g m^2, larger than an element (%g m)", r.mp1_area, P.mesh))
    end
    print("check passed")
  end
elseif figure == "14a" then
  local res = {}
  for _, size in ipairs{ 120, 100, 80 } do
    local r = run_case(cfg_with{ size = size, load = "dhi", boundary = "fixed" })
    r.label = string.format("%g m (PPV %.3f)", size, r.MP1)
    res[#res + 1] = r
  end
  plot_cmp("fig14a_vy_MP1.png", "Fig. 14a: DHI, Fixed BC, y-velocity at MP1", res, "MP1", "vy", "vy", "m/s")
elseif figure == "14b" then
  local res = {}
  for _, load in ipairs{ "dhi", "shi" } do
    -- sigma_yy frames every 1 ms of the DHI run (the paper's Fig. 14b), unless --set frames says otherwise
    local frames = (load == "dhi" and P.frames == 0) and 1e-3 or P.frames
    local r = run_case(cfg_with{ size = 100, load = load, boundary = "fixed", frames = frames })
    r.label = string.format("%s (PPV %.3f)", load:upper(), r.MP1)
    res[#res + 1] = r
  end
  plot_cmp("fig14b_vy_MP1.png", "Fig. 14b: 100 m, Fixed BC, y-velocity at MP1 (field PPV 0.95)", res, "MP1", "vy",
           "vy", "m/s")
elseif figure == "15" then
  local res = {}
  for _, b in ipairs{ "fixed", "vbc", "sbc" } do
    local r = run_case(cfg_with{ size = 100, load = "dhi", boundary = b, t_end = dda.param("t_end", 0.05) })
    r.label = b:upper()
    res[#res + 1] = r
  end
  plot_cmp("fig15_vy_MP1.png", "Fig. 15: y-velocity at MP1", res, "MP1", "vy", "vy", "m/s")
  plot_cmp("fig15_syy_MP1.png", "Fig. 15: sigma_yy at MP1", res, "MP1", "syy", "syy", "MPa", 1e-6)
  plot_cmp("fig16_vy_MP2.png", "Fig. 16: y-velocity at MP2", res, "MP2", "vy", "vy", "m/s")
  plot_cmp("fig16_syy_MP2.png", "Fig. 16: sigma_yy at MP2", res, "MP2", "syy", "syy", "MPa", 1e-6)
  plot_cmp("fig17_uy_MP3.png", "Fig. 17: y-displacement at MP3", res, nil, "uy_MP3", "uy", "mm", 1e3)
  if dda.has_render then
    local sbc = res[3]
    local xs, ys, xe, ye = {}, {}, {}, {}
    for _, p in ipairs(sbc.ppv_line) do xs[#xs + 1] = p.sd; ys[#ys + 1] = p.ppv; xe[#xe + 1] = p.sd; ye[#ye + 1] = p.eq23 end
    dda.plot{ file = "fig18_ppv_scaled_distance.png", title = "Fig. 18: PPV vs R/Q^(1/3), SBC p = E",
              series = { { name = "DDA (SBC)", x = xs, y = ys, color = {30, 80, 200} }, { name = "Eq. 23: 1.8 SD^-2.5", x = xe, y = ye, color = {215, 50, 30} } },
              x_label = "R/Q^(1/3)", x_unit = "m/kg^(1/3)", y_label = "PPV", y_unit = "m/s" }
  end
elseif figure == "mesh" then
  -- Mesh convergence of the PPV at MP1 (2 m joints unless --set spacing):
  -- one run per element size of --set meshes (coarse to fine, m), each
  -- meshed within --set mesh_radius; the table below and
  -- blast_mesh_convergence.csv; --set max_change=X: an error unless the PPV
  -- of the last two sizes differs by less than X (a fraction).
  local list = tostring(dda.param("meshes", "1,0.5,0.25"))
  local max_change = dda.param("max_change", 0)
  local meshes = {}
  for v in list:gmatch("[^,]+") do
    local x = tonumber(v)
    if not x or x <= 0 then error("--set meshes=" .. list .. ": element sizes in m, > 0, comma separated") end
    meshes[#meshes + 1] = x
  end
  if #meshes < 2 then error("--set meshes=" .. list .. ": give at least two element sizes") end
  local rows, prev = {}, nil
  local path = dda.output("blast_mesh_convergence.csv")
  local f = assert(io.open(path, "w"))
  f:write("mesh_m,mesh_radius_m,t_end_s,blocks,elements,steps,cpu_s,wall_s,cg_per_step,ppv_mp1,t_peak_mp1,change\n")
  for _, h in ipairs(meshes) do
    local r = run_case(cfg_with{ mesh = h })
    if not (r.MP1 > 0.01) then   -- m/s: below it, no wave has reached MP1
      error(string.format("--set figure=mesh: no wave at MP1 (PPV under 0.01 m/s) with %g m elements (the wave reaches MP1 after " ..
                          "about 1.1 ms: give a longer --set t_end)", h))
    end
    local change = prev and (r.MP1 / prev - 1) or nil
    rows[#rows + 1] = { h = h, r = r, change = change }
    f:write(string.format("%g,%g,%g,%d,%d,%d,%.1f,%.1f,%.1f,%.5g,%.5g,%s\n", h, P.mesh_radius, P.t_end, r.blocks,
                          r.elements, r.steps, r.cpu, r.wall, r.cg / r.steps, r.MP1, r.t_peak_MP1,
                          change and string.format("%.5f", change) or ""))
    f:flush()
    prev = r.MP1
  end
  docs_output.close(f, path)
  print(string.format("| element size (m) | elements | steps | CPU (s) | PPV at MP1 (m/s) | change |"))
  print("|---|---:|---:|---:|---:|---:|")
  for _, row in ipairs(rows) do
    print(string.format("| %g | %d | %d | %.0f | %.4f | %s |", row.h, row.r.elements, row.r.steps, row.r.cpu,
                        row.r.MP1, row.change and string.format("%+.1f %%", 100 * row.change) or "–"))
  end
  local last = rows[#rows].change
  if max_change > 0 then
    if math.abs(last) >= max_change then
      error(string.format("PPV at MP1 changed by %+.2f %% from %g m to %g m elements (allowed under %.1f %%)",
                          100 * last, meshes[#meshes - 1], meshes[#meshes], 100 * max_change))
    end
    print(string.format("PPV at MP1 %+.2f %% from %g m to %g m elements, the two finest given (under %.1f %%)",
                        100 * last, meshes[#meshes - 1], meshes[#meshes], 100 * max_change))
  end
else
  error("figure must be 14a, 14b, 15 or mesh, got " .. tostring(figure))
end
