"""Floating bodies from Python (theory.md §2.10): a parameter study over the push on a free block
converges where friction can hold it, with the friction force equal to the push, and raises
fricon.InputError with both figures where it cannot; the bodies and their free motions are in
the report, as in report.json."""
import pytest

import fricon
from conftest import ROOT

FREE_BLOCK = ROOT / "examples" / "floating" / "free-block.toml"
N = 1.0e6 * 0.2 * 0.1  # the 1 MPa on the block's top [N]
FACE = 0.1 * 0.05      # the back face x = 0, which the push acts on [m^2]


@pytest.mark.parametrize("push", [1.0e6, 2.0e6, 5.6e6])  # 5, 10 and 28 kN against mu N = 6 kN
def test_a_push_study_holds_below_mu_n_and_is_refused_above(push):
    p = fricon.load(FREE_BLOCK)
    p.traction[1].value = [push, 0.0, 0.0]  # Pa
    force = push * FACE
    if force <= 0.3 * N:
        r = fricon.solve(p, threads=1)
        assert r.converged
        [pair] = r.report["pairs"]
        assert pair["tangential_force"][0] == pytest.approx(-force, rel=1e-5)
        [body] = r.report["bodies"]
        assert body["floating"] and len(body["free_motions"]) == 6
    else:
        # mu N = 6 kN along x: the push alone exceeds what friction carries along it
        refused = (r"along \(1, 0, 0\) is [0-9.e+]+ N, "
                   r"but contact and friction can carry at most 6000 N")
        with pytest.raises(fricon.InputError, match=refused):
            fricon.solve(p, threads=1)


def test_a_clamped_body_is_reported_held():
    p = fricon.load(FREE_BLOCK)
    p.dirichlet.append({"boundary": "x1", "components": "xyz"})
    r = fricon.solve(p, threads=1)
    assert r.converged
    [body] = r.report["bodies"]
    assert not body["floating"] and body["free_motions"] == []
