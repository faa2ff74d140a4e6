"""Signals, for real: SIGINT, SIGTERM and SIGUSR1 during the QP phase stop the run with exit code 2 and
the last iterate in the .not-converged files; a signal while there is nothing to save (the
factorization) ends the run within a second, even with the machine's cores busy, with exit
code 2 and no result files.

Usage: check_signals.py FRICON EXAMPLES_DIR OUTDIR
"""
import os
import signal
import subprocess
import sys
import time

import common

exe, examples, out = common.arguments(__doc__)
paper = str(examples / "paper-brick.toml")
failures = common.Failures()


def start(args, outdir):
    return subprocess.Popen([exe, "solve", paper, "--out", str(outdir)] + args,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_line(proc, fragment, timeout):
    """Reads stderr until a line contains `fragment`; returns the lines read."""
    lines, t0 = [], time.time()
    while time.time() - t0 < timeout:
        line = proc.stderr.readline()
        if not line:
            break
        lines.append(line)
        if fragment in line:
            return lines
    failures.add(f"no progress line with {fragment!r} within {timeout} s: {lines}")
    return None


def qp_phase(sig):
    # The implicit operator and the paper's MPGP at a tight tolerance keep the run in its QP
    # steps for many seconds.
    outdir = out / f"qp-{sig.name}"
    proc = start(["--set", "mesh.cells=[18,6,6]", "--set", "solver.dual_operator=implicit",
                  "--set", "solver.qp_variant=paper", "--set", "solver.qp_expansion=fixed",
                  "--set", "solver.qp_active_discs=hold", "--set", "solver.qp_rtol=1e-12"],
                 outdir)
    # The monitor's first line (after the header) means outer iteration 1 is done.
    if wait_for_line(proc, "elapsed", 120) is None:
        proc.kill()
        return
    proc.stderr.readline()  # the line of iteration 1
    time.sleep(0.3)
    t0 = time.time()
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    took = time.time() - t0
    if proc.returncode != 2 or "interrupted" not in stderr:
        failures.add(f"{sig.name} in the QP phase: exit {proc.returncode}, expected 2 with "
                     f"'interrupted'\n{stderr}")
    if took > 5:
        failures.add(f"{sig.name} in the QP phase: took {took:.1f} s to stop")
    if (outdir / "report.json").exists():
        failures.add(f"{sig.name}: a report.json that looks complete was written")
    report = outdir / "report.not-converged.json"
    if not report.exists():
        failures.add(f"{sig.name}: no {report.name} with the last iterate")
        return
    r = common.read_report(outdir, report.name)
    if r["status"] != "not_converged" or r["termination"] != "interrupted":
        failures.add(f"{sig.name}: status {r['status']}, termination {r['termination']}")
    if r["outer_iterations"] < 2 or "interrupted" not in r["message"]:
        failures.add(f"{sig.name}: outer_iterations {r['outer_iterations']}, "
                     f"message {r['message']!r}")
    for name in ["solution.not-converged.vtu", "contact.not-converged.vtu",
                 "patches.not-converged.csv", "contact_nodes.not-converged.csv"]:
        if not (outdir / name).exists():
            failures.add(f"{sig.name}: {name} missing")
    rows = (outdir / "patches.not-converged.csv").read_text().splitlines()[1:]
    if len(rows) != r["contact"]["n_patches"] or max(float(x.split(",")[3]) for x in rows) <= 0:
        failures.add(f"{sig.name}: patches.not-converged.csv does not hold the multipliers")


def nothing_to_save():
    # Both cores busy (the case where OpenBLAS's spinning threads made Ctrl-C take 14.5 s); the
    # signal lands in the factorization of a 135,000-unknown stiffness matrix.
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
    try:
        # With the cores taken, the BLAS runs on one thread (no spinning workers).
        time.sleep(0.5)
        small = out / "busy-threads"
        threads = common.solve(exe, paper, small)["factor"]["blas_threads"]
        if threads != 1 and "OPENBLAS_NUM_THREADS" not in os.environ:
            failures.add(f"with both cores busy the BLAS got {threads} threads, expected 1")
        outdir = out / "factorize"
        proc = start(["--set", "mesh.cells=[72,24,24]"], outdir)
        if wait_for_line(proc, "factorize", 120) is None:
            proc.kill()
            return
        time.sleep(0.5)
        t0 = time.time()
        proc.send_signal(signal.SIGINT)
        _, stderr = proc.communicate(timeout=60)
        took = time.time() - t0
    finally:
        for b in busy:
            b.kill()
    if proc.returncode != 2 or "interrupted" not in stderr:
        failures.add(f"SIGINT in the factorization: exit {proc.returncode}\n{stderr}")
    if took > 1.0:
        failures.add(f"SIGINT in the factorization: took {took:.2f} s to stop (limit 1 s)")
    if outdir.exists() and any(outdir.iterdir()):
        failures.add(f"SIGINT in the factorization wrote {sorted(os.listdir(outdir))}")


qp_phase(signal.SIGINT)
qp_phase(signal.SIGTERM)
qp_phase(signal.SIGUSR1)
nothing_to_save()
failures.finish("signals: SIGINT/SIGTERM in the QP phase save the last iterate; before, the run "
                "ends at once")
