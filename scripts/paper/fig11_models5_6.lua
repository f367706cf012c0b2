-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- fig11_models5_6.lua: the paper's Fig. 11, wave incidence at an inclined boundary.
--
-- Models:  Models 5 and 6 (bars.lua: right end inclined at 60 and 30 deg, incidence
--          30 and 60 deg), and Model 1 (incidence 0) for the trend; one full sine
--          period (compression first), 5 MPa, 1000 Hz on the left end; g0 = 50 E;
--          joints phi = 40 deg, c = sigma_t = 8 MPa. Right end: Fixed, VBC, SBC
--          (Eq. 22, p per metre of edge) with p = 70E (Model 5), 40E (Model 6) and
--          50E (Model 1). Definitions as wave.lua (reflected = sxx of largest
--          magnitude at the centre after t_split = 4.5 ms; absorbed = 1 - |reflected|
--          / |reflected, Fixed|).
-- Run:     build/dda run scripts/paper/fig11_models5_6.lua [--set models=1,5,6]
--                   [--set sbc=true] [--set t_end=8e-3] [--set check=true] [--out out]
-- Writes:  out/fig11_model<M>_<bc>.csv, out/fig11_numbers.csv, out/fig11_model<M>.png.
--          check=true: error unless the VBC absorbs less as incidence grows
--          (Model 1 > Model 5 > Model 6, over the models run).

local dda = require "dda"
local wave = require "wave"

local t_end = dda.param("t_end", 8e-3)
local models = tostring(dda.param("models", "1,5,6"))
local with_sbc = dda.param("sbc", true)
local fig = wave.figure("fig11", "Fig. 11: incidence at the right end, Models 1, 5, 6, g0 = 50E, full sine")
local p_sbc = { [1] = 50, [5] = 70, [6] = 40 }
local incidence = { [1] = 0, [5] = 30, [6] = 60 }

local vbc_shares, txt = {}, {}
for mk in models:gmatch("[^,]+") do
  local model = tonumber(mk)
  local function go(bc, p)
    return wave.run{ tag = string.format("fig11_model%d_%s", model, bc), model = model, g0 = 50, load = "full",
                     right = bc, p = p, per_length = true, t_end = t_end }
  end
  local fixed = go("fixed")
  local ref = math.abs(wave.reflected(fixed))
  local pre = string.format("Model %d (incidence %d deg) ", model, incidence[model])
  fig:row(pre .. "Fixed reflected amplitude", nil, ref / 1e6, "MPa", fixed.T_over_dt)
  local runs, labels = { fixed }, { "Fixed" }
  local v = go("vbc")
  local av = 100 * (1 - math.abs(wave.reflected(v)) / ref)
  fig:row(pre .. "VBC absorbed share", nil, av, "%", v.T_over_dt)
  runs[#runs + 1] = v; labels[#labels + 1] = "VBC"
  vbc_shares[#vbc_shares + 1] = { incidence[model], av }
  txt[#txt + 1] = string.format("%d deg %.2f %%", incidence[model], av)
  if with_sbc then
    local s = go("sbc", p_sbc[model])
    local as = 100 * (1 - math.abs(wave.reflected(s)) / ref)
    fig:row(pre .. string.format("SBC p=%gE absorbed share", p_sbc[model]), nil, as, "%", s.T_over_dt)
    runs[#runs + 1] = s; labels[#labels + 1] = string.format("SBC p = %gE", p_sbc[model])
  end
  fig:plot(string.format("fig11_model%d.png", model), runs, labels, "sxx",
           string.format("Fig. 11: Model %d (incidence %d deg), sxx at the centre", model, incidence[model]))
end
if #vbc_shares >= 2 then
  table.sort(vbc_shares, function(a, b) return a[1] < b[1] end)
  local ok = true
  for i = 2, #vbc_shares do if not (vbc_shares[i][2] < vbc_shares[i - 1][2]) then ok = false end end
  fig:target("VBC absorbs less as incidence grows", ok, table.concat(txt, ", "))
end
return fig:finish()
