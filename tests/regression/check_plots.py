"""Solve the examples with the fricon program and render their figures with scripts/plot_results.py.

Checks:
  - the paper's brick (n = 4) gives the six figures (convergence, friction_law, contact_maps,
    friction_coefficient, friction_circles, deformed) in RESULTS/plots, the script prints exactly
    the files it wrote, and each is a PNG that reads back (matplotlib.image.imread) with a
    non-trivial size and more than one colour; no temporary file is left behind;
  - the elastic brick (no contact) gives only the deformed body, with --out, without error;
  - a folder without report.json is refused with exit status 1 and a message, not a traceback.
Usage: check_plots.py FRICON EXAMPLES_DIR OUTDIR
"""
import pathlib
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

import common  # noqa: E402

SCRIPT = common.REPOSITORY / "scripts" / "plot_results.py"
CONTACT_FIGURES = ["convergence", "friction_law", "contact_maps", "friction_coefficient",
                   "friction_circles", "deformed"]


def solve(exe, problem, out):
    """Solve `problem` into a fresh folder `out`."""
    shutil.rmtree(out, ignore_errors=True)
    common.solve(exe, problem, out, quiet=False)


def plot(results, *extra):
    """Run the plotting script; return the files it reports, one per stdout line."""
    r = common.run_ok([sys.executable, SCRIPT, results, *extra])
    return [pathlib.Path(line) for line in r.stdout.splitlines() if line.strip()]


def check_png(path):
    """The file is a readable PNG of reasonable size that is not a single colour."""
    assert path.is_file(), f"{path} missing"
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    img = mpimg.imread(path)
    assert img.ndim == 3 and img.shape[0] >= 300 and img.shape[1] >= 300, (path, img.shape)
    flat = img.reshape(-1, img.shape[2])
    assert np.ptp(flat, axis=0).max() > 0.1, f"{path} is (nearly) a single colour"
    assert len(np.unique(flat[:: max(1, len(flat) // 20000)], axis=0)) > 10, \
        f"{path} has almost no colours"


def check_folder(folder, expected):
    """Exactly the expected figures, each a valid PNG, and no temporary files."""
    names = sorted(p.name for p in folder.iterdir())
    assert names == sorted(f"{n}.png" for n in expected), (folder, names)
    for n in expected:
        check_png(folder / f"{n}.png")


def main():
    exe, examples, out = common.arguments(__doc__)

    brick = out / "paper-brick"
    solve(exe, examples / "paper-brick.toml", brick)
    written = plot(brick)
    assert sorted(written) == sorted(brick / "plots" / f"{n}.png" for n in CONTACT_FIGURES), \
        written
    check_folder(brick / "plots", CONTACT_FIGURES)

    elastic = out / "elastic-brick"
    solve(exe, examples / "elastic-brick.toml", elastic)
    elastic_plots = out / "elastic-plots"
    shutil.rmtree(elastic_plots, ignore_errors=True)
    written = plot(elastic, "--out", elastic_plots)
    assert written == [elastic_plots / "deformed.png"], written
    check_folder(elastic_plots, ["deformed"])
    assert not (elastic / "plots").exists(), "--out was not honoured"

    empty = out / "not-a-results-folder"
    empty.mkdir(exist_ok=True)
    r = common.run([sys.executable, SCRIPT, empty])
    assert r.returncode == 1, (r.returncode, r.stderr)
    assert "report.json" in r.stderr and "Traceback" not in r.stderr, r.stderr
    print("plots ok")


if __name__ == "__main__":
    main()
