"""Backend "tfeti" on the ranks of an MPI job against the direct solver, end to end
(docs/parallel.md, "Total FETI on ranks").

Usage: check_mpi_tfeti.py FRICON MPIRUN CASE OUTDIR

The truth is the serial CHOLMOD run of the same discrete problem (one factorization of K, no
subdomains) at tight tolerances (qp_rtol = 1e-9, outer_tol = 1e-8). The distributed run cuts the
bodies into subdomains, shares them out among the ranks, and must give the same peak contact
pressure (max lambda_n) and max |u| to 1e-6, and the same status:
  ranks1, ranks2, ranks3  the paper's brick at n = 8 on 16 subdomains, 1, 2 and 3 ranks; the
                          report's shares of the ranks add up to the subdomains and tetrahedra
  hertz2                  the Hertz hemisphere (a Gmsh mesh, a curved obstacle, its geometric
                          updates) on 8 subdomains and 2 ranks
  wheel2                  the wheel (two materials, Coulomb, a curved tread, driven by a prescribed
                          displacement only) on 8 subdomains and 2 ranks
  floating2               a body held only by contact (examples/floating/free-block.toml) on 2
  two_bodies2             two bodies on non-matching meshes (examples/two-bodies) on 2
  quadratic2              10-node tetrahedra on 2 ranks
  lumped2                 the brick at n = 8 on 16 subdomains and 2 ranks with the lumped
                          preconditioner (solver.tfeti_preconditioner, theory.md §8.5), whose
                          products with the subdomains' stiffnesses are sums over the ranks too
  dirichlet2              the same with the Dirichlet preconditioner (the subdomains' Schur
                          complements, each rank factoring its subdomains' interiors)
  path2                   a loading path (the Coulomb brick's friction hysteresis, 21 steps) on 8
                          subdomains and 2 ranks: every step's forces to 1e-6 of its normal force
  dump_dual2              --dump-dual (the contact QP alone) is refused once on 2 ranks, exit 1
  unbalanced2             the free block pushed beyond friction's limit (F = 0.1: 4000 N against
                          mu N = 2000 N): the QP's certificate, found on every rank's share of
                          the multipliers, refuses it once, exit 1, naming both forces; nothing
                          written
  stop_signal             SIGUSR1 to mpirun during the QPs: every rank stops at the same step,
                          rank 0 writes the last iterate (*.not-converged.*), exit code 2
  python2                 fricon.solve from a script under `mpirun -n 2 python3` (docs/python.md,
                          "Under mpirun"): with tfeti both ranks return the whole result (the
                          direct solver's max |u| to 1e-6, stresses on every tetrahedron, 2 ranks
                          in the report); with petsc rank 1 holds none, and its report, arrays and
                          write raise RuntimeError, writing nothing
  fault-PHASE-RANK-KIND   a fault injected on one rank (FRICON_TEST_FAULT, test only): every rank
                          ends within check_mpi.FAULT_TIMEOUT_S with the message, as FAULTS says
"""
import os
import pathlib
import shutil
import sys

import check_mpi
import common

TIGHT = ["--set", "solver.qp_rtol=1e-9", "--set", "solver.outer_tol=1e-8"]
TFETI = ["--set", "solver.backend=tfeti"]
TOL = 1e-6
# How an injected fault ends: "agreed" (every rank raises it, printed once by rank 0, the exit
# code of its kind) or "abort" (the failing rank ends the job: MPI_Abort, exit code 3).
FAULTS = {
    "model-1-bad_alloc": "agreed",        # before the ranks' first step together
    "subdomains-1-numerical": "agreed",   # factoring its own subdomains
    "products-1-bad_alloc": "abort",      # inside the sum of a product with F
}


def compare(label, direct, distributed):
    d, t = common.read_report(direct), common.read_report(distributed)
    bad = []
    # (Not the outer iterations: a stop at err(k) <= outer_tol may come one iteration apart.)
    for key in ("status", "n_primal"):
        if d.get(key) != t.get(key):
            bad.append(f"{key}: {d.get(key)} vs {t.get(key)}")
    for key in ("max_lambda_n", "max_displacement"):
        if key in d and abs(d[key] - t[key]) > TOL * abs(d[key]):
            bad.append(f"{key}: {d[key]!r} vs {t[key]!r}")
    # A loading path: every step's forces, to TOL of its normal force.
    steps_d, steps_t = d.get("steps", []), t.get("steps", [])
    if len(steps_d) != len(steps_t):
        bad.append(f"{len(steps_d)} steps vs {len(steps_t)}")
    for sd, st in zip(steps_d, steps_t):
        scale = abs(sd["normal_force"])
        change = max([abs(sd["normal_force"] - st["normal_force"])] +
                     [abs(a - b) for a, b in zip(sd["tangential_force"], st["tangential_force"])])
        if change > TOL * scale:
            bad.append(f"step {sd['step']}: forces differ by {change:.3e} N, more than {TOL} of "
                       f"the normal force {scale:.3e} N")
    if bad:
        sys.exit(f"FAIL {label}:\n  " + "\n  ".join(bad))
    print(f"ok   {label}")


def check_shares(report, ranks):
    f = report.get("feti", {})
    shares = f.get("ranks", [])
    if f.get("n_ranks") != ranks or len(shares) != ranks:
        sys.exit(f"FAIL: report.json feti has n_ranks {f.get('n_ranks')} and {len(shares)} "
                 f"shares, expected {ranks}")
    if sum(s["n_subdomains"] for s in shares) != f["n_subdomains"] or \
            sum(s["n_tets"] for s in shares) != report["n_tets"]:
        sys.exit(f"FAIL: the ranks' shares {shares} do not add up to {f['n_subdomains']} "
                 f"subdomains and {report['n_tets']} tetrahedra")
    if any(not 0.0 < s["model_memory_mib"] <= s["peak_memory_mib"] for s in shares):
        sys.exit(f"FAIL: the ranks' memory with the model built is not within (0, peak]: {shares}")
    # Every multiplier on one rank (theory.md §8.8), and ghosts only where a rank has neighbours.
    multipliers = f["n_contact"] + f["n_gluing"] + f["n_dirichlet"]
    if sum(s["n_multipliers"] for s in shares) != multipliers:
        sys.exit(f"FAIL: the ranks hold {[s['n_multipliers'] for s in shares]} multipliers, "
                 f"not {multipliers} in all")
    if (ranks == 1) != all(s["n_ghosts"] == 0 for s in shares):
        sys.exit(f"FAIL: ghosts {[s['n_ghosts'] for s in shares]} on {ranks} rank(s)")
    if any(s["n_subdomains"] > 0 and not (s["factor_mib"] > 0 and s["peak_memory_mib"] > 0)
           for s in shares):
        sys.exit(f"FAIL: a rank's figures are missing: {shares}")


def direct_and_tfeti(fricon, mpi, problem, out, ranks, subdomains, extra=(), tfeti_extra=()):
    direct, distributed = out / "direct", out / f"tfeti-{ranks}"
    check_mpi.run([fricon, "solve", str(problem), *TIGHT, *extra, "-q", "-o", str(direct)])
    r = check_mpi.run(check_mpi.mpirun(mpi, ranks) +
                      [fricon, "solve", str(problem), *TIGHT, *TFETI, "--set",
                       f"solver.subdomains={subdomains}", *extra, *tfeti_extra, "-o",
                       str(distributed)])
    if r.stdout.count("fricon 0.") != 1:
        sys.exit(f"FAIL: the summary is not printed once:\n{r.stdout}")
    check_shares(common.read_report(distributed), ranks)
    compare(f"{problem.name} {' '.join(extra)} by tfeti on {subdomains} subdomains and {ranks} "
            "rank(s) = direct", direct, distributed)


def stop_signal(fricon, mpi, brick, outdir):
    # Many subdomains and a tight QP keep the run in its QP steps for seconds.
    cmd = check_mpi.mpirun(mpi, 2) + [
        fricon, "solve", str(brick), *TFETI, "--set", "mesh.cells=[36,12,12]", "--set",
        "solver.subdomains=27", "--set", "solver.qp_rtol=1e-12", "-o", str(outdir)]
    check_mpi.interrupt_run(cmd, outdir)


def injected_fault(fricon, mpi, brick, out, fault):
    phase, rank, kind = fault.split("-")
    value = f"{phase}:{rank}:{kind}"
    folder = out / "f"  # unique to this case: the marker of its processes
    cmd = check_mpi.mpirun(mpi, 2) + [fricon, "solve", str(brick), *TFETI, "--set",
                                      "solver.subdomains=4", "-q", "-o", str(folder)]
    code, stderr = check_mpi.run_with_deadline(cmd, {**os.environ, "FRICON_TEST_FAULT": value},
                                               str(folder))
    message = f"rank {rank}: injected fault FRICON_TEST_FAULT={value}"
    if FAULTS[fault] == "abort":
        expected_code, prefix = 3, "fricon: internal error: "
    else:
        expected_code = check_mpi.KIND_EXIT_CODE[kind]
        prefix = "fricon: error: " if expected_code == 1 else "fricon: internal error: "
    lines = [line for line in stderr.splitlines() if line.startswith("fricon:")
             and line != "fricon: interrupted (no iterate to write yet)"]
    problems = []
    if code != expected_code:
        problems.append(f"exit code {code}, expected {expected_code}")
    if len(lines) != 1 or not lines[0].startswith(prefix + message):
        problems.append(f"expected one line starting {prefix + message!r}, got {lines}")
    if FAULTS[fault] == "agreed" and "MPI_ABORT" in stderr:
        problems.append("the ranks should agree on this failure, not abort")
    if problems:
        sys.exit(f"FAIL {fault} ({FAULTS[fault]}): " + "; ".join(problems) +
                 f"\nstderr:\n{stderr}")
    check_mpi.nothing_written(folder)
    print(f"ok   {value}: {FAULTS[fault]}, every rank ended, exit code {code}: {lines[0]}")


# Run by every rank: the same problem solved by tfeti and petsc on the ranks, then by cholmod on
# each rank alone (the truth); what each rank holds goes to OUT/rank-R.json.
PYTHON_SCRIPT = """
import json, os, sys
import fricon
rank = int(os.environ["OMPI_COMM_WORLD_RANK"])
out = sys.argv[2]
def solved(backend):
    p = fricon.load(sys.argv[1])
    p.update({"mesh.cells": [24, 8, 8], "solver.backend": backend, "solver.qp_rtol": 1e-9,
              "solver.outer_tol": 1e-8})
    return fricon.solve(p)
def attempt(f):
    try:
        f()
        return "ok"
    except RuntimeError as e:
        return "RuntimeError: " + str(e)
t = solved("tfeti")
seen = {"tfeti": {"converged": t.converged, "max_u": t.report["max_displacement"],
                  "n_ranks": t.report["feti"]["n_ranks"], "stress_rows": len(t.stress),
                  "n_tets": len(t.tets)}}
p = solved("petsc")
seen["petsc"] = {"converged": p.converged, "repr": repr(p),
                 "report": attempt(lambda: p.report), "stress": attempt(lambda: p.stress),
                 "write": attempt(lambda: p.write(os.path.join(out, f"petsc-{rank}")))}
seen["direct"] = {"max_u": solved("cholmod").report["max_displacement"]}
with open(os.path.join(out, f"rank-{rank}.json"), "w") as f:
    json.dump(seen, f)
"""


def python_on_ranks(mpi, brick, out):
    shutil.rmtree(out)  # (an earlier run's folders)
    out.mkdir(parents=True)
    script = out / "script.py"
    script.write_text(PYTHON_SCRIPT)
    check_mpi.run(check_mpi.mpirun(mpi, 2) + ["/usr/bin/python3", str(script), str(brick),
                                              str(out)])
    seen = [common.read_report(out, f"rank-{r}.json") for r in (0, 1)]
    problems = []
    for r, s in enumerate(seen):
        t = s["tfeti"]
        gap = abs(t["max_u"] - s["direct"]["max_u"]) / s["direct"]["max_u"]
        if not t["converged"] or t["n_ranks"] != 2 or gap > TOL or \
                t["stress_rows"] != t["n_tets"]:
            problems.append(f"rank {r} tfeti: {t}, direct {s['direct']}, relative gap {gap:.1e}")
    if seen[0]["tfeti"] != seen[1]["tfeti"]:
        problems.append(f"the ranks' tfeti results differ: {seen[0]['tfeti']} {seen[1]['tfeti']}")
    p0, p1 = seen[0]["petsc"], seen[1]["petsc"]
    if not p0["converged"] or any(p0[k] != "ok" for k in ("report", "stress", "write")):
        problems.append(f"rank 0 petsc: {p0}")
    if p1["converged"] != p0["converged"] or "rank 1 of 2" not in p1["repr"] or \
            any(not p1[k].startswith("RuntimeError") or "hold no result" not in p1[k]
                for k in ("report", "stress", "write")):
        problems.append(f"rank 1 petsc: {p1}")
    if (out / "petsc-1").exists():
        problems.append("rank 1 wrote a petsc results folder")
    if problems:
        sys.exit("FAIL: fricon.solve under mpirun:\n" + "\n".join(problems))
    print(f"ok   fricon.solve under mpirun -n 2: tfeti max |u| {seen[0]['tfeti']['max_u']:.9e} on "
          f"both ranks (direct {seen[0]['direct']['max_u']:.9e}); petsc's rank 1 holds no "
          "result and says so")


def main():
    fricon, mpi, case, out = sys.argv[1], sys.argv[2], sys.argv[3], pathlib.Path(sys.argv[4])
    examples = common.EXAMPLES
    brick = examples / "paper-brick.toml"
    n8 = ["--set", "mesh.cells=[24,8,8]"]
    out.mkdir(parents=True, exist_ok=True)
    if case.startswith("ranks"):
        direct_and_tfeti(fricon, mpi, brick, out, int(case[len("ranks"):]), 16, n8)
    elif case == "hertz2":
        direct_and_tfeti(fricon, mpi, examples / "geometry" / "hertz-hemisphere.toml", out, 2, 8)
    elif case == "wheel2":
        direct_and_tfeti(fricon, mpi, examples / "geometry" / "wheel.toml", out, 2, 8)
    elif case == "floating2":
        direct_and_tfeti(fricon, mpi, examples / "floating" / "free-block.toml", out, 2, 8)
    elif case == "two_bodies2":
        direct_and_tfeti(fricon, mpi, examples / "two-bodies" / "stacked-blocks.toml", out, 2, 8)
    elif case in ("lumped2", "dirichlet2"):
        kind = case[:-1]
        direct_and_tfeti(fricon, mpi, brick, out, 2, 16, n8,
                         ["--set", f'solver.tfeti_preconditioner="{kind}"'])
        if common.read_report(out / "tfeti-2")["feti"]["n_preconditioner"] <= 0:
            sys.exit(f"FAIL: the {kind} preconditioner was not applied")
    elif case == "quadratic2":
        direct_and_tfeti(fricon, mpi, examples / "paper-brick-quadratic.toml", out, 2, 8)
    elif case == "path2":
        direct_and_tfeti(fricon, mpi, examples / "loading" / "brick-hysteresis.toml", out, 2, 8)
        steps = sorted((out / "tfeti-2" / "steps").glob("patches-*.csv")) \
            if (out / "tfeti-2" / "steps").exists() else []
        print(f"     {len(steps)} step files written (by rank 0)")
    elif case == "dump_dual2":
        # Refused before the solve, on every rank: one message, exit code 1, nothing written.
        cmd = check_mpi.mpirun(mpi, 2) + [fricon, "solve", str(brick), *TFETI, "--dump-dual",
                                          str(out / "dual.json"), "-q", "-o", str(out / "d")]
        check_mpi.expect_error(cmd, ["--dump-dual", "tfeti", "solver.backend"],
                               "--dump-dual with tfeti on 2 ranks is refused once")
        check_mpi.nothing_written(out / "d")
    elif case == "unbalanced2":
        cmd = check_mpi.mpirun(mpi, 2) + [fricon, "solve", str(examples / "floating" /
                                                            "free-block.toml"), *TFETI,
                                          "--set", "contact.friction.value=0.1", "-q", "-o",
                                          str(out / "u")]
        check_mpi.expect_error(cmd, ["floats", "is 4000 N", "at most 2000 N"],
                               "a push beyond friction's limit on 2 ranks is refused once")
        check_mpi.nothing_written(out / "u")
    elif case == "python2":
        python_on_ranks(mpi, brick, out)
    elif case == "stop_signal":
        stop_signal(fricon, mpi, brick, out / "s")
    elif case.startswith("fault-") and case[len("fault-"):] in FAULTS:
        injected_fault(fricon, mpi, brick, out, case[len("fault-"):])
    else:
        sys.exit(f"unknown case {case!r}")


if __name__ == "__main__":
    main()
