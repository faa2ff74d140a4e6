"""Loading paths from Python: the same run as the command line, a callback per step, the steps'
table, a stop from the callback that keeps the steps done, and Result.write with the step files
that [output] chooses."""
import os
import subprocess
import sys
import time

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


def long_path(n):
    """The hysteresis example's push as a path of n steps (0 -> +5 -> -5 -> +5, in 0.1 mm)."""
    third = n // 3
    up = [5.0 * k / third for k in range(third)]
    down = [5.0 - 10.0 * k / third for k in range(third)]
    back = [-5.0 + 10.0 * k / (n - 2 * third - 1) for k in range(n - 2 * third)]
    return up + down + back


def test_on_step_sees_each_step_before_the_next_starts():
    # Issue 33: the run went on while the callback ran; after it raised at step 5 the run
    # stopped at step 6 to 8, with steps the callback never saw. The worker now waits for
    # the callback: the run ends right after the step it raised on.
    seen = []

    def stop_at_five(step):
        seen.append(step["step"])
        time.sleep(0.05)  # a slow callback: the worker must not run ahead
        if step["step"] == 5:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough") as stopped:
        fricon.solve(HYSTERESIS, threads=1, on_step=stop_at_five)
    partial = stopped.value.result
    assert seen == [1, 2, 3, 4, 5]
    assert list(partial.steps["step"]) == seen
    assert not partial.converged
    assert "interrupted after step 5 of 21" in partial.message


def test_set_changes_the_steps_and_a_path_together():
    # Issue 33: each key of set= was checked on its own, so a path and the steps it must
    # match could not change together (either order failed); two --set do.
    for order in ([("loading.steps", 3), ("dirichlet.1.path", [0, 1, 2])],
                  [("dirichlet.1.path", [0, 1, 2]), ("loading.steps", 3)]):
        r = fricon.solve(HYSTERESIS, set=dict(order), threads=1)
        assert r.converged
        assert list(r.steps["step"]) == [1, 2, 3]
        assert list(r.steps["factor.dirichlet[1]"]) == [0.0, 1.0, 2.0]
    p = fricon.load(HYSTERESIS)
    p.update({"dirichlet.1.path": [0, 1, 2, 3], "loading.steps": 4})
    assert p.loading.steps == 4 and p.dirichlet[1].path == [0.0, 1.0, 2.0, 3.0]
    with pytest.raises(fricon.InputError, match="dirichlet"):
        p.update({"loading.steps": 5})  # the path has 4 factors: refused, nothing changes
    assert p.loading.steps == 4


def test_a_long_path_from_python_costs_what_it_costs_from_a_file():
    # Issue 33: a path set from Python (or --set) was recorded with its whole text per
    # element, and every step copied that record: 2000 steps took 44 s and 352 MB (1.4 s from
    # a file). Reading the problem and setting up its steps must not grow as N^2 or N^3: the
    # problem is read and validated, and a path of 2000 elastic steps solved, in seconds.
    n = 2000
    p = fricon.load(HYSTERESIS)
    start = time.perf_counter()
    p.update({"loading.steps": n, "dirichlet.1.path": long_path(n)})
    assert time.perf_counter() - start < 2.0
    r = fricon.solve(p, set={"solver.qp_rtol": 1e-6, "solver.outer_tol": 1e-5,
                             "solver.certificate_tol": 1e-4}, threads=1)
    assert r.converged
    assert len(r.steps["step"]) == n
    assert time.perf_counter() - start < 20.0  # 0.9 s here; 44 s before


CTRL_C_SCRIPT = """
import os, signal, sys, threading
import fricon
p = fricon.load(sys.argv[1])
n = int(sys.argv[2])
third = n // 3
path = ([5.0 * k / third for k in range(third)] + [5.0 - 10.0 * k / third for k in range(third)]
        + [-5.0 + 10.0 * k / (n - 2 * third - 1) for k in range(n - 2 * third)])
p.update({"loading.steps": n, "dirichlet.1.path": path})
watch = None if sys.argv[4] == "none" else (lambda step: None)
threading.Timer(float(sys.argv[3]), lambda: os.kill(os.getpid(), signal.SIGINT)).start()
try:
    fricon.solve(p, threads=1, on_step=watch)
    print("finished")
except KeyboardInterrupt as e:
    result = getattr(e, "result", None)
    steps = [] if result is None or result.steps is None else list(result.steps["step"])
    print("interrupted", len(steps), steps == list(range(1, len(steps) + 1)))
"""


@pytest.mark.parametrize("on_step", ["none", "callback"])
def test_ctrl_c_during_a_path_raises_keyboard_interrupt_with_the_steps_done(on_step):
    # Issue 33: Ctrl-C during a path's solve killed the interpreter ("terminate called without
    # an active exception", SIGABRT), with or without on_step. In a child process, since the
    # failure is an abort; several delays, since it depends on where the signal lands.
    # The 1000 steps take 0.4 s here: 20000 steps (about 8 s) are still running when
    # the signal comes.
    # Under load (the CI runs tests side by side) the shortest delay may come before the first
    # step ends: every run must stop cleanly with its steps in order, and some must have steps.
    env = dict(os.environ)
    done = []
    for delay in ("1.5", "2.0", "3.0"):
        run = subprocess.run([sys.executable, "-c", CTRL_C_SCRIPT, str(HYSTERESIS), "20000",
                              delay, on_step], capture_output=True, text=True, env=env,
                             timeout=240)
        assert run.returncode == 0, (delay, run.stderr[-2000:])
        assert "terminate called" not in run.stderr
        words = run.stdout.split()
        assert words[0] == "interrupted", run.stdout
        assert words[2] == "True"  # the steps done, in order
        done.append(int(words[1]))
    assert max(done) > 0, done


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
