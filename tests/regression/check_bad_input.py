"""The bad-input corpus: every malformed or inconsistent problem file is refused cleanly.

Usage: check_bad_input.py FRICON CORPUS_DIR OUTDIR

Each CORPUS_DIR/*.toml starts with a line
    # expect: <fragment> | <fragment> ...
listing text that the error message must contain (the file name and line, the key, what is
wrong). Every file is run as `FRICON solve FILE --out OUTDIR/<name>` and must give exit code 1,
A second line "# requires: petsc" (or "no-petsc") runs the file only in a build with (without)
the PETSc backend, as `FRICON --version` says. Every file must give exit code 1,
exactly one line "fricon: error: ..." on stderr containing every fragment, no sanitizer report
or traceback, no crash or hang (10 s each), and no file in the --out folder.

`fricon check` must refuse what `solve` refuses before it factorizes K: every file is also run as
`FRICON check FILE`, with the same expectations (exit code 1, one error line with every
fragment), unless one of its first lines is "# solve-only: <why>" (an error that only the
factorization or the solve can find, e.g. an ill-conditioned K).
"""
import subprocess
import sys

import common

TIMEOUT_S = 10


def expectations(path):
    first = path.read_text(encoding="utf-8", errors="replace").splitlines()[:1]
    prefix = "# expect:"
    if not first or not first[0].startswith(prefix):
        return None
    frags = [f.strip() for f in first[0][len(prefix):].split("|")]
    return [f for f in frags if f]


def requirement(path):
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()[1:2]
    prefix = "# requires:"
    return lines[0][len(prefix):].strip() if lines and lines[0].startswith(prefix) else None


def solve_only(path):
    """Whether the file's error is one that `fricon check` cannot see (a "# solve-only:" line)."""
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()[:4]
    return any(line.startswith("# solve-only:") for line in lines)


def has_petsc(exe):
    return "petsc" in common.run_ok([exe, "--version"]).stdout


def check(exe, path, out_root):
    """Returns the list of problems with one corpus file (empty when it passes): `solve`, then
    `check` unless the file is solve-only."""
    frags = expectations(path)
    if not frags:
        return ["no '# expect: ...' first line"]
    out = out_root / path.stem
    problems = refused(exe, ["solve", path, "--out", out], frags, out)
    if not solve_only(path):
        problems += [f"fricon check: {p}" for p in refused(exe, ["check", path], frags, None)]
    return problems


def refused(exe, args, frags, out):
    """The problems with one run of the command `args` on a corpus file (empty when it refuses
    the file as expected); `out`, if given, must stay empty."""
    problems = []
    try:
        r = common.run([exe] + args, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return [f"{args[0]} did not finish within {TIMEOUT_S} s"]
    stderr, stdout = r.stderr, r.stdout
    if r.returncode != 1:
        problems.append(f"exit code {r.returncode}, expected 1")
    errors = common.error_lines(stderr)
    if len(errors) != 1:
        problems.append(f"{len(errors)} lines start with 'fricon: error:', expected 1")
    message = errors[0] if errors else ""
    for f in frags:
        if f not in message:
            problems.append(f"message lacks {f!r}")
    for alarm in common.alarms(stderr, stdout):
        problems.append(f"output contains {alarm!r}")
    if out is not None and out.exists() and any(out.iterdir()):
        problems.append(f"wrote into {out}: {sorted(p.name for p in out.iterdir())}")
    if problems:
        problems.append(f"stderr was:\n{stderr.rstrip()}")
    return problems


def main():
    exe, corpus, out_root = common.arguments(__doc__)
    files = sorted(corpus.glob("*.toml"))
    if not files:
        common.fail(f"no *.toml files in {corpus}")
    failed = 0
    petsc = has_petsc(exe)
    skipped = [p for p in files if requirement(p) == ("no-petsc" if petsc else "petsc")]
    for path in skipped:
        print(f"skip {path.name}: requires {requirement(path)}")
    files = [p for p in files if p not in skipped]
    for path in files:
        problems = check(exe, path, out_root)
        if problems:
            failed += 1
            print(f"FAIL {path.name}:\n  " + "\n  ".join(problems), flush=True)
    print(f"{len(files) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
