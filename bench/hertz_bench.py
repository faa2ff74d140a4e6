#!/usr/bin/python3
"""Hertz's hemisphere: a mesh refinement study and the cost of contact against no contact.

    /usr/bin/python3 bench/hertz_bench.py build/apps/fricon/fricon \
        [--size-factors 1 0.7 0.5 0.35] [--ratio-size-factors 0.6 0.45] [--out DIR] \
        [--markdown] [--threads N] [--repeat N] [--problem hemisphere|two-spheres]

--problem two-spheres runs the same studies on examples/two-bodies/hertz-spheres.toml (two
elastic spheres, R = 50 mm, E = 2e10 Pa, nu = 0.3, quarter models, pressed together by a total
approach of 4 mm; Hertz's formulas with R / 2 and E* = E / (2 (1 - nu^2)), and the force of the
whole spheres, four times the model's); the ratio target there is 1.5 at size factor 0.75
(about 150k unknowns), e.g. --size-factors 1 0.75 --ratio-size-factors 0.75.

Both studies solve examples/geometry/hertz-hemisphere.toml (an elastic hemisphere, R = 50 mm,
E = 2e11 Pa, nu = 0.3, pressed without friction on a rigid plane by a prescribed displacement of
its top) at the default solver settings, one `fricon solve --set mesh.size_factor=X` per mesh.

Refinement study, one row per size factor of --size-factors: the sizes (n_primal, the patches, the
candidate patches and the contact-search rounds when the build reports them), the cost (products
with Q, QP and outer iterations, time_s of report.json, the peak resident memory of the process)
and the answer against Hertz's for the total normal force P of the run:
    E* = E / (1 - nu^2),  a = (3 P R / (4 E*))^(1/3),  p0 = 3 P / (2 pi a^2),
    p(r) = p0 sqrt(1 - r^2 / a^2)
  a_h      the contact radius from the pressure's second moment, a_h^2 = 5/2 sum(p r^2 A) / sum(p A)
           (exact for Hertz's p), and its error against a
  p_max    the largest patch pressure, its error against p0
  L1       sum(A |lambda_n - p(r)|) / sum(A p(r)) over all patches (r of the patch's centroid)
  scatter  the standard deviation over the patches with r < 0.9 a of (lambda_n - p(r)) / p0
then the observed orders of |a_h / a - 1|, L1 and scatter between consecutive meshes against the
mesh size h ~ n_primal^(-1/3), order = log(e1 / e2) / log(h1 / h2), and the products with Q of the
finest mesh over those of the coarsest (target <= 2).

Ratio study, for each size factor of --ratio-size-factors: the same mesh with and without contact
(a copy of the problem file without its [contact] table, written into the results folder), one
after the other (--repeat N: alternated N times, the fastest time_s of each kept, as
build/bench/contact_bench does): n_primal, both time_s, their ratio (targets <= 1.15 at 0.6,
<= 1.3 at 0.45), the time of every phase of both runs (report.json "timings"; "other" is time_s
less their sum), the products with Q and the peak memory.

Every run must finish converged (report.json "status"), or the script stops with exit code 1
before printing any table; a missed performance target is printed, never an error. Results go to
--out DIR (one folder per run, with the run's log), or else to a temporary folder removed at the
end. The peak memory is the maximum resident set of each fricon process (os.wait4). The header
gives the machine's load average at the start: timings mean little on a busy machine. The program
must not change during the study (the study stops if its file does: one build per table).
"""
import argparse
import csv
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
# The problems (--problem): the file, and Hertz's equivalent sphere on a rigid plane: its radius
# [m] and the pair's modulus E* [Pa].
PROBLEMS = {
    # One hemisphere (R = 50 mm, E = 2e11 Pa, nu = 0.3) on the rigid plane: R, E / (1 - nu^2).
    "hemisphere": (ROOT / "examples" / "geometry" / "hertz-hemisphere.toml", 0.05,
                   2.0e11 / (1.0 - 0.3**2)),
    # Two spheres (R = 50 mm, E = 2e10 Pa, nu = 0.3) pressed together: R / 2, E / (2 (1 - nu^2));
    # quarter models, so the patches carry a quarter of the force.
    "two-spheres": (ROOT / "examples" / "two-bodies" / "hertz-spheres.toml", 0.025,
                    2.0e10 / (2.0 * (1.0 - 0.3**2))),
}
QUARTER = {"hemisphere": 1.0, "two-spheres": 4.0}  # the model's share of the whole
PRODUCT_TARGET = 2.0  # n_mult of the finest mesh over that of the coarsest
# time_s with contact over time_s without, per problem and size factor (two spheres: about 150k
# unknowns at 0.75)
RATIO_TARGETS = {"hemisphere": {0.6: 1.15, 0.45: 1.3}, "two-spheres": {0.75: 1.5}}
PHASES = ("mesh", "assembly", "contact", "factorize", "dual", "qp", "solve", "recovery",
          "postprocess")  # the order of a run; any other phase a report names follows


class RunFailed(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# Running fricon

def program_stamp(fricon):
    """What identifies the build: the program file's size and modification time."""
    path = shutil.which(fricon)
    if path is None:
        raise RunFailed(f"{fricon}: no such program")
    st = os.stat(path)
    return st.st_size, st.st_mtime_ns


def solve(fricon, toml, folder, size_factor, threads, sets=()):
    """One `fricon solve` (with the overrides `sets`, "KEY=VALUE" each); returns its report with
    the process's peak memory and wall time."""
    if folder.exists():  # a stale report.json must not pass for this run's
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    cmd = [fricon] + (["--threads", str(threads)] if threads else []) + [
        "solve", str(toml), "--set", f"mesh.size_factor={float(size_factor)!r}", "-o",
        str(folder), "-q"] + [arg for s in sets for arg in ("--set", s)]
    log = folder / "fricon.log"
    start = time.perf_counter()
    with open(log, "w") as out:
        try:
            proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT)
        except OSError as e:
            raise RunFailed(f"{' '.join(cmd)}: {e}") from None
        # wait4 gives this child's own rusage (RUSAGE_CHILDREN would be the largest of all).
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
    wall_s = time.perf_counter() - start
    if proc.returncode != 0:
        why = ("not converged" if (folder / "report.not-converged.json").exists()
               else f"exit code {proc.returncode}")
        raise RunFailed(f"{' '.join(cmd)}: {why}\n{tail(log)}")
    report_file = folder / "report.json"
    if not report_file.exists():
        raise RunFailed(f"{' '.join(cmd)}: no report.json in {folder}\n{tail(log)}")
    report = json.loads(report_file.read_text())
    if report.get("status") != "converged":
        raise RunFailed(f"{' '.join(cmd)}: status {report.get('status')!r}: "
                        f"{report.get('message', '')}")
    report["peak_mib"] = usage.ru_maxrss / 1024.0  # ru_maxrss is in KiB on Linux
    report["wall_s"] = wall_s
    return report


def results_folder(out, prefix):
    """(folder, tmp): `out` (a path, made if need be), or with None a temporary folder `tmp`
    that the caller cleans up."""
    if out is None:
        tmp = tempfile.TemporaryDirectory(prefix=prefix)
        return pathlib.Path(tmp.name), tmp
    out = out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    return out, None


def stamped_runner(fricon, threads):
    """run(toml, folder, size_factor, sets=()): one solve, refused (RunFailed) when the program
    changed since the runner was made (rebuilt during a study)."""
    stamp = program_stamp(fricon)

    def run(toml, folder, size_factor, sets=()):
        rep = solve(fricon, toml, folder, size_factor, threads, sets)
        if program_stamp(fricon) != stamp:
            raise RunFailed(f"{fricon} changed during the study (rebuilt?): run it again")
        return rep
    return run


def fastest(best, new):
    """The report of the faster run, with the larger peak memory of the two."""
    if best is None:
        return new
    keep = dict(new if new["time_s"] < best["time_s"] else best)
    keep["peak_mib"] = max(best["peak_mib"], new["peak_mib"])
    return keep


def tail(log, lines=20):
    return "\n".join(log.read_text(errors="replace").splitlines()[-lines:])


def write_without_contact(src, dst):
    """A copy of the problem file src without its [contact] table (and sub-tables), its mesh file
    made absolute (a relative path is taken from the problem file's folder, which changes)."""
    header = re.compile(r"^\s*\[\[?\s*([A-Za-z0-9_.\"' -]+?)\s*\]\]?\s*(#.*)?$")
    mesh_file = re.compile(r'^(\s*file\s*=\s*)"([^"]*)"(.*)$')
    table, lines = "", []
    for line in src.read_text().splitlines():
        m = header.match(line)
        if m:
            table = m.group(1).replace(" ", "")
        if table == "contact" or table.startswith("contact."):
            continue
        m = mesh_file.match(line)
        if table == "mesh" and m:
            path = (src.parent / m.group(2)).resolve()
            line = f"{m.group(1)}{json.dumps(str(path))}{m.group(3)}"
        lines.append(line)
    dst.write_text("\n".join(lines) + "\n")
    # The copy must be the same problem less its contact.
    original, copy = tomllib.loads(src.read_text()), tomllib.loads(dst.read_text())
    original.pop("contact", None)
    original["mesh"]["file"] = str((src.parent / original["mesh"]["file"]).resolve())
    if copy != original:
        raise RunFailed(f"{dst}: the copy without [contact] differs from {src} in more than that")


# ---------------------------------------------------------------------------------------------
# Hertz's measures (as tests/regression/check_geometry.py)

def read_patches(folder):
    with open(folder / "patches.csv") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise RunFailed(f"{folder}/patches.csv: no patches")
    return {k: np.array([float(r[k]) for r in rows]) for k in ("x", "y", "area", "lambda_n")}


PROBLEM = "hemisphere"  # --problem


def hertz_measures(report, patches):
    p, area = patches["lambda_n"], patches["area"]
    r = np.hypot(patches["x"], patches["y"])
    force = float(np.sum(p * area))
    if abs(force - report["total_normal_force"]) > 1e-9 * abs(force):
        raise RunFailed(f"the patches' force {force:.6e} N is not the report's "
                        f"total_normal_force {report['total_normal_force']:.6e} N")
    _, radius, e_star = PROBLEMS[PROBLEM]
    whole = QUARTER[PROBLEM] * force
    a = (3.0 * whole * radius / (4.0 * e_star)) ** (1.0 / 3.0)
    p0 = 3.0 * whole / (2.0 * math.pi * a * a)
    a_h = math.sqrt(2.5 * float(np.sum(p * area * r**2)) / force)
    hertz = p0 * np.sqrt(np.maximum(0.0, 1.0 - (r / a) ** 2))
    inner = r < 0.9 * a
    return {
        "P": force, "a": a, "p0": p0, "a_h": a_h,
        "a_err": a_h / a - 1.0,
        "pmax_err": float(np.max(p)) / p0 - 1.0,
        "l1": float(np.sum(area * np.abs(p - hertz)) / np.sum(area * hertz)),
        "scatter": float(np.std((p[inner] - hertz[inner]) / p0)) if inner.any() else math.nan,
        "n_inner": int(np.count_nonzero(inner)),
    }


def order(e1, e2, h1, h2):
    if not (e1 > 0 and e2 > 0) or h1 == h2:
        return "-"
    return f"{math.log(e1 / e2) / math.log(h1 / h2):.2f}"


# ---------------------------------------------------------------------------------------------
# Tables

def table(headers, rows, markdown):
    if markdown:  # a "|" inside a cell (|u|) would end it
        headers = [h.replace("|", "\\|") for h in headers]
        lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
        lines += ["| " + " | ".join(row) + " |" for row in rows]
    else:
        widths = [max(len(h), *(len(row[i]) for row in rows)) for i, h in enumerate(headers)]
        lines = ["  ".join(h.rjust(w) for h, w in zip(headers, widths))]
        lines += ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in rows]
    return "\n".join(lines)


def opt(report, key):
    return str(report[key]) if key in report else "-"


def met(value, target):
    return f"target <= {target:g}: {'met' if value <= target else 'NOT met'}"


def refinement_section(runs, markdown):
    rows = []
    for sf, rep, h in runs:
        n_patches = rep.get("n_patches", rep.get("contact", {}).get("n_patches", "-"))
        rows.append([
            f"{sf:g}", str(rep["n_primal"]), str(n_patches), opt(rep, "n_candidate_patches"),
            opt(rep, "search_rounds"), str(rep["n_mult"]), str(rep["qp_iterations"]),
            str(rep["outer_iterations"]), f"{rep['time_s']:.2f}", f"{rep['peak_mib']:.0f}",
            f"{h['P']:.4e}", f"{h['a'] * 1e3:.4f}", f"{h['p0']:.4e}", f"{h['a_h'] * 1e3:.4f}",
            f"{100 * h['a_err']:+.2f}", f"{100 * h['pmax_err']:+.2f}", f"{100 * h['l1']:.2f}",
            f"{100 * h['scatter']:.2f}"])
    headers = ["size_factor", "n_primal", "n_patches", "n_candidate", "search_rounds", "n_mult",
               "QP its", "outer", "time_s [s]", "peak RSS [MiB]", "P [N]", "a [mm]", "p0 [Pa]",
               "a_h [mm]", "a_h err [%]", "p_max err [%]", "L1 [%]", "scatter [% p0]"]
    out = [table(headers, rows, markdown), ""]

    by_size = sorted(runs, key=lambda run: run[1]["n_primal"])  # coarsest first
    rows = []
    for (sf1, r1, h1), (sf2, r2, h2) in zip(by_size, by_size[1:]):
        m1, m2 = r1["n_primal"] ** (-1.0 / 3.0), r2["n_primal"] ** (-1.0 / 3.0)
        rows.append([f"{sf1:g} -> {sf2:g}", f"{m1 / m2:.3f}",
                     order(abs(h1["a_err"]), abs(h2["a_err"]), m1, m2),
                     order(h1["l1"], h2["l1"], m1, m2),
                     order(h1["scatter"], h2["scatter"], m1, m2)])
    if rows:
        out += ["Observed orders between consecutive meshes, against "
                "h ~ n_primal^(-1/3) (order = log(e1/e2) / log(h1/h2)):", "",
                table(["size_factor", "h1/h2", "order a_h err", "order L1", "order scatter"],
                      rows, markdown), ""]
    coarse, fine = by_size[0][1], by_size[-1][1]
    ratio = fine["n_mult"] / coarse["n_mult"]
    out.append(f"Products with Q, finest mesh (size_factor {by_size[-1][0]:g}, "
               f"{fine['n_primal']} unknowns) over the coarsest (size_factor "
               f"{by_size[0][0]:g}, {coarse['n_primal']} unknowns): {fine['n_mult']} / "
               f"{coarse['n_mult']} = {ratio:.2f} ({met(ratio, PRODUCT_TARGET)})")
    return out


def ratio_section(pairs, markdown):
    rows = []
    for sf, with_c, without in pairs:
        ratio = with_c["time_s"] / without["time_s"]
        target = RATIO_TARGETS[PROBLEM].get(sf)
        rows.append([f"{sf:g}", str(with_c["n_primal"]), f"{with_c['time_s']:.2f}",
                     f"{without['time_s']:.2f}", f"{ratio:.2f}",
                     f"{target:g}" if target else "-",
                     ("met" if ratio <= target else "NOT met") if target else "-",
                     str(with_c["n_mult"]), f"{with_c['peak_mib']:.0f}",
                     f"{without['peak_mib']:.0f}",
                     f"{with_c['wall_s']:.2f}", f"{without['wall_s']:.2f}"])
    headers = ["size_factor", "n_primal", "contact [s]", "no contact [s]", "ratio", "target",
               "target met", "n_mult", "peak RSS contact [MiB]", "peak RSS no contact [MiB]",
               "process contact [s]", "process no contact [s]"]
    out = [table(headers, rows, markdown), ""]

    named = {p for _, with_c, without in pairs for rep in (with_c, without)
             for p in rep.get("timings", {})}
    phases = [p for p in PHASES if p in named] + sorted(named - set(PHASES))
    rows = []
    for sf, with_c, without in pairs:
        for label, rep in (("contact", with_c), ("no contact", without)):
            t = rep.get("timings", {})
            other = rep["time_s"] - sum(t.values())
            rows.append([f"{sf:g}", label] + [f"{t[p]:.3f}" if p in t else "-" for p in phases]
                        + [f"{other:.3f}", f"{rep['time_s']:.3f}"])
    out += ["Time per phase [s] (report.json timings; other = time_s less their sum):", "",
            table(["size_factor", "run"] + phases + ["other", "time_s"], rows, markdown)]
    return out


# ---------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon", help="the fricon program")
    ap.add_argument("--size-factors", type=float, nargs="+", default=[1.0, 0.7, 0.5, 0.35],
                    metavar="X", help="refinement study (default: 1 0.7 0.5 0.35)")
    ap.add_argument("--ratio-size-factors", type=float, nargs="*", default=[0.6, 0.45],
                    metavar="X", help="contact against no contact (default: 0.6 0.45)")
    ap.add_argument("--out", type=pathlib.Path, help="keep the results here (default: a "
                    "temporary folder, removed at the end)")
    ap.add_argument("--markdown", action="store_true", help="print the tables as Markdown")
    ap.add_argument("--threads", type=int, help="fricon --threads N (default: fricon's choice "
                    "from the machine's load)")
    ap.add_argument("--repeat", type=int, default=1, metavar="N", help="ratio study: alternate "
                    "the two runs N times, keep the fastest of each (default: 1)")
    ap.add_argument("--problem", choices=sorted(PROBLEMS), default="hemisphere",
                    help="hemisphere: examples/geometry/hertz-hemisphere.toml on the plane; "
                    "two-spheres: examples/two-bodies/hertz-spheres.toml, two elastic bodies")
    opts = ap.parse_args()
    global PROBLEM, HERTZ
    PROBLEM = opts.problem
    HERTZ = PROBLEMS[PROBLEM][0]
    if any(x <= 0 for x in opts.size_factors + opts.ratio_size_factors):
        ap.error("size factors must be > 0")
    if opts.repeat < 1:
        ap.error("--repeat must be >= 1")
    load = os.getloadavg()[0]

    out, tmp = results_folder(opts.out, "fricon-hertz-bench-")
    fricon = str(pathlib.Path(opts.fricon).resolve()) if os.sep in opts.fricon else opts.fricon

    def progress(what, rep):
        print(f"hertz_bench: {what}: n_primal {rep['n_primal']}, time_s {rep['time_s']:.2f} s, "
              f"peak {rep['peak_mib']:.0f} MiB", file=sys.stderr, flush=True)

    try:
        run = stamped_runner(fricon, opts.threads)

        version = subprocess.run([fricon, "--version"], capture_output=True, text=True)
        if version.returncode != 0:
            raise RunFailed(f"{fricon} --version: exit code {version.returncode}\n"
                            f"{version.stdout}{version.stderr}")
        runs, pairs = [], []
        for sf in opts.size_factors:
            folder = out / f"refine-sf{sf:g}"
            rep = run(HERTZ, folder, sf)
            runs.append((sf, rep, hertz_measures(rep, read_patches(folder))))
            progress(f"refinement, size_factor {sf:g}", rep)
        if opts.ratio_size_factors:
            bare = out / "hertz-hemisphere-no-contact.toml"
            write_without_contact(HERTZ, bare)
        for sf in opts.ratio_size_factors:
            with_c = without = None
            for i in range(opts.repeat):
                c = run(HERTZ, out / f"ratio-sf{sf:g}-contact", sf)
                progress(f"ratio, size_factor {sf:g}, contact ({i + 1}/{opts.repeat})", c)
                n = run(bare, out / f"ratio-sf{sf:g}-no-contact", sf)
                progress(f"ratio, size_factor {sf:g}, no contact ({i + 1}/{opts.repeat})", n)
                with_c, without = fastest(with_c, c), fastest(without, n)
            if without["n_primal"] != with_c["n_primal"]:
                raise RunFailed(f"size_factor {sf:g}: not the same mesh with and without contact "
                                f"({with_c['n_primal']} and {without['n_primal']} unknowns)")
            pairs.append((sf, with_c, without))
    except (RunFailed, OSError) as e:
        sys.exit(f"hertz_bench: {e}\nhertz_bench: FAILED, no table printed")
    finally:
        if tmp is not None:
            tmp.cleanup()

    md = opts.markdown
    reports = [r for _, r, _ in runs] + [r for _, r, _ in pairs]
    threads = sorted({str(r["factor"]["blas_threads"]) for r in reports if "factor" in r})
    lines = [f"Hertz ({HERTZ.relative_to(ROOT)}), default solver settings; "
             f"{version.stdout.strip()}, BLAS threads {', '.join(threads) or '-'}; load "
             f"average at the start {load:.2f} on {os.cpu_count()} cores", ""]
    lines += ["Refinement study (errors against Hertz's a, p0 and p(r) for the run's P; "
              "scatter over the patches with r < 0.9 a):", ""]
    lines += refinement_section(runs, md)
    if pairs:
        best = f", the fastest of {opts.repeat} alternated runs each" if opts.repeat > 1 else ""
        lines += ["", "Contact against no contact, the same mesh (the problem file "
                  f"without [contact]{best}); ratio = time_s with contact / without:", ""]
        lines += ratio_section(pairs, md)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
