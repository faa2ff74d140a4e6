#!/usr/bin/python3
"""The wheel of examples/geometry: a graded Gmsh mesh with Coulomb friction, at the issue's size.

    /usr/bin/python3 bench/wheel_bench.py build/apps/fricon/fricon [--h-near 0.004] [--markdown]

Copies examples/geometry/wheel.geo with `h_near` set to --h-near (default 0.004 m: about 37,000
tetrahedra and 375 patches) next to wheel.toml in a temporary folder, solves it at the default
solver settings, and prints the sizes, the contact search's candidates, the products with Q over
the run (target <= 5,000), the share of the run spent in the QPs (target <= 25 %), the outer
iterations, the certificate and the time of every phase (report.json "timings"). It also solves
the same mesh with the search off and without scaling (`dual_scaling = "none"`,
`contact_search = "off"`, the path of before) for the ratio of products, and with
qp_rtol = 1e-13 for the accuracy of the default run: the largest difference of a patch pressure,
relative to the peak (target <= 1e-3). Exits 1 if a run fails or is not converged; a missed
target is printed, not an error.
"""
import argparse
import csv
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
GEOMETRY = ROOT / "examples" / "geometry"
PRODUCT_TARGET, QP_SHARE_TARGET, ACCURACY_TARGET = 5000, 0.25, 1e-3


def prepare(folder, h_near):
    geo = (GEOMETRY / "wheel.geo").read_text()
    geo, n = re.subn(r"^h_near = [0-9.eE+-]+;", f"h_near = {h_near};", geo, flags=re.M)
    if n != 1:
        sys.exit("wheel_bench: wheel.geo has no line 'h_near = ...;'")
    (folder / "wheel.geo").write_text(geo)
    shutil.copy(GEOMETRY / "wheel.toml", folder / "wheel.toml")
    return folder / "wheel.toml"


def solve(fricon, toml, out, *sets, may_fail=False):
    """report.json and the patch pressures of a run; with may_fail, a run that ends not
    converged (exit 2) returns its report.not-converged.json and no pressures."""
    args = [fricon, "solve", str(toml), "-q", "-o", str(out)]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True)
    report = out / "report.json"
    if may_fail and r.returncode == 2 and (out / "report.not-converged.json").exists():
        return json.loads((out / "report.not-converged.json").read_text()), None
    if r.returncode != 0 or not report.exists():
        sys.exit(f"wheel_bench: {' '.join(args)}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    rep = json.loads(report.read_text())
    if rep["status"] != "converged":
        sys.exit(f"wheel_bench: {out.name}: {rep['status']}: {rep['message']}")
    with open(out / "patches.csv") as f:
        pressures = [float(row["lambda_n"]) for row in csv.DictReader(f)]
    return rep, pressures


def table(headers, rows, markdown):
    if markdown:
        lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    else:
        widths = [max(len(str(c)) for c in col) for col in zip(headers, *rows)]
        lines = ["  ".join(str(c).rjust(w) for c, w in zip(row, widths))
                 for row in [headers, *rows]]
    print("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("fricon")
    ap.add_argument("--h-near", type=float, default=0.004)
    ap.add_argument("--markdown", action="store_true")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="wheel_bench.") as tmp:
        folder = pathlib.Path(tmp)
        toml = prepare(folder, args.h_near)
        runs = {
            "default": solve(args.fricon, toml, folder / "default"),
            "every patch, unscaled": solve(args.fricon, toml, folder / "before",
                                           'solver.contact_search="off"',
                                           'solver.dual_scaling="none"', may_fail=True),
        }
        _, tight = solve(args.fricon, toml, folder / "tight", "solver.qp_rtol=1e-13")
    version = subprocess.run([args.fricon, "--version"], capture_output=True, text=True).stdout
    print(f"The wheel (examples/geometry/wheel.geo, h_near = {args.h_near} m), Coulomb 0.3; "
          f"{version.strip()}\n")
    rows = []
    for name, (rep, _) in runs.items():
        seconds = rep["timings"]
        qp_share = seconds.get("qp", 0.0) / rep["time_s"]
        rows.append([name, rep["n_tets"], rep["n_primal"], rep["contact"]["n_patches"],
                     rep.get("n_candidate_patches", "-"), rep.get("search_rounds", "-"),
                     rep["outer_iterations"], rep["qp_iterations"], rep["n_mult"],
                     f"{seconds.get('dual', 0.0):.2f}", f"{seconds.get('qp', 0.0):.2f}",
                     f"{qp_share:.1%}", f"{rep['time_s']:.2f}", f"{rep['kkt']['max']:.1e}",
                     rep["status"]])
    table(["run", "tets", "n_primal", "patches", "candidates", "rounds", "outer", "QP steps",
           "n_mult", "dual [s]", "qp [s]", "qp share", "time_s [s]", "KKT max", "status"], rows,
          args.markdown)
    for name, (rep, _) in runs.items():
        if rep["status"] != "converged":
            print(f"{name}: {rep['message']}\n")
    default, pressures = runs["default"]
    before = runs["every patch, unscaled"][0]
    peak = max(tight)
    worst = max(abs(a - b) for a, b in zip(pressures, tight)) / peak
    qp_share = default["timings"].get("qp", 0.0) / default["time_s"]
    fewer = before["n_mult"] / default["n_mult"]
    print(f"products with Q: {default['n_mult']} (target <= {PRODUCT_TARGET}: "
          f"{'met' if default['n_mult'] <= PRODUCT_TARGET else 'NOT met'}); {fewer:.0f}x fewer "
          f"than with every patch unscaled (same stopping test"
          f"{'' if before['status'] == 'converged' else ', which did not converge'})")
    print(f"QP share of the run: {qp_share:.1%} (target <= {QP_SHARE_TARGET:.0%}: "
          f"{'met' if qp_share <= QP_SHARE_TARGET else 'NOT met'})")
    print(f"largest patch-pressure difference from qp_rtol = 1e-13: {worst:.1e} of the peak "
          f"(target <= {ACCURACY_TARGET:g}: {'met' if worst <= ACCURACY_TARGET else 'NOT met'})")


if __name__ == "__main__":
    main()
