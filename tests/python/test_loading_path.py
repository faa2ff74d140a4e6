"""Loading paths from Python: the same run as the command line, a callback per step, the steps'
table, a stop from the callback that keeps the steps done, and Result.write with the step files
that [output] chooses."""
import pytest

import fricon
from conftest import ROOT, numbers_of, run_cli

HYSTERESIS = ROOT / "examples" / "loading" / "brick-hysteresis.toml"


def test_a_path_equals_the_command_line(fricon_exe, tmp_path):
    rc, cli = run_cli(fricon_exe, HYSTERESIS, tmp_path / "cli")
    assert rc == 0
    seen = []
    r = fricon.solve(HYSTERESIS, threads=1, on_step=seen.append)
    assert r.converged
    assert numbers_of(r.report) == numbers_of(cli)
    n = r.report["problem"]["loading"]["steps"]
    assert [s["step"] for s in seen] == list(range(1, n + 1))
    assert numbers_of(seen) == numbers_of(cli["steps"])
    steps = r.steps
    assert list(steps["step"]) == list(range(1, n + 1))
    assert list(steps["normal_force"]) == [s["normal_force"] for s in cli["steps"]]
    assert "factor.dirichlet[1]" in steps and "tangential_force_x" in steps


def test_a_static_run_has_no_steps():
    r = fricon.solve(ROOT / "examples" / "paper-brick.toml", threads=1)
    assert r.steps is None


def test_a_stop_from_the_callback_keeps_the_steps_done():
    def stop_at_three(step):
        if step["step"] == 3:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough") as stopped:
        fricon.solve(HYSTERESIS, threads=1, on_step=stop_at_three)
    partial = stopped.value.result
    assert not partial.converged
    done = list(partial.steps["step"])
    assert done[:3] == [1, 2, 3]
    assert len(done) < partial.report["problem"]["loading"]["steps"]


def _step_numbers(folder, base="solution", ext=".vtu"):
    return sorted(int(p.stem.split("-")[1]) for p in (folder / "steps").glob(f"{base}-*{ext}"))


def _pvd_steps(folder):
    import xml.etree.ElementTree as ET
    return sorted({int(float(d.get("timestep")))
                   for d in ET.parse(folder / "solution.pvd").getroot().iter("DataSet")})


def test_write_honours_the_chosen_step_files_and_drops_an_earlier_runs(tmp_path):
    # Issue 33, item 7 and the feature "path output that can be thinned": Result.write writes
    # the files of the steps [output] step_files_every chooses (and the last), solution.pvd
    # lists exactly those, steps.csv keeps every step, and steps/ of an earlier run is removed.
    folder = tmp_path / "results"
    (folder / "steps").mkdir(parents=True)
    stale = folder / "steps" / "solution-0999.vtu"
    stale.write_text("an earlier run's step\n")
    (folder / "plots").mkdir()
    (folder / "plots" / "force_displacement.png").write_bytes(b"old")
    r = fricon.solve(HYSTERESIS, threads=1,
                     set={"mesh.cells": [6, 2, 2], "output.step_files_every": 4})
    assert r.converged
    n = r.report["problem"]["loading"]["steps"]
    r.write(str(folder))
    expected = [k for k in range(1, n + 1) if k % 4 == 0 or k == n]
    assert not stale.exists()
    assert not (folder / "plots" / "force_displacement.png").exists()
    assert _step_numbers(folder) == expected
    assert _step_numbers(folder, "patches", ".csv") == expected
    assert _pvd_steps(folder) == expected
    with open(folder / "steps.csv") as f:
        assert len(f.read().splitlines()) == n + 1  # the header and every step


def test_write_into_a_file_raises_oserror(tmp_path):
    # Issue 33, item 6: a results folder that is a file is an OSError naming it.
    r = fricon.solve(ROOT / "examples" / "elastic-brick.toml", threads=1)
    a_file = tmp_path / "a-file"
    a_file.write_text("mine\n")
    with pytest.raises(OSError, match="a-file"):
        r.write(str(a_file))
    assert a_file.read_text() == "mine\n"
