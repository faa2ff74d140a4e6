"""The PETSc backend against the serial one, end to end, under mpirun (docs/parallel.md).

Usage: check_mpi.py FRICON MPIRUN CASE OUTDIR

Every case runs `fricon solve` and reads back what it wrote (report.json, patches.csv,
contact_nodes.csv). The truth of the distributed runs is the serial CHOLMOD run of the same
discrete problem at tight tolerances (qp_rtol = 1e-12, outer_tol = 2.5e-10), a different
factorization (CHOLMOD's supernodal Cholesky of K against MUMPS's multifrontal LDL^T of the
augmented matrix) and a different dual operator:
  ranks1, ranks2, ranks3  the paper's brick on 1, 2 and 3 ranks
  gmsh2                   the Hertz hemisphere (a Gmsh mesh, a prescribed displacement) on 2 ranks
  quadratic2              the paper's brick with 10-node tetrahedra on 2 ranks
  implicit2               the brick with dual_operator = "implicit" (a distributed solve per
                          product with Q) on 2 ranks
  elastic2                the brick without contact, with gravity, on 2 ranks
  single                  backend petsc without mpirun (a job of one rank)
  partitions              two partitions of the tetrahedra on 2 ranks (graph, blocks) agree
  failing_rank            rank 1 reads a bad value, rank 0 a good one: both end with exit code 1
                          and the message of rank 1, printed once; no hang
  failing_write           rank 0 cannot write its results (checked before the solve): every
                          rank ends with its exit code (4, as a serial run's)
  failing_model           bad input that only rank 0 can find (it alone builds the whole model:
                          a contact boundary the mesh does not have): every rank ends with its
                          error (seen with FRICON_RANK_OUTPUT=all) and exit code 1, printed once
  failing_factorization   the factorization cannot run within solver.memory_per_rank: every
                          rank ends with the same error (seen with FRICON_RANK_OUTPUT=all) and
                          exit code 1, printed once normally; nothing is written
  stop_signal             SIGUSR1 to mpirun during the outer loop: every rank stops, rank 0
                          writes the last iterate (*.not-converged.*), exit code 2
  cholmod_under_mpirun    backend cholmod on 2 ranks is refused once, with the fix
  floating2               a floating body (examples/floating/free-block.toml) on 2 ranks is
                          refused once, naming the body and the backend that solves it
  fault-PHASE-RANK-KIND   a fault injected on one rank in one phase of the run (the test-only
                          FRICON_TEST_FAULT=PHASE:RANK:KIND, docs/parallel.md) on 2 ranks: every
                          rank ends within FAULT_TIMEOUT_S (no process of the job is left) with
                          the message; a failure the ranks agree on is printed once by rank 0
                          with the exit code of its kind (FAULTS), one inside a step that all
                          ranks take together by the failing rank, which ends the job
                          (MPI_Abort, exit code 3)
  fault-single            the same fault in a job of one rank without mpirun: an ordinary error
  fault-malformed         a malformed FRICON_TEST_FAULT is refused, naming it
Agreement: the same number of outer iterations and err(k) to 1e-8; multipliers (per patch) to
1e-8 of the largest; contact-node displacements and the penetration measures to 1e-8 of max |u|;
forces, max |u| and max von Mises to 1e-8 relative.
"""
import os
import pathlib
import signal
import subprocess
import sys
import time

import common

# outer_tol sits between two err(k) of every case here, at least a factor 1.8 from each: at
# 1e-10 the brick's err(13) (1.11e-10 to 1.16e-10 by rank count and operator) made the outer
# iteration count of the serial and the distributed run differ by one on another machine.
TIGHT = ["--set", "solver.qp_rtol=1e-12", "--set", "solver.outer_tol=2.5e-10"]
PETSC = ["--set", "solver.backend=petsc"]
TOL = 1e-8
TIMEOUT_S = 240
# A run with an injected fault ends in seconds (the brick on 2 ranks): longer is a hang.
FAULT_TIMEOUT_S = 60
# Seconds given to mpirun, on SIGTERM, to end its ranks before the whole group is killed, and
# to the job's processes to be gone once mpirun has ended; polled every POLL_S seconds.
KILL_GRACE_S = 10
POLL_S = 0.1
# How each injected fault must end (tests/regression/CMakeLists.txt runs these cases):
# "agreed": every rank learns the error and rank 0 prints it once (exit code 1 for a
# NumericalError, 3 for an internal error); "abort": the failing rank prints it and ends the job
# with MPI_Abort (exit code 3), since the others wait for it inside a collective step.
FAULTS = {
    "model-1-bad_alloc": "agreed",      # validation / rank 0's model
    "share-1-bad_alloc": "abort",       # sizes and B broadcast to every rank
    "partition-1-bad_alloc": "abort",   # PT-Scotch on the distributed dual graph
    "scatter-1-bad_alloc": "abort",     # receiving the part of the model from rank 0
    "assembly-1-numerical": "agreed",   # element matrices of the rank's part
    "analysis-1-bad_alloc": "agreed",   # preparing the MUMPS input, before its analysis
    "factorize-1-bad_alloc": "abort",   # between MUMPS's analysis and its factorization
    "schur-1-generic": "agreed",        # after the factorization (rank 0 completes S)
    "setup-1-bad_alloc": "agreed",      # the distributed solves' right-hand side rows
    "outer-0-numerical": "agreed",      # rank 0 alone, between two distributed solves
    "solve-1-numerical": "abort",       # inside a distributed solve, following rank 0
    "solve-1-bad_alloc": "abort",
    "solve-0-bad_alloc": "abort",       # inside a distributed solve, on rank 0's side
    "gather-1-generic": "abort",        # the ranks' figures gathered for the report
}
KIND_EXIT_CODE = {"numerical": 1, "bad_alloc": 3, "generic": 3}


def mpirun(mpi, ranks):
    return [mpi, "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)]


def run(cmd, expect=0):
    return common.run_ok(cmd, timeout=TIMEOUT_S, expect=expect)


def read_csv(path):
    """The numeric columns of a CSV file by name; {} when there is none (no contact)."""
    if not path.exists():  # no contact: no patches or contact nodes
        return {}
    rows = common.read_rows(path)
    return {k: [float(r[k]) for r in rows] for k in rows[0] if k != "state"} if rows else {}


def results(folder):
    folder = pathlib.Path(folder)
    return (common.read_report(folder), read_csv(folder / "patches.csv"),
            read_csv(folder / "contact_nodes.csv"))


def max_abs(values):
    return max((abs(v) for v in values), default=0.0)


def differences(a_dir, b_dir):
    """What differs beyond TOL between two result folders (empty when they agree)."""
    (ra, pa, na), (rb, pb, nb) = results(a_dir), results(b_dir)
    bad = []
    for key in ("status", "outer_iterations", "n_primal", "n_dual"):
        if ra.get(key) != rb.get(key):
            bad.append(f"{key}: {ra.get(key)} vs {rb.get(key)}")
    ea, eb = ra.get("err_history", []), rb.get("err_history", [])
    if len(ea) == len(eb) and any(abs(x - y) > TOL for x, y in zip(ea, eb)):
        bad.append(f"err_history: {ea} vs {eb}")
    u_scale = ra["max_displacement"]
    for key in ("max_displacement", "max_von_mises", "max_lambda_n", "max_lambda_t",
                "total_normal_force"):
        if key in ra and abs(ra[key] - rb[key]) > TOL * max(abs(ra[key]), 1e-300):
            bad.append(f"{key}: {ra[key]!r} vs {rb[key]!r}")
    for key in ("wn_pos_inf", "max_neg_wn", "max_wt"):
        if key in ra and abs(ra[key] - rb[key]) > TOL * u_scale:
            bad.append(f"{key}: {ra[key]!r} vs {rb[key]!r} (scale max |u| = {u_scale:.3e})")
    lam = [k for k in ("lambda_n", "lambda_t1", "lambda_t2") if k in pa]
    lam_scale = max((max_abs(pa[k]) for k in lam), default=0.0)
    for k in lam:
        d = max_abs([x - y for x, y in zip(pa[k], pb[k])])
        if d > TOL * lam_scale:
            bad.append(f"patches.csv {k}: max difference {d:.3e} > {TOL} x {lam_scale:.3e}")
    for k in ("w_n", "w_t1", "w_t2"):
        if k in na:
            d = max_abs([x - y for x, y in zip(na[k], nb[k])])
            if d > TOL * u_scale:
                bad.append(f"contact_nodes.csv {k}: max difference {d:.3e} > {TOL} x {u_scale:.3e}")
    return bad


def agree(label, a_dir, b_dir):
    bad = differences(a_dir, b_dir)
    if bad:
        sys.exit(f"FAIL {label}:\n  " + "\n  ".join(bad))
    print(f"ok   {label}")


def serial_and_distributed(fricon, mpi, problem, out, ranks, extra=()):
    serial, distributed = out / "serial", out / f"petsc-{ranks}"
    run([fricon, "solve", str(problem), *TIGHT, *extra, "-q", "-o", str(serial)])
    r = run(mpirun(mpi, ranks) + [fricon, "solve", str(problem), *TIGHT, *PETSC, *extra, "-o",
                                  str(distributed)])
    report = common.read_report(distributed)
    par = report.get("parallel", {})
    if par.get("n_ranks") != ranks or len(par.get("ranks", [])) != ranks:
        sys.exit(f"FAIL: report.json parallel = {par}, expected {ranks} ranks")
    if sum(x["n_tets"] for x in par["ranks"]) != report["n_tets"]:
        sys.exit(f"FAIL: the ranks assembled {[x['n_tets'] for x in par['ranks']]} tetrahedra, "
                 f"the mesh has {report['n_tets']}")
    # Only rank 0 holds the whole mesh: the others the nodes of their own tetrahedra.
    held = [x["n_nodes"] for x in par["ranks"]]
    if held[0] != report["n_nodes"] or any(not 0 < h < report["n_nodes"] for h in held[1:]) \
            or sum(held[1:]) > report["n_nodes"] * (ranks - 1) / ranks * 1.5:
        sys.exit(f"FAIL: the ranks hold {held} nodes of the mesh's {report['n_nodes']}: "
                 "rank 0 all, the others only those of their tetrahedra")
    for x in par["ranks"]:
        if not (0 < x["model_memory_mib"] <= x["peak_memory_mib"] and x["mumps_estimate_mib"] > 0):
            sys.exit(f"FAIL: a rank's memory figures are inconsistent: {x}")
    if r.stdout.count("fricon 0.") != 1:
        sys.exit(f"FAIL: the summary is not printed once:\n{r.stdout}")
    agree(f"{problem.name} {' '.join(extra)} on {ranks} rank(s) = serial", serial, distributed)


def expect_error(cmd, fragments, label, code=1, prefix="fricon: error:", env=None):
    r = common.run(cmd, timeout=TIMEOUT_S, env=env)
    errors = common.error_lines(r.stderr, prefix)
    problems = []
    if r.returncode != code:
        problems.append(f"exit code {r.returncode}, expected {code}")
    if len(errors) != 1:
        problems.append(f"{len(errors)} error lines, expected 1")
    for f in fragments:
        if not any(f in e for e in errors):
            problems.append(f"no error line contains {f!r}")
    if problems:
        sys.exit(f"FAIL {label}: " + "; ".join(problems) + f"\nstderr:\n{r.stderr}")
    print(f"ok   {label}: {errors[0]}")
    return errors[0][len(prefix):].strip()


def on_every_rank(cmd, message, ranks=2):
    """Runs cmd with every rank's own output kept: each rank must end with `message`, exit 1."""
    r = common.run(cmd, timeout=TIMEOUT_S, env={**os.environ, "FRICON_RANK_OUTPUT": "all"})
    if r.returncode != 1 or r.stderr.count(message) != ranks:
        sys.exit(f"FAIL: every rank should end with {message!r} and exit code 1; exit code "
                 f"{r.returncode}, stderr:\n{r.stderr}")
    print(f"ok   all {ranks} ranks end with the same error")


def nothing_written(folder):
    if folder.exists() and any(folder.iterdir()):
        sys.exit(f"FAIL: a failed run wrote {sorted(p.name for p in folder.iterdir())}")


def stop_signal(fricon, mpi, brick, outdir):
    # The implicit operator and a tight QP keep the run in its QP steps for many seconds.
    cmd = mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "--set", "mesh.cells=[18,6,6]",
                            "--set", "solver.dual_operator=implicit", "--set",
                            "solver.qp_variant=paper", "--set", "solver.qp_rtol=1e-12", "-o",
                            str(outdir)]
    interrupt_run(cmd, outdir)


def interrupt_run(cmd, outdir):
    """Runs cmd (mpirun ... fricon solve ... -o outdir), sends SIGUSR1 to mpirun once the second
    outer iteration has started: every rank must stop, rank 0 write the last iterate, exit 2."""
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    seen = []
    while time.time() - t0 < 120:  # the monitor's header, then the line of outer iteration 1
        line = proc.stderr.readline()
        seen.append(line)
        if not line or "elapsed" in line:
            break
    if not seen or "elapsed" not in seen[-1]:
        proc.kill()
        sys.exit(f"FAIL: no monitor line within 120 s: {seen}")
    seen.append(proc.stderr.readline())
    time.sleep(0.3)
    proc.send_signal(signal.SIGUSR1)
    stdout, stderr = proc.communicate(timeout=120)
    report = outdir / "report.not-converged.json"
    if proc.returncode != 2 or not report.exists() or (outdir / "report.json").exists():
        sys.exit(f"FAIL: SIGUSR1: exit code {proc.returncode} (expected 2), files "
                 f"{sorted(p.name for p in outdir.iterdir()) if outdir.exists() else []}\n"
                 f"stderr:\n{''.join(seen)}{stderr}")
    r = common.read_report(outdir, report.name)
    if r["termination"] != "interrupted" or r["outer_iterations"] < 2:
        sys.exit(f"FAIL: SIGUSR1: termination {r['termination']}, outer iterations "
                 f"{r['outer_iterations']}")
    for name in ["solution.not-converged.vtu", "patches.not-converged.csv"]:
        if not (outdir / name).exists():
            sys.exit(f"FAIL: SIGUSR1: {name} missing")
    print(f"ok   SIGUSR1 to mpirun: the last iterate (outer iteration {r['outer_iterations']}) "
          f"written, exit code 2")


def processes_with(marker):
    """The processes (pid, command line) whose command line contains `marker`."""
    found = []
    for proc in pathlib.Path("/proc").iterdir():
        if not proc.name.isdigit() or int(proc.name) == os.getpid():
            continue
        try:
            cmdline = (proc / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if marker in cmdline:
            found.append((int(proc.name), cmdline.strip()))
    return found


def run_with_deadline(cmd, env, marker):
    """Runs cmd in its own process group; a run longer than FAULT_TIMEOUT_S fails the test (after
    mpirun, then the whole group, is killed); so does any process of the job (its command line
    contains `marker`) left after mpirun ended. Returns (exit code, stderr)."""
    t0 = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env, start_new_session=True)
    try:
        _, stderr = proc.communicate(timeout=FAULT_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        proc.terminate()  # mpirun ends its ranks on SIGTERM
        try:
            _, stderr = proc.communicate(timeout=KILL_GRACE_S)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            _, stderr = proc.communicate()
        for pid, _ in processes_with(marker):  # ranks outside the group
            os.kill(pid, signal.SIGKILL)
        sys.exit(f"FAIL: HANG: {' '.join(cmd)} did not end within {FAULT_TIMEOUT_S} s "
                 f"(killed)\nstderr:\n{stderr}")
    left = []
    for _ in range(int(KILL_GRACE_S / POLL_S)):  # the ranks may take a moment to be reaped
        left = processes_with(marker)
        if not left:
            break
        time.sleep(POLL_S)
    if left:
        for pid, _ in left:
            os.kill(pid, signal.SIGKILL)
        sys.exit(f"FAIL: processes of the job left after mpirun ended: {left}\nstderr:\n{stderr}")
    print(f"     ended in {time.time() - t0:.1f} s with exit code {proc.returncode}")
    return proc.returncode, stderr


def injected_fault(fricon, mpi, brick, out, fault):
    """A fault injected on one rank of 2 (fault = PHASE-RANK-KIND, FAULTS says how it ends)."""
    phase, rank, kind = fault.split("-")
    value = f"{phase}:{rank}:{kind}"
    folder = out / "f"  # unique to this case: the marker of its processes
    cmd = mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "-q", "-o", str(folder)]
    code, stderr = run_with_deadline(cmd, {**os.environ, "FRICON_TEST_FAULT": value}, str(folder))
    message = f"injected fault FRICON_TEST_FAULT={value}"
    if rank != "0" or FAULTS[fault] == "abort":  # (rank 0's agreed error is printed as it is)
        message = f"rank {rank}: {message}"
    if FAULTS[fault] == "abort":
        expected_code, prefix = 3, "fricon: internal error: "
    else:
        expected_code = KIND_EXIT_CODE[kind]
        prefix = "fricon: error: " if expected_code == 1 else "fricon: internal error: "
    lines = [line for line in stderr.splitlines() if line.startswith("fricon:")]
    if FAULTS[fault] == "abort":
        # The ranks that mpirun ends on MPI_Abort (SIGTERM) may say they were interrupted.
        lines = [line for line in lines if line != "fricon: interrupted (no iterate to write yet)"]
    problems = []
    if code != expected_code:
        problems.append(f"exit code {code}, expected {expected_code}")
    if len(lines) != 1 or not lines[0].startswith(prefix + message):
        problems.append(f"expected one line of fricon's starting {prefix + message!r}, got "
                        f"{lines}")
    if FAULTS[fault] == "agreed" and "MPI_ABORT" in stderr:
        problems.append("the ranks should agree on this failure, not abort")
    if problems:
        sys.exit(f"FAIL {fault} ({FAULTS[fault]}): " + "; ".join(problems) +
                 f"\nstderr:\n{stderr}")
    nothing_written(folder)
    print(f"ok   {value}: {FAULTS[fault]}, every rank ended, exit code {code}: {lines[0]}")


def main():
    fricon, mpi, case, out = sys.argv[1], sys.argv[2], sys.argv[3], pathlib.Path(sys.argv[4])
    examples = common.EXAMPLES
    brick = examples / "paper-brick.toml"
    out.mkdir(parents=True, exist_ok=True)
    if case.startswith("ranks"):
        serial_and_distributed(fricon, mpi, brick, out, int(case[len("ranks"):]))
    elif case == "gmsh2":
        # Frictionless Hertz has an ill-conditioned Q (agglomerated patches on a curved face):
        # at qp_rtol = 1e-12 two correct operators differ by 1e-8 in lambda; tighter here.
        serial_and_distributed(fricon, mpi, examples / "geometry" / "hertz-hemisphere.toml", out, 2,
                               ["--set", "solver.qp_rtol=1e-14"])
    elif case == "quadratic2":
        # 10-node tetrahedra: each rank assembles its part of K and of the loads with the same
        # element (docs/theory.md §2.12), the mesh's edge nodes scattered with its corners.
        serial_and_distributed(fricon, mpi, examples / "paper-brick-quadratic.toml", out, 2)
    elif case == "implicit2":
        serial_and_distributed(fricon, mpi, brick, out, 2,
                               ["--set", "solver.dual_operator=implicit"])
    elif case == "elastic2":
        # With gravity too: every kind of load is assembled in parts by the ranks.
        serial_and_distributed(fricon, mpi, examples / "elastic-brick.toml", out, 2,
                               ["--set", "volume_force=[0.0,0.0,-7.7e4]"])
    elif case == "single":
        run([fricon, "solve", str(brick), *TIGHT, "-q", "-o", str(out / "serial")])
        run([fricon, "solve", str(brick), *TIGHT, *PETSC, "-q", "-o", str(out / "single")])
        agree("backend petsc without mpirun = serial", out / "serial", out / "single")
    elif case == "partitions":
        dirs = []
        for kind in ("graph", "blocks"):
            dirs.append(out / kind)
            run(mpirun(mpi, 2) + [fricon, "solve", str(brick), *TIGHT, *PETSC, "--set",
                                  f"solver.partition={kind}", "-q", "-o", str(dirs[-1])])
            tets = [x["n_tets"] for x in common.read_report(dirs[-1])["parallel"]["ranks"]]
            print(f"     partition {kind}: tetrahedra per rank {tets}")
        agree("partition graph = partition blocks on 2 ranks", *dirs)
    elif case == "failing_rank":
        good = [fricon, "solve", str(brick), *PETSC, "-q", "-o", str(out / "r")]
        cmd = [mpi, "--allow-run-as-root", "--oversubscribe", "-n", "1", *good, ":", "-n", "1",
               *good, "--set", "material.young=-1"]
        expect_error(cmd, ["rank 1:", "material.young", "expected a positive number"],
                     "a bad value on rank 1 ends both ranks")
        nothing_written(out / "r")
    elif case == "failing_write":
        blocker = out / "not-a-folder"
        blocker.write_text("a file where the results folder should be\n")
        expect_error(mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "-q", "-o",
                                        str(blocker / "results")],
                     [str(blocker), "cannot write the results"],
                     "rank 0 cannot write: both ranks end with its exit code", code=4)
    elif case == "failing_factorization":
        # The brick's MUMPS estimate is about 2 MiB per rank: 1 MiB is too little.
        cmd = mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "--set",
                                "solver.memory_per_rank=1", "-q", "-o", str(out / "f")]
        fragments = ["--set solver.memory_per_rank=1: solver.memory_per_rank:",
                     "MUMPS's analysis estimates", "run on more ranks"]
        message = expect_error(cmd, fragments, "the factorization fails on every rank: one message")
        # Every rank's own output (the two ranks' lines may interleave): the same message twice.
        on_every_rank(cmd, message)
        nothing_written(out / "f")
    elif case == "failing_model":
        cmd = mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "--set",
                                "contact.boundary=nowhere", "-q", "-o", str(out / "m")]
        message = expect_error(cmd, ["contact.boundary", "nowhere"],
                               "bad input found by rank 0 alone ends both ranks: one message")
        if message.startswith("rank "):
            sys.exit(f"FAIL: rank 0's error is given as another rank's: {message!r}")
        on_every_rank(cmd, message)
        nothing_written(out / "m")
    elif case == "floating2":
        # The distributed operator has no balance G lambda = e: a floating body is refused by
        # name before any factorization, once, and nothing is written.
        block = examples / "floating" / "free-block.toml"
        cmd = mpirun(mpi, 2) + [fricon, "solve", str(block), *PETSC, "-q", "-o", str(out / "fl")]
        expect_error(cmd, ["solver.backend", "body 0", "floats", "does not solve floating bodies",
                           "cholmod"], "a floating body under the PETSc backend is refused")
        nothing_written(out / "fl")
    elif case == "stop_signal":
        stop_signal(fricon, mpi, brick, out / "s")
    elif case.startswith("fault-") and case[len("fault-"):] in FAULTS:
        injected_fault(fricon, mpi, brick, out, case[len("fault-"):])
    elif case == "fault-single":
        # One rank without mpirun: nobody waits, the fault is an ordinary error.
        expect_error([fricon, "solve", str(brick), *PETSC, "-q", "-o", str(out / "f")],
                     ["injected fault FRICON_TEST_FAULT=solve:0:bad_alloc"],
                     "a fault in a job of one rank is an ordinary error", code=3,
                     prefix="fricon: internal error:",
                     env={**os.environ, "FRICON_TEST_FAULT": "solve:0:bad_alloc"})
    elif case == "fault-malformed":
        expect_error(mpirun(mpi, 2) + [fricon, "solve", str(brick), *PETSC, "-q", "-o",
                                        str(out / "f")],
                     ["FRICON_TEST_FAULT=solve:one:bad_alloc", "expected <phase>:<rank>:<kind>"],
                     "a malformed FRICON_TEST_FAULT is refused",
                     env={**os.environ, "FRICON_TEST_FAULT": "solve:one:bad_alloc"})
    elif case == "cholmod_under_mpirun":
        expect_error(mpirun(mpi, 2) + [fricon, "solve", str(brick), "-q", "-o", str(out / "c")],
                     ["solver.backend", "runs on one process", "--set solver.backend=petsc or tfeti"],
                     "backend cholmod under mpirun -n 2 is refused")
    else:
        sys.exit(f"unknown case {case!r}")


if __name__ == "__main__":
    main()
