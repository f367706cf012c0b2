-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_meshed_summary.lua: Figs. 15-18 of the paper's Section 4 with meshed
-- 2 m blocks, from the CSV files of blast.lua's 0.05 s runs. No simulation.
--
-- Models:  none; reads the runs of
--            build/dda run scripts/paper/blast.lua --set boundary=fixed|vbc|sbc
--              --set mesh=H [--set mesh_radius=R] --set t_end=0.05 --out <folder>
--          (one folder per run or several runs in one: each folder's
--          blast_runs.csv names its runs; a run is found by its tag,
--          dhi_<boundary>_100_m<H>[_r<R>]).
--          The report's definitions (docs/validation.md, Section 4): reflected
--          energy = integral of vx^2 + vy^2 over t >= 15 ms at MP1 and MP2
--          (the first boundary reflections reach them at about 16 ms); MP3's
--          uy at the end of the run; Fig. 18 = PPV (max |vy|) of the line
--          monitors above the chamber (R = y) in the SBC run against Eq. 23,
--          PPV = 1.8 (R/Q^(1/3))^-2.5, Q = 606 kg, and how many lie within a
--          factor of 2 of it.
-- Run:     build/dda run scripts/paper/blast_meshed_summary.lua --set dirs=D1,D2,...
--            [--set plot=m0.25_r12] [--out out/blast-meshed]
--          --set check=true: an error unless the SBC run at 0.5 m within 12 m
--          (tag dhi_sbc_100_m0.5_r12) gives the numbers of the reference runs
--          (below, REFERENCE) within their tolerances.
-- Writes:  <out>/blast_meshed_summary.csv  mesh,boundary,ppv_mp1,ppv_mp2,
--            refl_mp1,refl_mp2,uy_mp3,fig18_within2,fig18_points,fig18_min,fig18_max
--          the tables on stdout (Markdown);
--          <out>/blast_meshed_<plot>_fig15_vy_MP1.png (<plot> with p for the point: m0p25_r12), _fig16_vy_MP2.png,
--            _fig17_uy_MP3.png (the three boundaries of the mesh `plot`), and
--          <out>/blast_meshed_fig18_ppv_scaled_distance.png (every SBC run, log10
--            axes, Eq. 23 and its factor-2 band).

local dda = require "dda"
local docs_output = require "docs_output"
local Q = require("blast_model").charge_kg

local T_REFLECT = 15e-3   -- s: start of the reflected-energy window (as docs/validation.md)
local dirs_param = tostring(dda.param("dirs", ""))
local plot_mesh = tostring(dda.param("plot", ""))
local check = dda.param("check", false)
if dirs_param == "" then error("--set dirs=D1,D2,...: the folders of blast.lua's meshed 0.05 s runs", 0) end

-- The 0.5 m SBC run as measured (the runs of docs/validation.md, "Figs. 15-18
-- with meshed 2 m blocks"; bit-identical for any thread count). Tolerances:
-- the meshed solver may change within its CG tolerance (another solver order
-- moves a PPV by ~1e-4), so 1 % on PPVs and MP3's displacement, 5 % on the
-- reflected energies (sums of small late signals), and the Fig. 18 count
-- within one point.
local REFERENCE = { tag = "dhi_sbc_100_m0.5_r12", ppv_mp1 = 1.2984, ppv_mp2 = 1.8178, uy_mp3 = 0.0017107,
                    refl_mp1 = 3.77615e-05, refl_mp2 = 1.0991e-04, within2 = 9 }
local TOL = { ppv = 0.01, uy = 0.01, refl = 0.05, count = 1 }

local blast_csv = require "blast_csv"
local read_csv, column = blast_csv.read, blast_csv.column
local function reflected_energy(rows) return blast_csv.reflected_energy(rows, T_REFLECT) end

-- runs[mesh][boundary] = { dir, row (blast_runs.csv), hist = { MP1 =, MP2 =, MP3 = }, line = ppv rows }
local runs, meshes = {}, {}
for dir in dirs_param:gmatch("[^,]+") do
  dir = dir:gsub("/+$", "")
  local rows = read_csv(dir .. "/blast_runs.csv")
  if not rows then error("no blast_runs.csv in " .. dir .. " (run blast.lua --out " .. dir .. " first)", 0) end
  for _, r in ipairs(rows) do
    local b, mesh = tostring(r.tag):match("^dhi_(%a+)_100_(m[%d%.]+.*)$")
    if b and r.t_end >= 0.05 then
      if not runs[mesh] then runs[mesh] = {}; meshes[#meshes + 1] = mesh end
      local run = { dir = dir, row = r, hist = {} }
      for _, mp in ipairs{ "MP1", "MP2", "MP3" } do
        run.hist[mp] = read_csv(string.format("%s/blast_%s_%s.csv", dir, r.tag, mp))
        if not run.hist[mp] or run.hist[mp][#run.hist[mp]].time < 0.999 * r.t_end then
          error(string.format("%s/blast_%s_%s.csv: missing or shorter than the run", dir, r.tag, mp), 0)
        end
      end
      run.line = read_csv(string.format("%s/blast_%s_ppv.csv", dir, r.tag))
      runs[mesh][b] = run
    end
  end
end
if #meshes == 0 then error("no 0.05 s meshed DHI runs of the 100 m model in " .. dirs_param, 0) end
table.sort(meshes, function(a, b) return tonumber(a:match("^m([%d%.]+)")) > tonumber(b:match("^m([%d%.]+)")) end)

local function measure(run)
  local m = { ppv_mp1 = run.row.ppv_mp1, ppv_mp2 = run.row.ppv_mp2, uy_mp3 = run.row.uy_mp3_final,
              refl_mp1 = reflected_energy(run.hist.MP1), refl_mp2 = reflected_energy(run.hist.MP2) }
  if run.line and #run.line > 0 then
    m.points, m.within2, m.min, m.max = #run.line, 0, math.huge, 0
    for _, p in ipairs(run.line) do
      m.min, m.max = math.min(m.min, p.ratio), math.max(m.max, p.ratio)
      if p.ratio >= 0.5 and p.ratio <= 2 then m.within2 = m.within2 + 1 end
    end
    m.first, m.last, m.R_last = run.line[1].ratio, run.line[#run.line].ratio, run.line[#run.line].R_m
  end
  return m
end

local csv_path = dda.output("blast_meshed_summary.csv")
local f = assert(io.open(csv_path, "w"))
f:write("mesh,boundary,ppv_mp1,ppv_mp2,refl_mp1,refl_mp2,uy_mp3,fig18_within2,fig18_points,fig18_min,fig18_max\n")
local B = { "fixed", "vbc", "sbc" }
print("| mesh | boundary | PPV MP1 (m/s) | PPV MP2 (m/s) | MP1 ∫v² dt after 15 ms (m²/s) | MP2 ∫v² dt after 15 ms (m²/s) | MP3 uy at 0.05 s (m) |")
print("|---|---|---:|---:|---:|---:|---:|")
local measured = {}
for _, mesh in ipairs(meshes) do
  measured[mesh] = {}
  for _, b in ipairs(B) do
    local run = runs[mesh][b]
    if run then
      local m = measure(run)
      measured[mesh][b] = m
      print(string.format("| %s | %s | %.4f | %.4f | %.4g | %.4g | %.4g |", mesh, b:upper(), m.ppv_mp1, m.ppv_mp2,
                          m.refl_mp1, m.refl_mp2, m.uy_mp3))
      f:write(string.format("%s,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%s,%s,%s\n", mesh, b, m.ppv_mp1, m.ppv_mp2, m.refl_mp1,
                            m.refl_mp2, m.uy_mp3, tostring(m.within2 or ""), tostring(m.points or ""),
                            m.min and string.format("%.4g", m.min) or "", m.max and string.format("%.4g", m.max) or ""))
    end
  end
end
docs_output.close(f, csv_path)
print()
print("| mesh (SBC run) | points | within a factor 2 of Eq. 23 | PPV/Eq. 23 smallest | largest | nearest (R = 4 m) | farthest |")
print("|---|---:|---:|---:|---:|---:|---:|")
for _, mesh in ipairs(meshes) do
  local m = measured[mesh].sbc
  if m and m.points then
    print(string.format("| %s | %d | %d | %.3g | %.3g | %.3g | %.3g (R = %g m) |", mesh, m.points, m.within2, m.min,
                        m.max, m.first, m.last, m.R_last))
  end
end

-- figures
local colors = { {30, 80, 200}, {215, 50, 30}, {30, 150, 50}, {120, 120, 120}, {150, 60, 170} }
if dda.has_render then
  if plot_mesh == "" then
    for _, mesh in ipairs(meshes) do
      if runs[mesh].fixed and runs[mesh].vbc and runs[mesh].sbc then plot_mesh = mesh end
    end
  end
  local set = runs[plot_mesh]
  if set then
    local function curves(file, title, mp, field, ylab, yunit, yscale)
      local s = {}
      for i, b in ipairs(B) do
        local h = set[b] and set[b].hist[mp]
        if h then s[#s + 1] = { name = b:upper(), x = column(h, "time"), y = column(h, field), color = colors[i] } end
      end
      print("wrote " .. dda.plot{ file = "blast_meshed_" .. plot_mesh:gsub("%.", "p") .. "_" .. file, title = title, series = s,
                                  x_label = "t", x_unit = "ms", x_scale = 1e3, y_label = ylab, y_unit = yunit,
                                  y_scale = yscale or 1 })
    end
    local lbl = " (2 m joints, meshed " .. plot_mesh .. ")"
    curves("fig15_vy_MP1.png", "Fig. 15" .. lbl .. ": vy at MP1", "MP1", "vy", "vy", "m/s")
    curves("fig16_vy_MP2.png", "Fig. 16" .. lbl .. ": vy at MP2", "MP2", "vy", "vy", "m/s")
    curves("fig17_uy_MP3.png", "Fig. 17" .. lbl .. ": uy at MP3 (paper, SBC: final 2.36 mm)", "MP3", "uy", "uy", "mm",
           1e3)
  end
  -- Fig. 18 on log10 axes (dda.plot draws linear axes; Eq. 23 is a power law)
  local s, n = {}, 0
  local x0
  for _, mesh in ipairs(meshes) do
    local run = runs[mesh].sbc
    if run and run.line and #run.line > 0 then
      n = n + 1
      local x, y = {}, {}
      for i, p in ipairs(run.line) do x[i] = math.log(p.scaled_distance, 10); y[i] = math.log(p.ppv_m_s, 10) end
      s[#s + 1] = { name = "DDA SBC, " .. mesh, x = x, y = y, color = colors[({ 1, 3, 5 })[(n - 1) % 3 + 1]] }
      if not x0 or #run.line > #x0.line then x0 = run end
    end
  end
  if x0 then
    local x, eq, up, down = {}, {}, {}, {}
    for i, p in ipairs(x0.line) do
      x[i] = math.log(p.scaled_distance, 10); eq[i] = math.log(p.eq23_m_s, 10)
      up[i], down[i] = eq[i] + math.log(2, 10), eq[i] - math.log(2, 10)
    end
    s[#s + 1] = { name = "Eq. 23: 1.8 (R/Q^(1/3))^-2.5", x = x, y = eq, color = colors[2] }
    s[#s + 1] = { name = "Eq. 23 x 2 and / 2", x = x, y = up, color = colors[4], width = 1 }
    s[#s + 1] = { name = "", x = x, y = down, color = colors[4], width = 1 }
    print("wrote " .. dda.plot{ file = "blast_meshed_fig18_ppv_scaled_distance.png",
                                title = "Fig. 18, meshed 2 m blocks: PPV vs R/Q^(1/3), SBC p = E, Q = " .. Q .. " kg",
                                series = s, x_label = "log10 R/Q^(1/3)", x_unit = "m/kg^(1/3)", y_label = "log10 PPV",
                                y_unit = "m/s" })
  end
end

if check then
  local mesh = REFERENCE.tag:match("^dhi_sbc_100_(.*)$")
  local m = measured[mesh] and measured[mesh].sbc
  if not m then error("check: no run " .. REFERENCE.tag .. " in " .. dirs_param, 0) end
  local bad = {}
  local function near(name, got, want, tol)
    local ok = math.abs(got - want) <= tol * math.abs(want)
    print(string.format("check: %s %.5g against %.5g (within %.0f %%): %s", name, got, want, 100 * tol, ok and "ok" or "NO"))
    if not ok then bad[#bad + 1] = name end
  end
  near("PPV MP1", m.ppv_mp1, REFERENCE.ppv_mp1, TOL.ppv)
  near("PPV MP2", m.ppv_mp2, REFERENCE.ppv_mp2, TOL.ppv)
  near("MP3 uy at 0.05 s", m.uy_mp3, REFERENCE.uy_mp3, TOL.uy)
  near("MP1 reflected energy", m.refl_mp1, REFERENCE.refl_mp1, TOL.refl)
  near("MP2 reflected energy", m.refl_mp2, REFERENCE.refl_mp2, TOL.refl)
  local ok = math.abs(m.within2 - REFERENCE.within2) <= TOL.count
  print(string.format("check: Fig. 18 points within a factor 2 of Eq. 23: %d against %d (within %d): %s", m.within2,
                      REFERENCE.within2, TOL.count, ok and "ok" or "NO"))
  if not ok then bad[#bad + 1] = "Fig. 18 count" end
  if #bad > 0 then error("check failed: " .. table.concat(bad, ", "), 0) end
  print("check passed")
end
