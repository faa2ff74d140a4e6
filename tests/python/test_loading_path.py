"""Loading paths from Python: the same run as the command line, a callback per step, the steps'
table, and a stop from the callback that keeps the steps done."""
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
