"""`fricon mesh brick` writes the paper's brick as a Gmsh file; `fricon mesh info` reads it back.

The counts printed by `mesh info` must be those of the brick: (nx+1)(ny+1)(nz+1) nodes,
5 nx ny nz tetrahedra, 2 triangles per boundary square, and per side one entity per 2 x 2 block;
a .geo file's physical curves and points are listed with their nodes; and `--order 2` writes
10-node tetrahedra (a node at the midpoint of every edge: vertices + edges nodes, the edges from
Euler's formula) that `mesh info` reads back at order 2.

Usage: check_gmsh_mesh.py FRICON UNUSED OUTDIR
"""
import re

import common

exe, _, out = common.arguments(__doc__)
failures = common.Failures(separator="\n")
nx, ny, nz = 6, 4, 2
blocks = {"x": (ny // 2) * (nz // 2), "y": (nz // 2) * (nx // 2), "z": (nx // 2) * (ny // 2)}
squares = {"x": ny * nz, "y": nz * nx, "z": nx * ny}
sizes = {"x": 1.0 * 0.5, "y": 0.5 * 3.0, "z": 3.0 * 1.0}  # area of the side normal to each axis


def run(args):
    r = common.run([exe] + args)
    if r.returncode != 0:
        failures.add(f"{args}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    return r.stdout


for version, binary in (("41", False), ("41", True), ("22", False)):
    msh = out / f"brick{version}{'b' if binary else ''}.msh"
    run(["mesh", "brick", "--size", "3,1,0.5", "--cells", f"{nx},{ny},{nz}", "--out", str(msh),
         "--msh-version", version] + (["--binary"] if binary else []))
    info = run(["mesh", "info", str(msh)])
    head = re.search(r"(\d+) nodes, (\d+) (?:\d+-node )?tetrahedra, (\d+) boundary triangles", info)
    if not head:
        failures.add(f"{msh}: no size line in\n{info}")
        continue
    nodes, tets, triangles = map(int, head.groups())
    if nodes != (nx + 1) * (ny + 1) * (nz + 1) or tets != 5 * nx * ny * nz:
        failures.add(f"{msh}: {nodes} nodes, {tets} tetrahedra")
    if triangles != 4 * sum(squares.values()):
        failures.add(f"{msh}: {triangles} boundary triangles")
    region = re.search(r"body\s+(\d+) tetrahedra, volume (\S+) m\^3", info)
    if not region or int(region.group(1)) != tets or abs(float(region.group(2)) - 1.5) > 1e-12:
        failures.add(f"{msh}: region line wrong in\n{info}")
    for axis in "xyz":
        for side in "01":
            m = re.search(rf"{axis}{side}\s+(\d+) triangles, area (\S+) m\^2, (\d+) entities", info)
            expected = (2 * squares[axis], sizes[axis], blocks[axis])
            if not m or (int(m.group(1)), int(m.group(3))) != (expected[0], expected[2]) or abs(
                    float(m.group(2)) - expected[1]) > 1e-12:
                failures.add(f"{msh}: tag {axis}{side} expected {expected} in\n{info}")

# Order 2: every edge of the tetrahedra gets one node, so nodes = vertices + edges, the edges
# from Euler's formula for the tetrahedra filling the box (a ball): V - E + F - T = 1.
msh = out / "brick-quadratic.msh"
run(["mesh", "brick", "--size", "3,1,0.5", "--cells", f"{nx},{ny},{nz}", "--out", str(msh),
     "--order", "2"])
info = run(["mesh", "info", str(msh)])
head = re.search(r"(\d+) nodes, (\d+) 10-node tetrahedra, (\d+) boundary triangles", info)
vertices, tets = (nx + 1) * (ny + 1) * (nz + 1), 5 * nx * ny * nz
boundary = 4 * sum(squares.values())
faces = (4 * tets + boundary) // 2  # each inner face in two tetrahedra, each boundary one in one
edges = vertices + faces - tets - 1
if not head or tuple(map(int, head.groups())) != (vertices + edges, tets, boundary):
    failures.add(f"{msh}: expected {vertices + edges} nodes, {tets} 10-node tetrahedra in\n{info}")

r = common.run([exe, "mesh", "info", out / "missing.msh"])
if r.returncode != 1 or "missing.msh: no such file" not in r.stderr:
    failures.add(f"mesh info of a missing file: exit {r.returncode}\n{r.stderr}")

# Physical curves and points (for [[dirichlet]]) are listed with their node counts: the edge
# y = z = 0 of the 1 m plate at mesh size 0.25 m has 5 nodes, the point one.
plate = common.REPOSITORY / "tests" / "bad_input" / "143-plate-edge.geo"
info = run(["mesh", "info", str(plate)])
for name, count, kind in (("edge", 5, "curve"), ("corner", 1, "point")):
    if not re.search(rf"{name}\s+{count} nodes?, a {kind} \(for \[\[dirichlet\]\] only\)", info):
        failures.add(f"{plate}: {kind} {name} of {count} node(s) not listed in\n{info}")

failures.finish("fricon mesh brick / mesh info: counts as expected")
