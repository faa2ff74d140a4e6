"""Curved rigid obstacles from Python (theory.md §2.11), as a user sweeps them: a ball pressed
into a block at several depths; the truths are outside the solver's own output:
  - equilibrium: the force of the obstacle on the block is the opposite of the clamp's reaction;
  - geometry: a rigid ball presses only where it overlaps the undeformed block, within
    sqrt(2 R delta) of its axis (plus a patch);
  - the report names the obstacle's kind, its parameters and its displacement;
  - a path written as rows [fx, fy, fz] is the same path written flat;
  - a scratch far beyond the contact radius keeps its normal force only with geometric updates."""
import math

import numpy as np
import pytest

import fricon
from conftest import ROOT

SCRATCH = ROOT / "examples" / "obstacles" / "scratch.toml"
R = 2.0                   # the ball's radius [m]
AXIS = (0.5, 0.5)         # where its axis meets the block's bottom [m]
PATCH = 2 * 1.0 / 20.0    # about two cells of the 20 x 20 bottom: an agglomerate patch [m]


def pressed(delta):
    """scratch.toml as a static run: the ball only pressed delta [m] into the block."""
    p = fricon.load(SCRATCH)
    p.set("contact.obstacle", {"kind": "sphere", "center": [0.5, 0.5, -R], "radius": R,
                               "displacement": [0.0, 0.0, delta]})
    p.set("loading.steps", 1)
    return p


@pytest.mark.parametrize("delta", [5e-3, 1e-2, 2e-2])
def test_a_pressed_ball_is_in_equilibrium_and_presses_only_where_it_overlaps(delta):
    r = fricon.solve(pressed(delta), threads=1)
    assert r.converged
    [pair] = r.report["pairs"]
    assert pair["obstacle"] == "sphere"
    geometry = pair["obstacle_geometry"]
    assert geometry["radius"] == R and geometry["displacement"] == [0.0, 0.0, delta]
    reaction = r.report["reaction_force"]
    force = pair["force"]
    assert force[2] > 0.0
    for c in range(3):
        assert force[c] == pytest.approx(-reaction[c], abs=1e-6 * force[2])
    reach = math.sqrt(2.0 * R * delta) + PATCH
    patches = r.patches
    pressed_patches = patches["lambda_n"] > 0.0
    assert pressed_patches.any()
    distance = np.hypot(patches["x"] - AXIS[0], patches["y"] - AXIS[1])
    assert distance[pressed_patches].max() <= reach, (distance[pressed_patches].max(), reach)


def test_a_path_written_as_rows_is_the_path_written_flat():
    rows = fricon.load(SCRATCH)
    flat = fricon.load(SCRATCH)
    flat.set("contact.obstacle.path", [0, 0, 1, 1, 0, 1, 2, 0, 1, 3, 0, 1])
    a = fricon.solve(rows, threads=1)
    b = fricon.solve(flat, threads=1)
    assert a.converged and b.converged
    assert list(a.steps["normal_force"]) == list(b.steps["normal_force"])
    assert list(a.steps["obstacle.contact_x"]) == pytest.approx([0.0, 0.05, 0.1, 0.15])


def test_a_scratch_keeps_its_normal_force_only_with_geometric_updates():
    # The ball slid 0.15 m, beyond its contact radius (about 0.1 m): with the updates each step
    # is linearized at its own solution and the normal force stays that of the pressed ball
    # (the patches it slides over make it vary by a few per cent); frozen at the first step's
    # linearization, the tangent planes left behind lift the block more and more.
    updated = fricon.solve(fricon.load(SCRATCH), threads=1)
    frozen_problem = fricon.load(SCRATCH)
    frozen_problem.set("contact.geometry_updates", 0)
    frozen = fricon.solve(frozen_problem, threads=1)
    assert updated.converged and frozen.converged
    pressed = updated.steps["normal_force"][0]
    assert frozen.steps["normal_force"][0] == pytest.approx(pressed, rel=1e-9)
    assert max(abs(updated.steps["normal_force"] / pressed - 1.0)) < 0.06
    assert frozen.steps["normal_force"][-1] > 1.5 * pressed
    # Sliding, the friction force is mu times the normal force (Coulomb, mu = 0.3).
    ratio = updated.steps["tangential_force_x"][1:] / updated.steps["normal_force"][1:]
    assert ratio == pytest.approx(0.3, rel=2e-2)
    assert any("linearized gap" in w for w in frozen.report["warnings"])
