"""Solve the elastic brick with the fricon program and read solution.vtu back with meshio.

Checks against independent facts, not against stored output:
  - the grid has the brick's node and tetrahedron counts;
  - the displacement vanishes on the clamped face x = 0 and nowhere else is exactly zero;
  - max |u| in the file equals the report's max_displacement;
  - von Mises per element agrees with the stress tensor written beside it;
  - the --set override of mesh.cells changes the mesh as asked, and is recorded in the report.
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
print("elastic brick: solution.vtu read back by meshio and checked")
