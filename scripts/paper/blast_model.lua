-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- blast_model.lua: the paper's Section 4 blasting model, shared by blast.lua
-- (runs) and usable by any script that needs the same geometry (the recipe of
-- blast_geometry.lua). No run, no output: build{...} returns the model.
--
--   local blast_model = require "blast_model"
--   local M = blast_model.build{ size = 100 }
--   -- M.m (model), M.rock, M.joint, M.chamber (hole), M.blocks, M.info,
--   -- M.wall (chamber wall edges), M.outer (outer boundary edges), M.h (size/2)
--   blast_model.load(M, "dhi")   -- or "shi": the paper's load on the chamber wall
--
-- Square jointed rock mass centred at the origin (the detonation centre), two
-- joint sets at 45 and 135 deg, 2 m spacing, and the 8 m x 4 m chamber
-- centred at the origin. Rock: 2650 kg/m^3, E = 74 GPa, nu = 0.2 (plane
-- strain); joints: phi = 25 deg, c = 2 MPa, sigma_t = 0. Controls g0 = 100e9
-- N/m, g1 = 1e-5 s, gg = 1, g2 = 0.005, contact_law = "shi", integrator = "shi",
-- mesh_size = 0 (first-order blocks), mesh_mass = "consistent".

local dda = require "dda"

local blast_model = {}

blast_model.rock = { density = 2650, E = 74e9, nu = 0.2 }
blast_model.joint = { friction = 25, cohesion = 2e6, tension = 0 }
-- contact_law = "shi": the paper's DDA contact law, which its figures and
-- docs/validation.md were made with (docs/contacts.md; not the "shi" load).
-- The paper's first-order blocks and Shi's scheme, pinned (the engine would
-- mesh the 2 m blocks for the blast's pulse, docs/waves.md); meshed variants
-- give the rock a mesh_size, with the consistent mass their tables were
-- measured with.
blast_model.controls = { plane = "strain", g0 = 100e9, g1 = 1e-5, g2 = 0.005, gg = 1, contact_law = "shi",
                         integrator = "shi", mesh_size = 0, mesh_mass = "consistent" }
blast_model.chamber = { -4, -2, 4, 2 }   -- m: 8 m wide, 4 m high, roof at y = 2
blast_model.charge_kg = 606               -- TNT of the field test (Eq. 23 uses R/Q^(1/3))

-- opts: size (m, default 100), spacing (m, default 2), controls (table of
-- extra/overriding model controls, optional), min_area (m^2: slivers below it
-- are merged into a neighbour; default none), joint_origin ({x, y}: a point
-- both joint sets pass through; default the detonation centre {0, 0}. The
-- paper does not say where its joints lie; with 2 m joints the PPV at MP1
-- depends on it, see blast_joint_offset.lua),
-- mesh (m: blocks meshed into elements of about this size, docs/meshed_blocks.md;
-- default 0, first-order blocks), mesh_radius (m: only the blocks whose
-- centroid lies within this distance of the detonation centre are meshed, the
-- rest stay first-order; default 0, every block), kn (Pa/m: the joints' own
-- normal stiffness; default none, the penalty g0 per contact; blast.lua gives
-- meshed models 2*g0/spacing, the paper's joint read as a stiffness per length),
-- first_order_corners (true: with mesh > 0, the four blocks the chamber's
-- corners cut concave stay first-order, as before CGAL meshed concave blocks;
-- only for blast_corner_block.lua, which shows why that over-drives the wave).
-- A block whose outline turns clockwise somewhere (the chamber's corners cut four such blocks).
local function concave(b)
  local v = b:vertices()
  local n = #v
  for k = 1, n do
    local a, p, c = v[(k - 2) % n + 1], v[k], v[k % n + 1]
    local cross = (p[1] - a[1]) * (c[2] - p[2]) - (p[2] - a[2]) * (c[1] - p[1])
    if cross < -1e-12 then return true end
  end
  return false
end
blast_model.concave = concave

function blast_model.build(opts)
  opts = opts or {}
  local size = opts.size or 100
  local spacing = opts.spacing or 2
  local h = size / 2
  local controls = {}
  for k, v in pairs(blast_model.controls) do controls[k] = v end
  for k, v in pairs(opts.controls or {}) do controls[k] = v end
  local mesh, mesh_radius = opts.mesh or 0, opts.mesh_radius or 0
  -- Meshed: the number of blocks the joints cut (every element counts as a
  -- block once meshed), from the same geometry cut first-order (no run).
  local rock_blocks, corner_centroids = nil, {}
  if mesh > 0 then
    local plain = {}
    for k, v in pairs(opts) do plain[k] = v end
    plain.mesh, plain.kn = 0, nil
    local P = blast_model.build(plain)
    rock_blocks = #P.blocks
    if opts.first_order_corners then
      for _, b in ipairs(P.blocks) do
        if concave(b) then corner_centroids[#corner_centroids + 1] = { b:centroid() } end
      end
    end
    P.m:close()
  end

  local m = dda.model(controls)
  local rock_props = {}
  for k, v in pairs(blast_model.rock) do rock_props[k] = v end
  if mesh > 0 and mesh_radius == 0 then rock_props.mesh_size = mesh end
  local rock = m:rock(rock_props)
  local joint_props = {}
  for k, v in pairs(blast_model.joint) do joint_props[k] = v end
  joint_props.kn = opts.kn
  local joint = m:joint(joint_props)
  m:domain{ box = {-h, -h, h, h}, rock = rock, joint = joint }
  local chamber = m:hole{ box = blast_model.chamber, joint = joint }
  if mesh > 0 and mesh_radius > 0 then
    -- the same rock, meshed, in a disc about the detonation centre (a polygon
    -- of 64 sides; a block is in it when its centroid is)
    rock_props.mesh_size = mesh
    local disc = {}
    for k = 0, 63 do
      local a = 2 * math.pi * k / 64
      disc[#disc + 1] = { mesh_radius * math.cos(a), mesh_radius * math.sin(a) }
    end
    m:region{ polygon = disc, rock = m:rock(rock_props) }
  end
  -- first_order_corners: a first-order region over each concave block's centroid
  for _, c in ipairs(corner_centroids) do
    m:region{ box = { c[1] - 1e-3, c[2] - 1e-3, c[1] + 1e-3, c[2] + 1e-3 }, rock = m:rock(blast_model.rock) }
  end
  local origin = opts.joint_origin or {0, 0}
  m:joint_set{ dip = 45, spacing = spacing, joint = joint, origin = origin }
  m:joint_set{ dip = 135, spacing = spacing, joint = joint, origin = origin }
  local blocks, info = m:generate(opts.min_area and { min_area = opts.min_area } or nil)
  return { m = m, rock = rock, mesh = mesh, mesh_radius = mesh_radius,
           rock_blocks = rock_blocks or #blocks, joint = joint, chamber = chamber, blocks = blocks, info = info,
           wall = chamber:edges(), outer = m:edges{ boundary = "domain" }, h = h, size = size }
end

-- The blast load on the chamber wall of a built model M (paper Fig. 13):
-- "shi", a triangular pressure 0 -> 30.23 MPa at 0.5 ms -> 0 at 2.5 ms, or
-- "dhi", a triangular particle velocity with the same times and a 2.03 m/s
-- peak, normal to each wall edge (integrated to a displacement history).
function blast_model.load(M, kind)
  local times = { {0, 0}, {0.5e-3, 1}, {2.5e-3, 0} }
  local function scaled(a) local r = {} for i, p in ipairs(times) do r[i] = {p[1], a * p[2]} end return r end
  if kind == "shi" then
    M.wall:pressure(scaled(30.23e6))
  elseif kind == "dhi" then
    M.wall:target{ velocity = scaled(2.03) }
  else
    error("load must be dhi or shi, got " .. tostring(kind), 2)
  end
end

return blast_model
