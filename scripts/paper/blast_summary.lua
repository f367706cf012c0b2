-- blast_summary.lua: the Section 4 (blast) numbers against the paper, from the
-- CSV files blast.lua wrote. No simulation.
--
-- Run:     build/dda run scripts/paper/blast_summary.lua --set dir=out/blast --out out/blast
--          after  blast.lua --set figure=14a --out out/blast/fig14a
--                 blast.lua --set figure=14b --out out/blast/fig14b
--                 blast.lua --set figure=15  --out out/blast/fig15
--          (missing runs are skipped).
-- Writes:  blast_summary.csv  figure,quantity,paper,ours,unit,difference_percent,run_wall_s
--          fig14a_vy_MP1.png, fig14b_vy_MP1.png (redrawn from the CSV files)

local dda = require "dda"
local dir = dda.param("dir", "out/blast")

local function read_csv(path)
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

local function column(rows, k) local v = {} for i, r in ipairs(rows) do v[i] = r[k] end return v end

local runs = {}
for _, sub in ipairs{ "fig14a", "fig14b", "fig15" } do
  for _, r in ipairs(read_csv(dir .. "/" .. sub .. "/blast_runs.csv") or {}) do runs[sub .. ":" .. r.tag] = r end
end

local out = assert(io.open(dda.output("blast_summary.csv"), "w"))
out:write("figure,quantity,paper,ours,unit,difference_percent,run_wall_s\n")
local function row(fig, q, paper, ours, unit, wall)
  if ours == nil then return end
  local diff = paper and string.format("%.1f", 100 * (ours - paper) / paper) or ""
  out:write(string.format("%s,%s,%s,%.4g,%s,%s,%s\n", fig, q, paper and string.format("%g", paper) or "", ours, unit,
                          diff, wall and string.format("%.1f", wall) or ""))
  print(string.format("%-8s %-40s paper %-8s ours %.4g %s (%s %%)", fig, q, paper and tostring(paper) or "-", ours,
                      unit, diff))
end

local function get(key, field) local r = runs[key] return r and r[field], r and r.wall_s end
for _, s in ipairs{ {120, 0.967}, {100, 0.951}, {80, 0.713} } do
  local v, w = get("fig14a:dhi_fixed_" .. s[1], "ppv_mp1")
  row("14a", string.format("PPV MP1 DHI Fixed %d m", s[1]), s[2], v, "m/s", w)
end
do
  local v, w = get("fig14b:dhi_fixed_100", "ppv_mp1")
  row("14b", "PPV MP1 DHI Fixed 100 m vs field", 0.95, v, "m/s", w)
  v, w = get("fig14b:shi_fixed_100", "ppv_mp1")
  row("14b", "PPV MP1 SHI Fixed 100 m", 0.814, v, "m/s", w)
end
for _, b in ipairs{ "fixed", "vbc", "sbc" } do
  local v, w = get("fig15:dhi_" .. b .. "_100", "ppv_mp1")
  row("15", "PPV MP1 DHI " .. b .. " 100 m 0.05 s", nil, v, "m/s", w)
  v = get("fig15:dhi_" .. b .. "_100", "ppv_mp2")
  row("16", "PPV MP2 DHI " .. b .. " 100 m 0.05 s", nil, v, "m/s")
  v = get("fig15:dhi_" .. b .. "_100", "uy_mp3_final")
  row("17", "final uy MP3 DHI " .. b .. " 100 m", b == "sbc" and 2.36e-3 or nil, v, "m")
end
-- reflected energy: integral of vx^2 + vy^2 over t >= 15 ms (after the direct
-- pulse and its coda; the first boundary reflections reach MP1 and MP2
-- at ~16 ms at C_P = 5570 m/s), per boundary
for _, mp in ipairs{ "MP1", "MP2" } do
  for _, b in ipairs{ "fixed", "vbc", "sbc" } do
    local rows = read_csv(string.format("%s/fig15/blast_dhi_%s_100_%s.csv", dir, b, mp))
    if rows then
      local e = 0
      for i = 2, #rows do
        if rows[i].time >= 15e-3 then
          e = e + (rows[i].vx ^ 2 + rows[i].vy ^ 2) * (rows[i].time - rows[i - 1].time)
        end
      end
      row("15-16", string.format("int v^2 dt after 15 ms %s %s", mp, b), nil, e, "m^2/s")
    end
  end
end
local ppv = read_csv(dir .. "/fig15/blast_dhi_sbc_100_ppv.csv")
if ppv then
  local lo, hi, inside = math.huge, 0, 0
  for _, p in ipairs(ppv) do
    lo, hi = math.min(lo, p.ratio), math.max(hi, p.ratio)
    if p.ratio >= 0.5 and p.ratio <= 2 then inside = inside + 1 end
  end
  row("18", "PPV/Eq.23 smallest ratio (SBC line)", nil, lo, "-")
  row("18", "PPV/Eq.23 largest ratio (SBC line)", nil, hi, "-")
  row("18", string.format("points within factor 2 of Eq.23 (of %d)", #ppv), nil, inside, "count")
end
out:close()
print("written to " .. dda.output("blast_summary.csv"))

if dda.has_render then
  local colors = { {30, 80, 200}, {215, 50, 30}, {30, 150, 50} }
  local function replot(file, title, entries)
    local s = {}
    for i, e in ipairs(entries) do
      local rows = read_csv(e.path)
      if rows then s[#s + 1] = { name = e.name, x = column(rows, "time"), y = column(rows, "vy"), color = colors[i] } end
    end
    if #s > 0 then
      dda.plot{ file = file, title = title, series = s, x_label = "t", x_unit = "ms", x_scale = 1e3,
                y_label = "vy", y_unit = "m/s" }
    end
  end
  local e = {}
  for _, size in ipairs{ 120, 100, 80 } do
    local v = get("fig14a:dhi_fixed_" .. size, "ppv_mp1")
    e[#e + 1] = { path = string.format("%s/fig14a/blast_dhi_fixed_%d_MP1.csv", dir, size),
                  name = string.format("%d m (PPV %.3f)", size, v or 0) }
  end
  replot("fig14a_vy_MP1.png", "Fig. 14a: DHI, Fixed BC, y-velocity at MP1 (paper: 0.967 / 0.951 / 0.713)", e)
  e = {}
  for _, load in ipairs{ "dhi", "shi" } do
    local v = get("fig14b:" .. load .. "_fixed_100", "ppv_mp1")
    e[#e + 1] = { path = string.format("%s/fig14b/blast_%s_fixed_100_MP1.csv", dir, load),
                  name = string.format("%s (PPV %.3f)", load:upper(), v or 0) }
  end
  replot("fig14b_vy_MP1.png", "Fig. 14b: 100 m, Fixed BC, vy at MP1 (paper DHI 0.951, SHI 0.814, field 0.95)", e)
end
