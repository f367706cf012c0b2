# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""ParaView output read back with VTK's own XML reader (python3-vtk9): a
block falls onto a fixed base and slides; every frame's blocks file must hold
one polygon per block with the values m:blocks() gives, and the contacts file
one line per contact with the forces and states m:contacts() gives; the PVD
collections list every frame with its time. Run: vtu_test.py path/to/dda"""
import os
import sys
import xml.etree.ElementTree as ET

from common import SOURCE, check, finish, read, run, scratch, write

try:
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError as e:
    print("python3-vtk9 is not installed (scripts/setup.sh installs it): %s" % e)
    sys.exit(77)  # skipped

SCRIPT = r"""
local dda = require "dda"
local m = dda.model{ plane = "stress", gravity = {0, -9.81}, g1 = 1e-3, g2 = 0.01, g0 = 1e9 }
local rock = m:rock{ density = 2500, E = 1e9, nu = 0.25 }
local soft = m:rock{ density = 2000, E = 5e8, nu = 0.2 }
local j = m:joint{ friction = 20, cohesion = 0, tension = 0 }
local base = m:add_block{ {0, 0}, {4, 0}, {4, 1}, {0, 1}, rock = rock, joint = j }
base:fix()
local top = m:add_block{ {1, 1}, {2, 1}, {2, 2}, {1, 2}, rock = soft, joint = j }
top:set_velocity(0.5, 0)
local v = m:vtu{ folder = "vtu", every = 10 }
m:step(30)
-- the state of the last frame, for the reader to compare with
local f = assert(io.open(dda.output("expected.txt"), "w"))
f:write(string.format("time %.17g\n", m:time()))
for _, b in ipairs(m:blocks()) do
  local sxx, syy, txy = b:stress()
  local vx, vy = b:velocity()
  local ux, uy = b:displacement()
  f:write(string.format("block %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", b:id(),
                        b == top and 1 or 0, sxx, syy, txy, vx, vy, ux, uy, b:area()))
end
for _, c in ipairs(m:contacts()) do
  local states = { open = 0, sliding = 1, locked = 2 }
  f:write(string.format("contact %d %d %d %d %.17g %.17g\n", c.vblock:id(), c.eblock:id(), states[c.state],
                        c.intact and 1 or 0, c.normal_force, c.shear_force))
end
f:close()
return { frames = v:count(), pvd = v:pvd() }
"""

d = scratch("vtu")
write(os.path.join(d, "fall.lua"), SCRIPT)
r = run(["run", "fall.lua", "--out", "out", "--quiet"], d)
check(r.returncode == 0, "the script runs", r.stderr)
out = os.path.join(d, "out")
vtu = os.path.join(out, "vtu")

# frames: steps 0, 10, 20, 30
files = sorted(f for f in os.listdir(vtu) if f.endswith(".vtu"))
check(files == ["blocks_0000%d.vtu" % i for i in range(4)] + ["contacts_0000%d.vtu" % i for i in range(4)],
      "4 frames of blocks and contacts (steps 0, 10, 20, 30)", files)
check(not any(f.endswith(".part") for f in os.listdir(vtu)), "no partial files left")


def load(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def cell_array(grid, name):
    a = grid.GetCellData().GetArray(name)
    return [a.GetTuple(i) for i in range(a.GetNumberOfTuples())] if a else None


expected = [line.split() for line in read(os.path.join(out, "expected.txt")).splitlines()]
t_end = float(expected[0][1])
blocks = [e for e in expected if e[0] == "block"]
contacts = [e for e in expected if e[0] == "contact"]

g = load(os.path.join(vtu, "blocks_00003.vtu"))
check(g.GetNumberOfCells() == 2 and g.GetNumberOfPoints() == 8, "blocks: 2 polygons, 8 points",
      (g.GetNumberOfCells(), g.GetNumberOfPoints()))
check(all(g.GetCellType(i) == 7 for i in range(g.GetNumberOfCells())), "blocks are VTK_POLYGON cells")
time_value = g.GetFieldData().GetArray("TimeValue").GetTuple1(0)
check(time_value == t_end, "TimeValue is the model's time", (time_value, t_end))
ids = cell_array(g, "block_id")
materials = cell_array(g, "material")
check([int(x[0]) for x in materials] == [0, 1], "material ids (rock, soft)", materials)
for k, e in enumerate(blocks):
    bid = int(e[1])
    row = [x[0] for x in ids].index(bid)
    vals = [float(x) for x in e[3:]]
    got = [cell_array(g, "sigma_xx")[row][0], cell_array(g, "sigma_yy")[row][0], cell_array(g, "tau_xy")[row][0],
           cell_array(g, "velocity")[row][0], cell_array(g, "velocity")[row][1],
           cell_array(g, "displacement")[row][0], cell_array(g, "displacement")[row][1],
           cell_array(g, "area")[row][0]]
    check(got == vals, "block %d: stress, velocity, displacement, area as m:blocks() gives them (bit for bit)" % bid,
          (got, vals))
# the top block moved: its polygon's points are where the block is now
top_row = [x[0] for x in ids].index(1)
cell = g.GetCell(top_row)
xs = [cell.GetPoints().GetPoint(i)[0] for i in range(cell.GetNumberOfPoints())]
disp = cell_array(g, "displacement")[top_row][0]
check(abs(min(xs) - (1 + disp)) < 1e-4 and disp > 0.005, "the top block's outline has moved with it",
      (min(xs), disp))

c = load(os.path.join(vtu, "contacts_00003.vtu"))
check(c.GetNumberOfCells() == len(contacts) and len(contacts) >= 2, "one line per contact (%d)" % len(contacts),
      c.GetNumberOfCells())
check(all(c.GetCellType(i) == 3 for i in range(c.GetNumberOfCells())), "contacts are VTK_LINE cells")
got = [(int(a[0]), int(b[0]), int(s[0]), int(i[0]), n[0], sh[0]) for a, b, s, i, n, sh in
       zip(cell_array(c, "vblock"), cell_array(c, "eblock"), cell_array(c, "state"), cell_array(c, "intact"),
           cell_array(c, "normal_force"), cell_array(c, "shear_force"))]
want = [(int(e[1]), int(e[2]), int(e[3]), int(e[4]), float(e[5]), float(e[6])) for e in contacts]
check(got == want, "contacts: blocks, state, intact, normal and shear force as m:contacts() gives them", (got, want))
check(any(s == 1 for _, _, s, _, _, _ in got), "the sliding block's contacts are sliding (state 1)", got)
check(all(n > 0 for _, _, _, _, n, _ in got), "the resting block presses on the base (normal force > 0)", got)

# the PVD collections
for kind in ("blocks", "contacts"):
    root = ET.parse(os.path.join(vtu, kind + ".pvd")).getroot()
    sets = root.findall("./Collection/DataSet")
    check([s.get("file") for s in sets] == ["%s_0000%d.vtu" % (kind, i) for i in range(4)],
          "%s.pvd lists the 4 frames in order" % kind)
    times = [float(s.get("timestep")) for s in sets]
    check(times[0] == 0 and times[-1] == t_end and times == sorted(times), "%s.pvd times 0 .. t_end" % kind, times)
    for s in sets:
        f = load(os.path.join(vtu, s.get("file")))
        ok = f.GetFieldData().GetArray("TimeValue").GetTuple1(0) == float(s.get("timestep"))
        if not ok:
            break
    check(ok, "%s: each file's TimeValue matches its PVD timestep" % kind)

# the run's results, and --vtu from the command line
res = read(os.path.join(out, "result.csv")).splitlines()
check(res[0] == "frames,pvd" and res[1].startswith("4,"), "return {...} written to result.csv", res)
r = run(["run", os.path.join(SOURCE, "scripts", "free_fall.lua"), "--out", "cli",
         "--quiet", "--set", "t_end=0.1", "--vtu", "5"], d)
files = sorted(os.listdir(os.path.join(d, "cli", "vtu"))) if r.returncode == 0 else []
check("blocks_00002.vtu" in files and "blocks.pvd" in files and "blocks_00003.vtu" not in files,
      "--vtu 5 writes a frame every 5 steps (0, 5, 10 of 10)", (r.stderr, files))
finish()
