#!/usr/bin/python3
"""A rigid ball pressed into a block (examples/obstacles/ball-block.toml): a mesh refinement study
against Hertz, and the cost of the contact against one linear solve of the same mesh.

    /usr/bin/python3 bench/obstacle_bench.py build/apps/fricon/fricon \
        [--size-factors 1.6 1.25 1 0.8] [--ratio-size-factor 0.84] [--repeat N] [--out DIR] \
        [--markdown] [--threads N]

The problem: a rigid ball (contact.obstacle kind "sphere", R = 10 mm) moved 1 um into a steel
block (E = 200 GPa, nu = 0.3), frictionless, a quarter model; one `fricon solve --set
mesh.size_factor=X` per mesh. Hertz for the prescribed indentation delta, E* = E / (1 - nu^2):
    P = (4/3) E* sqrt(R) delta^(3/2),  a = sqrt(R delta),  p0 = 3 P / (2 pi a^2).

Refinement study, one row per size factor of --size-factors: the sizes (n_primal, the patches,
those pressed, the candidates of the contact search), the cost (products with Q, QP and outer
iterations, time_s of report.json, the peak resident memory) and the errors against Hertz of
  P        4 x the quarter's force on the ball (report.json's pair "force", z),
  a, p0    a least-squares fit of p^2 = p0^2 (1 - r^2/a^2) over the pressed patches (area
           weights), as tests/regression/check_obstacles.py,
  a_2nd    the contact radius from the pressure's second moment, a^2 = 5/2 int p r^2 / int p,
then the observed orders of each error between consecutive meshes against h ~ n_primal^(-1/3),
order = log(e1 / e2) / log(h1 / h2). The force's error has a part that no mesh removes (a / R =
0.01 and the finite block: a few tenths of a percent), so its order falls on fine meshes; the
fitted a and p0 scatter with the patches' layout and have no clean order.

Cost study, at --ratio-size-factor (0.84: about 150k unknowns): the same mesh with and without
contact (a copy of the problem file without its [contact] table: one assembly, factorization
and solve of the same K; hertz_bench.py's comparison), --repeat times alternated, the fastest
time_s of each kept, and the contact run again with geometric updates forced
(contact.geometry_tolerance = 1e-9, which the first solve does not meet: theory.md §2.11): the
process wall times and time_s and their ratios to the linear run, the updates made, the peak
memory, the solver's counts of the contact runs (outer iterations, QP steps, products
with Q, solves with K, candidate patches and search rounds) and the time of every phase.

Every run must converge, or the script stops with exit code 1 before printing any table. Results
go to --out DIR or to a temporary folder removed at the end. The header gives the machine's load
average at the start: timings mean little on a busy machine. The program must not change during
the study (it stops if its file does).
"""
import argparse
import csv
import math
import os
import pathlib
import subprocess
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import hertz_bench as hb  # noqa: E402  (its runner, its copy without [contact], its tables)

ROOT = pathlib.Path(__file__).resolve().parents[1]
BALL = ROOT / "examples" / "obstacles" / "ball-block.toml"
QUARTER = 4.0  # the model's share of the whole
PHASES = hb.PHASES
# The cost study's run with geometric updates: a tolerance that the first solve does not meet
# (its linearized gap is about 1e-6 of the normal displacement off the true one), so that at least
# one update is made.
UPDATE_TOLERANCE = 1e-9


def patches_of(folder):
    """patches.csv: x, y, area, lambda_n as arrays, and "pressed" (state not "separated")."""
    rows = hb.read_patches(folder)
    with open(folder / "patches.csv", newline="") as f:
        rows["pressed"] = np.array([r["state"] != "separated" for r in csv.DictReader(f)])
    return rows


def ellipse_fit(s, p, w):
    """Weighted least squares of p^2 = p0^2 (1 - s^2 / a^2), a line in s^2: (p0, a)."""
    design = np.c_[np.ones_like(s), s**2] * np.sqrt(w)[:, None]
    (c0, c1), *_ = np.linalg.lstsq(design, p**2 * np.sqrt(w), rcond=None)
    if not (c0 > 0 and c1 < 0):
        raise hb.RunFailed(f"the pressures are no ellipse: p^2 = {c0:.4e} + {c1:.4e} s^2")
    return math.sqrt(c0), math.sqrt(-c0 / c1)


def hertz_errors(report, folder):
    pair = report["pairs"][0]
    sphere = pair["obstacle_geometry"]
    radius, delta = sphere["radius"], -sphere["displacement"][2]
    material = report["problem"]["material"]
    e_star = material["young"] / (1.0 - material["poisson"] ** 2)
    P_h = 4.0 / 3.0 * e_star * math.sqrt(radius) * delta**1.5
    a_h = math.sqrt(radius * delta)
    p0_h = 3.0 * P_h / (2.0 * math.pi * a_h**2)
    pt = patches_of(folder)
    r = np.hypot(pt["x"], pt["y"])
    on = pt["pressed"]
    p0, a = ellipse_fit(r[on], pt["lambda_n"][on], pt["area"][on])
    load = float(np.sum(pt["lambda_n"] * pt["area"]))
    a2 = math.sqrt(2.5 * float(np.sum(pt["lambda_n"] * pt["area"] * r**2)) / load)
    P = -QUARTER * pair["force"][2]
    return {"P": P, "P_h": P_h, "a_h": a_h, "p0_h": p0_h, "n_pressed": int(on.sum()),
            "n_patches": len(on), "P_err": P / P_h - 1.0, "a_err": a / a_h - 1.0,
            "p0_err": p0 / p0_h - 1.0, "a2_err": a2 / a_h - 1.0}


def refinement_section(runs, markdown):
    rows = []
    for sf, rep, h in runs:
        rows.append([f"{sf:g}", str(rep["n_primal"]), str(h["n_patches"]), str(h["n_pressed"]),
                     hb.opt(rep, "n_candidate_patches"), str(rep["n_mult"]),
                     str(rep["qp_iterations"]), str(rep["outer_iterations"]),
                     f"{rep['time_s']:.2f}", f"{rep['peak_mib']:.0f}", f"{h['P']:.4e}",
                     f"{100 * h['P_err']:+.2f}", f"{100 * h['a_err']:+.2f}",
                     f"{100 * h['p0_err']:+.2f}", f"{100 * h['a2_err']:+.2f}"])
    headers = ["size_factor", "n_primal", "n_patches", "pressed", "n_candidate", "n_mult",
               "QP its", "outer", "time_s [s]", "peak RSS [MiB]", "P [N]", "P err [%]",
               "a err [%]", "p0 err [%]", "a_2nd err [%]"]
    out = [hb.table(headers, rows, markdown), ""]
    by_size = sorted(runs, key=lambda run: run[1]["n_primal"])
    rows = []
    for (sf1, r1, h1), (sf2, r2, h2) in zip(by_size, by_size[1:]):
        m1, m2 = r1["n_primal"] ** (-1.0 / 3.0), r2["n_primal"] ** (-1.0 / 3.0)
        rows.append([f"{sf1:g} -> {sf2:g}", f"{m1 / m2:.3f}"] +
                    [hb.order(abs(h1[k]), abs(h2[k]), m1, m2)
                     for k in ("P_err", "a_err", "p0_err", "a2_err")])
    if rows:
        out += ["Observed orders between consecutive meshes, against h ~ n_primal^(-1/3) "
                "(order = log(e1/e2) / log(h1/h2)):", "",
                hb.table(["size_factor", "h1/h2", "order P", "order a", "order p0",
                          "order a_2nd"], rows, markdown)]
    return out


def cost_section(sf, with_c, updated, without, markdown):
    headers = ["size_factor", "run", "n_primal", "geometric updates", "process contact [s]",
               "process linear [s]", "ratio (process)", "time_s contact [s]", "time_s linear [s]",
               "ratio (time_s)", "peak RSS contact [MiB]", "peak RSS linear [MiB]"]
    rows = []
    for label, c in (("default", with_c), (f"tolerance {UPDATE_TOLERANCE:g}", updated)):
        rows.append([f"{sf:g}", label, str(c["n_primal"]),
                     str(c.get("geometry", {}).get("updates", "-")), f"{c['wall_s']:.2f}",
                     f"{without['wall_s']:.2f}", f"{c['wall_s'] / without['wall_s']:.2f}",
                     f"{c['time_s']:.2f}", f"{without['time_s']:.2f}",
                     f"{c['time_s'] / without['time_s']:.2f}", f"{c['peak_mib']:.0f}",
                     f"{without['peak_mib']:.0f}"])
    out = [hb.table(headers, rows, markdown), ""]
    counts = ["outer_iterations", "qp_iterations", "n_mult", "n_kinv", "n_dual",
              "n_candidate_patches", "search_rounds"]
    out += ["Solver counts of the contact runs (report.json; with updates, of every solve):", "",
            hb.table(["run"] + counts,
                     [[label] + [hb.opt(c, k) for k in counts]
                      for label, c in (("default", with_c), ("updated", updated))], markdown), ""]
    named = {p for rep in (with_c, updated, without) for p in rep.get("timings", {})}
    phases = [p for p in PHASES if p in named] + sorted(named - set(PHASES))
    rows = []
    for label, rep in (("contact", with_c), ("updated", updated), ("linear", without)):
        t = rep.get("timings", {})
        rows.append([label] + [f"{t[p]:.3f}" if p in t else "-" for p in phases] +
                    [f"{rep['time_s'] - sum(t.values()):.3f}", f"{rep['time_s']:.3f}"])
    out += ["Time per phase [s] (report.json timings; other = time_s less their sum):", "",
            hb.table(["run"] + phases + ["other", "time_s"], rows, markdown)]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon", help="the fricon program")
    ap.add_argument("--size-factors", type=float, nargs="+", default=[1.6, 1.25, 1.0, 0.8],
                    metavar="X", help="refinement study (default: 1.6 1.25 1 0.8)")
    ap.add_argument("--ratio-size-factor", type=float, default=0.84, metavar="X",
                    help="cost study: contact against one linear solve (default 0.84, about "
                    "150k unknowns; 0: none)")
    ap.add_argument("--repeat", type=int, default=1, metavar="N",
                    help="cost study: alternate the two runs N times, keep the fastest of each")
    ap.add_argument("--out", type=pathlib.Path, help="keep the results here (default: a "
                    "temporary folder, removed at the end)")
    ap.add_argument("--markdown", action="store_true", help="print the tables as Markdown")
    ap.add_argument("--threads", type=int, help="fricon --threads N (default: fricon's choice)")
    opts = ap.parse_args()
    if any(x <= 0 for x in opts.size_factors) or opts.ratio_size_factor < 0:
        ap.error("size factors must be > 0")
    if opts.repeat < 1:
        ap.error("--repeat must be >= 1")
    load = os.getloadavg()[0]
    out, tmp = hb.results_folder(opts.out, "fricon-obstacle-bench-")
    fricon = str(pathlib.Path(opts.fricon).resolve()) if os.sep in opts.fricon else opts.fricon

    def progress(what, rep):
        print(f"obstacle_bench: {what}: n_primal {rep['n_primal']}, time_s {rep['time_s']:.2f} s, "
              f"peak {rep['peak_mib']:.0f} MiB", file=sys.stderr, flush=True)

    try:
        run = hb.stamped_runner(fricon, opts.threads)

        version = subprocess.run([fricon, "--version"], capture_output=True, text=True)
        if version.returncode != 0:
            raise hb.RunFailed(f"{fricon} --version: exit code {version.returncode}")
        runs = []
        for sf in opts.size_factors:
            folder = out / f"refine-sf{sf:g}"
            rep = run(BALL, folder, sf)
            runs.append((sf, rep, hertz_errors(rep, folder)))
            progress(f"refinement, size_factor {sf:g}", rep)
        cost = None
        if opts.ratio_size_factor > 0:
            sf = opts.ratio_size_factor
            bare = out / "ball-block-no-contact.toml"
            hb.write_without_contact(BALL, bare)
            with_c = updated = without = None
            for i in range(opts.repeat):
                c = run(BALL, out / f"cost-sf{sf:g}-contact", sf)
                progress(f"cost, size_factor {sf:g}, contact ({i + 1}/{opts.repeat})", c)
                u = run(BALL, out / f"cost-sf{sf:g}-updated", sf,
                        (f"contact.geometry_tolerance={UPDATE_TOLERANCE!r}",))
                progress(f"cost, size_factor {sf:g}, updated ({i + 1}/{opts.repeat})", u)
                if u.get("geometry", {}).get("updates", 0) < 1:
                    raise hb.RunFailed("the run with geometric updates made none")
                updated = hb.fastest(updated, u)
                n = run(bare, out / f"cost-sf{sf:g}-linear", sf)
                progress(f"cost, size_factor {sf:g}, linear ({i + 1}/{opts.repeat})", n)
                with_c, without = hb.fastest(with_c, c), hb.fastest(without, n)
            if with_c["n_primal"] != without["n_primal"]:
                raise hb.RunFailed(f"size_factor {sf:g}: not the same mesh with and without "
                                   f"contact ({with_c['n_primal']} and {without['n_primal']})")
            cost = (sf, with_c, updated, without)
    except (hb.RunFailed, OSError) as e:
        sys.exit(f"obstacle_bench: {e}\nobstacle_bench: FAILED, no table printed")
    finally:
        if tmp is not None:
            tmp.cleanup()

    md = opts.markdown
    reports = [r for _, r, _ in runs] + (list(cost[1:]) if cost else [])
    threads = sorted({str(r["factor"]["blas_threads"]) for r in reports if "factor" in r})
    h = runs[0][2]
    lines = [f"Rigid ball on a block ({BALL.relative_to(ROOT)}), default solver settings; "
             f"{version.stdout.strip()}, BLAS threads {', '.join(threads) or '-'}; load average "
             f"at the start {load:.2f} on {os.cpu_count()} cores", "",
             f"Refinement study against Hertz for the prescribed indentation (P = {h['P_h']:.4e} "
             f"N, a = {h['a_h'] * 1e3:.4f} mm, p0 = {h['p0_h']:.4e} Pa):", ""]
    lines += refinement_section(runs, md)
    if cost:
        best = f", the fastest of {opts.repeat} alternated runs each" if opts.repeat > 1 else ""
        lines += ["", "The whole contact run against one linear solve of the same mesh (the "
                  f"problem file without [contact]{best}):", ""]
        lines += cost_section(*cost, md)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
