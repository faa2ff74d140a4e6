"""Shared fixtures of the Python module's tests (run by CTest: tests/CMakeLists.txt).

The environment gives the build: PYTHONPATH holds build/python (the fricon package) and
FRICON_EXE the command-line program, to compare the module with it.
"""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAPER_BRICK = ROOT / "examples" / "paper-brick.toml"


@pytest.fixture(scope="session")
def fricon_exe():
    exe = os.environ.get("FRICON_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("FRICON_EXE (the fricon program) is not set")
    return exe


def run_cli(exe, problem, out, *sets, threads=1):
    """`fricon solve PROBLEM --out OUT --set ...`; returns (exit code, report dict or None)."""
    args = [exe, "--threads", str(threads), "solve", str(problem), "--out", str(out), "--quiet"]
    for s in sets:
        args += ["--set", s]
    rc = subprocess.run(args, capture_output=True, text=True).returncode
    reports = list(pathlib.Path(out).glob("report*.json"))
    return rc, (json.loads(reports[0].read_text()) if reports else None)


# Report entries that depend on the run, not on the answer: times, the command, the source.
_VOLATILE = {"time_s", "timings", "seconds", "command_line", "overrides", "source", "version",
             "threads", "blas_threads", "phases"}


def numbers_of(report):
    """The report without its timings and provenance, for comparing two runs' answers."""
    if isinstance(report, dict):
        return {k: numbers_of(v) for k, v in report.items() if k not in _VOLATILE}
    if isinstance(report, list):
        return [numbers_of(v) for v in report]
    return report
