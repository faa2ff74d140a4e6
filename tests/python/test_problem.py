"""fricon.load / fricon.Problem: the problem file's keys as attributes, validated by the library."""
import pytest

import fricon
from conftest import PAPER_BRICK


def test_attributes_are_the_keys_of_the_file():
    p = fricon.load(PAPER_BRICK)
    assert p.material.young == 21.19e10
    assert p.contact.friction.param == 6.0e4
    assert p.contact.friction.law == "paper"
    assert p.solver.qp_rtol == 1.0e-6           # in the file
    assert p.solver.warm_start is True          # a default, not in the file
    assert p.mesh.cells == [12, 4, 4]
    assert len(p.traction) == 2 and p.traction[1].boundary == "z1"
    assert p.dirichlet[0].components == "xyz"
    assert p.to_dict()["contact"]["slip_bound"] == 2.0e7


def test_assignment_changes_the_problem():
    p = fricon.load(PAPER_BRICK)
    p.contact.friction.param = 3.0e4
    p.mesh.cells = [24, 8, 8]
    p.traction[0].value = [0.0, 0.0, 1.0e7]
    assert p.contact.friction.param == 3.0e4
    assert p.mesh.cells == [24, 8, 8]
    assert p.traction[0].value == [0.0, 0.0, 1.0e7]


@pytest.mark.parametrize("key, value, fragment", [
    ("material.young", -1.0, "material.young: expected a positive number [Pa], got -1"),
    ("material.poisson", 0.5, "material.poisson"),
    ("solver.outer_max", "many", "solver.outer_max"),
    ("solver.qp_rtol", 2.0, "solver.qp_rtol"),
    ("mesh.cells", [12, 4], "mesh.cells"),
    ("contact.friction.law", "coulomb-ish", "contact.friction.law"),
    ("material.yuong", 1.0, "did you mean 'material.young'"),
])
def test_a_bad_value_raises_naming_the_key_and_changes_nothing(key, value, fragment):
    p = fricon.load(PAPER_BRICK)
    before = p.to_dict()
    with pytest.raises(ValueError) as e:
        p.set(key, value)
    assert isinstance(e.value, fricon.InputError)
    assert fragment in str(e.value), str(e.value)
    assert key.split(".")[0] in str(e.value)
    assert p.to_dict() == before


def test_the_message_says_where_the_value_came_from():
    p = fricon.load(PAPER_BRICK)
    with pytest.raises(fricon.InputError, match=r"^fricon.Problem material.young=-5.0: "):
        p.material.young = -5.0


def test_a_problem_from_scratch_equals_the_file():
    p = fricon.Problem()
    p.title = "Paper brick, n = 4"
    p.mesh = {"kind": "brick", "size": [3.0, 1.0, 1.0], "cells": [12, 4, 4]}
    p.material = {"young": 21.19e10, "poisson": 0.277}
    p.dirichlet.append({"boundary": "x0"})
    p.traction.append({"boundary": "x1", "value": [1.0e7, 0.0, 2.0e7]})
    p.traction.append({"boundary": "z1", "value": [0.0, 0.0, -3.0e7]})
    p.contact = {"boundary": "z0", "slip_bound": 2.0e7}
    p.contact.friction = fricon.FrictionLaw.paper(6.0e4)
    p.output.dir = "results/paper-brick"
    assert p.to_dict() == fricon.load(PAPER_BRICK).to_dict()


def test_absent_keys_say_how_to_add_them():
    p = fricon.Problem()
    with pytest.raises(AttributeError, match="contact"):
        p.contact.boundary


def test_a_file_that_does_not_exist_is_an_input_error(tmp_path):
    with pytest.raises(fricon.InputError, match="cannot open the problem file"):
        fricon.load(tmp_path / "missing.toml")


def test_a_malformed_file_names_line_and_column(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[mesh]\nkind = \"brick\"\ncells = [1, 2\n[material]\n")
    with pytest.raises(fricon.InputError, match=r"bad.toml:\d+:\d+: invalid TOML"):
        fricon.load(bad)


def test_a_mesh_kind_arrays_needs_a_mesh():
    p = fricon.Problem()
    with pytest.raises(fricon.InputError, match="given by code"):
        p.mesh = {"kind": "arrays"}


def test_save_writes_a_problem_file_the_command_line_solves_alike(fricon_exe, tmp_path):
    from conftest import numbers_of, run_cli

    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.expression("0.1 + 0.4*exp(-t/5e-5)")
    p.solver.qp_rtol = 1e-8
    p.save(tmp_path / "saved.toml")
    assert fricon.load(tmp_path / "saved.toml").to_dict() == p.to_dict()
    rc, cli = run_cli(fricon_exe, tmp_path / "saved.toml", tmp_path / "cli")
    assert rc == 0
    ours = numbers_of(fricon.solve(p, threads=1).report)
    assert ours == numbers_of(cli)


def test_what_code_gave_cannot_be_saved(tmp_path):
    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.function(lambda t: 0.3 + 0 * t)
    with pytest.raises(fricon.InputError, match="cannot be written to a problem file"):
        p.save(tmp_path / "x.toml")
    assert not (tmp_path / "x.toml").exists()
