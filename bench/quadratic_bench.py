#!/usr/bin/python3
"""Quadratic against linear tetrahedra on Hertz's hemisphere: the time to reach a given accuracy
of the contact radius and the peak pressure, and the cost of a quadratic run against one linear
solve of the same quadratic mesh.

    /usr/bin/python3 bench/quadratic_bench.py build/apps/fricon/fricon \
        [--linear-size-factors 1 0.7 0.5] [--quadratic-size-factors 2 1.5 1] \
        [--ratio-size-factor 1.5] [--repeat N] [--out DIR] [--markdown] [--threads N]

The problem is examples/geometry/hertz-hemisphere.toml (an elastic hemisphere, R = 50 mm,
E = 2e11 Pa, nu = 0.3, pressed without friction on a rigid plane), solved at each size factor
with `--set mesh.order=1` (4-node tetrahedra) and `--set mesh.order=2` (10-node tetrahedra, the
.geo meshed by Gmsh at order 2: edge nodes on the sphere). Against Hertz's formulas for the run's
total force P (bench/hertz_bench.py's measures):
  a_h    the contact radius from the pressure's second moment, its error against
         a = (3 P R / (4 E*))^(1/3)
  p_max  the largest patch pressure, its error against p0 = 3 P / (2 pi a^2)
  L1     sum(A |lambda_n - p(r)|) / sum(A p(r)) over the patches

Time to accuracy: for each order, the fastest run (time_s of report.json) whose |a_h error| <= 1 %
and |p_max error| <= 2 % (the issue's targets), and the ratio of the two times (order 2 should
be faster). A series that never reaches both is reported as such, with its best errors.

Cost at --ratio-size-factor (order 2): the same mesh with and without contact (a copy of the
problem file without its [contact] table: one assembly, factorization and solve of the same K),
--repeat times alternated, the fastest time_s of each kept; target ratio <= 1.3.

Every run must converge, or the script stops with exit code 1 before printing any table. Results
go to --out DIR or to a temporary folder removed at the end. The header gives the machine's load
average at the start: timings mean little on a busy machine.
"""
import argparse
import os
import pathlib
import subprocess
import sys

import hertz_bench as hb

HEMISPHERE = hb.PROBLEMS["hemisphere"][0]
RADIUS_TARGET = 0.01    # |a_h / a - 1| (the 1 %)
PRESSURE_TARGET = 0.02  # |p_max / p0 - 1| (2 %)
RATIO_TARGET = 1.3      # a quadratic run against one linear solve of its mesh


def accurate(h):
    return abs(h["a_err"]) <= RADIUS_TARGET and abs(h["pmax_err"]) <= PRESSURE_TARGET


def study_section(runs, markdown):
    headers = ["order", "size_factor", "n_primal", "n_patches", "n_mult", "time_s [s]",
               "peak RSS [MiB]", "a_h err [%]", "p_max err [%]", "L1 [%]", "within 1 % / 2 %"]
    rows = [[str(o), f"{sf:g}", str(rep["n_primal"]), str(rep["n_dual"] // 3), str(rep["n_mult"]),
             f"{rep['time_s']:.2f}", f"{rep['peak_mib']:.0f}", f"{100 * h['a_err']:+.2f}",
             f"{100 * h['pmax_err']:+.2f}", f"{100 * h['l1']:.2f}", "yes" if accurate(h) else "no"]
            for o, sf, rep, h in runs]
    out = [hb.table(headers, rows, markdown), ""]
    best = {}
    for o, sf, rep, h in runs:
        if accurate(h) and (o not in best or rep["time_s"] < best[o][1]["time_s"]):
            best[o] = (sf, rep)
    lines = []
    for o in (1, 2):
        if o in best:
            sf, rep = best[o]
            lines.append(f"order {o}: fastest run within 1 % / 2 %: size_factor {sf:g}, "
                         f"n_primal {rep['n_primal']}, {rep['time_s']:.2f} s")
        else:
            lines.append(f"order {o}: no run within 1 % / 2 % (refine further)")
    if 1 in best and 2 in best:
        ratio = best[1][1]["time_s"] / best[2][1]["time_s"]
        lines.append(f"time to accuracy, order 1 / order 2: {ratio:.2f} "
                     f"({'order 2 wins' if ratio > 1 else 'order 1 wins'})")
    return out + lines


def cost_section(sf, with_c, without, markdown):
    ratio = with_c["time_s"] / without["time_s"]
    headers = ["size_factor", "n_primal", "time_s contact [s]", "time_s linear [s]", "ratio",
               "process contact [s]", "process linear [s]", "peak RSS contact [MiB]",
               "peak RSS linear [MiB]", "n_mult", "n_kinv"]
    row = [f"{sf:g}", str(with_c["n_primal"]), f"{with_c['time_s']:.2f}",
           f"{without['time_s']:.2f}", f"{ratio:.2f}", f"{with_c['wall_s']:.2f}",
           f"{without['wall_s']:.2f}", f"{with_c['peak_mib']:.0f}", f"{without['peak_mib']:.0f}",
           hb.opt(with_c, "n_mult"), hb.opt(with_c, "n_kinv")]
    return [hb.table(headers, [row], markdown), "", f"ratio {ratio:.2f}, "
            + hb.met(ratio, RATIO_TARGET)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon", help="the fricon program")
    ap.add_argument("--linear-size-factors", type=float, nargs="+", default=[1.0, 0.7, 0.5],
                    metavar="X", help="order 1 runs (default: 1 0.7 0.5)")
    ap.add_argument("--quadratic-size-factors", type=float, nargs="+", default=[2.0, 1.5, 1.0],
                    metavar="X", help="order 2 runs (default: 2 1.5 1)")
    ap.add_argument("--ratio-size-factor", type=float, default=1.5, metavar="X",
                    help="cost of an order-2 run against one linear solve (default 1.5; 0: none)")
    ap.add_argument("--repeat", type=int, default=1, metavar="N",
                    help="cost study: alternate the two runs N times, keep the fastest of each")
    ap.add_argument("--out", type=pathlib.Path, help="keep the results here (default: a "
                    "temporary folder, removed at the end)")
    ap.add_argument("--markdown", action="store_true", help="print the tables as Markdown")
    ap.add_argument("--threads", type=int, help="fricon --threads N (default: fricon's choice)")
    opts = ap.parse_args()
    if any(x <= 0 for x in opts.linear_size_factors + opts.quadratic_size_factors) or \
            opts.ratio_size_factor < 0 or opts.repeat < 1:
        ap.error("size factors must be > 0 and --repeat >= 1")
    load = os.getloadavg()[0]
    out, tmp = hb.results_folder(opts.out, "fricon-quadratic-bench-")
    fricon = str(pathlib.Path(opts.fricon).resolve()) if os.sep in opts.fricon else opts.fricon

    def progress(what, rep):
        print(f"quadratic_bench: {what}: n_primal {rep['n_primal']}, time_s {rep['time_s']:.2f} s, "
              f"peak {rep['peak_mib']:.0f} MiB", file=sys.stderr, flush=True)

    try:
        run = hb.stamped_runner(fricon, opts.threads)
        runs = []
        for o, factors in ((1, opts.linear_size_factors), (2, opts.quadratic_size_factors)):
            for sf in factors:
                folder = out / f"order{o}-sf{sf:g}"
                rep = run(HEMISPHERE, folder, sf, [f"mesh.order={o}"])
                runs.append((o, sf, rep, hb.hertz_measures(rep, hb.read_patches(folder))))
                progress(f"order {o}, size_factor {sf:g}", rep)
        cost = None
        if opts.ratio_size_factor > 0:
            sf = opts.ratio_size_factor
            linear_toml = out / "hertz-hemisphere-no-contact.toml"
            hb.write_without_contact(HEMISPHERE, linear_toml)
            with_c = without = None
            for _ in range(opts.repeat):
                with_c = hb.fastest(with_c, run(HEMISPHERE, out / "cost-contact", sf,
                                                 ["mesh.order=2"]))
                without = hb.fastest(without, run(linear_toml, out / "cost-linear", sf,
                                                  ["mesh.order=2"]))
            progress(f"cost, contact, size_factor {sf:g}", with_c)
            progress(f"cost, linear, size_factor {sf:g}", without)
            cost = (sf, with_c, without)
    except hb.RunFailed as e:
        print(f"quadratic_bench: {e}", file=sys.stderr)
        return 1
    finally:
        if tmp is not None:
            tmp.cleanup()

    lines = [f"Hertz's hemisphere at orders 1 and 2 ({fricon}; load average {load:.2f} at the "
             "start)", ""]
    lines += study_section(runs, opts.markdown)
    if cost is not None:
        lines += ["", "Order 2 against one linear solve of the same quadratic mesh:", ""]
        lines += cost_section(*cost, opts.markdown)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
