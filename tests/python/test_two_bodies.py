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
    with pytest.raises(fricon.InputError, match="contact\\[1\\].model"):
        p.contact = [p.contact[0], {"boundary": "lower_top"}]  # Tresca: another model
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
