"""Determinism: the same input gives bitwise the same results on the same machine and thread count.

Runs the paper's brick twice (n = 4 and n = 8) and compares every result file byte for byte, and
report.json field by field except wall times and the command line.
Usage: check_determinism.py FRICON PROBLEM.toml OUTDIR
"""
import common

exe, problem, out = common.arguments(__doc__)
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
        common.solve(exe, problem, folder, f"mesh.cells={cells}")
        folders.append(folder)
    a, b = folders
    for name in ["solution.vtu", "contact.vtu", "contact_nodes.csv", "patches.csv"]:
        assert (a / name).read_bytes() == (b / name).read_bytes(), f"{cells}: {name} differs between runs"
    ra = strip(common.read_report(a))
    rb = strip(common.read_report(b))
    assert ra == rb, f"{cells}: report.json differs between runs"
print("two runs gave bitwise identical results")
