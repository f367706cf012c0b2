-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_summary.lua: the Section 4 (blast) numbers against the paper, from the
-- CSV files blast.lua wrote, and the Section 4 part of the validation report.
-- No simulation.
--
-- Models:  none; reads the runs of blast.lua. One folder per joint spacing
--          (discretisation), with subfolders fig14a, fig14b, fig15 as written by
--          blast.lua --set figure=14a|14b|15 --out <folder>/fig14a ... A run counts
--          once its row is in blast_runs.csv (written when the run ends; the
--          last row of a tag wins); a missing run is reported as "not run".
--          Quantities: PPV = max |vy| (blast_runs.csv). Reflected energy at MP1
--          and MP2 (Figs. 15-16): integral of vx^2 + vy^2 over t >= 15 ms of the
--          0.05 s runs, after the direct pulse and its coda (the first boundary
--          reflections reach MP1 and MP2 at ~16 ms at C_P = 5570 m/s). Fig. 17:
--          uy at MP3 at the end of the 0.05 s runs. Fig. 18: PPV of the line
--          monitors above the chamber in the SBC run against Eq. 23.
-- Run:     build/dda run scripts/paper/blast_summary.lua --set dirs=out/blast-h2,out/blast-h1
--                   [--set labels="2 m joints (paper),1 m joints"] [--set spacings=2,1]
--                   [--set docs=docs] [--set notes=docs/validation_section4_notes.md]
--                   [--out out/blast-summary]
--          after, for each folder (--set spacing=1 for out/blast-h1):
--            build/dda run scripts/paper/blast.lua --set figure=14a --out out/blast-h2/fig14a
--            build/dda run scripts/paper/blast.lua --set figure=14b --out out/blast-h2/fig14b
--            build/dda run scripts/paper/blast.lua --set figure=15  --out out/blast-h2/fig15
--          dirs: relative to the working directory. Joint spacing of a folder:
--          --set spacings, else the -h<N> ending of its name, else the run tags in
--          it (no _h suffix = the paper's 2 m). docs and notes: relative to the
--          repository root (two folders above this script) or absolute.
-- Writes:  <out>/blast_summary.csv  figure,quantity,paper,ours,unit,difference_percent,run_wall_s
--          <out>/blast_h<N>_fig*.png  the figures redrawn from the CSV files
--          <out>/validation_section4.md  the report's Section 4 block
--          and only with --set write_docs=true (docs/ is the committed report):
--          <docs>/validation.md   in the block between the "section 4" marker lines,
--                                 the sub-block of each joint spacing given here
--                                 replaced; the other spacings' sub-blocks kept
--          <docs>/validation.csv  rows merged by (figure, quantity): the rows of
--                                 the spacings given replaced, every other row kept
--          <docs>/figures/blast_h<N>_*.png  (copies of the redrawn figures)
--          So a summary of the 2 m runs alone leaves the 1 m and 0.5 m rows as they were.

local dda = require "dda"

local here = debug.getinfo(1, "S").source:gsub("^@", ""):match("^(.*)/[^/]*$") or "."
local root = here .. "/../.."
local function from_root(p) return p:sub(1, 1) == "/" and p or root .. "/" .. p end

local docs_output = require "docs_output"

local dirs_param = tostring(dda.param("dirs", ""))
if dirs_param == "" then dirs_param = tostring(dda.param("dir", "out/blast")) end   -- the old one-folder form
local labels_param = tostring(dda.param("labels", ""))
local spacings_param = tostring(dda.param("spacings", ""))
local write_docs = dda.param("write_docs", false)
local docs_param = tostring(dda.param("docs", "docs"))
local docs = write_docs and from_root(docs_param) or nil
local notes_param = tostring(dda.param("notes", ""))
local notes_path = notes_param ~= "" and from_root(notes_param) or from_root(docs_param) .. "/validation_section4_notes.md"

local BEGIN = "<!-- section 4: begin (written by scripts/paper/blast_summary.lua) -->"
local END = "<!-- section 4: end -->"
local SUBS = { "fig14a", "fig14b", "fig15" }
local T_REFLECT = 15e-3      -- s: start of the reflected-energy window
local CLEARLY = 0.10         -- "clearly below": the 80 m PPV at least 10 % under both (paper: 25 %)
local Q = require("blast_model").charge_kg   -- kg TNT (Eq. 23 uses R/Q^(1/3))

local function split(s)
  local t = {}
  for item in s:gmatch("[^,]+") do t[#t + 1] = item:match("^%s*(.-)%s*$") end
  return t
end

local blast_csv = require "blast_csv"
local read_csv, column = blast_csv.read, blast_csv.column

local function copy(src, dst)
  local i = io.open(src, "rb")
  if not i then return false end
  local data = i:read("a"); i:close()
  local o = assert(io.open(dst, "wb")); o:write(data); docs_output.close(o, dst)
  return true
end

-- ---------------------------------------------------------------- run folders

-- one discretisation: a folder of runs at one joint spacing
local function load_set(dir, spacing, label)
  local S = { dir = dir, runs = {}, extra = {} }
  local found = {}
  for _, sub in ipairs(SUBS) do
    for _, r in ipairs(read_csv(dir .. "/" .. sub .. "/blast_runs.csv") or {}) do
      r.sub = sub
      local key = sub .. ":" .. r.tag
      if not S.runs[key] then found[#found + 1] = key end
      S.runs[key] = r                                  -- a re-run's row replaces the older one
    end
  end
  -- spacing: given, else the folder's name (out/blast-h1), else its first run's tag
  spacing = spacing or tonumber(dir:match("%-h([%d%.]+)$"))
  if not spacing and found[1] then spacing = tonumber(found[1]:match("_h([%d%.]+)$")) or 2 end
  S.spacing = spacing or 2
  S.suffix = S.spacing ~= 2 and string.format("_h%g", S.spacing) or ""
  S.id = string.format("h%g", S.spacing):gsub("%.", "p")        -- file names: blast_h2_..., blast_h0p5_...
  S.prefix = string.format("h=%gm", S.spacing)                    -- CSV quantity prefix
  S.label = label or (S.spacing == 2 and "2 m joints (paper)" or string.format("%g m joints", S.spacing))
  S.found = found
  S.histories = {}
  return S
end

local sets, ids = {}, {}
do
  local labels, spacings = split(labels_param), split(spacings_param)
  for i, dir in ipairs(split(dirs_param)) do
    local S = load_set(dir:gsub("/+$", ""), tonumber(spacings[i]), labels[i])
    if ids[S.id] then
      error(string.format("folders %s and %s both hold %g m joints; give one folder per joint spacing",
                          ids[S.id], dir, S.spacing), 0)
    end
    ids[S.id] = dir
    sets[#sets + 1] = S
  end
end

local function tag_of(S, load, boundary, size) return string.format("%s_%s_%g%s", load, boundary, size, S.suffix) end
local function run_of(S, sub, load, boundary, size) return S.runs[sub .. ":" .. tag_of(S, load, boundary, size)] end

-- a finished run's monitor history; nil and why otherwise (a history shorter
-- than its run's t_end belongs to a re-run still going)
local function history(S, run, mp)
  if not run then return nil, "not run" end
  local key = run.sub .. ":" .. run.tag .. ":" .. mp
  if S.histories[key] == nil then
    local rows = read_csv(string.format("%s/%s/blast_%s_%s.csv", S.dir, run.sub, run.tag, mp))
    if not rows or #rows == 0 then S.histories[key] = "no history file"
    elseif rows[#rows].time < 0.999 * run.t_end then
      S.histories[key] = string.format("history ends at %.4g s of %.4g s", rows[#rows].time, run.t_end)
    else S.histories[key] = rows end
  end
  local h = S.histories[key]
  if type(h) == "string" then return nil, h end
  return h
end

-- integral of vx^2 + vy^2 over t >= T_REFLECT
local function reflected_energy(rows) return blast_csv.reflected_energy(rows, T_REFLECT) end

-- ------------------------------------------------------------------ the numbers

-- rows: { fig, q, paper = number | nil, paper_text = qualitative | nil, ours = number | nil,
--         why = reason ours is missing, unit, wall = the run's wall time }
local function measure(S)
  local rows, targets = {}, {}
  local function row(fig, q, paper, ours, unit, run, why, paper_text)
    rows[#rows + 1] = { fig = fig, q = q, paper = paper, paper_text = paper_text, ours = ours, unit = unit,
                        wall = run and run.wall_s, why = ours == nil and (why or "not run") or nil }
    return rows[#rows]
  end
  local function ppv(sub, load, boundary, size)
    local r = run_of(S, sub, load, boundary, size)
    return r and r.ppv_mp1, r
  end

  -- Fig. 14a: model size
  local p14a, r14a = {}, {}
  for _, s in ipairs{ {120, 0.967}, {100, 0.951}, {80, 0.713} } do
    local v, r = ppv("fig14a", "dhi", "fixed", s[1])
    p14a[s[1]] = v
    r14a[#r14a + 1] = row("fig14a", string.format("DHI Fixed PPV MP1 %d m", s[1]), s[2], v, "m/s", r)
  end
  -- Fig. 14b: DHI vs SHI vs the field
  local dhi, rd = ppv("fig14b", "dhi", "fixed", 100)
  local shi, rs = ppv("fig14b", "shi", "fixed", 100)
  local r14b = { row("fig14b", "DHI Fixed PPV MP1 100 m vs field", 0.95, dhi, "m/s", rd) }
  row("fig14b", "DHI Fixed PPV MP1 100 m", 0.951, dhi, "m/s", rd)
  r14b[2] = row("fig14b", "SHI Fixed PPV MP1 100 m", 0.814, shi, "m/s", rs)

  -- Figs. 15-16: reflected energy after the first arrival; the paper describes it only in words
  local said = { MP1 = { fixed = "strong reflections", vbc = "clean", sbc = "almost no reflections" },
                 MP2 = { fixed = "strong reflections", vbc = "still reflects", sbc = "almost no reflections" } }
  local energy, r16 = { MP1 = {}, MP2 = {} }, {}
  for _, mp in ipairs{ "MP1", "MP2" } do
    for _, b in ipairs{ "fixed", "vbc", "sbc" } do
      local run = run_of(S, "fig15", "dhi", b, 100)
      local h, why = history(S, run, mp)
      energy[mp][b] = h and reflected_energy(h)
      r16[#r16 + 1] = row(mp == "MP1" and "fig15" or "fig16", string.format("%s int v^2 dt after 15 ms %s", mp, b:upper()), nil,
          energy[mp][b], "m^2/s", run, why, said[mp][b] .. " (in words)")
    end
  end

  -- Fig. 17: final y-displacement at MP3
  local uy = {}
  for _, b in ipairs{ "fixed", "vbc", "sbc" } do
    local run = run_of(S, "fig15", "dhi", b, 100)
    uy[b] = run and run.uy_mp3_final
    row("fig17", "final uy MP3 " .. b:upper(), b == "sbc" and 2.36e-3 or nil, uy[b], "m", run, nil,
        b == "vbc" and "less than SBC (in words)" or nil)
  end
  row("fig17", "final uy MP3 SBC/VBC", nil, uy.sbc and uy.vbc and uy.vbc ~= 0 and uy.sbc / uy.vbc or nil, "-",
      nil, nil, "> 1 (in words)")

  -- Fig. 18: PPV along the line above the chamber, SBC run, against Eq. 23
  local sbc = run_of(S, "fig15", "dhi", "sbc", 100)
  local line = sbc and read_csv(string.format("%s/fig15/blast_%s_ppv.csv", S.dir, sbc.tag))
  local inside, lo, hi
  if line and #line > 0 then
    inside, lo, hi = 0, math.huge, 0
    for _, p in ipairs(line) do
      lo, hi = math.min(lo, p.ratio), math.max(hi, p.ratio)
      if p.ratio >= 0.5 and p.ratio <= 2 then inside = inside + 1 end
    end
  end
  local why18 = sbc and not line and "no ppv file" or nil
  row("fig18", "PPV points on the line", nil, line and #line, "count", sbc, why18)
  local r18 = row("fig18", "PPV points within a factor 2 of Eq. 23", nil, inside, "count", sbc, why18,
      "scatter around Eq. 23 (in words)")
  row("fig18", "PPV/Eq. 23 smallest ratio", nil, lo, "-", sbc, why18)
  row("fig18", "PPV/Eq. 23 largest ratio", nil, hi, "-", sbc, why18)
  row("fig18", "PPV/Eq. 23 at the point nearest the chamber", nil, line and line[1].ratio, "-", sbc, why18,
      "below 1 (in words)")
  row("fig18", "PPV/Eq. 23 at the farthest point", nil, line and line[#line].ratio, "-", sbc, why18,
      "above 1 (in words)")

  -- the Section 4 targets; when a number they need is missing, the result says
  -- which and why (needs: the rows the target reads)
  local function target(text, met, result, needs)
    local miss = {}
    for _, r in ipairs(needs) do if r.ours == nil then miss[#miss + 1] = r.q .. ": " .. r.why end end
    if #miss > 0 then result, met = "*missing: " .. table.concat(miss, "; ") .. "*", nil end
    targets[#targets + 1] = { text = text, met = met, result = result }
  end
  do
    local v, from = dhi, ""
    if not v then v, from = p14a[100], " (the Fig. 14a run: same model and load)" end
    target("DHI PPV at MP1, 100 m model, within 15 % of the field's 0.95 m/s",
           v and math.abs(v - 0.95) <= 0.15 * 0.95,
           v and string.format("%.3f m/s (%+.1f %%)%s", v, 100 * (v - 0.95) / 0.95, from), v and {} or { r14b[1] })
  end
  target("SHI PPV at MP1 lower than DHI (100 m, Fixed)", dhi and shi and shi < dhi,
         dhi and shi and string.format("SHI %.3f, DHI %.3f m/s", shi, dhi), r14b)
  do
    local a, b, c = p14a[80], p14a[100], p14a[120]
    local ok = a and b and c and a <= (1 - CLEARLY) * b and a <= (1 - CLEARLY) * c
    target(string.format("80 m model's PPV clearly below the 100 m and 120 m ones (at least %d %% below both; " ..
                         "paper: 25 %%)", 100 * CLEARLY), a and b and c and ok,
           a and b and c and string.format("80 m %.3f, 100 m %.3f (%+.1f %%), 120 m %.3f (%+.1f %%) m/s", a, b,
                                           100 * (a - b) / b, c, 100 * (a - c) / c), r14a)
  end
  do
    local e = energy.MP2
    target("SBC (p = E) leaves less reflected energy at MP2 after 15 ms than Fixed and VBC",
           e.sbc and e.fixed and e.vbc and e.sbc < e.fixed and e.sbc < e.vbc,
           e.sbc and e.fixed and e.vbc and
           string.format("int v^2 dt: SBC %.3g, Fixed %.3g, VBC %.3g m^2/s (SBC/Fixed %.2f, SBC/VBC %.2f)",
                         e.sbc, e.fixed, e.vbc, e.sbc / e.fixed, e.sbc / e.vbc), { r16[4], r16[5], r16[6] })
  end
  target("Fig. 18: the PPV points within a factor of 2 of Eq. 23", inside and inside == #line,
         inside and string.format("%d of %d (PPV/Eq. 23 from %.2f to %.2f)", inside, #line, lo, hi), { r18 })
  return rows, targets
end

-- ------------------------------------------------------------------------ plots

local colors = { {30, 80, 200}, {215, 50, 30}, {30, 150, 50}, {120, 120, 120} }

-- the report's figures, redrawn from the CSV files of finished runs (so a
-- figure whose runs are partly missing still shows the others); without the
-- renderer, the PNGs blast.lua drew are copied instead
local function plots(S)
  local made = {}
  local function add(path, caption) if path then made[#made + 1] = { path = path, caption = caption } end end
  local function curves(file, title, entries, mp, field, ylab, yunit, yscale)
    local s = {}
    for i, e in ipairs(entries) do
      local h = history(S, e.run, mp)
      if h then s[#s + 1] = { name = e.name, x = column(h, "time"), y = column(h, field), color = colors[i] } end
    end
    if #s == 0 then return nil end
    return dda.plot{ file = "blast_" .. S.id .. "_" .. file, title = title, series = s, x_label = "t",
                     x_unit = "ms", x_scale = 1e3, y_label = ylab, y_unit = yunit, y_scale = yscale or 1 }
  end
  local lbl = ", " .. S.label
  if not dda.has_render then
    for _, p in ipairs{ {"fig14a", "fig14a_vy_MP1.png"}, {"fig14b", "fig14b_vy_MP1.png"}, {"fig15", "fig15_vy_MP1.png"},
                        {"fig15", "fig15_syy_MP1.png"}, {"fig15", "fig16_vy_MP2.png"}, {"fig15", "fig16_syy_MP2.png"},
                        {"fig15", "fig17_uy_MP3.png"}, {"fig15", "fig18_ppv_scaled_distance.png"} } do
      local src = S.dir .. "/" .. p[1] .. "/" .. p[2]
      local f = io.open(src, "rb")
      if f then f:close(); add(src, p[2] .. lbl) end
    end
    return made
  end
  local e = {}
  for _, size in ipairs{ 120, 100, 80 } do
    local r = run_of(S, "fig14a", "dhi", "fixed", size)
    e[#e + 1] = { run = r, name = string.format("%d m (PPV %.3f)", size, r and r.ppv_mp1 or 0) }
  end
  add(curves("fig14a_vy_MP1.png", "Fig. 14a" .. lbl .. ": DHI, Fixed, vy at MP1 (paper PPV 0.967 / 0.951 / 0.713)",
             e, "MP1", "vy", "vy", "m/s"), "Fig. 14a: y-velocity at MP1, model sizes")
  e = {}
  for _, load in ipairs{ "dhi", "shi" } do
    local r = run_of(S, "fig14b", load, "fixed", 100)
    e[#e + 1] = { run = r, name = string.format("%s (PPV %.3f)", load:upper(), r and r.ppv_mp1 or 0) }
  end
  add(curves("fig14b_vy_MP1.png", "Fig. 14b" .. lbl .. ": 100 m, Fixed, vy at MP1 (paper DHI 0.951, SHI 0.814, " ..
             "field 0.95)", e, "MP1", "vy", "vy", "m/s"), "Fig. 14b: y-velocity at MP1, DHI and SHI")
  e = {}
  for _, b in ipairs{ "fixed", "vbc", "sbc" } do e[#e + 1] = { run = run_of(S, "fig15", "dhi", b, 100), name = b:upper() } end
  add(curves("fig15_vy_MP1.png", "Fig. 15" .. lbl .. ": vy at MP1", e, "MP1", "vy", "vy", "m/s"),
      "Fig. 15: y-velocity at MP1, boundaries")
  add(curves("fig15_syy_MP1.png", "Fig. 15" .. lbl .. ": sigma_yy at MP1", e, "MP1", "syy", "syy", "MPa", 1e-6),
      "Fig. 15: sigma_yy at MP1")
  add(curves("fig16_vy_MP2.png", "Fig. 16" .. lbl .. ": vy at MP2", e, "MP2", "vy", "vy", "m/s"),
      "Fig. 16: y-velocity at MP2, boundaries")
  add(curves("fig16_syy_MP2.png", "Fig. 16" .. lbl .. ": sigma_yy at MP2", e, "MP2", "syy", "syy", "MPa", 1e-6),
      "Fig. 16: sigma_yy at MP2")
  add(curves("fig17_uy_MP3.png", "Fig. 17" .. lbl .. ": uy at MP3 (paper: final 2.36 mm)", e, "MP3", "uy", "uy",
             "mm", 1e3), "Fig. 17: y-displacement at MP3")
  -- Fig. 18 on log10 axes (dda.plot draws linear axes only; Eq. 23 is a power law)
  local sbc = run_of(S, "fig15", "dhi", "sbc", 100)
  local line = sbc and read_csv(string.format("%s/fig15/blast_%s_ppv.csv", S.dir, sbc.tag))
  if line and #line > 0 then
    local x, y, eq, up, down = {}, {}, {}, {}, {}
    for i, p in ipairs(line) do
      x[i] = math.log(p.scaled_distance, 10); y[i] = math.log(p.ppv_m_s, 10)
      eq[i] = math.log(p.eq23_m_s, 10); up[i] = eq[i] + math.log(2, 10); down[i] = eq[i] - math.log(2, 10)
    end
    add(dda.plot{ file = "blast_" .. S.id .. "_fig18_ppv_scaled_distance.png",
                  title = "Fig. 18" .. lbl .. ": PPV vs R/Q^(1/3), SBC p = E, Q = " .. Q .. " kg",
                  series = { { name = "DDA (SBC), line above the chamber", x = x, y = y, color = colors[1] },
                             { name = "Eq. 23: 1.8 (R/Q^(1/3))^-2.5", x = x, y = eq, color = colors[2] },
                             { name = "Eq. 23 x 2 and / 2", x = x, y = up, color = colors[4], width = 1 },
                             { name = "", x = x, y = down, color = colors[4], width = 1 } },
                  x_label = "log10 R/Q^(1/3)", x_unit = "m/kg^(1/3)", y_label = "log10 PPV", y_unit = "m/s" },
        "Fig. 18: PPV against scaled distance (log10 axes), with Eq. 23 and the factor-2 band")
  end
  return made
end

-- ----------------------------------------------------------------- formatting

local function num(v) return string.format("%.4g", v) end
local function paper_cell(r)
  if r.paper then return num(r.paper) end
  return r.paper_text or "–"
end
local function diff_cell(r)
  if not (r.paper and r.ours) then return "–" end
  local d = r.ours - r.paper
  return string.format("%+.3g (%+.1f %%)", d, 100 * d / math.abs(r.paper))
end
local function q_cell(r) return r.q .. (r.unit ~= "" and r.unit ~= "-" and " (" .. r.unit .. ")" or "") end

local function machine()
  local cpu, cores = nil, nil
  local f = io.open("/proc/cpuinfo", "r")
  if f then
    for l in f:lines() do
      cpu = cpu or l:match("^model name%s*:%s*(.-)%s*$")
      if l:match("^processor%s*:") then cores = (cores or 0) + 1 end
    end
    f:close()
  end
  if not cpu then return "this machine" end
  return string.format("%s, %d cores", cpu, cores or 0)
end

-- ------------------------------------------------------------------- the report

local out_csv = dda.output("blast_summary.csv")
local outdir = out_csv:match("^(.*)/[^/]*$") or "."
local summary_lines = { "figure,quantity,paper,ours,unit,difference_percent,run_wall_s" }

-- The Section 4 block: a header, one sub-block per joint spacing (each opened
-- by a "<!-- set hN -->" line), the notes. `w` writes into the current part.
local md, csv_rows = {}, {}
local set_blocks, notes_md = {}, {}
local current = md
local function w(s) current[#current + 1] = s end

local cmd = "build/dda run scripts/paper/blast_summary.lua --set dirs=" .. dirs_param
if labels_param ~= "" then cmd = cmd .. string.format(' --set labels="%s"', labels_param) end
if spacings_param ~= "" then cmd = cmd .. " --set spacings=" .. spacings_param end
if write_docs then cmd = cmd .. " --set write_docs=true" end
if docs_param ~= "docs" then cmd = cmd .. " --set docs=" .. docs_param end
if notes_param ~= "" then cmd = cmd .. " --set notes=" .. notes_param end
cmd = cmd .. " --out " .. outdir

w(BEGIN)
w("## Section 4: underground blast (Figs. 14-18)")
w("")
w("Generated by `" .. cmd .. "` on " .. os.date("!%Y-%m-%d %H:%M UTC") .. " from the CSV files of the runs " ..
  "listed below (no simulation in that command; every number is read or computed from those files). " ..
  "Paper values: `../shared/paper/reference-numbers.md`, Section 4. The same rows are in " ..
  "[validation.csv](validation.csv) (figures `fig14a` … `fig18`, quantities prefixed with the joint spacing, " ..
  "e.g. `h=2m`).")
w("")
w("**Model** (`scripts/paper/blast.lua`, `blast_model.lua`): square jointed rock mass, 100 m (also 120 m and 80 m " ..
  "for Fig. 14a), joint sets at 45° and 135° 2 m apart as in the paper or 1 m apart (slivers under 1 % of a " ..
  "block merged), 8 m × 4 m chamber centred on the detonation centre; rock 2650 kg/m³, " ..
  "E = 74 GPa, ν = 0.2, plane strain; joints φ = 25°, c = 2 MPa, σ_t = 0; g0 = 100 GN/m, g1 = 10⁻⁵ s, gg = 1, " ..
  "g2 = 0.005. DHI: triangular particle velocity on the chamber wall, 2.03 m/s at 0.5 ms, 0 at 2.5 ms; SHI: " ..
  "triangular pressure, 30.23 MPa. MP1 (0, 8), MP2 (−6, 5), MP3 (0, size/2 − 1), from the detonation centre.")
w("")
w("**Definitions.** PPV = max |vy| over the run (Figs. 14a-b: 12 ms runs). Reflected energy (Figs. 15-16) = " ..
  "∫(vx² + vy²) dt over t ≥ 15 ms of the 0.05 s runs: the direct pulse and its coda have passed and the first " ..
  "boundary reflections reach MP1 and MP2 at about 16 ms (C_P = 5570 m/s); the paper describes these figures " ..
  "only in words, quoted in the paper column. Fig. 17: uy at MP3 at 0.05 s. Fig. 18: PPV of the monitors on the " ..
  "line above the chamber (y = 4, 6, … m, R = y) in the SBC run, against Eq. 23, PPV = 1.8 (R/Q^(1/3))^−2.5 " ..
  "with Q = 606 kg. A run missing from its folder's `blast_runs.csv` (not run, or still running) is marked " ..
  "*not run*.")
w("")
w("**Reproduce**: each joint spacing's runs are listed in its part below (each `figure=` command runs its " ..
  "models one after the other); this table then comes from (`--set write_docs=true` writes it here, replacing " ..
  "only the parts of the spacings given):")
w("")
w("```")
w(cmd)
w("```")
w("")

local expected = {
  fig14a = { {"dhi", "fixed", 120}, {"dhi", "fixed", 100}, {"dhi", "fixed", 80} },
  fig14b = { {"dhi", "fixed", 100}, {"shi", "fixed", 100} },
  fig15 = { {"dhi", "fixed", 100}, {"dhi", "vbc", 100}, {"dhi", "sbc", 100} },
}
local figure_files = {}
for _, S in ipairs(sets) do
  local rows, targets = measure(S)
  current = {}
  set_blocks[#set_blocks + 1] = { id = S.id, lines = current }
  w("<!-- set " .. S.id .. " -->")
  w(string.format("### %s — `%s`", S.label, S.dir))
  w("")
  w("```")
  for _, sub in ipairs(SUBS) do
    w(string.format("build/dda run scripts/paper/blast.lua --set figure=%s%s --out %s/%s", sub:gsub("^fig", ""),
                    S.spacing ~= 2 and string.format(" --set spacing=%g", S.spacing) or "", S.dir, sub))
  end
  w("```")
  w("")
  w("| figure | quantity | paper | ours | difference |")
  w("|---|---|---:|---:|---:|")
  for _, r in ipairs(rows) do
    w(string.format("| %s | %s | %s | %s | %s |", r.fig:gsub("^fig", ""), q_cell(r), paper_cell(r),
                    r.ours and num(r.ours) or "*" .. r.why .. "*", diff_cell(r)))
    local q = S.prefix .. " " .. r.q
    csv_rows[#csv_rows + 1] = string.format("%s,%s,%s,%s,%s", r.fig, q, r.paper and string.format("%.6g", r.paper) or "",
                                            r.ours and string.format("%.6g", r.ours) or "", r.unit)
    summary_lines[#summary_lines + 1] = string.format("%s,%s,%s,%s,%s,%s,%s", r.fig, q,
      r.paper and string.format("%g", r.paper) or "", r.ours and string.format("%.4g", r.ours) or "", r.unit,
      r.paper and r.ours and string.format("%.1f", 100 * (r.ours - r.paper) / r.paper) or "",
      r.wall and string.format("%.1f", r.wall) or "")
    print(string.format("%-6s %-8s %-48s paper %-10s ours %s", S.prefix, r.fig, r.q, paper_cell(r),
                        r.ours and num(r.ours) or r.why))
  end
  w("")
  w("Targets:")
  w("")
  w("| target | result | met |")
  w("|---|---|---|")
  for _, t in ipairs(targets) do
    w(string.format("| %s | %s | %s |", t.text, t.result, t.met == nil and "–" or (t.met and "yes" or "**no**")))
  end
  w("")
  w("Run times (wall time of each run as `blast.lua` measured it, from `blast_runs.csv`; machine: " ..
    machine() .. "):")
  w("")
  w("| figure | run | simulated (s) | blocks | steps | wall (s) | ms/step | step cuts | open-close iterations |")
  w("|---|---|---:|---:|---:|---:|---:|---:|---:|")
  local total, listed = 0, {}
  local function runtime_row(sub, tag, r)
    listed[sub .. ":" .. tag] = true
    if not r then
      w(string.format("| %s | %s | *not run* | | | | | | |", sub:gsub("^fig", ""), tag))
      return
    end
    total = total + r.wall_s
    w(string.format("| %s | %s | %g | %d | %d | %.1f | %.2f | %d | %d |", sub:gsub("^fig", ""), tag, r.t_end,
                    r.blocks, r.steps, r.wall_s, r.ms_per_step, r.step_cuts, r.open_close_iterations))
  end
  for _, sub in ipairs(SUBS) do
    for _, c in ipairs(expected[sub]) do
      local tag = tag_of(S, c[1], c[2], c[3])
      runtime_row(sub, tag, S.runs[sub .. ":" .. tag])
    end
  end
  for _, key in ipairs(S.found) do           -- other runs in the folders (other settings)
    if not listed[key] then runtime_row(S.runs[key].sub, S.runs[key].tag, S.runs[key]) end
  end
  w(string.format("| | total | | | | %.1f | | | |", total))
  w("")
  local figs = plots(S)
  if docs and #figs > 0 then
    os.execute(string.format("mkdir -p '%s/figures'", docs))
    for _, p in ipairs(figs) do
      local base = p.path:match("([^/]+)$")
      if not base:match("^blast_" .. S.id .. "_") then base = "blast_" .. S.id .. "_" .. base end
      if copy(p.path, docs .. "/figures/" .. base) then
        figure_files[#figure_files + 1] = base
        w(string.format("![%s](figures/%s)", p.caption, base))
        w("")
      end
    end
  elseif #figs == 0 then
    w("*No figures: no finished run in this folder.*")
    w("")
  end
end
docs_output.write(out_csv, table.concat(summary_lines, "\n") .. "\n")
print("written to " .. out_csv)

current = notes_md
w("### Notes")
w("")
local nf = notes_path and io.open(notes_path, "r")
if nf then
  local text = nf:read("a"):gsub("%s+$", "")
  nf:close()
  w(text)
else
  w("*No notes file (" .. tostring(notes_path) .. ").*")
end
w("")

-- The sub-blocks of an existing Section 4 block: by their "<!-- set hN -->"
-- lines, or (a block written before those lines) by their "### ... N m joints" headings.
local function old_sets(block)
  local parts, cur = {}, nil
  for line in (block .. "\n"):gmatch("([^\n]*)\n") do
    local id = line:match("^<!%-%- set (%S+) %-%->$")
    if not id and not block:find("<!-- set ", 1, true) then
      local n = line:match("^### .-([%d%.]+) m joints")
      id = n and (string.format("h%g", tonumber(n)):gsub("%.", "p"))
      if id and cur and cur.id == id then id = nil end
    end
    if line:match("^### Notes") or line == END then cur = nil
    elseif id then
      cur = { id = id, lines = {} }
      parts[#parts + 1] = cur
      if not line:match("^<!%-%-") then cur.lines[1] = "<!-- set " .. id .. " -->" end
    end
    if cur then cur.lines[#cur.lines + 1] = line end
  end
  return parts
end

-- The whole block: the header, every spacing's part (ours replacing the old
-- one of the same spacing, the others kept in their order), the notes.
local function section4_block(old_block)
  local out = { table.concat(md, "\n") }
  local ours = {}
  for _, b in ipairs(set_blocks) do ours[b.id] = b end
  local done = {}
  for _, part in ipairs(old_block and old_sets(old_block) or {}) do
    if not done[part.id] then
      done[part.id] = true
      local lines = ours[part.id] and ours[part.id].lines or part.lines
      while #lines > 0 and lines[#lines] == "" do lines[#lines] = nil end
      out[#out + 1] = table.concat(lines, "\n") .. "\n"
    end
  end
  for _, b in ipairs(set_blocks) do
    if not done[b.id] then
      while #b.lines > 0 and b.lines[#b.lines] == "" do b.lines[#b.lines] = nil end
      out[#out + 1] = table.concat(b.lines, "\n") .. "\n"
    end
  end
  out[#out + 1] = table.concat(notes_md, "\n")
  return table.concat(out, "\n") .. "\n" .. END
end

docs_output.write(outdir .. "/validation_section4.md", section4_block(nil) .. "\n")
print("written to " .. outdir .. "/validation_section4.md")

if docs then
  local path = docs .. "/validation.md"
  local old = docs_output.find_block(docs_output.read(path) or "", BEGIN, END)
  docs_output.replace_block(path, BEGIN, END, section4_block(old))
  local replaced, added, kept = docs_output.merge_csv(docs .. "/validation.csv", "figure,quantity,paper,ours,unit",
                                                      csv_rows)
  print(string.format("wrote the Section 4 block of %s (spacings given: %d); %s/validation.csv: %d rows replaced, " ..
                      "%d added, %d kept (figures: %d)", path, #set_blocks, docs, replaced, added, kept,
                      #figure_files))
else
  print("docs/ left as it is (--set write_docs=true writes the report there)")
end
