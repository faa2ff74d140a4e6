"""Curved rigid obstacles from Python (theory.md §2.11), as a user sweeps them: a ball pressed
into a block at several depths; the truths are outside the solver's own output:
  - equilibrium: the force of the obstacle on the block is the opposite of the clamp's reaction;
  - geometry: a rigid ball presses only where it overlaps the undeformed block, within
    sqrt(2 R delta) of its axis (plus a patch);
  - the report names the obstacle's kind, its parameters and its displacement;
  - a path written as rows [fx, fy, fz] is the same path written flat."""
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
