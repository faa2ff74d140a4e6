"""The Python examples run as a user runs them, and say what they should."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

from conftest import ROOT

EXAMPLES = ROOT / "examples" / "python"


def run(script, tmp_path, *args):
    out = tmp_path / (script.stem + ".png")
    proc = subprocess.run([sys.executable, str(script), "--out", str(out), *args],
                          capture_output=True, text=True, cwd=tmp_path, env=dict(os.environ),
                          timeout=240)
    assert proc.returncode == 0, proc.stderr
    assert out.stat().st_size > 10_000  # a rendered figure
    return proc.stdout


def test_parameter_study(tmp_path):
    out = run(EXAMPLES / "parameter_study.py", tmp_path)
    rows = [line.split() for line in out.splitlines() if re.match(r"^\s+\d", line)]
    assert len(rows) == 15  # three laws x five slip bounds
    # A larger slip bound g lets less slip: max ||w_t|| falls with g for every law.
    for law in range(3):
        slips = [float(r[4]) for r in rows[5 * law:5 * law + 5]]
        assert slips == sorted(slips, reverse=True), slips


def test_friction_fit(tmp_path):
    out = run(EXAMPLES / "friction_fit.py", tmp_path)
    a, b, c = map(float, re.search(r"F\(t\) = ([\d.]+) \+ ([\d.]+) exp\(-t / ([\d.e+-]+) m\)",
                                    out).groups())
    # The fit recovers the law behind the noisy points (0.15 + 0.2 exp(-t/2e-5)).
    assert a == pytest.approx(0.15, abs=0.02) and b == pytest.approx(0.2, abs=0.03)
    assert c == pytest.approx(2e-5, rel=0.3)
    slips = [float(x) for x in re.findall(r"max \|\|w_t\|\| = ([\d.e+-]+) m", out)]
    assert len(slips) == 2 and slips[0] == pytest.approx(slips[1], rel=0.1)
