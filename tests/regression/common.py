"""What the regression scripts (check_*.py) share: their command line, running the fricon
program, reading its results back, and how a script reports failures and skips.

Each script runs as `python3 check_NAME.py FRICON INPUT OUTDIR` (tests/regression/CMakeLists.txt)
and ends with exit code 0 (passed), 1 (failed: the failures on stderr) or SKIPPED (77, CTest's
SKIP_RETURN_CODE) when the data it needs is absent.
"""
import csv
import json
import pathlib
import subprocess
import sys

SKIPPED = 77  # CTest's SKIP_RETURN_CODE for the tests that set it (CMakeLists.txt)
REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = REPOSITORY / "examples"
# The prefix of the one line a refused input prints on stderr.
ERROR_PREFIX = "fricon: error:"
# Text that only a crash, a sanitizer or an uncaught exception prints.
ALARMS = ("AddressSanitizer", "UndefinedBehaviorSanitizer", "LeakSanitizer", "runtime error:",
          "Traceback", "terminate called", "internal error", "Segmentation fault", "Aborted")


def arguments(usage):
    """The script's arguments FRICON INPUT OUTDIR: FRICON as given, INPUT and OUTDIR as paths,
    OUTDIR created. Another count of arguments ends the script with `usage` (its docstring) and
    exit code 1."""
    if len(sys.argv) != 4:
        sys.exit(usage)
    out = pathlib.Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    return sys.argv[1], pathlib.Path(sys.argv[2]), out


def run(cmd, timeout=None, env=None):
    """Runs a command (its arguments converted to strings) with stdout and stderr captured as
    UTF-8 text (undecodable bytes replaced). A timeout raises subprocess.TimeoutExpired."""
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True,
                          encoding="utf-8", errors="replace", timeout=timeout, env=env)


def run_ok(cmd, timeout=None, expect=0):
    """run(), ending the script (fail) when the exit code is not `expect`."""
    r = run(cmd, timeout=timeout)
    if r.returncode != expect:
        fail(f"{' '.join(map(str, cmd))}: exit code {r.returncode}, expected {expect}\n"
             f"stdout:\n{r.stdout}\nstderr:\n{r.stderr}")
    return r


def solve(exe, problem, folder, *sets, quiet=True, timeout=None, extra=()):
    """`fricon solve PROBLEM --out FOLDER [--quiet] [--set S]... EXTRA...`, which must exit with 0;
    returns the report.json it wrote."""
    cmd = [exe, "solve", problem] + (["--quiet"] if quiet else []) + ["--out", folder]
    for s in sets:
        cmd += ["--set", s]
    run_ok(cmd + list(extra), timeout=timeout)
    return read_report(folder)


def read_report(folder, name="report.json"):
    return json.loads((pathlib.Path(folder) / name).read_text())


def read_rows(path):
    """The rows of a CSV file with a header, as dicts of strings."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_patches(folder, name="patches.csv"):
    """patches.csv of a results folder: one dict per patch, numbers as floats, the state as text."""
    return [{k: (v if k == "state" else float(v)) for k, v in row.items()}
            for row in read_rows(pathlib.Path(folder) / name)]


def error_lines(stderr, prefix=ERROR_PREFIX):
    """The lines of `stderr` that start with `prefix`."""
    return [line for line in stderr.splitlines() if line.startswith(prefix)]


def alarms(*texts):
    """The ALARMS that any of `texts` contains."""
    return [a for a in ALARMS if any(a in t for t in texts)]


def fail(message):
    """Ends the script: the message on stderr, exit code 1."""
    sys.exit(message)


def skip_unless(folder):
    """Ends the script as skipped (SKIPPED) when `folder` (data beside the repository, such as
    ../shared) is absent."""
    if not pathlib.Path(folder).is_dir():
        print(f"skipped: {folder} is absent")
        sys.exit(SKIPPED)


class Failures:
    """The failures a script collects before it ends: finish() exits with 1 and all of them, or
    prints the message of success."""

    def __init__(self, separator="\n\n"):
        self.messages = []
        self.separator = separator

    def add(self, message):
        self.messages.append(message)

    def __bool__(self):
        return bool(self.messages)

    def finish(self, success):
        if self.messages:
            fail(self.separator.join(self.messages))
        print(success)
