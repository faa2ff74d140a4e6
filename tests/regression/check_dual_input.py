"""The dual-solve corpus: small hand-made problem files for `fricon dual solve` (Siconos .dat,
local and global, dense and sparse-block; fricon's own dual files), good and bad.

Usage: check_dual_input.py FRICON CORPUS_DIR OUTDIR

Each problem file CORPUS_DIR/NAME.* has a sibling NAME.expect whose lines (after '#' comments)
say what must happen:
    exit <code>                        the exit code (0 solved, 1 bad input)
    stdout: <fragment> | <fragment>    text that standard output must contain
    stderr: <fragment> | <fragment>    text of the one "fricon: error:" line (bad input)
    r: <numbers>                       the reactions (checked by tests/unit/driver/dual_input_test.cpp)
Every bad file must give exactly one line "fricon: error: ..." on stderr containing every
fragment, no crash, sanitizer report or hang (10 s each).
"""
import subprocess

import common

TIMEOUT_S = 10

exe, corpus, out = common.arguments(__doc__)


def expectations(path):
    exp = {"exit": None, "stdout": [], "stderr": []}
    for line in path.read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        key, _, value = line.partition(" ")
        key = key.rstrip(":")
        if key == "exit":
            exp["exit"] = int(value)
        elif key in ("stdout", "stderr"):
            exp[key] += [f.strip() for f in value.split("|") if f.strip()]
        elif key != "r":
            raise ValueError(f"{path}: unknown line {line!r}")
    return exp


def check(path, exp):
    try:
        r = common.run([exe, "dual", "solve", path], timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return [f"did not finish within {TIMEOUT_S} s"]
    problems = []
    if r.returncode != exp["exit"]:
        problems.append(f"exit code {r.returncode}, expected {exp['exit']}")
    problems += [f"alarm {a!r} in the output" for a in common.alarms(r.stdout + r.stderr)]
    problems += [f"stdout lacks {f!r}" for f in exp["stdout"] if f not in r.stdout]
    if exp["exit"] == 0 and "  solved" not in r.stdout:
        problems.append("not 'solved'")
    if exp["stderr"]:
        errors = common.error_lines(r.stderr)
        if len(errors) != 1:
            problems.append(f"{len(errors)} 'fricon: error:' lines, expected 1")
        else:
            problems += [f"the error lacks {f!r}" for f in exp["stderr"] if f not in errors[0]]
    if problems:
        problems.append(f"stdout:\n{r.stdout}\nstderr:\n{r.stderr}")
    return problems


files = sorted(p for p in corpus.iterdir() if p.suffix not in (".expect", ".md"))
failures = common.Failures(separator="\n")
for path in files:
    expect = path.with_suffix(".expect")
    if not expect.exists():
        failures.add(f"{path.name}: no {expect.name}")
        continue
    for p in check(path, expectations(expect)):
        failures.add(f"{path.name}: {p}")
orphans = [e.name for e in corpus.glob("*.expect")
           if not any(p.stem == e.stem for p in files)]
for o in orphans:
    failures.add(f"{o}: no problem file")
good = sum(1 for p in files if expectations(p.with_suffix(".expect"))["exit"] == 0
           if p.with_suffix(".expect").exists())
if len(files) < 10 or good < 3:
    failures.add(f"the corpus is too small: {len(files)} files, {good} good")
failures.finish(f"dual input corpus: {len(files)} files ({good} good, {len(files) - good} bad) "
                "checked")
