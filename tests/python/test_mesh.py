"""fricon.Mesh: meshes from numpy arrays, checked like mesh files, solved like built-in ones."""
import numpy as np
import pytest

import fricon
from conftest import PAPER_BRICK, numbers_of


def brick_arrays():
    m = fricon.Mesh.brick([3.0, 1.0, 1.0], [12, 4, 4])
    return np.array(m.points), np.array(m.tets), {k: np.array(v) for k, v in m.boundary.items()}


def test_a_mesh_from_arrays_equals_the_generators():
    points, tets, boundary = brick_arrays()
    p = fricon.load(PAPER_BRICK)
    p.mesh = fricon.Mesh(points, tets, boundary)
    # The arrays carry no Gmsh entities (the brick's chessboard): agglomerate patches on both.
    p.contact.patches = "agglomerate"
    ref = fricon.load(PAPER_BRICK)
    ref.contact.patches = "agglomerate"
    a, b = fricon.solve(p, threads=1), fricon.solve(ref, threads=1)
    np.testing.assert_array_equal(a.displacement, b.displacement)
    ra, rb = numbers_of(a.report), numbers_of(b.report)
    ra.pop("problem"), rb.pop("problem")
    assert ra == rb


def test_the_answer_does_not_depend_on_the_numbering():
    points, tets, boundary = brick_arrays()
    rng = np.random.default_rng(7)
    perm = rng.permutation(len(points))           # new index of old node i: inv[i]
    inv = np.empty_like(perm)
    inv[perm] = np.arange(len(perm))
    order = rng.permutation(len(tets))
    mesh = fricon.Mesh(points[perm], inv[tets[order]],
                       {k: inv[v[rng.permutation(len(v))]] for k, v in boundary.items()})
    p = fricon.load(PAPER_BRICK)
    p.set("contact.patches", "agglomerate")
    p.solver.qp_rtol = 1e-10
    p.solver.outer_tol = 1e-8
    ref = fricon.solve(p, threads=1)
    p.mesh = mesh
    r = fricon.solve(p, threads=1)
    scale = np.abs(ref.displacement).max()
    np.testing.assert_allclose(r.displacement, ref.displacement[perm], rtol=0, atol=1e-7 * scale)


def kuhn_cube(n, size):
    """A cube [0, size]^3 split into n^3 cells of 6 tetrahedra each (Kuhn), in numpy alone."""
    g = np.linspace(0.0, size, n + 1)
    X, Y, Z = np.meshgrid(g, g, g, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    idx = np.arange((n + 1) ** 3).reshape(n + 1, n + 1, n + 1)
    tets = []
    paths = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    for i in range(n):
        for j in range(n):
            for k in range(n):
                for path in paths:
                    c = [i, j, k]
                    tet = [idx[tuple(c)]]
                    for axis in path:
                        c[axis] += 1
                        tet.append(idx[tuple(c)])
                    a, b, cc, d = points[tet]
                    if np.linalg.det(np.array([b - a, cc - a, d - a])) < 0:
                        tet[2], tet[3] = tet[3], tet[2]
                    tets.append(tet)
    tets = np.array(tets)
    # Boundary: the faces of single tetrahedra, tagged by the coordinate plane they lie on.
    faces = {}
    for t in tets:
        for f in ([t[1], t[2], t[3]], [t[0], t[2], t[3]], [t[0], t[1], t[3]], [t[0], t[1], t[2]]):
            key = tuple(sorted(f))
            faces[key] = faces.get(key, 0) + 1
    boundary = {}
    for key, count in faces.items():
        if count != 1:
            continue
        x = points[list(key)]
        for axis, name in enumerate("xyz"):
            for side, value in ((0, 0.0), (1, size)):
                if np.all(np.isclose(x[:, axis], value)):
                    boundary.setdefault(f"{name}{side}", []).append(key)
    return points, tets, {k: np.array(v) for k, v in boundary.items()}


def test_uniaxial_compression_of_a_numpy_cube_is_exact():
    # Symmetry planes x0, y0, z0 and a pressure on z1: the exact solution is linear, which P1
    # elements reproduce to round-off: u_z = -s z / E, u_x = nu s x / E, u_y = nu s y / E.
    E, nu, s, size = 2.0e11, 0.3, 1.0e8, 0.5
    points, tets, boundary = kuhn_cube(3, size)
    p = fricon.Problem()
    p.mesh = fricon.Mesh(points, tets, boundary)
    p.material = {"young": E, "poisson": nu}
    for name, comp in (("x0", "x"), ("y0", "y"), ("z0", "z")):
        p.dirichlet.append({"boundary": name, "components": comp})
    p.traction.append({"boundary": "z1", "value": [0.0, 0.0, -s]})
    r = fricon.solve(p)
    x = r.points
    exact = np.column_stack([nu * s * x[:, 0] / E, nu * s * x[:, 1] / E, -s * x[:, 2] / E])
    np.testing.assert_allclose(r.displacement, exact, rtol=0, atol=1e-12 * s * size / E)
    np.testing.assert_allclose(r.stress[:, 2], -s, rtol=1e-10)


def test_regions_from_arrays_take_their_materials():
    points, tets, boundary = kuhn_cube(2, 1.0)
    lower = np.flatnonzero(points[tets].mean(axis=1)[:, 2] < 0.5)
    upper = np.setdiff1d(np.arange(len(tets)), lower)
    mesh = fricon.Mesh(points, tets, boundary, regions={"soft": lower, "hard": upper})
    assert sorted(mesh.regions) == ["hard", "soft"]
    p = fricon.Problem()
    p.mesh = mesh
    p.material = [{"region": "soft", "young": 1e9, "poisson": 0.3},
                  {"region": "hard", "young": 1e11, "poisson": 0.3}]
    p.dirichlet.append({"boundary": "z0"})
    p.traction.append({"boundary": "z1", "value": [0.0, 0.0, -1e6]})
    r = fricon.solve(p)
    assert r.converged
    assert [g["name"] for g in r.report["regions"]] == ["hard", "soft"] or r.report["regions"]


@pytest.mark.parametrize("change, fragment", [
    (lambda p, t, b: (p, t[:, [1, 0, 2, 3]].copy(), b), "inverted"),
    (lambda p, t, b: (p, t + len(p), b), "refers to node"),
    (lambda p, t, b: (p, t[:, :3].copy(), b), r"shape \(k, 4\)"),
    (lambda p, t, b: (np.vstack([p, [[9.0, 9.0, 9.0]]]), t, b), "belongs to no tetrahedron"),
    (lambda p, t, b: (p, t, {"z0": np.array([[0, 1, 6]])}), "is no face of any"),
    (lambda p, t, b: (np.where(np.arange(p.size).reshape(p.shape) == 0, np.nan, p), t, b),
     "non-finite"),
    # Issue 33: fractional indices were truncated silently, and a tag without triangles was
    # accepted here and "does not exist" where it was used.
    (lambda p, t, b: (p, t + 0.5, b), r"tets\[0, 0\]: expected an integer index, got \d+\.5$"),
    (lambda p, t, b: (p, t, {**b, "z0": b["z0"] + 0.25}),
     r"boundary\['z0'\]\[0, 0\]: expected an integer index, got \d+\.25$"),
    (lambda p, t, b: (p, t, {**b, "empty": np.zeros((0, 3), dtype=int)}),
     r"boundary\['empty'\]: expected at least one triangle, got none"),
    (lambda p, t, b: (p, t.astype(bool), b), "expected an array of integer indices"),
])
def test_a_bad_mesh_is_an_input_error(change, fragment):
    points, tets, boundary = kuhn_cube(1, 1.0)
    with pytest.raises(fricon.InputError, match=fragment):
        fricon.Mesh(*change(points, tets, boundary))


def test_whole_float_indices_are_indices():
    points, tets, boundary = kuhn_cube(1, 1.0)
    m = fricon.Mesh(points, tets.astype(float), {k: v.astype(float) for k, v in boundary.items()})
    np.testing.assert_array_equal(m.tets, fricon.Mesh(points, tets, boundary).tets)


def test_an_empty_region_is_an_input_error():
    points, tets, boundary = kuhn_cube(1, 1.0)
    with pytest.raises(fricon.InputError, match=r"regions\['none'\]: expected at least one"):
        fricon.Mesh(points, tets, boundary,
                    {"all": np.arange(len(tets)), "none": np.zeros(0, dtype=int)})
    with pytest.raises(fricon.InputError,
                       match=r"regions\['all'\]\[0\]: expected an integer index, got 0.5$"):
        fricon.Mesh(points, tets, boundary, {"all": np.arange(len(tets)) + 0.5})


def test_a_mesh_can_only_go_to_p_mesh():
    points, tets, boundary = kuhn_cube(1, 1.0)
    p = fricon.Problem()
    with pytest.raises(fricon.InputError, match="p.mesh"):
        p.material = fricon.Mesh(points, tets, boundary)


def test_a_gmsh_file_read_by_meshio_equals_the_same_file_read_by_fricon(fricon_exe, tmp_path):
    meshio = pytest.importorskip("meshio")
    import subprocess

    msh = tmp_path / "brick.msh"
    subprocess.run([fricon_exe, "mesh", "brick", "--size", "3", "1", "1", "--cells", "12", "4", "4",
                    "--out", str(msh)], check=True, capture_output=True)
    by_fricon = fricon.load(PAPER_BRICK)
    by_fricon.mesh = {"kind": "gmsh", "file": str(msh)}
    by_fricon.contact.patches = "agglomerate"
    by_meshio = by_fricon.copy()
    by_meshio.mesh = fricon.Mesh.from_meshio(meshio.read(msh))
    assert sorted(by_meshio.to_dict()["mesh"]) == ["kind"]
    a, b = fricon.solve(by_fricon, threads=1), fricon.solve(by_meshio, threads=1)
    # Same nodes in the same order (both keep the file's); the same answer.
    np.testing.assert_array_equal(a.points, b.points)
    np.testing.assert_allclose(b.displacement, a.displacement, rtol=0,
                               atol=1e-12 * np.abs(a.displacement).max())
    assert a.report["outer_iterations"] == b.report["outer_iterations"]
