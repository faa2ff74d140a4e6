#!/usr/bin/python3
"""Floating bodies: the cost of solving a body through its free rigid motions against the same
mesh with those motions held by Dirichlet conditions (theory.md §2.10, §4.6).

    /usr/bin/python3 bench/floating_bench.py build/apps/fricon/fricon [--repeat N] [--out DIR]
        [--markdown]

For each example of examples/floating (nafems-punch-frictionless, nafems-punch-coulomb,
free-block) two runs of `fricon solve`, alternated --repeat times (the fastest time_s of each
kept):
  floating  the example as it is: the punch floats in z, the free block in all six motions;
  held      the same file with the floating motions held: the loaded top face (punch_top, z1)
            gets a [[dirichlet]] entry prescribing the rigid displacement the floating run
            found there (its amplitudes in report.json "bodies": z for the punch, the three
            translations for the block) instead of its traction. The mesh, the contact
            pairs, the patches and the friction are the same; the contact state is close.
Printed per example: n_primal, time_s of both runs and their ratio (target <= 1.3), the products
with the dual Hessian (n_mult) and their ratio (target <= 2), the QP steps, the solves with K,
SMALSE-M's outer steps, the time of the qp phase, and the peak resident memory of each process.
Every run must converge, or the script stops with exit code 1 before printing; a missed target is
printed, never an error. The header gives the machine's load average at the start.
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples" / "floating"
CASES = ("nafems-punch-frictionless", "nafems-punch-coulomb", "free-block")
TIME_TARGET = 1.3     # time_s floating / held
PRODUCT_TARGET = 2.0  # n_mult floating / held


def run(exe, problem, out, sets=()):
    """One `fricon solve`; returns (report.json, peak resident memory [MiB])."""
    cmd = [exe, "solve", str(problem), "--out", str(out), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    with open(out.parent / (out.name + ".log"), "w") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(proc.pid, 0)
    report = out / "report.json"
    if os.waitstatus_to_exitcode(status) != 0 or not report.exists():
        sys.exit(f"floating_bench: {' '.join(cmd)} failed (exit "
                 f"{os.waitstatus_to_exitcode(status)}); see {out}.log")
    r = json.loads(report.read_text())
    if r["status"] != "converged":
        sys.exit(f"floating_bench: {problem} did not converge: {r['message']}")
    return r, usage.ru_maxrss / 1024.0


def held_copy(case, report, folder):
    """The example with its floating motions held at the displacement the floating run found on
    the loaded face, written into `folder` (the mesh file named by its absolute path)."""
    text = (EXAMPLES / f"{case}.toml").read_text()
    text = re.sub(r'file = "([^"]+)"', lambda m: f'file = "{EXAMPLES / m.group(1)}"', text)
    floating = [b for b in report["bodies"] if b["floating"]]
    body = floating[0]
    amplitude = dict(zip(body["free_motions"], body["amplitudes"]))
    t = [amplitude.get(f"translation {c}", 0.0) for c in "xyz"]
    face = "punch_top" if case.startswith("nafems") else "z1"
    components = "z" if case.startswith("nafems") else "xyz"
    text += (f'\n[[dirichlet]]\nboundary = "{face}"\ncomponents = "{components}"\n'
             f"value = [{t[0]!r}, {t[1]!r}, {t[2]!r}]\n")
    path = folder / f"{case}-held.toml"
    path.write_text(text)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fricon")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out")
    parser.add_argument("--markdown", action="store_true")
    args = parser.parse_args()
    out = pathlib.Path(args.out) if args.out else pathlib.Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for case in CASES:
        problem = EXAMPLES / f"{case}.toml"
        first, _ = run(args.fricon, problem, out / f"{case}-floating-0")
        held = held_copy(case, first, out)
        # The held file prescribes the loaded face instead of loading it: its traction is 0.
        sets = ["traction[0].value=[0.0,0.0,0.0]"]
        best = {"floating": None, "held": None}
        for k in range(args.repeat):
            for kind, path, s in (("floating", problem, []), ("held", held, sets)):
                r, mem = run(args.fricon, path, out / f"{case}-{kind}-{k + 1}", s)
                if best[kind] is None or r["time_s"] < best[kind][0]["time_s"]:
                    best[kind] = (r, mem)
        rows.append((case, best["floating"], best["held"]))

    print(f"floating bodies against held ones (load average {os.getloadavg()[0]:.2f}, "
          f"fastest of {args.repeat})")
    header = ("example", "n_primal", "time floating [s]", "time held [s]", "ratio",
              "n_mult floating", "n_mult held", "ratio", "QP steps fl/held", "K solves fl/held",
              "SMALSE outer", "qp phase fl/held [s]", "peak MiB fl/held")
    lines = []
    for case, (f, fm), (h, hm) in rows:
        fc, hc = f, h  # the contact report is at the top of report.json
        tr = f["time_s"] / h["time_s"]
        pr = fc["n_mult"] / hc["n_mult"]
        lines.append((case, str(f["n_primal"]), f"{f['time_s']:.3f}", f"{h['time_s']:.3f}",
                      f"{tr:.2f}{'' if tr <= TIME_TARGET else ' (> 1.3)'}",
                      str(fc["n_mult"]), str(hc["n_mult"]),
                      f"{pr:.2f}{'' if pr <= PRODUCT_TARGET else ' (> 2)'}",
                      f"{fc['qp_iterations']}/{hc['qp_iterations']}",
                      f"{fc['n_kinv']}/{hc['n_kinv']}",
                      str(fc.get("balance", {}).get("smalse_outer_iterations", 0)),
                      f"{f['timings'].get('qp', 0):.3f}/{h['timings'].get('qp', 0):.3f}",
                      f"{fm:.0f}/{hm:.0f}"))
    if args.markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        for line in lines:
            print("| " + " | ".join(line) + " |")
    else:
        for line in lines:
            print("  ".join(f"{h}: {v}" for h, v in zip(header, line)))
    if not args.out:
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
