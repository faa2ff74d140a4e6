"""Determinism: the same input gives bitwise the same results on the same machine and thread count.

Runs the paper's brick twice (n = 4 and n = 8) and compares every result file byte for byte, and
report.json field by field except wall times and the command line.
Usage: check_determinism.py FRICON PROBLEM.toml OUTDIR
"""
import json
import pathlib
import subprocess
import sys

exe, problem, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
TIMING_KEYS = {"timings", "time_s", "command_line", "seconds"}


def strip(value):
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


for cells in ["[12,4,4]", "[24,8,8]"]:
    folders = []
    for run in ["a", "b"]:
        folder = out / f"{cells}-{run}"
        r = subprocess.run([exe, "solve", problem, "--quiet", "--out", str(folder), "--set", f"mesh.cells={cells}"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        folders.append(folder)
    a, b = folders
    for name in ["solution.vtu", "contact.vtu", "contact_nodes.csv", "patches.csv"]:
        assert (a / name).read_bytes() == (b / name).read_bytes(), f"{cells}: {name} differs between runs"
    ra = strip(json.loads((a / "report.json").read_text()))
    rb = strip(json.loads((b / "report.json").read_text()))
    assert ra == rb, f"{cells}: report.json differs between runs"
print("two runs gave bitwise identical results")
