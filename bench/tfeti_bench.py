#!/usr/bin/python3
"""Total FETI (solver.backend = "tfeti", docs/theory.md §8) on the paper's brick: numerical
scalability with the subdomain size fixed, and the direct solver against TFETI in one series.

    /usr/bin/python3 bench/tfeti_bench.py build/apps/fricon/fricon \
        [--scalability 8 16 24 32] [--cells-per-subdomain 4] [--series 16 24 32] \
        [--series-subdomain-size 1000] [--series-tfeti-only 64] [--scaling] \
        [--sizes N S1 S2 ...] [--threads N] [--out DIR] [--markdown]

The problem is examples/paper-brick.toml (Tresca friction with the paper's F(s), 3n x n x n cubes
of 5 tetrahedra, 4-node elements) with mesh.cells = [3n, n, n].

Numerical scalability (--scalability n...): the brick cut into (n / c)^3 subdomains, c =
--cells-per-subdomain, so that every subdomain has about 3 c^3 cubes whatever n (H/h fixed). Per
n: subdomains, unknowns, multipliers (contact, gluing, Dirichlet), coarse rows, QPs (the outer
iterations), products with F per QP, MPGP steps per QP, the time. Theory (theory.md §8.3): the
products per QP stay bounded as n grows. The table gives the largest ratio of products per QP
between two sizes.

Series (--series n...): each n solved by the direct backend ("cholmod") and by "tfeti" with
solver.subdomain_size = --series-subdomain-size, alternated; wall time, the process's peak
memory (its own rusage), products with Q or F, and the ratios tfeti/direct measured in the same
run. --series-tfeti-only n...: sizes that only TFETI runs (the direct factor does not fit).

--sizes N S1 S2 ...: the brick at n = N with solver.subdomain_size = S1, S2, ...: the time, the
products with F and the memory of each, from which the default subdomain_size is chosen.

--scaling: at the first --scalability size, tfeti_scaling "stiffness" against "uniform" (the
diagonal scaling of the equality rows, theory.md §8.5): products with F of whole runs.

Every run must converge, or the script stops with exit code 1. Results go to --out DIR or to a
temporary folder removed at the end. The header gives the machine's load average at the start:
timings mean little on a busy machine.
"""
import argparse
import os
import pathlib
import subprocess
import sys

import hertz_bench as hb

ROOT = pathlib.Path(__file__).resolve().parent.parent
BRICK = ROOT / "examples" / "paper-brick.toml"


def solve(fricon, folder, n, threads, sets=()):
    """One solve of the brick at n with the overrides `sets`; its report with peak memory."""
    import json
    import shutil
    import time
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    cmd = [fricon] + (["--threads", str(threads)] if threads else []) + [
        "solve", str(BRICK), "--set", f"mesh.cells=[{3 * n},{n},{n}]", "-o", str(folder),
        "-q"] + [arg for s in sets for arg in ("--set", s)]
    log = folder / "fricon.log"
    start = time.perf_counter()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(proc.pid, 0)  # this child's own rusage
    wall_s = time.perf_counter() - start
    code = os.waitstatus_to_exitcode(status)
    report_file = folder / "report.json"
    if code != 0 or not report_file.exists():
        raise hb.RunFailed(f"{' '.join(cmd)}: exit code {code}\n{hb.tail(log)}")
    report = json.loads(report_file.read_text())
    report["peak_mib"] = usage.ru_maxrss / 1024.0  # KiB on Linux
    report["wall_s"] = wall_s
    return report


def scalability(fricon, out, sizes, c, threads, markdown):
    headers = ["n", "subdomains", "n_primal", "contact", "gluing", "Dirichlet", "coarse rows",
               "QPs", "products with F", "products / QP", "MPGP steps / QP", "time [s]",
               "peak RSS [MiB]"]
    rows, per_qp = [], []
    for n in sizes:
        subdomains = max(1, round((n / c) ** 3))
        rep = solve(fricon, out / f"scal-{n}", n, threads,
                    ['solver.backend="tfeti"', f"solver.subdomains={subdomains}"])
        f = rep["feti"]
        qps = rep["outer_iterations"]
        per_qp.append(f["n_products"] / qps)
        rows.append([str(n), str(f["n_subdomains"]), str(rep["n_primal"]), str(f["n_contact"]),
                     str(f["n_gluing"]), str(f["n_dirichlet"]), str(f["n_coarse"]), str(qps),
                     str(f["n_products"]), f"{per_qp[-1]:.0f}", f"{rep['qp_iterations'] / qps:.0f}",
                     f"{rep['time_s']:.1f}", f"{rep['peak_mib']:.0f}"])
        print(f"  scalability n = {n}: {rows[-1]}", file=sys.stderr, flush=True)
    spread = max(per_qp) / min(per_qp)
    return [f"Numerical scalability: the brick cut into (n/{c})^3 subdomains (H/h fixed)", "",
            hb.table(headers, rows, markdown), "",
            f"largest ratio of products with F per QP between two sizes: {spread:.2f}", ""]


def series(fricon, out, sizes, tfeti_only, size, threads, markdown):
    headers = ["n", "backend", "n_primal", "subdomains", "products", "time [s]",
               "peak RSS [MiB]", "max |u| [m]", "time tfeti/direct", "memory tfeti/direct"]
    rows = []
    for n in sizes + tfeti_only:
        direct = None
        if n in sizes:
            direct = solve(fricon, out / f"direct-{n}", n, threads, ['solver.backend="cholmod"'])
            rows.append([str(n), "cholmod", str(direct["n_primal"]), "-",
                         str(direct["n_mult"]), f"{direct['wall_s']:.1f}",
                         f"{direct['peak_mib']:.0f}", f"{direct['max_displacement']:.6e}", "",
                         ""])
            print(f"  direct n = {n}: {rows[-1]}", file=sys.stderr, flush=True)
        rep = solve(fricon, out / f"tfeti-{n}", n, threads,
                    ['solver.backend="tfeti"', f"solver.subdomain_size={size}"])
        rows.append([str(n), "tfeti", str(rep["n_primal"]), str(rep["feti"]["n_subdomains"]),
                     str(rep["feti"]["n_products"]), f"{rep['wall_s']:.1f}",
                     f"{rep['peak_mib']:.0f}", f"{rep['max_displacement']:.6e}",
                     f"{rep['wall_s'] / direct['wall_s']:.2f}" if direct else "",
                     f"{rep['peak_mib'] / direct['peak_mib']:.2f}" if direct else ""])
        print(f"  tfeti n = {n}: {rows[-1]}", file=sys.stderr, flush=True)
    return [f"Direct against TFETI (subdomain_size = {size}), wall time and peak memory of each "
            "process", "", hb.table(headers, rows, markdown), ""]


def subdomain_sizes(fricon, out, n, sizes, threads, markdown):
    rows = []
    for size in sizes:
        rep = solve(fricon, out / f"size-{size}", n, threads,
                    ['solver.backend="tfeti"', f"solver.subdomain_size={size}"])
        f = rep["feti"]
        rows.append([str(size), str(f["n_subdomains"]), f"{f['subdomain_nodes']['mean']:.0f}",
                     str(f["n_gluing"]), str(f["n_products"]), f"{f['factor_mib']:.0f}",
                     f"{rep['wall_s']:.1f}", f"{rep['peak_mib']:.0f}"])
        print(f"  size {size}: {rows[-1]}", file=sys.stderr, flush=True)
    return [f"Subdomain size at n = {n}", "",
            hb.table(["subdomain_size", "subdomains", "mean nodes", "gluing", "products with F",
                      "factors [MiB]", "time [s]", "peak RSS [MiB]"], rows, markdown), ""]


def row_scaling(fricon, out, n, c, threads, markdown):
    subdomains = max(1, round((n / c) ** 3))
    rows = []
    for kind in ("stiffness", "uniform"):
        rep = solve(fricon, out / f"scaling-{kind}", n, threads,
                    ['solver.backend="tfeti"', f"solver.subdomains={subdomains}",
                     f'solver.tfeti_scaling="{kind}"'])
        rows.append([kind, str(rep["feti"]["n_products"]), str(rep["qp_iterations"]),
                     f"{rep['time_s']:.1f}"])
    return [f"Scaling of the equality rows at n = {n}, {subdomains} subdomains", "",
            hb.table(["tfeti_scaling", "products with F", "MPGP steps", "time [s]"], rows,
                     markdown), ""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon")
    ap.add_argument("--scalability", type=int, nargs="*", default=[8, 16, 24])
    ap.add_argument("--cells-per-subdomain", type=int, default=4)
    ap.add_argument("--series", type=int, nargs="*", default=[16, 24])
    ap.add_argument("--series-subdomain-size", type=int, default=1000)
    ap.add_argument("--sizes", type=int, nargs="*", default=[])
    ap.add_argument("--series-tfeti-only", type=int, nargs="*", default=[])
    ap.add_argument("--scaling", action="store_true")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", type=pathlib.Path)
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args()
    out, tmp = hb.results_folder(a.out, "fricon-tfeti-bench-")
    load = os.getloadavg()[0]
    version = subprocess.run([a.fricon, "--version"], capture_output=True, text=True)
    lines = [f"fricon {version.stdout.strip()}; load average at the start {load:.2f} on "
             f"{os.cpu_count()} cores", ""]
    try:
        if a.scalability:
            lines += scalability(a.fricon, out, a.scalability, a.cells_per_subdomain, a.threads,
                                 a.markdown)
        if a.scaling and a.scalability:
            lines += row_scaling(a.fricon, out, a.scalability[0], a.cells_per_subdomain,
                                 a.threads, a.markdown)
        if len(a.sizes) > 1:
            lines += subdomain_sizes(a.fricon, out, a.sizes[0], a.sizes[1:], a.threads,
                                     a.markdown)
        if a.series or a.series_tfeti_only:
            lines += series(a.fricon, out, a.series, a.series_tfeti_only,
                            a.series_subdomain_size, a.threads, a.markdown)
    except hb.RunFailed as e:
        print(f"tfeti_bench: {e}", file=sys.stderr)
        return 1
    finally:
        if tmp:
            tmp.cleanup()
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
