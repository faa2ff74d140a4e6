"""The command line's contract: exit codes, messages naming file/line/key, no partial results.

Usage: check_cli.py FRICON EXAMPLES_DIR OUTDIR
"""
import common

exe, examples, out = common.arguments(__doc__)
failures = common.Failures()


def expect(args, code, *fragments, results=None):
    r = common.run([exe] + args)
    if r.returncode != code:
        failures.add(f"{args}: exit {r.returncode}, expected {code}\n{r.stdout}{r.stderr}")
    for frag in fragments:
        if frag not in r.stderr + r.stdout:
            failures.add(f"{args}: output lacks {frag!r}\n{r.stderr}")
    if results is not None and (results / "report.json").exists():
        failures.add(f"{args}: a failed run left {results / 'report.json'}")


elastic = str(examples / "elastic-brick.toml")
expect(["--help"], 0, "solve", "check")
expect(["solve", "--help"], 0, "--set", "--out")
expect(["check", elastic], 0, "valid")
expect(["solve", str(out / "missing.toml")], 1, "missing.toml")

bad = out / "bad.toml"
bad.write_text('[mesh]\nkind = "brick"\nsize = [3.0, 1.0, 1.0]\ncells = [6, 2, 2]\n\n'
               '[material]\nyoung = -5.0\npoisson = 0.3\n\n[[dirichlet]]\nboundary = "x0"\n')
expect(["solve", str(bad), "--out", str(out / "bad")], 1, "bad.toml", ":7", "young",
       results=out / "bad")

typo = out / "typo.toml"
typo.write_text('[mesh]\ncells = [6, 2, 2]\n\n[material]\nyoung = 2e11\npoisson = 0.3\n'
                'poison = 0.3\n\n[[dirichlet]]\nboundary = "x0"\n')
expect(["solve", str(typo), "--out", str(out / "typo")], 1, "typo.toml", ":7", "poison",
       results=out / "typo")

notag = out / "notag.toml"
notag.write_text('[mesh]\ncells = [6, 2, 2]\n\n[material]\nyoung = 2e11\npoisson = 0.3\n\n'
                 '[[dirichlet]]\nboundary = "left"\n')
expect(["solve", str(notag), "--out", str(out / "notag")], 1, "left", "does not exist",
       results=out / "notag")

free = out / "free.toml"
free.write_text('[mesh]\ncells = [6, 2, 2]\n\n[material]\nyoung = 2e11\npoisson = 0.3\n\n'
                '[[traction]]\nboundary = "x1"\nvalue = [1e6, 0, 0]\n')
expect(["solve", str(free), "--out", str(out / "free")], 1, "not positive definite",
       results=out / "free")

expect(["solve", elastic, "--out", str(out / "set"), "--set", "material.poisson=0.7"], 1,
       "poisson", results=out / "set")
expect(["solve", elastic, "--out", str(out / "set2"), "--set", "material.nonsense=1"], 1,
       "nonsense", results=out / "set2")

# --threads sets the BLAS threads (recorded in report.json) and refuses nonsense.
expect(["solve", elastic, "--out", str(out / "threads"), "--threads", "1", "--quiet"], 0)
report = out / "threads" / "report.json"
if not report.exists() or common.read_report(out / "threads")["factor"]["blas_threads"] != 1:
    failures.add("--threads 1: report.json factor.blas_threads is not 1")
expect(["solve", elastic, "--out", str(out / "threads0"), "--threads", "0"], 1, "--threads",
       results=out / "threads0")

# Not converged: exit 2, the last iterate under names that say so, no report.json.
paper = str(examples / "paper-brick.toml")
nc = out / "nc"
expect(["solve", paper, "--out", str(nc), "--set", "solver.outer_max=2"], 2, "NOT CONVERGED",
       "err(k)", results=nc)
for name in ["report.not-converged.json", "solution.not-converged.vtu", "patches.not-converged.csv"]:
    if not (nc / name).exists():
        failures.add(f"not converged run did not write {name}")
# The report of a run that did not converge says so, with the reason (README).
if (nc / "report.not-converged.json").exists():
    r = common.read_report(nc, "report.not-converged.json")
    if r["status"] != "not_converged" or r["termination"] != "iteration_limit":
        failures.add(f"report.not-converged.json: status {r['status']}, "
                     f"termination {r['termination']}")
# A later converged run in the same folder replaces the not-converged files.
expect(["solve", paper, "--out", str(nc), "--quiet"], 0)
if (nc / "report.not-converged.json").exists() or not (nc / "report.json").exists():
    failures.add("a converged run must replace the not-converged results")

failures.finish("command line: exit codes and messages as documented")
