"""Contact pairs from Python: p.contact is the list of pairs ([contact] a list of one), pairs
given as a list solve as the problem file's [[contact]] does, and the results carry the pairs."""
import pytest

import fricon
from conftest import ROOT, numbers_of, run_cli

STACKED = ROOT / "examples" / "two-bodies" / "stacked-blocks.toml"
SHEARED = ROOT / "examples" / "two-bodies" / "sheared-blocks.toml"


def test_one_pair_is_a_table_and_a_list_of_one():
    p = fricon.load(SHEARED)
    assert len(p.contact) == 1
    assert p.contact[0].boundary == p.contact.boundary == "upper_bottom"
    assert [c.obstacle.kind for c in p.contact] == ["body"]
    with pytest.raises(IndexError):
        p.contact[1]


def test_pairs_as_a_list_equal_the_command_line(fricon_exe, tmp_path):
    rc, cli = run_cli(fricon_exe, STACKED, tmp_path / "cli")
    assert rc == 0
    p = fricon.load(STACKED)
    assert [c.obstacle.kind for c in p.contact] == ["body", "plane"]
    p.contact = [p.contact[0], p.contact[1]]  # reassigned as a list: the same problem
    r = fricon.solve(p, threads=1)
    assert r.converged
    assert numbers_of(r.report) == numbers_of(cli)
    assert [q["key"] for q in r.report["pairs"]] == ["contact[0]", "contact[1]"]
    assert set(r.patches["pair"]) == {0.0, 1.0}
    assert set(r.contact_nodes["pair"]) == {0.0, 1.0}


def test_a_pair_added_from_python_is_checked():
    p = fricon.load(SHEARED)
    with pytest.raises(fricon.InputError, match="contact\\[1\\].start_slip_bound"):
        # a pair has a model of its own, and the keys of that model only
        p.contact = [p.contact[0], {"boundary": "lower_top", "start_slip_bound": 1e7}]
    second = {"boundary": "upper_bottom", "model": "coulomb",
              "friction": {"law": "constant", "value": 0.3}}
    with pytest.raises(fricon.InputError, match="contact\\[1\\].boundary.*of its own"):
        p.contact = [p.contact[0], second]  # the same surface twice
    assert len(p.contact) == 1  # a refused assignment changes nothing


def test_one_pair_written_as_contact_entries_is_edited_and_named_as_written():
    # Issue 33: errors about a single [[contact]] entry named the table header and dropped the
    # [0]; its keys, recorded as contact[0].*, are named so, and p.contact.KEY edits them.
    p = fricon.load(ROOT / "examples" / "two-bodies" / "sheared-blocks.toml")
    p.contact.search_distance = 0.002
    assert p.contact.search_distance == 0.002
    p.contact[0].friction.value = 0.25
    assert p.contact.friction.value == 0.25
    with pytest.raises(fricon.InputError) as bad:
        p.contact.search_distance = -1.0
    assert str(bad.value).startswith(
        "fricon.Problem contact.0.search_distance=-1.0: contact[0].search_distance: expected")
    with pytest.raises(fricon.InputError) as bad:
        fricon.solve(p, set={"contact.0.search_distance": 0})
    assert str(bad.value).startswith(
        "--set contact.0.search_distance=0: contact[0].search_distance: expected")
    with pytest.raises(fricon.InputError) as bad:
        p.set("contact.x.y", 1)  # an override's own error names where it came from
    assert str(bad.value).startswith("fricon.Problem contact.x.y=1: 'contact' is an array")


def lower_pair(**friction):
    """The stacked blocks' second pair (the lower block on the plane) with its own friction."""
    return dict({"boundary": "lower_bottom", "patches": "agglomerate",
                 "obstacle": {"kind": "plane", "point": [0.0, 0.0, 0.0],
                              "normal": [0.0, 0.0, 1.0]}}, **friction)


def test_each_pair_has_its_own_model_and_law():
    # The lower pair frictionless in two ways that share the normal response: Tresca with g = 0
    # and Coulomb with F = 0. The upper pair (Coulomb, F = 0.2) must not see the difference,
    # which it would if the pairs shared one model or one law.
    p = fricon.load(STACKED)
    # tight, so that both runs end within round-off of the fixed point (at the defaults the
    # Coulomb certificate, over the Coulomb pairs only, may refine one run and not the other)
    p.solver.outer_tol = 1e-9
    p.solver.qp_rtol = 1e-11
    p.contact = [p.contact[0], lower_pair(model="tresca", slip_bound=0.0,
                                          friction={"law": "paper", "param": 6e4})]
    tresca = fricon.solve(p, threads=1)
    p.contact = [p.contact[0], lower_pair(model="coulomb",
                                          friction={"law": "constant", "value": 0.0})]
    coulomb = fricon.solve(p, threads=1)
    assert tresca.converged and coulomb.converged
    assert tresca.report["model"] == "mixed"
    assert [q["model"] for q in tresca.report["pairs"]] == ["coulomb", "tresca"]
    assert tresca.report["pairs"][0]["friction_law"] != tresca.report["pairs"][1]["friction_law"]
    assert coulomb.report["model"] == "coulomb"
    scale = max(abs(coulomb.patches["lambda_n"]))
    assert max(abs(tresca.patches["lambda_n"] - coulomb.patches["lambda_n"])) < 1e-5 * scale
    upper = tresca.patches["pair"] == 0.0
    for name in ("lambda_t1", "lambda_t2"):
        assert max(abs(tresca.patches[name][upper] - coulomb.patches[name][upper])) < 1e-5 * scale
    assert max(abs(tresca.patches["lambda_t1"][~upper])) == 0.0  # frictionless: no traction
