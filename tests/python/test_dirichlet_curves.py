"""[[dirichlet]] on Gmsh curves and points (issue 33): a physical curve or point holds all its
nodes, with the checks of a surface.

The plate 1 x 1 x 0.2 m is pulled by sigma on its faces y = 0 and y = 1 (no net force), held by
u_x = 0 on x = 0, u_z = 0 on z = 0 and u_y = 0 on the edge y = z = 0 (a curve, as Code_Aster's
plate benchmark fixes DY on one edge). Uniform tension, u_y = sigma/E y, u_x = -nu sigma/E x,
u_z = -nu sigma/E z, satisfies every condition (u_y vanishes on the whole line y = 0), and P1
elements reproduce a linear field: the edge gives it to rounding. A strip of width w on z = 0
along the edge, held instead, forces u_y = 0 at y = w too, against the uniform field by
sigma/E w: the strip's answer tends to the edge's as w -> 0.
"""
import numpy as np
import pytest

import fricon

E, NU, SIGMA = 1.0e9, 0.3, 1.0e6  # [Pa], [-], [Pa]
L, W, T = 1.0, 1.0, 0.2  # plate size x, y, z [m]
SIZE = 0.2  # mesh size away from the strip [m]

GEO = """SetFactory("OpenCASCADE");
w = {w};
Box(1) = {{0, 0, 0, {L}, w, {T}}};
Box(2) = {{0, w, 0, {L}, {W} - w, {T}}};
BooleanFragments{{ Volume{{1}}; Delete; }}{{ Volume{{2}}; Delete; }}
e = 1e-6;
Physical Volume("plate") = {{1, 2}};
Physical Surface("x0") = Surface In BoundingBox{{-e, -e, -e, e, {W} + e, {T} + e}};
Physical Surface("y0") = Surface In BoundingBox{{-e, -e, -e, {L} + e, e, {T} + e}};
Physical Surface("y1") = Surface In BoundingBox{{-e, {W} - e, -e, {L} + e, {W} + e, {T} + e}};
Physical Surface("z0") = Surface In BoundingBox{{-e, -e, -e, {L} + e, {W} + e, e}};
Physical Surface("strip") = Surface In BoundingBox{{-e, -e, -e, {L} + e, w + e, e}};
Physical Curve("edge") = Curve In BoundingBox{{-e, -e, -e, {L} + e, e, e}};
Physical Point("origin") = Point In BoundingBox{{-e, -e, -e, e, e, e}};
Physical Point("far_corner") = Point In BoundingBox{{-e, {W} - e, -e, e, {W} + e, e}};
MeshSize{{ PointsOf{{ Volume{{2}}; }} }} = {size};
MeshSize{{ PointsOf{{ Volume{{1}}; }} }} = w;
"""

TOML = """[mesh]
kind = "gmsh"
file = "plate.geo"

[material]
young = {E}
poisson = {NU}

[[traction]]
boundary = "y1"
value = [0.0, {SIGMA}, 0.0]

[[traction]]
boundary = "y0"
value = [0.0, {minus_sigma}, 0.0]

[[dirichlet]]
boundary = "z0"
components = "z"
"""


def plate(tmp_path, w, supports):
    """The plate with the strip of width w meshed in, held by z0 (z) and `supports`, a list of
    (boundary, components)."""
    folder = tmp_path / f"w{w}"
    folder.mkdir(exist_ok=True)
    (folder / "plate.geo").write_text(GEO.format(w=w, L=L, W=W, T=T, size=SIZE))
    text = TOML.format(E=E, NU=NU, SIGMA=SIGMA, minus_sigma=-SIGMA)
    for boundary, components in supports:
        text += f'\n[[dirichlet]]\nboundary = "{boundary}"\ncomponents = "{components}"\n'
    name = "_".join(b for b, _ in supports)
    (folder / f"{name}.toml").write_text(text)
    return fricon.load(folder / f"{name}.toml")


def uniform_tension(points):
    """The exact displacement of uniform tension sigma along y, zero at the supports [m]."""
    strain = SIGMA / E
    return np.column_stack([-NU * strain * points[:, 0], strain * points[:, 1],
                            -NU * strain * points[:, 2]])


def error_against_uniform_tension(r):
    exact = uniform_tension(np.asarray(r.points))
    return np.abs(np.asarray(r.displacement) - exact).max() / np.abs(exact).max()


def test_a_curve_holds_the_edge_exactly(tmp_path):
    r = fricon.solve(plate(tmp_path, 0.1, [("x0", "x"), ("edge", "y")]), threads=1)
    assert r.converged
    assert error_against_uniform_tension(r) < 1e-8


def test_points_hold_what_they_are_given(tmp_path):
    # u_x = 0 at two corners of x = 0 instead of the face: with the edge, still every rigid
    # motion held, and the same uniform tension (its u_x vanishes on all of x = 0).
    r = fricon.solve(plate(tmp_path, 0.1, [("origin", "x"), ("far_corner", "x"), ("edge", "y")]),
                     threads=1)
    assert r.converged
    assert error_against_uniform_tension(r) < 1e-8


def test_the_edge_is_the_limit_of_a_thin_strip(tmp_path):
    widths = [0.2, 0.1, 0.05]
    errors = []
    for w in widths:
        edge = fricon.solve(plate(tmp_path, w, [("x0", "x"), ("edge", "y")]), threads=1)
        strip = fricon.solve(plate(tmp_path, w, [("x0", "x"), ("strip", "y")]), threads=1)
        assert edge.converged and strip.converged
        assert np.asarray(edge.points).shape == np.asarray(strip.points).shape  # one mesh
        scale = np.abs(np.asarray(edge.displacement)).max()
        errors.append(np.abs(np.asarray(strip.displacement) -
                             np.asarray(edge.displacement)).max() / scale)
    # The strip's misfit is sigma/E w against a largest displacement of sigma/E (at y = 1): the
    # relative difference is about w, and halves with it.
    for w, error in zip(widths, errors):
        assert error < 1.05 * w, (widths, errors)
    for wider, narrower in zip(errors, errors[1:]):
        assert narrower < 0.6 * wider, errors


def test_a_curve_is_no_surface_for_a_traction(tmp_path):
    p = plate(tmp_path, 0.1, [("x0", "x"), ("edge", "y")])
    p.traction.append({"boundary": "edge", "value": [0.0, 1.0, 0.0]})
    with pytest.raises(fricon.InputError, match="boundary 'edge' is a curve"):
        fricon.solve(p, threads=1)
