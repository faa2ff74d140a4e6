"""Strong scaling of the PETSc backend on this machine, against the CHOLMOD backend.

Usage: /usr/bin/python3 bench/petsc_scaling.py FRICON [--mpirun MPIRUN] [--n 32 48] [--ranks 1 2]

For each mesh parameter n of the paper's brick (3n x n x n cubes, 5 tetrahedra each, n = 48 is
1.04 million unknowns) it runs, one after the other and on an otherwise idle machine:
  cholmod     `fricon solve` on one process (the default backend)
  petsc P     `mpirun -n P fricon solve --set solver.backend=petsc` for each P of --ranks
and prints, from each run's report.json: wall time in all and per phase, the factor's entries
and operations, the outer iterations, the peak resident memory of every rank (getrusage, as the
run reports it; for cholmod, of the process, measured by this script the same way) and the
memory MUMPS allocated on every rank (and each rank's peak once its input is built: on rank 0
the whole model, mesh, f and contact discretization, on the others their part of the mesh); then the ratios measured in the same run: petsc 1 rank /
cholmod (time), and the peak memory per rank of P ranks / 1 rank.
Each run solves the paper's problem (param = 6e4, g = 2e7) with fricon's default tolerances.
Results go to a temporary folder that is removed at the end.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "paper-brick.toml"
PHASES = ("mesh", "assembly", "contact", "partition", "factorize", "dual", "qp", "recovery",
          "postprocess")

# A process that runs the command and prints the peak resident memory of its largest child [KiB].
PEAK_WRAPPER = ("import resource, subprocess, sys; r = subprocess.run(sys.argv[1:]); "
                "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss); sys.exit(r.returncode)")


def solve(cmd, out):
    r = subprocess.run([sys.executable, "-c", PEAK_WRAPPER, *cmd, "-q", "-o", str(out)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    report = json.loads((out / "report.json").read_text())
    report["wrapper_peak_mib"] = int(r.stdout.split()[-1]) / 1024.0
    return report


def describe(label, rep):
    t = rep["timings"]
    phases = "  ".join(f"{p} {t[p]:.2f}" for p in PHASES if p in t)
    par = rep.get("parallel")
    if par:
        memory = ", ".join(f"{x['peak_memory_mib']:.0f}" for x in par["ranks"])
        mumps = ", ".join(f"{x['mumps_memory_mib']:.0f}" for x in par["ranks"])
        model = ", ".join(f"{x['model_memory_mib']:.0f}" for x in par["ranks"])
        tets = ", ".join(str(x["n_tets"]) for x in par["ranks"])
        mem = (f"peak memory per rank [MiB] {memory}; MUMPS per rank [MiB] {mumps}; tets per rank "
               f"{tets}\n  {'':<10} peak memory per rank with its input built (rank 0: "
               f"the whole model; others: their part) [MiB] {model}\n  {'':<10} MUMPS analysis {par['analysis_s']:.2f} s (rank 0), numerical "
               f"factorization {par['factorization_s']:.2f} s; BLAS threads per rank "
               f"{rep['factor']['blas_threads']}")
    else:
        mem = f"peak memory [MiB] {rep['wrapper_peak_mib']:.0f}"
    f = rep["factor"]
    print(f"  {label:<10} {rep['time_s']:8.2f} s  outer its {rep['outer_iterations']}  "
          f"nnz(factor) {f['nnz_L']:.3e}  flops {f['flops']:.3e}")
    print(f"  {'':<10} phases [s]: {phases}")
    print(f"  {'':<10} {mem}")


def peak_per_rank(rep):
    par = rep.get("parallel")
    return max(x["peak_memory_mib"] for x in par["ranks"]) if par else rep["wrapper_peak_mib"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fricon")
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--n", type=int, nargs="+", default=[32, 48])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    opts = ap.parse_args()
    mpi = [opts.mpirun, "--allow-run-as-root", "--oversubscribe", "-n"]
    with tempfile.TemporaryDirectory() as tmp:
        for n in opts.n:
            mesh = ["--set", f"mesh.cells=[{3 * n},{n},{n}]"]
            base = [opts.fricon, "solve", str(EXAMPLE), *mesh]
            serial = solve(base, pathlib.Path(tmp) / f"cholmod-{n}")
            print(f"paper brick n = {n}: {serial['n_primal']} unknowns, "
                  f"n_dual = {serial['n_dual']}")
            describe("cholmod", serial)
            runs = {}
            for p in opts.ranks:
                runs[p] = solve(mpi + [str(p)] + base + ["--set", "solver.backend=petsc"],
                                pathlib.Path(tmp) / f"petsc-{n}-{p}")
                describe(f"petsc {p}", runs[p])
            if 1 in runs:
                print(f"  ratio      petsc 1 rank / cholmod: time "
                      f"{runs[1]['time_s'] / serial['time_s']:.2f}, peak memory "
                      f"{peak_per_rank(runs[1]) / peak_per_rank(serial):.2f}")
                for p in opts.ranks:
                    if p != 1:
                        print(f"  ratio      petsc {p} ranks / 1 rank: time "
                              f"{runs[p]['time_s'] / runs[1]['time_s']:.2f}, largest peak memory "
                              f"per rank {peak_per_rank(runs[p]) / peak_per_rank(runs[1]):.2f}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
