"""Solve the elastic brick with the fricon program and read solution.vtu back with meshio.

Checks against independent facts, not against stored output:
  - the grid has the brick's node and tetrahedron counts;
  - the displacement vanishes on the clamped face x = 0 and nowhere else is exactly zero;
  - max |u| in the file equals the report's max_displacement;
  - von Mises per element agrees with the stress tensor written beside it;
  - the --set override of mesh.cells changes the mesh as asked, and is recorded in the report;
  - with backend "tfeti", the same mesh and displacement (to 1e-6), and the cell field
    "subdomain" numbers every subdomain the report counts, each face-connected (theory.md
    §8.1), with the report's smallest and largest node counts; the direct run has no such field.
Usage: check_elastic_vtu.py FRICON PROBLEM.toml OUTDIR
"""
import meshio
import numpy as np

import common

exe, problem, out = common.arguments(__doc__)


def check(folder, report, nx, ny, nz):
    mesh = meshio.read(folder / "solution.vtu")
    n_nodes = (nx + 1) * (ny + 1) * (nz + 1)
    assert mesh.points.shape == (n_nodes, 3), mesh.points.shape
    tets = mesh.cells_dict["tetra"]
    assert tets.shape == (5 * nx * ny * nz, 4), tets.shape
    u = mesh.point_data["displacement"]
    clamped = np.isclose(mesh.points[:, 0], 0.0)
    assert np.all(u[clamped] == 0.0), "displacement on x = 0 must be exactly zero"
    assert np.all(np.linalg.norm(u[~clamped], axis=1) > 0.0)
    assert abs(np.linalg.norm(u, axis=1).max() - report["max_displacement"]) <= 1e-12 * report["max_displacement"]
    s = mesh.cell_data["stress"][0]
    vm = mesh.cell_data["von_mises"][0].ravel()
    vm_check = np.sqrt(0.5 * ((s[:, 0] - s[:, 1]) ** 2 + (s[:, 1] - s[:, 2]) ** 2 + (s[:, 2] - s[:, 0]) ** 2)
                       + 3 * (s[:, 3] ** 2 + s[:, 4] ** 2 + s[:, 5] ** 2))
    assert np.allclose(vm, vm_check, rtol=1e-12), "von Mises does not match the stress tensor"
    assert report["status"] == "converged"
    assert report["equilibrium_residual"] < 1e-10, report["equilibrium_residual"]
    assert report["n_primal"] == 3 * nx * (ny + 1) * (nz + 1)


report = common.solve(exe, problem, out / "default", quiet=False)
check(out / "default", report, 12, 4, 4)
assert report["n_primal"] == 900  # the paper's n_p for n = 4
report = common.solve(exe, problem, out / "coarse", "mesh.cells=[6,2,2]", quiet=False)
check(out / "coarse", report, 6, 2, 2)
assert report["overrides"] == ["mesh.cells=[6,2,2]"], report["overrides"]
assert "subdomain" not in meshio.read(out / "default" / "solution.vtu").cell_data

# The text encoding: the same run, every value equal to the binary file's (both are exact: raw
# doubles, and text with round-trip precision), and the binary file the smaller.
common.solve(exe, problem, out / "ascii", 'output.vtu_encoding="ascii"', quiet=False)
binary, text = (meshio.read(out / f / "solution.vtu") for f in ("default", "ascii"))
assert b'format="ascii"' not in (out / "default" / "solution.vtu").read_bytes()
assert b"AppendedData" not in (out / "ascii" / "solution.vtu").read_bytes()
assert np.array_equal(binary.points, text.points)
assert np.array_equal(binary.cells_dict["tetra"], text.cells_dict["tetra"])
for name in binary.point_data:
    assert np.array_equal(binary.point_data[name], text.point_data[name]), name
for name in binary.cell_data:
    assert np.array_equal(binary.cell_data[name][0], text.cell_data[name][0]), name
assert set(binary.point_data) == set(text.point_data)
assert set(binary.cell_data) == set(text.cell_data)
sizes = [(out / f / "solution.vtu").stat().st_size for f in ("default", "ascii")]
assert sizes[0] < 0.5 * sizes[1], sizes


def face_connected(tets):
    """True when the tetrahedra (rows of node indices) form one piece through shared faces."""
    owner = {}
    parent = list(range(len(tets)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, tet in enumerate(tets):
        for skip in range(4):
            face = tuple(sorted(int(v) for k, v in enumerate(tet) if k != skip))
            if face in owner:
                parent[root(i)] = root(owner[face])
            else:
                owner[face] = i
    return len({root(i) for i in range(len(tets))}) == 1


report = common.solve(exe, problem, out / "tfeti", "solver.backend=\"tfeti\"",
                      "solver.subdomains=8", quiet=False)
mesh = meshio.read(out / "tfeti" / "solution.vtu")
direct = meshio.read(out / "default" / "solution.vtu")
assert np.array_equal(mesh.cells_dict["tetra"], direct.cells_dict["tetra"])
u, u_direct = mesh.point_data["displacement"], direct.point_data["displacement"]
assert np.abs(u - u_direct).max() <= 1e-6 * np.abs(u_direct).max()  # the gluing's tolerance
part = mesh.cell_data["subdomain"][0].ravel()
tets = mesh.cells_dict["tetra"]
feti = report["feti"]
assert sorted(set(part.tolist())) == list(range(feti["n_subdomains"])), (set(part), feti)
nodes = [len(np.unique(tets[part == s])) for s in range(feti["n_subdomains"])]
assert (min(nodes), max(nodes)) == (feti["subdomain_nodes"]["min"],
                                    feti["subdomain_nodes"]["max"]), (nodes, feti)
for s in range(feti["n_subdomains"]):
    assert face_connected(tets[part == s]), f"subdomain {s} is not face-connected"
print("elastic brick: solution.vtu read back by meshio and checked")
