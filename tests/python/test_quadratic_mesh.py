"""fricon.Mesh with quadratic (10-node) tetrahedra (theory.md §2.12): the arrays are taken in
Gmsh's node order (corners, then the edges 01, 12, 20, 30, 32, 31), boundary triangles with 3
nodes (the edge nodes are the tetrahedra's) or 6 (checked against them), read back whole, and a
meshio "tetra10" mesh (VTK's order) is put into Gmsh's. The solve at the end needs the quadratic
element: a uniaxial compression, whose exact solution is linear, reproduced to round-off, and
solution.vtu written as VTK's 10-node tetrahedra."""
import numpy as np
import pytest

import fricon
from test_mesh import kuhn_cube

# Gmsh's 10-node tetrahedron: node 4 + e is the middle of the edge TET_EDGES[e]; the 6-node
# triangle: node 3 + e of TRIANGLE_EDGES[e].
TET_EDGES = [(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)]
TRIANGLE_EDGES = [(0, 1), (1, 2), (2, 0)]
CORNERS = 4
# VTK's (and meshio's) 10-node tetrahedron lists the edges 13 and 23 as nodes 8 and 9, Gmsh's the
# edges 32 and 31: the same permutation goes either way.
VTK_ORDER = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]


def with_edge_nodes(points, tets, boundary):
    """The mesh made quadratic with straight edges, in numpy alone: a node at the middle of every
    edge (after the others), the tetrahedra (m, 10) and the triangles (k, 6) in Gmsh's order."""
    edges = np.sort(tets[:, TET_EDGES].reshape(-1, 2), axis=1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    middle = len(points) + np.arange(len(unique))
    quadratic_points = np.vstack([points, points[unique].mean(axis=1)])
    edge_nodes = middle[inverse.reshape(-1)].reshape(len(tets), len(TET_EDGES))
    quadratic_tets = np.hstack([tets, edge_nodes])
    node_of = {(int(a), int(b)): int(m) for (a, b), m in zip(unique, middle)}

    def triangle(t):
        return [*t, *(node_of[tuple(sorted((int(t[a]), int(t[b]))))] for a, b in TRIANGLE_EDGES)]

    quadratic_boundary = {k: np.array([triangle(t) for t in v]) for k, v in boundary.items()}
    return quadratic_points, quadratic_tets, quadratic_boundary


def one_tetrahedron():
    """The unit tetrahedron, quadratic: (10, 3) points, (1, 10) tets, its faces as "all" (4, 6)."""
    corners = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    faces = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]])
    return with_edge_nodes(corners, np.array([[0, 1, 2, 3]]), {"all": faces})


def assert_edge_nodes_are_midpoints(points, cells, edges):
    """Node (corners + e) of every cell (a row of `cells`) is the middle of its edge edges[e]."""
    corners = cells.shape[1] - len(edges)
    for e, (a, b) in enumerate(edges):
        np.testing.assert_array_equal(points[cells[:, corners + e]],
                                      0.5 * (points[cells[:, a]] + points[cells[:, b]]))


def test_a_quadratic_tetrahedron_is_accepted_and_read_back_whole():
    points, tets, boundary = one_tetrahedron()
    for given in ({"all": boundary["all"][:, :3]}, boundary):  # 3-node and 6-node triangles
        m = fricon.Mesh(points, tets, given)
        assert m.order == 2
        assert m.n_nodes == 10 and m.n_tets == 1
        np.testing.assert_array_equal(m.tets, tets)
        assert m.boundary["all"].shape == (4, 6)
        assert_edge_nodes_are_midpoints(m.points, m.boundary["all"], TRIANGLE_EDGES)
        assert "quadratic" in repr(m)
        again = fricon.Mesh(m.points, m.tets, m.boundary)
        np.testing.assert_array_equal(again.tets, m.tets)
        for name, triangles in m.boundary.items():
            np.testing.assert_array_equal(again.boundary[name], triangles)


def test_a_linear_mesh_stays_linear():
    points, tets, boundary = kuhn_cube(1, 1.0)
    m = fricon.Mesh(points, tets, boundary)
    assert m.order == 1 and m.tets.shape == (len(tets), 4)
    assert all(t.shape[1] == 3 for t in m.boundary.values())


def test_a_quadratic_cube_is_accepted():
    points, tets, boundary = with_edge_nodes(*kuhn_cube(2, 1.0))
    m = fricon.Mesh(points, tets, boundary)
    assert m.order == 2 and m.tets.shape == (len(tets), 10)
    assert_edge_nodes_are_midpoints(m.points, m.tets, TET_EDGES)
    assert sorted(m.boundary) == ["x0", "x1", "y0", "y1", "z0", "z1"]


@pytest.mark.parametrize("change, fragment", [
    (lambda p, t, b: (p, t[:, :5].copy(), b), r"tets: expected an array of shape \(k, 4\) or "
                                              r"\(k, 10\), got 2 dimension\(s\) of shape \(1, 5\)"),
    (lambda p, t, b: (p, t, {"all": b["all"][:, :4].copy()}),
     r"boundary\['all'\]: expected an array of shape \(k, 3\) or \(k, 6\), got .* \(4, 4\)"),
    (lambda p, t, b: (p[:4], t[:, :4].copy(), b), "6-node triangles on linear"),
    # The edge nodes of the first triangle's edges 01 and 12 swapped.
    (lambda p, t, b: (p, t, {"all": b["all"][:, [0, 1, 2, 4, 3, 5]].copy()}),
     r"boundary\['all'\]\[0, 3\] is node \d+, but the tetrahedra give the edge"),
    # An edge node that is a corner.
    (lambda p, t, b: (p, np.where(np.arange(10) == 9, 0, t), {"all": b["all"][:, :3]}),
     r"tets\[0, 9\] is node 0, the edge node of the edge 1-3 and a corner"),
])
def test_a_bad_quadratic_mesh_is_an_input_error(change, fragment):
    with pytest.raises(fricon.InputError, match=fragment):
        fricon.Mesh(*change(*one_tetrahedron()))


def test_tetrahedra_that_give_an_edge_two_nodes_do_not_conform():
    points, tets, boundary = with_edge_nodes(*kuhn_cube(1, 1.0))
    # A second node at the middle of the first tetrahedron's edge 01, for it alone.
    a, b = tets[0, 0], tets[0, 1]
    assert sum(set(t[:4]) >= {a, b} for t in tets) > 1  # the edge is shared
    tets = tets.copy()
    tets[0, CORNERS] = len(points)
    points = np.vstack([points, 0.5 * (points[a] + points[b])])
    with pytest.raises(fricon.InputError, match="two edge nodes"):
        fricon.Mesh(points, tets, {k: v[:, :3] for k, v in boundary.items()})


def test_a_meshio_tetra10_mesh_is_put_into_gmsh_order():
    meshio = pytest.importorskip("meshio")
    points, tets, boundary = with_edge_nodes(*kuhn_cube(1, 1.0))
    names = sorted(boundary)
    cells = [("tetra10", tets[:, VTK_ORDER])] + [("triangle6", boundary[k]) for k in names]
    sets = {}
    for i, k in enumerate(names):  # each tag: all of its own triangle6 block
        sets[k] = [np.zeros(0, dtype=int)] * len(cells)
        sets[k][1 + i] = np.arange(len(boundary[k]))
    m = fricon.Mesh.from_meshio(meshio.Mesh(points, cells, cell_sets=sets))
    assert m.order == 2
    np.testing.assert_array_equal(m.tets, tets)
    assert sorted(m.boundary) == names


def test_uniaxial_compression_of_a_quadratic_cube_is_exact(tmp_path):
    # Needs the quadratic element (theory.md §2.12). Symmetry planes x0, y0, z0 and a pressure
    # on z1: the exact solution is linear, which quadratic elements reproduce to round-off at
    # every node (the edge nodes too), with the stress -s along z everywhere.
    E, nu, s, size = 2.0e11, 0.3, 1.0e8, 0.5
    points, tets, boundary = with_edge_nodes(*kuhn_cube(2, size))
    p = fricon.Problem()
    p.mesh = fricon.Mesh(points, tets, boundary)
    p.material = {"young": E, "poisson": nu}
    for name, comp in (("x0", "x"), ("y0", "y"), ("z0", "z")):
        p.dirichlet.append({"boundary": name, "components": comp})
    p.traction.append({"boundary": "z1", "value": [0.0, 0.0, -s]})
    r = fricon.solve(p)
    assert r.converged
    x = r.points
    exact = np.column_stack([nu * s * x[:, 0] / E, nu * s * x[:, 1] / E, -s * x[:, 2] / E])
    np.testing.assert_allclose(r.displacement, exact, rtol=0, atol=1e-12 * s * size / E)
    np.testing.assert_allclose(r.stress[:, 2], -s, rtol=1e-10)
    assert abs(r.stress[:, 2].mean() + s) <= 1e-10 * s
    np.testing.assert_array_equal(r.tets, tets)
    # solution.vtu: VTK's 10-node tetrahedra, the edge nodes 8 and 9 swapped.
    meshio = pytest.importorskip("meshio")
    r.write(str(tmp_path))
    body = meshio.read(tmp_path / "solution.vtu")
    np.testing.assert_array_equal(body.cells_dict["tetra10"], tets[:, VTK_ORDER])
