"""fricon.solve: the same answers and files as `fricon solve`, progress, interrupts."""
import os
import pathlib
import signal
import threading

import meshio
import numpy as np
import pytest

import fricon
from conftest import PAPER_BRICK, numbers_of, run_cli


def test_solve_of_a_path_equals_the_command_line(fricon_exe, tmp_path):
    rc, cli = run_cli(fricon_exe, PAPER_BRICK, tmp_path / "cli")
    assert rc == 0
    r = fricon.solve(PAPER_BRICK, threads=1)
    assert r.converged and r.message == ""
    assert numbers_of(r.report) == numbers_of(cli)
    assert r.report["outer_iterations"] == cli["outer_iterations"] > 1


def test_an_attribute_change_equals_set(fricon_exe, tmp_path):
    rc, cli = run_cli(fricon_exe, PAPER_BRICK, tmp_path / "cli", "contact.friction.param=3e4",
                      "solver.qp_rtol=1e-8")
    assert rc == 0
    p = fricon.load(PAPER_BRICK)
    p.contact.friction.param = 3e4
    p.solver.qp_rtol = 1e-8
    by_attribute = fricon.solve(p, threads=1)
    by_set = fricon.solve(PAPER_BRICK, set={"contact.friction.param": 3e4,
                                            "solver.qp_rtol": 1e-8}, threads=1)
    assert numbers_of(by_attribute.report) == numbers_of(cli)
    assert numbers_of(by_set.report) == numbers_of(cli)
    assert p.contact.friction.param == 3e4  # set= works on a copy
    assert fricon.load(PAPER_BRICK).contact.friction.param == 6e4


def test_the_arrays_are_those_of_the_files(fricon_exe, tmp_path):
    rc, _ = run_cli(fricon_exe, PAPER_BRICK, tmp_path / "cli")
    assert rc == 0
    r = fricon.solve(PAPER_BRICK, threads=1)
    n, m = r.report["n_nodes"], r.report["n_tets"]
    assert r.points.shape == (n, 3) and r.displacement.shape == (n, 3)
    assert r.tets.shape == (m, 4) and r.stress.shape == (m, 6) and r.von_mises.shape == (m,)
    assert not r.displacement.flags.writeable
    assert np.max(np.linalg.norm(r.displacement, axis=1)) == pytest.approx(
        r.report["max_displacement"], rel=1e-14)
    for name in ("contact_nodes", "patches"):
        csv = np.genfromtxt(tmp_path / "cli" / f"{name}.csv", delimiter=",", names=True,
                            dtype=None, encoding="utf-8")
        table = getattr(r, name)
        assert list(table) == list(csv.dtype.names)
        for column in table:
            if table[column].dtype.kind == "U":
                assert list(table[column]) == list(csv[column])
            else:
                np.testing.assert_array_equal(table[column], csv[column])


def test_the_subdomains_are_those_of_the_file(fricon_exe, tmp_path):
    """Backend tfeti: Result.subdomain is solution.vtu's cell field; the other backends: None."""
    tfeti = ["solver.backend=\"tfeti\"", "solver.subdomains=6"]
    rc, cli = run_cli(fricon_exe, PAPER_BRICK, tmp_path / "cli", *tfeti)
    assert rc == 0
    r = fricon.solve(PAPER_BRICK, set={"solver.backend": "tfeti", "solver.subdomains": 6},
                     threads=1)
    grid = meshio.read(tmp_path / "cli" / "solution.vtu")
    assert r.subdomain.shape == (r.report["n_tets"],)
    np.testing.assert_array_equal(r.subdomain, grid.cell_data["subdomain"][0].ravel())
    assert set(r.subdomain.tolist()) == set(range(cli["feti"]["n_subdomains"]))
    assert fricon.solve(PAPER_BRICK, threads=1).subdomain is None


def test_write_writes_the_files_of_the_command_line(fricon_exe, tmp_path):
    rc, _ = run_cli(fricon_exe, PAPER_BRICK, tmp_path / "cli")
    assert rc == 0
    written = fricon.solve(PAPER_BRICK, threads=1).write(str(tmp_path / "py"))
    names = sorted(pathlib.Path(w).name for w in written)
    assert names == sorted(f.name for f in (tmp_path / "cli").iterdir())
    for name in ("contact_nodes.csv", "patches.csv"):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text()


def test_a_run_that_does_not_converge_says_so(tmp_path):
    r = fricon.solve(PAPER_BRICK, set={"solver.outer_max": 1}, threads=1)
    assert not r.converged
    assert "outer" in r.message or "iteration" in r.message
    assert r.report["status"] == "not_converged"
    names = [pathlib.Path(w).name for w in r.write(str(tmp_path))]
    assert "report.not-converged.json" in names and "report.json" not in names


def test_progress_sees_every_outer_iteration():
    seen = []
    r = fricon.solve(PAPER_BRICK, progress=seen.append, threads=1)
    assert [it.k for it in seen] == list(range(1, r.report["outer_iterations"] + 1))
    assert [it.err for it in seen] == r.report["err_history"]
    assert sum(it.qp_products for it in seen) == r.report["n_mult"]


def test_an_exception_in_progress_stops_the_run_and_propagates():
    class Stop(Exception):
        pass

    def progress(it):
        if it.k == 2:
            raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        fricon.solve(PAPER_BRICK, progress=progress, threads=1)


def test_ctrl_c_raises_keyboard_interrupt_and_the_interpreter_goes_on():
    def interrupt(it):
        if it.k == 2:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        fricon.solve(PAPER_BRICK, progress=interrupt, threads=1)
    assert fricon.solve(PAPER_BRICK, threads=1).converged


def test_ctrl_c_from_outside_during_a_longer_run():
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            fricon.solve(PAPER_BRICK, set={"mesh.cells": [48, 16, 16], "solver.qp_rtol": 1e-10},
                         threads=1)
    finally:
        timer.cancel()
    assert fricon.solve(PAPER_BRICK, threads=1).converged


def test_bad_input_found_by_the_run_is_an_input_error():
    with pytest.raises(fricon.InputError, match="nowhere"):
        fricon.solve(PAPER_BRICK, set={"contact.boundary": "nowhere"})


def test_an_unsupported_body_is_refused_before_it_is_solved():
    p = fricon.Problem()
    p.traction.append({"boundary": "x1", "value": [1.0e6, 0.0, 0.0]})
    with pytest.raises(fricon.InputError, match="rigid motion"):
        fricon.solve(p)
    assert issubclass(fricon.InputError, ValueError)
    assert issubclass(fricon.NumericalError, ArithmeticError)


def test_the_arrays_are_views_of_the_result_not_copies():
    r = fricon.solve(PAPER_BRICK, threads=1)
    a, b = r.displacement, r.displacement
    assert a.ctypes.data == b.ctypes.data  # the same memory each time
    assert isinstance(a.base, fricon.Result) or a.base is not None
    del r
    assert np.isfinite(a).all()  # the view keeps the result alive


def test_the_petsc_backend_in_the_interpreter_gives_the_serial_answer():
    """backend petsc from Python: a job of one rank in this process (docs/parallel.md)."""
    # outer_tol a factor 1.8 or more from every err(k) of the brick (as check_mpi.py's): at 1e-10
    # its err(13), 1.1e-10, lets rounding move the stop by one iteration.
    tight = {"solver.qp_rtol": 1e-12, "solver.outer_tol": 2.5e-10}
    serial = fricon.solve(PAPER_BRICK, set=tight)
    try:
        distributed = fricon.solve(PAPER_BRICK, set={**tight, "solver.backend": "petsc"})
    except fricon.InputError as e:
        assert "built without PETSc" in str(e)
        pytest.skip("this fricon was built without PETSc")
    assert distributed.report["parallel"]["n_ranks"] == 1
    assert distributed.report["outer_iterations"] == serial.report["outer_iterations"]
    scale = np.abs(serial.displacement).max()
    assert np.abs(distributed.displacement - serial.displacement).max() <= 1e-8 * scale
    lam = serial.patches["lambda_n"]
    assert np.abs(distributed.patches["lambda_n"] - lam).max() <= 1e-8 * np.abs(lam).max()
