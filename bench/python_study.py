#!/usr/bin/python3
"""A parameter study from Python against the same study as command-line runs (make bench).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_study.py build/apps/fricon/fricon \
        [--n 8] [--runs 20] [--threads 1]

Both do the same RUNS solves of the paper's brick at mesh parameter n (the friction law's param
swept over RUNS values), in the same run of this script:
  python       fricon.solve(...) in this process, and again with Result.write() of every file
  command line `fricon solve --quiet --out DIR` per run, one process each
  start-up     `fricon --version` per run: what a process costs before it solves anything
Printed: wall time of each, the command line less its start-up, the ratio python / (command line
- start-up), the library's own time (report time_s) summed, and the peak resident memory of this
process and of the largest child.
"""
import argparse
import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

import fricon

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAPER_BRICK = ROOT / "examples" / "paper-brick.toml"


def timed(fn):
    start = time.perf_counter()
    value = fn()
    return time.perf_counter() - start, value


def main():
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("fricon", help="the fricon program")
    args.add_argument("--n", type=int, default=8)
    args.add_argument("--runs", type=int, default=20)
    args.add_argument("--threads", type=int, default=1)
    opts = args.parse_args()
    params = np.geomspace(2.0e4, 3.0e5, opts.runs)
    cells = f"[{3 * opts.n},{opts.n},{opts.n}]"
    work = pathlib.Path(tempfile.mkdtemp(prefix="fricon-python-study-"))

    problem = fricon.load(PAPER_BRICK)
    problem.mesh.cells = [3 * opts.n, opts.n, opts.n]

    def python_study(write):
        library = 0.0
        for i, param in enumerate(params):
            problem.contact.friction.param = float(param)
            r = fricon.solve(problem, threads=opts.threads)
            if not r.converged:
                sys.exit(f"param = {param:g}: NOT CONVERGED: {r.message}")
            library += r.report["time_s"]
            if write:
                r.write(str(work / f"py{i}"))
        return library

    def cli_study():
        for i, param in enumerate(params):
            subprocess.run([opts.fricon, "--threads", str(opts.threads), "solve", str(PAPER_BRICK),
                            "--quiet", "--out", str(work / f"cli{i}"), "--set",
                            f"mesh.cells={cells}", "--set", f"contact.friction.param={param!r}"],
                           check=True)

    def startup():
        for _ in params:
            subprocess.run([opts.fricon, "--version"], check=True, capture_output=True)

    python_solve_s, library_s = timed(lambda: python_study(False))
    python_write_s, _ = timed(lambda: python_study(True))
    cli_s, _ = timed(cli_study)
    startup_s, _ = timed(startup)
    own_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    child_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024

    print(f"python study: {opts.runs} solves of the paper brick, n = {opts.n} "
          f"({problem.to_dict()['mesh']['cells']} cubes), BLAS threads {opts.threads}")
    print(f"  python, solve only          {python_solve_s:8.3f} s  "
          f"(library time_s summed {library_s:.3f} s)")
    print(f"  python, solve + write       {python_write_s:8.3f} s")
    print(f"  command line                {cli_s:8.3f} s")
    print(f"  command-line start-up       {startup_s:8.3f} s  ({opts.runs} x fricon --version)")
    print(f"  command line - start-up     {cli_s - startup_s:8.3f} s")
    print(f"  ratio python (solve + write) / (command line - start-up) = "
          f"{python_write_s / (cli_s - startup_s):.3f}")
    print(f"  peak memory: this process {own_mib:.0f} MiB, largest child {child_mib:.0f} MiB")
    for d in work.iterdir():
        for f in d.iterdir():
            f.unlink()
        d.rmdir()
    work.rmdir()


if __name__ == "__main__":
    main()
