-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- jointed_bar_exact.lua: the exact response of a 1-D elastic bar crossed by
-- linear elastic joints (the displacement-discontinuity model), by
-- characteristics in time: the reference the DDA bars are measured against.
--
-- Model:   a bar of density rho and modulus E (wave speed c = sqrt(E/rho),
--          impedance Z = rho*c), its left end (x = 0) loaded by a stress
--          history, joints at given positions, each a normal spring k_n
--          (Pa/m): the stress is continuous across a joint and the joint
--          closes by sigma/k_n. The right end is free, fixed or absorbing.
-- Method:  a right-going wave f and a left-going wave g (stress = f + g,
--          tension positive) travel unchanged between joints; the bar is cut
--          into cells that a wave crosses in one time step h, and each step
--          shifts f right and g left by one cell. At a joint the incoming waves
--          f_in (from the left) and g_in (from the right) drive the joint's
--          stress:  d(sigma)/dt = (2 k_n / Z) (f_in + g_in - sigma),  integrated
--          exactly for inputs linear over the step; the joint sends
--          f_out = sigma - g_in and g_out = sigma - f_in. A single joint under a
--          harmonic wave transmits |T| = [1 + (omega Z / 2 k_n)^2]^(-1/2).
--          The only approximation is the load's linear interpolation within a
--          step: the answer converges as h^2 (h = 1e-7 s reproduces 1e-6 s to
--          1e-5 of the amplitude for the paper's pulses).
-- Use:     local exact = require "jointed_bar_exact"
--          local t, records = exact.run{ length = 20, rho = 2000, E = 50e9,
--            joints = {0.2, 0.4, ...} (or spacing = 0.2), kn = 5e11 (or a list),
--            load = function(t) return sigma_at_x0 end, right = "free",
--            receivers = {10.1}, t_end = 4e-3, h = 1e-6 }
--          records[r][n] is the stress at receiver r at time t[n] = n*h.
--          exact.peaks(record) -> most compressive (min), most tensile (max).
-- Writes:  nothing. Tested by tests (scripts/paper/jointed_bar_exact_check.lua).

local exact = {}

function exact.run(o)
  local length, rho, E = o.length, o.rho, o.E
  local c = math.sqrt(E / rho)
  local z = rho * c
  local h = o.h or 1e-6
  local dx = c * h
  local right = o.right or "free"
  assert(right == "free" or right == "fixed" or right == "absorbing",
         "jointed_bar_exact: right must be \"free\", \"fixed\" or \"absorbing\", got " .. tostring(right))
  local joints = o.joints
  if not joints then
    joints = {}
    local k = 1
    while k * o.spacing < length - 1e-9 do joints[#joints + 1] = k * o.spacing; k = k + 1 end
  end
  -- Node positions of the segments: segment s runs from bounds[s] to bounds[s + 1]
  -- over m[s] cells (its length rounded to whole cells).
  local bounds = {0}
  for _, x in ipairs(joints) do bounds[#bounds + 1] = x end
  bounds[#bounds + 1] = length
  local nseg = #bounds - 1
  -- Each segment keeps its two waves in ring buffers of m + 1 slots: the
  -- right-going value written at its left end at step n reaches node i at step
  -- n + i, the left-going value written at its right end reaches node i at step
  -- n + m - i (so a step costs one update per joint, not one per cell).
  local m, F, G = {}, {}, {}
  for s = 1, nseg do
    m[s] = math.max(1, math.floor((bounds[s + 1] - bounds[s]) / dx + 0.5))
    F[s], G[s] = {}, {}
    for i = 0, m[s] do F[s][i], G[s][i] = 0, 0 end
  end
  local function f_at(s, i, n) return F[s][(n - i) % (m[s] + 1)] end
  local function g_at(s, i, n) return G[s][(n - (m[s] - i)) % (m[s] + 1)] end
  local kn = {}
  for j = 1, nseg - 1 do kn[j] = type(o.kn) == "table" and o.kn[j] or o.kn end
  local sigma, s_last = {}, {}
  for j = 1, nseg - 1 do sigma[j], s_last[j] = 0, 0 end
  -- Receivers: the segment and node nearest to each position.
  local where = {}
  for r, x in ipairs(o.receivers) do
    local s = 1
    while s < nseg and x > bounds[s + 1] do s = s + 1 end
    local i = math.floor((x - bounds[s]) / (bounds[s + 1] - bounds[s]) * m[s] + 0.5)
    where[r] = {s, i}
  end
  -- The joint's exact step for inputs linear over it.
  local decay, w0, w1 = {}, {}, {}
  for j = 1, nseg - 1 do
    local lh = 2 * kn[j] / z * h
    local e = math.exp(-lh)
    decay[j] = e
    w1[j] = (1 - e) - (1 - e - lh * e) / lh  -- weight of the input's rise over the step
    w0[j] = 1 - e
  end
  local times, records = {}, {}
  for r = 1, #o.receivers do records[r] = {} end
  local steps = math.floor(o.t_end / h + 0.5)
  local f_out, g_out = {}, {}
  for n = 1, steps do
    local t = n * h
    -- What arrives at each end of each segment at step n (written m steps ago),
    -- then what leaves: the left end's load, each joint, the right end.
    f_out[1] = o.load(t) - g_at(1, 0, n)
    for j = 1, nseg - 1 do
      local f_in, g_in = f_at(j, m[j], n), g_at(j + 1, 0, n)
      local s_in = f_in + g_in
      sigma[j] = decay[j] * sigma[j] + w0[j] * s_last[j] + w1[j] * (s_in - s_last[j])
      s_last[j] = s_in
      g_out[j] = sigma[j] - f_in
      f_out[j + 1] = sigma[j] - g_in
    end
    local f_end = f_at(nseg, m[nseg], n)
    g_out[nseg] = right == "free" and -f_end or right == "fixed" and f_end or 0
    for s = 1, nseg do
      F[s][n % (m[s] + 1)] = f_out[s]
      G[s][n % (m[s] + 1)] = g_out[s]
    end
    times[n] = t
    for r, at in ipairs(where) do
      records[r][n] = f_at(at[1], at[2], n) + g_at(at[1], at[2], n)
    end
  end
  return times, records
end

function exact.peaks(record)
  local lo, hi = math.huge, -math.huge
  for _, v in ipairs(record) do
    if v < lo then lo = v end
    if v > hi then hi = v end
  end
  return lo, hi
end

return exact
