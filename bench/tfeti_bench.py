#!/usr/bin/python3
"""Total FETI (solver.backend = "tfeti", docs/theory.md §8) on the paper's brick: numerical
scalability with the subdomain size fixed, and the direct solver against TFETI in one series.

    /usr/bin/python3 bench/tfeti_bench.py build/apps/fricon/fricon \
        [--scalability 8 16 24 32] [--cells-per-subdomain 4] [--series 16 24 32] \
        [--series-subdomain-size 1000] [--series-tfeti-only 64] [--scaling] [--preconditioners] \
        [--sizes N S1 S2 ...] [--counts N C1 C2 ...] [--weak N1 N2] [--search [EXAMPLE ...]]
        [--mpirun MPIRUN]
        [--threads N] [--out DIR] [--markdown]

The problem is examples/paper-brick.toml (Tresca friction with the paper's F(s), 3n x n x n cubes
of 5 tetrahedra, 4-node elements) with mesh.cells = [3n, n, n].

Numerical scalability (--scalability n...): the brick cut into (n / c)^3 subdomains, c =
--cells-per-subdomain, so that every subdomain has about 3 c^3 cubes whatever n (H/h fixed). Per
n: subdomains, unknowns, multipliers (contact, gluing, Dirichlet), coarse rows, QPs (the outer
iterations), products with F per QP (all of them, and MPGP's alone: n_mult), MPGP's steps per QP
by kind (report.json qp_steps), the time; and the products with Q per QP of the direct solver on
the same mesh (the same contact QP without gluing multipliers: how much of any growth is the
contact problem's own). Theory (theory.md §8.3): the products per QP stay bounded as n grows.
The table gives the largest ratio of products per QP between two sizes.

Series (--series n...): each n solved by the direct backend ("cholmod") and by "tfeti" with
solver.subdomain_size = --series-subdomain-size, alternated; wall time, the process's peak
memory (its own rusage), products with Q or F, and the ratios tfeti/direct measured in the same
run. --series-tfeti-only n...: sizes that only TFETI runs (the direct factor does not fit).

--sizes N S1 S2 ...: the brick at n = N with solver.subdomain_size = S1, S2, ...: the time, the
products with F and the memory of each, from which the default subdomain_size is chosen.

--counts N C1 C2 ...: the brick at n = N cut into C1, C2, ... subdomains (solver.subdomains):
how much the products with F depend on the partition at one mesh, first with METIS's partition
as it comes (solver.tfeti_neck_cuts = 0), then with the subdomains joined by a neck cut again (the
default, theory.md §8.9). Per count: how many times the softest subdomain is softer than the
median (report.json feti.softness.ratio, after the cuts), the subdomains cut again, the products
of the first QP and of the whole run, SMALSE-M's outer steps (theory.md §4.6), max |u| and the
peak pressure relative to the direct solver's on the same mesh; then the spread (largest over
smallest) of the first QP's and the whole run's products.

--preconditioners: in place of the scalability table, the --scalability sizes with
solver.tfeti_preconditioner "none", "lumped" and "dirichlet" (theory.md §8.5), alternated: first
the elastic brick (examples/elastic-brick.toml, the gluing alone: CG steps), then the paper's
brick: products with F, the preconditioner's applications and time, and the QP's and the whole
run's time; per preconditioner, the largest ratio of CG steps or products per QP.

--scaling: at the first --scalability size, tfeti_scaling "stiffness" against "uniform" (the
diagonal scaling of the equality rows, theory.md §8.5): products with F of whole runs.

--weak N1 N2: weak scaling with MPI ranks (docs/parallel.md, "Total FETI on ranks"): the brick at
n = N1 on 1 rank and at n = N2 on 2 ranks (choose N2^3 close to 2 N1^3: the same size per rank),
both with solver.subdomain_size = --series-subdomain-size and one thread per rank. Per run: wall
time, products with F, the QP's time per product, the factorization, and per rank its
subdomains, factor memory and peak memory. Then a model of a run of 10^8 unknowns on 100 and
1000 ranks, from these runs' measured costs: per subdomain (factor memory, factorization time),
per unknown (what every rank holds whole: mesh, model, multipliers; the growth of a rank's
memory besides its factors between the two runs), and the time of a product split by the run's
own clocks (report.json feti.products_s, sums_s, coarse_s, timings.qp) into a part per
subdomain of the rank, a part per multiplier of the rank (the QP's own vector operations on its
share of the multipliers, theory.md §8.8), the exchanges with the neighbouring ranks (grown with
the surface of a rank's block of subdomains, (subdomains per rank)^(2/3)) and the coarse
problem's (its decompositions and solves on every rank, grown with its rows as a sparse 3D
factor's solves, rows^(4/3)). Its assumptions are printed with it.

--search [EXAMPLE ...]: the contact search under Total FETI (theory.md §8.7): each example
(a path under examples/ without .toml; by default five static ones on curved bodies) solved
directly and by "tfeti" with solver.contact_search "gap" and "off" (every patch in the QP):
patches in the QP, products, wall time, max |u|. Use with --scalability and --series given
empty to run it alone.

Every run must converge, or the script stops with exit code 1. Results go to --out DIR or to a
temporary folder removed at the end. The header gives the machine's load average at the start:
timings mean little on a busy machine.
"""
import argparse
import math
import os
import pathlib
import subprocess
import sys

import hertz_bench as hb

ROOT = pathlib.Path(__file__).resolve().parent.parent
BRICK = ROOT / "examples" / "paper-brick.toml"
ELASTIC = ROOT / "examples" / "elastic-brick.toml"


def solve(fricon, folder, n, threads, sets=(), launcher=(), problem=BRICK):
    """One solve of the brick at n with the overrides `sets` (under `launcher`, e.g. mpirun -n 2,
    when given); its report with the peak memory of the process started (mpirun's own, under a
    launcher: the ranks' are in the report)."""
    return solve_file(fricon, folder, problem, threads,
                      [f"mesh.cells=[{3 * n},{n},{n}]"] + list(sets), launcher)


def solve_file(fricon, folder, problem, threads, sets=(), launcher=()):
    """One solve of the problem file `problem` with the overrides `sets`, as solve()."""
    import json
    import shutil
    import time
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    cmd = list(launcher) + [fricon] + (["--threads", str(threads)] if threads else []) + [
        "solve", str(problem), "-o", str(folder), "-q"] + [
        arg for s in sets for arg in ("--set", s)]
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
               "QPs", "products with F", "products / QP", "MPGP products / QP",
               "steps / QP: CG, expansion, proportioning", "direct: products / QP", "time [s]",
               "peak RSS [MiB]"]
    rows, per_qp, mpgp_per_qp, direct_per_qp = [], [], [], []
    for n in sizes:
        subdomains = max(1, round((n / c) ** 3))
        rep = solve(fricon, out / f"scal-{n}", n, threads,
                    ['solver.backend="tfeti"', f"solver.subdomains={subdomains}"])
        direct = solve(fricon, out / f"scal-direct-{n}", n, threads, ['solver.backend="cholmod"'])
        f = rep["feti"]
        qps = rep["outer_iterations"]
        per_qp.append(f["n_products"] / qps)
        mpgp_per_qp.append(rep["n_mult"] / qps)
        direct_per_qp.append(direct["n_mult"] / direct["outer_iterations"])
        steps = rep["qp_steps"]
        rows.append([str(n), str(f["n_subdomains"]), str(rep["n_primal"]), str(f["n_contact"]),
                     str(f["n_gluing"]), str(f["n_dirichlet"]), str(f["n_coarse"]), str(qps),
                     str(f["n_products"]), f"{per_qp[-1]:.0f}", f"{mpgp_per_qp[-1]:.0f}",
                     ", ".join(f"{steps[k] / qps:.0f}" for k in
                               ("cg", "expansion", "proportioning")),
                     f"{direct_per_qp[-1]:.0f}", f"{rep['time_s']:.1f}",
                     f"{rep['peak_mib']:.0f}"])
        print(f"  scalability n = {n}: {rows[-1]}", file=sys.stderr, flush=True)

    def spread(values):
        return max(values) / min(values)

    return [f"Numerical scalability: the brick cut into (n/{c})^3 subdomains (H/h fixed)", "",
            hb.table(headers, rows, markdown), "",
            "largest ratio between two sizes of the products per QP: with F (all of them) "
            f"{spread(per_qp):.2f}, MPGP's {spread(mpgp_per_qp):.2f}; the direct solver's "
            f"(the same contact QP without gluing) {spread(direct_per_qp):.2f}", ""]


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


def subdomain_counts(fricon, out, n, counts, threads, markdown):
    direct = solve(fricon, out / "counts-direct", n, threads)
    lines = [f"Subdomain counts at n = {n} (direct: {direct['n_mult']} products with Q)", ""]
    # METIS's partition as it comes (no neck cuts), then the default (theory.md §8.9).
    for cuts, title in ((0, "METIS's partition as it comes (solver.tfeti_neck_cuts = 0)"),
                        (None, "with the necked subdomains cut again (the default)")):
        rows, first, whole = [], [], []
        for count in counts:
            sets = ['solver.backend="tfeti"', f"solver.subdomains={count}"]
            if cuts is not None:
                sets.append(f"solver.tfeti_neck_cuts={cuts}")
            tag = "plain" if cuts == 0 else "cut"
            rep = solve(fricon, out / f"count-{count}-{tag}", n, threads, sets)
            f = rep["feti"]
            soft = f["softness"]
            first.append(rep["contact"]["history"][0]["qp_products"])
            whole.append(f["n_products"])
            du = abs(rep["max_displacement"] / direct["max_displacement"] - 1.0)
            dl = abs(rep["max_lambda_n"] / direct["max_lambda_n"] - 1.0)
            rows.append([str(count), str(f["n_subdomains"]), f"{soft['ratio']:.1f}",
                         str(soft["n_recut"]), str(rep["outer_iterations"]), str(first[-1]),
                         str(whole[-1]), str(f["smalse_outer_iterations"]), f"{du:.1e}",
                         f"{dl:.1e}"])
            print(f"  count {count} ({tag}): {rows[-1]}", file=sys.stderr, flush=True)
        lines += [title, "",
                  hb.table(["subdomains asked", "subdomains", "softest / median", "re-cut",
                            "QPs", "first QP products", "products with F",
                            "SMALSE-M outer steps", "max |u| vs direct",
                            "peak lambda_n vs direct"], rows, markdown), "",
                  f"Spread (largest / smallest): first QP {max(first) / min(first):.2f}, whole "
                  f"run {max(whole) / min(whole):.2f}; first QP products in all {sum(first)}, "
                  f"whole runs {sum(whole)}.", ""]
    return lines


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


PRECONDITIONERS = ("none", "lumped", "dirichlet")


def each_preconditioner(fricon, out, tag, sizes, c, threads, problem=BRICK):
    """Per size n of `sizes` with (n/c)^3 subdomains, and per preconditioner (alternated): n,
    the preconditioner and the run's report."""
    for n in sizes:
        subdomains = max(1, round((n / c) ** 3))
        for kind in PRECONDITIONERS:
            yield n, kind, solve(fricon, out / f"{tag}-{n}-{kind}", n, threads,
                                 ['solver.backend="tfeti"', f"solver.subdomains={subdomains}",
                                  f'solver.tfeti_preconditioner="{kind}"'], problem=problem)


def elastic_preconditioners(fricon, out, sizes, c, threads, markdown):
    """The gluing alone: examples/elastic-brick.toml (the brick without contact) at the
    scalability sizes with each preconditioner: SMALSE-M's steps (CG steps, there being no
    bounds), the products with F (the steps and the estimate of ||P F P||) and the time."""
    headers = ["n", "subdomains", "preconditioner", "CG steps", "products with F",
               "applications", "time [s]", "peak RSS [MiB]"]
    rows, steps = [], {kind: [] for kind in PRECONDITIONERS}
    for n, kind, rep in each_preconditioner(fricon, out, "elastic", sizes, c, threads, ELASTIC):
        f = rep["feti"]
        steps[kind].append(f["qp_iterations"])
        rows.append([str(n), str(f["n_subdomains"]), kind, str(f["qp_iterations"]),
                     str(f["n_products"]), str(f["n_preconditioner"]),
                     f"{rep['time_s']:.1f}", f"{rep['peak_mib']:.0f}"])
        print(f"  elastic n = {n}: {rows[-1]}", file=sys.stderr, flush=True)
    lines = [f"The elastic brick (gluing alone) with (n/{c})^3 subdomains", "",
             hb.table(headers, rows, markdown), ""]
    for kind, values in steps.items():
        lines.append(f"{kind}: largest ratio of CG steps between two sizes "
                     f"{max(values) / min(values):.2f}")
    return lines + [""]


def preconditioners(fricon, out, sizes, c, threads, markdown):
    """The scalability sizes solved with each solver.tfeti_preconditioner (theory.md §8.5),
    alternated: products with F per QP, the preconditioner's applications and time, the QP's
    time and the whole run's."""
    headers = ["n", "subdomains", "preconditioner", "products with F", "products / QP",
               "MPGP steps", "applications", "preconditioner [s]", "products [s]", "QP [s]",
               "time [s]", "peak RSS [MiB]"]
    rows, per_qp = [], {kind: [] for kind in PRECONDITIONERS}
    for n, kind, rep in each_preconditioner(fricon, out, "precond", sizes, c, threads):
        f = rep["feti"]
        per_qp[kind].append(f["n_products"] / rep["outer_iterations"])
        rows.append([str(n), str(f["n_subdomains"]), kind, str(f["n_products"]),
                     f"{per_qp[kind][-1]:.0f}", str(rep["qp_iterations"]),
                     str(f["n_preconditioner"]), f"{f['preconditioner_s']:.1f}",
                     f"{f['products_s']:.1f}", f"{rep['timings']['qp']:.1f}",
                     f"{rep['time_s']:.1f}", f"{rep['peak_mib']:.0f}"])
        print(f"  preconditioner n = {n}: {rows[-1]}", file=sys.stderr, flush=True)
    lines = [f"Preconditioners (solver.tfeti_preconditioner) with (n/{c})^3 subdomains", "",
             hb.table(headers, rows, markdown), ""]
    for kind, values in per_qp.items():
        lines.append(f"{kind}: largest ratio of products with F per QP between two sizes "
                     f"{max(values) / min(values):.2f}")
    return lines + [""]


MODEL_UNKNOWNS = 1e8
MODEL_RANKS = (100, 1000)


def weak_run(fricon, out, n, ranks, size, mpirun):
    launcher = [mpirun, "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)]
    rep = solve(fricon, out / f"weak-{n}-{ranks}", n, 1,
                ['solver.backend="tfeti"', f"solver.subdomain_size={size}"], launcher)
    f = rep["feti"]
    rep["per_product_s"] = rep["timings"]["qp"] / f["n_products"]
    rep["n_multipliers"] = f["n_contact"] + f["n_gluing"] + f["n_dirichlet"]
    rep["rank_peak"] = max(r["peak_memory_mib"] for r in f["ranks"])
    rep["rank_factor"] = max(r["factor_mib"] for r in f["ranks"])
    rep["rank_model"] = max(r.get("model_memory_mib", 0.0) for r in f["ranks"])
    rep["per_rank_subdomains"] = max(r["n_subdomains"] for r in f["ranks"])
    return rep


def weak_scaling(fricon, out, n1, n2, size, mpirun, markdown):
    runs = [(n1, 1, weak_run(fricon, out, n1, 1, size, mpirun)),
            (n2, 2, weak_run(fricon, out, n2, 2, size, mpirun))]
    headers = ["n", "ranks", "n_primal", "unknowns / rank", "subdomains", "multipliers",
               "products", "QP time / product [ms]", "factorization [s]", "time [s]",
               "factors / rank [MiB]", "peak / rank [MiB]"]
    rows = []
    for n, ranks, r in runs:
        f = r["feti"]
        rows.append([str(n), str(ranks),
                     str(r["n_primal"]), str(r["n_primal"] // ranks), str(f["n_subdomains"]),
                     str(r["n_multipliers"]), str(f["n_products"]),
                     f"{1e3 * r['per_product_s']:.2f}", f"{f['factorization_s']:.2f}",
                     f"{r['wall_s']:.1f}", f"{r['rank_factor']:.0f}", f"{r['rank_peak']:.0f}"])
        print(f"  weak n = {rows[-1][0]} on {ranks}: {rows[-1]}", file=sys.stderr, flush=True)
    (_, _, a), (_, _, b) = runs
    lines = ["Weak scaling with MPI ranks (one thread per rank, subdomain_size "
             f"{size})", "", hb.table(headers, rows, markdown), "",
             f"2 ranks at n = {n2} against 1 rank at n = {n1}: time x"
             f"{b['wall_s'] / a['wall_s']:.2f}, products x"
             f"{b['feti']['n_products'] / a['feti']['n_products']:.2f}, time per product x"
             f"{b['per_product_s'] / a['per_product_s']:.2f}, peak memory per rank x"
             f"{b['rank_peak'] / a['rank_peak']:.2f}", ""]
    return lines + model(a, b, n2)


def model(a, b, n_b):
    """The model of docs/benchmarks.md (Total FETI, "Weak scaling and a model") from runs a
    (1 rank) and b (2 ranks, the brick at n = n_b)."""
    fb = b["feti"]
    # Per subdomain: factor memory and factorization time (one thread).
    factor_mib = fb["factor_mib"] / fb["n_subdomains"]
    factor_s = fb["factorization_cpu_s"] / fb["n_subdomains"]
    subdomains_per_unknown = fb["n_subdomains"] / b["n_primal"]
    multipliers_per_unknown = b["n_multipliers"] / b["n_primal"]
    # What every rank holds whole, per unknown: the growth of (peak - own factors) between runs.
    held_a = a["rank_peak"] - a["rank_factor"]
    held_b = b["rank_peak"] - b["rank_factor"]
    held_mib = max(held_b - held_a, 0.0) / (b["n_primal"] - a["n_primal"])
    # Of it, the model every rank builds whole before its subdomains (mesh, loads, contact).
    model_held_mib = max(b["rank_model"] - a["rank_model"], 0.0) / (b["n_primal"] - a["n_primal"])
    # Time per product, from run b's own clocks: rank 0's subdomain solves per subdomain, and
    # the preconditioner's applications (local solves with each subdomain's interior, counted
    # per product) likewise; per multiplier of the rank the rest of the QP's time (its vector
    # operations on its share, theory.md §8.8, and their reductions); the exchanges with the
    # neighbours (waiting for the slowest rank included) per product, grown with the surface of
    # a rank's block of subdomains.
    n_prod = fb["n_products"]
    ranks_b = len(fb["ranks"])
    c_s = fb["products_s"] / n_prod / b["per_rank_subdomains"]
    c_pre = fb.get("preconditioner_s", 0.0) / n_prod / b["per_rank_subdomains"]
    exchange_b = fb["sums_s"] / n_prod
    # The coarse problem (report.json feti.coarse_s: G G^T's decompositions and solves, on every
    # rank) per product at run b's rows, grown to the model's rows as a sparse factor of a 3D
    # graph's matrix is solved: nnz(L), hence a solve, as rows^(4/3) (nested dissection). The
    # exponent the two runs give is printed beside it.
    coarse_b = fb.get("coarse_s", 0.0) / n_prod
    coarse_a = a["feti"].get("coarse_s", 0.0) / a["feti"]["n_products"]
    rows_a, rows_b = a["feti"]["n_coarse"], fb["n_coarse"]
    measured_exponent = (math.log(coarse_b / coarse_a) / math.log(rows_b / rows_a)
                         if coarse_a > 0.0 and coarse_b > 0.0 and rows_b != rows_a else float("nan"))
    c_m = (b["timings"]["qp"] - fb["products_s"] - fb["sums_s"] - fb.get("preconditioner_s", 0.0) -
           fb.get("coarse_s", 0.0)) / n_prod / (b["n_multipliers"] / ranks_b)
    products = fb["n_products"]
    lines = [f"Model for {MODEL_UNKNOWNS:.0e} unknowns (from the two runs above):",
             f"  per subdomain: factors {factor_mib:.3f} MiB, factorization {1e3 * factor_s:.1f} "
             f"ms; per million unknowns {1e6 * subdomains_per_unknown:.0f} subdomains and "
             f"{1e6 * multipliers_per_unknown:.0f} multipliers",
             f"  held whole by every rank: {1e6 * held_mib:.0f} MiB per million unknowns, of "
             f"which {1e6 * model_held_mib:.0f} MiB the model before the subdomains (mesh, "
             f"loads, contact; report.json feti.ranks[].model_memory_mib) and the rest Total "
             f"FETI's whole rows, vectors and maps",
             f"  time per product: {1e3 * c_s:.3f} ms per subdomain of the rank (its solve) + "
             f"{1e3 * c_pre:.3f} ms per subdomain of the rank (the preconditioner's "
             f"applications, per product) + {1e9 * c_m:.1f} ns per multiplier of the rank (the "
             f"QP's own work on its share) + the exchanges with the neighbours, "
             f"{1e3 * exchange_b:.3f} ms at {b['per_rank_subdomains']} subdomains per rank, as "
             f"(subdomains per rank)^(2/3) + the coarse problem, "
             f"{1e3 * coarse_b:.3f} ms at {rows_b} rows, as rows^(4/3) (the two runs: "
             f"{1e3 * coarse_a:.3f} ms at {rows_a} rows, exponent {measured_exponent:.2f})",
             f"  assumed: products per run as at n = {n_b} "
             f"({products}, bounded for fixed H/h by theory.md §8.3; measured growth in the "
             "scalability table), one thread per rank, the exchanges and the QP's reductions "
             "as on one machine (no network latency), the coarse problem solved redundantly on "
             "every rank (theory.md §8.8)", ""]
    headers = ["ranks", "subdomains / rank", "multipliers", "factors / rank [MiB]",
               "held whole / rank [MiB]", "factorization [s]", "time per product [s]",
               "subdomains' part [s]", "QP's own part [s]", "exchanges [s]",
               "coarse rows", "coarse part [s]", "QPs' time [s]"]
    rows = []
    for ranks in MODEL_RANKS:
        subdomains = subdomains_per_unknown * MODEL_UNKNOWNS
        per_rank = subdomains / ranks
        multipliers = multipliers_per_unknown * MODEL_UNKNOWNS
        coarse_rows = rows_b / fb["n_subdomains"] * subdomains
        coarse = coarse_b * (coarse_rows / rows_b) ** (4.0 / 3.0)
        exchange = exchange_b * (per_rank / b["per_rank_subdomains"]) ** (2.0 / 3.0)
        per_product = (c_s + c_pre) * per_rank + c_m * multipliers / ranks + exchange + coarse
        rows.append([str(ranks), f"{per_rank:.0f}", f"{multipliers:.3g}",
                     f"{per_rank * factor_mib:.0f}", f"{held_mib * MODEL_UNKNOWNS:.0f}",
                     f"{per_rank * factor_s:.1f}", f"{per_product:.3f}",
                     f"{(c_s + c_pre) * per_rank:.3f}", f"{c_m * multipliers / ranks:.3f}",
                     f"{exchange:.3f}", f"{coarse_rows:.3g}", f"{coarse:.3f}",
                     f"{products * per_product:.0f}"])
    return lines + [hb.table(headers, rows, False), ""]


SEARCH_EXAMPLES = ["geometry/hertz-hemisphere", "geometry/wheel", "obstacles/ball-block",
                   "obstacles/cylinder-slab", "two-bodies/sphere-on-block"]


def contact_search(fricon, out, examples, threads, markdown):
    """The contact search under Total FETI (theory.md §8.7): each example of `examples` (paths
    under examples/, without .toml) solved directly and by "tfeti" with solver.contact_search
    "gap" and "off" (every patch): patches in the QP, products with Q or F, wall time, max |u|."""
    headers = ["example", "backend", "contact_search", "subdomains", "patches in the QP",
               "patches", "products", "time [s]", "max |u| [m]"]
    rows = []
    for name in examples:
        problem = ROOT / "examples" / f"{name}.toml"
        runs = [("cholmod", "gap"), ("tfeti", "gap"), ("tfeti", "off")]
        for backend, search in runs:
            tag = f"{name.replace('/', '-')}-{backend}-{search}"
            rep = solve_file(fricon, out / tag, problem, threads,
                             [f'solver.backend="{backend}"', f'solver.contact_search="{search}"'])
            products = rep["feti"]["n_products"] if "feti" in rep else rep["n_mult"]
            rows.append([name, backend, search,
                         str(rep["feti"]["n_subdomains"]) if "feti" in rep else "-",
                         str(rep["n_candidate_patches"]), str(rep["contact"]["n_patches"]), str(products),
                         f"{rep['wall_s']:.1f}", f"{rep['max_displacement']:.6e}"])
            print(f"  {rows[-1]}", file=sys.stderr, flush=True)
    return ["The contact search: direct, and Total FETI with and without it (products: with Q "
            "directly, with F under tfeti)", "", hb.table(headers, rows, markdown), ""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon")
    ap.add_argument("--scalability", type=int, nargs="*", default=[8, 16, 24])
    ap.add_argument("--cells-per-subdomain", type=int, default=4)
    ap.add_argument("--series", type=int, nargs="*", default=[16, 24])
    ap.add_argument("--series-subdomain-size", type=int, default=1000)
    ap.add_argument("--sizes", type=int, nargs="*", default=[])
    ap.add_argument("--counts", type=int, nargs="*", default=[])
    ap.add_argument("--series-tfeti-only", type=int, nargs="*", default=[])
    ap.add_argument("--scaling", action="store_true")
    ap.add_argument("--preconditioners", action="store_true")
    ap.add_argument("--weak", type=int, nargs=2, default=None)
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", type=pathlib.Path)
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--search", nargs="*", default=None)
    a = ap.parse_args()
    out, tmp = hb.results_folder(a.out, "fricon-tfeti-bench-")
    load = os.getloadavg()[0]
    version = subprocess.run([a.fricon, "--version"], capture_output=True, text=True)
    lines = [f"fricon {version.stdout.strip()}; load average at the start {load:.2f} on "
             f"{os.cpu_count()} cores", ""]
    try:
        if a.scalability and not a.preconditioners:  # its "none" rows are this table's
            lines += scalability(a.fricon, out, a.scalability, a.cells_per_subdomain, a.threads,
                                 a.markdown)
        if a.scaling and a.scalability:
            lines += row_scaling(a.fricon, out, a.scalability[0], a.cells_per_subdomain,
                                 a.threads, a.markdown)
        if a.preconditioners and a.scalability:
            lines += elastic_preconditioners(a.fricon, out, a.scalability,
                                             a.cells_per_subdomain, a.threads, a.markdown)
            lines += preconditioners(a.fricon, out, a.scalability, a.cells_per_subdomain,
                                     a.threads, a.markdown)
        if len(a.sizes) > 1:
            lines += subdomain_sizes(a.fricon, out, a.sizes[0], a.sizes[1:], a.threads,
                                     a.markdown)
        if len(a.counts) > 1:
            lines += subdomain_counts(a.fricon, out, a.counts[0], a.counts[1:], a.threads,
                                      a.markdown)
        if a.weak:
            lines += weak_scaling(a.fricon, out, a.weak[0], a.weak[1], a.series_subdomain_size,
                                  a.mpirun, a.markdown)
        if a.search is not None:
            lines += contact_search(a.fricon, out, a.search or SEARCH_EXAMPLES, a.threads,
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
