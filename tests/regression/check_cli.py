"""The command line's contract: exit codes, messages naming file/line/key, no partial results.

Besides the exit codes 0-3, issue 33:
  - item 6: a results folder that cannot be written ends the run with exit code 4 and a message
    naming it, before the solve (no phase "assembly" on stderr): --out naming a file (left as it
    was), a path under a file, a path under /proc; on a small tmpfs (when mount works here: the
    tests run as root), a full disk before the run (exit 4 before the solve), a disk that fills
    while the results are written (exit 4 after the solve, and neither the earlier run's
    report.json nor a partial file of this run left), and a read-only folder (exit 4 before the
    solve);
  - item 15: `--out ""` is refused (exit 1, naming --out), for solve and plot;
  - item 16: a folder given as the problem file is refused naming it, by solve and check;
  - item 7: a static run removes an earlier run's step files (steps/) and figures (plots/), and
    leaves the other files of those folders;
  - item 25: `fricon mesh info --unit mm` of a brick meshed in millimetres gives its volume and
    face areas in m^3 and m^2 (3 x 1 x 1 m: 3 m^3, the face x0 1 m^2).

Usage: check_cli.py FRICON EXAMPLES_DIR OUTDIR
"""
import re
import subprocess

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

# ---------------------------------------------------------------------------------------------
# Issue 33, item 6: results that cannot be written: exit code 4, before the solve if possible.
# ---------------------------------------------------------------------------------------------
OUTPUT_ERROR = 4


def expect_unwritable(args, *fragments, before_solve=True):
    """A run whose results cannot be written: exit 4, the fragments in its error line, and, when
    `before_solve`, no phase of the solve on stderr."""
    r = common.run([exe] + [str(a) for a in args], timeout=120)
    errors = common.error_lines(r.stderr)
    if r.returncode != OUTPUT_ERROR or len(errors) != 1:
        failures.add(f"{args}: exit {r.returncode} with {len(errors)} error lines, expected "
                     f"{OUTPUT_ERROR} and one\n{r.stderr}")
    for frag in fragments:
        if frag not in "".join(errors):
            failures.add(f"{args}: the error lacks {frag!r}\n{r.stderr}")
    if before_solve and "assembly" in r.stderr:
        failures.add(f"{args}: the solve ran before the folder was found unwritable\n{r.stderr}")
    for alarm in common.alarms(r.stderr, r.stdout):
        failures.add(f"{args}: output contains {alarm!r}")
    return r


a_file = out / "a-file"
a_file.write_text("not a folder\n")
expect_unwritable(["solve", paper, "--out", a_file], str(a_file), "not a folder")
if a_file.read_text() != "not a folder\n":
    failures.add("--out naming a file: the file was changed")
expect_unwritable(["solve", elastic, "--out", a_file / "sub"], str(a_file))
expect_unwritable(["solve", elastic, "--out", "/proc/fricon-results"], "/proc/fricon-results")
expect(["--help"], 0, "4 the results")


def mount_tmpfs(folder, size):
    """A tmpfs of `size` at folder; False when mounting is not permitted here."""
    folder.mkdir(parents=True, exist_ok=True)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(folder)],
                       capture_output=True, text=True)
    return r.returncode == 0


disk = out / "small-disk"
subprocess.run(["umount", str(disk)], capture_output=True)
if not mount_tmpfs(disk, "2m"):
    print("skip the tmpfs cases (full disk, read-only folder): mount is not permitted here")
else:
    try:
        results = disk / "results"
        # An earlier run that fits, then one whose solution.vtu (about 13 MB) does not.
        expect(["solve", elastic, "--out", str(results), "--quiet"], 0)
        if not (results / "report.json").is_file():
            failures.add("full disk: the earlier (small) run wrote no report.json")
        r = expect_unwritable(["solve", elastic, "--out", results, "--set",
                               "mesh.cells=[48,16,16]"], "solution.vtu", before_solve=False)
        left = sorted(p.name for p in results.rglob("*") if p.is_file())
        if left:
            failures.add(f"full disk while writing: files left in the folder: {left}")
        # A disk already full: refused before the solve.
        with open(disk / "filler", "wb") as f:
            try:
                while True:
                    f.write(b"\0" * 65536)
                    f.flush()
            except OSError:
                pass
        expect_unwritable(["solve", elastic, "--out", results], str(results), "No space left")
        (disk / "filler").unlink()
        # A read-only folder holding an earlier run: refused before the solve.
        expect(["solve", elastic, "--out", str(results), "--quiet"], 0)
        subprocess.run(["mount", "-o", "remount,ro", str(disk)], check=True)
        expect_unwritable(["solve", elastic, "--out", results], str(results),
                          "Read-only file system")
    finally:
        subprocess.run(["umount", str(disk)], capture_output=True)

# ---------------------------------------------------------------------------------------------
# Issue 33, items 15, 16 and 25.
# ---------------------------------------------------------------------------------------------
expect(["solve", elastic, "--out", ""], 1, "--out", "empty")
expect(["plot", str(out / "threads"), "--out", ""], 1, "--out", "empty")

folder_problem = out / "a-folder.toml"
folder_problem.mkdir(exist_ok=True)
for command in ("solve", "check"):
    expect([command, str(folder_problem)], 1, str(folder_problem), "is a folder")

stale = out / "stale"
for name in ["steps/solution-0003.vtu", "steps/patches-0003.csv", "steps/notes.txt",
             "plots/force_displacement.png", "plots/notes.txt", "report.json"]:
    (stale / name).parent.mkdir(parents=True, exist_ok=True)
    (stale / name).write_text("an earlier run's\n")
expect(["solve", elastic, "--out", str(stale), "--quiet"], 0)
kept = sorted(str(p.relative_to(stale)) for p in stale.rglob("*") if p.is_file())
expected_kept = ["plots/notes.txt", "report.json", "solution.pvd", "solution.vtu", "steps/notes.txt"]
if kept != expected_kept:
    failures.add(f"a static run into a folder with an earlier run's files left {kept}, expected "
                 f"{expected_kept}")
if "an earlier run" in (stale / "report.json").read_text():
    failures.add("the earlier run's report.json was not replaced")

mm_mesh = out / "brick-mm.msh"
expect(["mesh", "brick", "--size", "3000,1000,1000", "--cells", "6,2,2", "--out", str(mm_mesh)], 0)
info = common.run([exe, "mesh", "info", mm_mesh, "--unit", "mm"])
if info.returncode != 0:
    failures.add(f"mesh info --unit mm: exit {info.returncode}\n{info.stderr}")
volume = re.search(r"volume ([0-9.e+-]+) m\^3", info.stdout)
area = re.search(r"x0 +\d+ triangles, area ([0-9.e+-]+) m\^2", info.stdout)
if not volume or abs(float(volume.group(1)) - 3.0) > 1e-9:
    failures.add(f"mesh info --unit mm: the volume of the 3 x 1 x 1 m brick is not 3 m^3\n"
                 f"{info.stdout}")
if not area or abs(float(area.group(1)) - 1.0) > 1e-9:
    failures.add(f"mesh info --unit mm: the face x0 (1 x 1 m) is not 1 m^2\n{info.stdout}")
expect(["mesh", "info", str(mm_mesh), "--unit", "km"], 1, "--unit")

failures.finish("command line: exit codes and messages as documented")
