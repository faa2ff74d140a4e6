"""Solve the examples with the fricon program and render their figures with scripts/plot_results.py.

Checks:
  - the paper's brick (n = 4) gives the six figures (convergence, friction_law, contact_maps,
    friction_coefficient, friction_circles, deformed) in RESULTS/plots, the script prints exactly
    the files it wrote, and each is a PNG that reads back (matplotlib.image.imread) with a
    non-trivial size and more than one colour; no temporary file is left behind;
  - the elastic brick (no contact) gives only the deformed body, with --out, without error;
  - a folder without report.json is refused with exit status 1 and a message, not a traceback;
  - a run that did not converge (issue 33, item 14: paper brick with solver.outer_max = 2,
    exit 2): `fricon plot` and `fricon solve --plot` draw its last iterate, the six figures
    named NAME.not-converged.png, and no figure of a converged run;
  - the figures of an earlier run are removed (issue 33, item 7): the path's
    force_displacement.png and stick_slip_steps.png, plotted again into the same folder from the
    static brick's results, are gone; a file of another name stays;
  - a loading path: a copy of the brick's folder with a fabricated steps.csv and
    steps/patches-NNNN.csv (fabricate_steps; the patches of patches.csv, their states changed
    from step to step) gives force_displacement and stick_slip_steps besides the six figures;
  - the zoom of the contact-surface maps (plot_results.map_limits): on Hertz's hemisphere
    (geometry/hertz-hemisphere.toml, a contact zone of a few mm on a surface of 10 cm) the window
    is zoomed, holds the whole contact zone and is below ZOOM_MAX_WINDOW of the surface's bounding
    box, and its figures are written; on the brick, where the whole face touches, no zoom.
Usage: check_plots.py FRICON EXAMPLES_DIR OUTDIR
"""
import csv
import json
import pathlib
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

import common  # noqa: E402

SCRIPT = common.REPOSITORY / "scripts" / "plot_results.py"
sys.path.insert(0, str(SCRIPT.parent))
import plot_results  # noqa: E402

CONTACT_FIGURES = ["convergence", "friction_law", "contact_maps", "friction_coefficient",
                   "friction_circles", "deformed"]
STEP_FIGURES = ["force_displacement", "stick_slip_steps"]
FABRICATED_STEPS = 5
# The zoomed window of Hertz's maps against the surface's bounding box (areas): a contact zone of
# radius ~3.3 mm on a hemisphere of radius 50 mm gives ~1 %.
ZOOM_MAX_WINDOW = 0.05


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


def fabricate_steps(folder, n):
    """Turns a results folder into that of a loading path of `n` steps on its first traction:
    steps.csv (the columns fricon writes) and steps/patches-NNNN.csv, copies of patches.csv
    whose patches not separated stick, then slip from the lowest x on, more at every step;
    report.json gets problem.loading.steps."""
    rows = common.read_rows(folder / "patches.csv")
    x = [float(r["x"]) for r in rows]
    order = sorted(range(len(rows)), key=x.__getitem__)
    (folder / "steps").mkdir(exist_ok=True)
    table = []
    for k in range(1, n + 1):
        f = k / n
        slipping = set(order[:int(len(rows) * (k - 1) / n)])
        states = [r["state"] if r["state"] == "separated" else
                  "slip" if i in slipping else "stick" for i, r in enumerate(rows)]
        with open(folder / "steps" / f"patches-{k:04d}.csv", "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(dict(r, state=s) for r, s in zip(rows, states))
        normal = sum(float(r["lambda_n"]) * float(r["area"]) for r in rows)
        tangential = -0.3 * normal * min(1.0, 1.5 * f)
        table.append([k, f, normal, tangential, 0.0, 0.0, -tangential, 0.0, normal,
                      2e-5 * f, 0.0, 1e-5 * f, 1e-6 * f, 1e-6 * f, states.count("stick"),
                      states.count("slip"), states.count("separated"), 3, 40, 1e-12, 0.5,
                      "converged"])
    with open(folder / "steps.csv", "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["step", "factor.traction[0]", "normal_force", "tangential_force_x",
                         "tangential_force_y", "tangential_force_z", "reaction_x", "reaction_y",
                         "reaction_z", "displacement.traction[0]_x", "displacement.traction[0]_y",
                         "displacement.traction[0]_z", "max_slip", "max_accumulated_slip",
                         "n_stick", "n_slip", "n_separated", "outer_iterations", "n_mult",
                         "equilibrium_residual", "time_s", "status"])
        writer.writerows(table)
    report = common.read_report(folder)
    report["problem"]["loading"] = {"steps": n}
    (folder / "report.json").write_text(json.dumps(report, indent=2))


def check_zoom(hertz, brick):
    """The maps of Hertz's results folder `hertz` zoom to the contact zone, those of the brick
    (the whole face touches) do not."""
    report = plot_results.read_report(hertz)
    surface = plot_results.load_contact(hertz, report)
    limits = plot_results.map_limits(surface)
    window = (limits["xlim"], limits["ylim"])
    ratio = plot_results.box_area(window) / plot_results.box_area(limits["full"])
    assert limits["zoomed"] and ratio < ZOOM_MAX_WINDOW, (limits["zoomed"], ratio)
    tri = surface["tri"]
    corners = tri.triangles[limits["in_contact"]]
    assert corners.size, "hertz: no triangle in contact"
    for values, (lo, hi) in ((tri.x[corners], limits["xlim"]), (tri.y[corners], limits["ylim"])):
        assert lo <= values.min() and values.max() <= hi, ("contact zone outside the window",
                                                            lo, hi, values.min(), values.max())
    print(f"hertz: the maps' window is {ratio:.2%} of the surface's bounding box")
    written = plot(hertz)
    assert sorted(written) == sorted(hertz / "plots" / f"{n}.png" for n in CONTACT_FIGURES), \
        written
    check_folder(hertz / "plots", CONTACT_FIGURES)

    report = plot_results.read_report(brick)
    assert not plot_results.map_limits(plot_results.load_contact(brick, report))["zoomed"], \
        "the brick's maps are zoomed"


def main():
    exe, examples, out = common.arguments(__doc__)

    brick = out / "paper-brick"
    solve(exe, examples / "paper-brick.toml", brick)
    written = plot(brick)
    assert sorted(written) == sorted(brick / "plots" / f"{n}.png" for n in CONTACT_FIGURES), \
        written
    check_folder(brick / "plots", CONTACT_FIGURES)

    path = out / "paper-brick-steps"
    shutil.rmtree(path, ignore_errors=True)
    shutil.copytree(brick, path, ignore=shutil.ignore_patterns("plots"))
    fabricate_steps(path, FABRICATED_STEPS)
    written = plot(path)
    assert sorted(written) == sorted(path / "plots" / f"{n}.png"
                                     for n in CONTACT_FIGURES + STEP_FIGURES), written
    check_folder(path / "plots", CONTACT_FIGURES + STEP_FIGURES)

    hertz = out / "hertz"
    solve(exe, examples / "geometry" / "hertz-hemisphere.toml", hertz)
    check_zoom(hertz, brick)

    elastic = out / "elastic-brick"
    solve(exe, examples / "elastic-brick.toml", elastic)
    elastic_plots = out / "elastic-plots"
    shutil.rmtree(elastic_plots, ignore_errors=True)
    written = plot(elastic, "--out", elastic_plots)
    assert written == [elastic_plots / "deformed.png"], written
    check_folder(elastic_plots, ["deformed"])
    assert not (elastic / "plots").exists(), "--out was not honoured"

    # Figures of an earlier run in the output folder: the path's go, another file stays.
    mine = path / "plots" / "notes.txt"
    mine.write_text("mine\n")
    written = plot(brick, "--out", path / "plots")
    check_png(path / "plots" / "convergence.png")
    names = sorted(p.name for p in (path / "plots").iterdir())
    assert names == sorted([f"{n}.png" for n in CONTACT_FIGURES] + ["notes.txt"]), names

    # A run that did not converge: its last iterate, every figure marked.
    nc = out / "not-converged"
    shutil.rmtree(nc, ignore_errors=True)
    r = common.run([exe, "solve", examples / "paper-brick.toml", "--quiet", "--out", nc, "--set",
                    "solver.outer_max=2", "--plot"])
    assert r.returncode == 2, (r.returncode, r.stderr)
    check_folder(nc / "plots", [f"{n}.not-converged" for n in CONTACT_FIGURES])
    r = common.run([exe, "plot", nc])
    assert r.returncode == 0, (r.returncode, r.stderr)
    check_folder(nc / "plots", [f"{n}.not-converged" for n in CONTACT_FIGURES])

    empty = out / "not-a-results-folder"
    empty.mkdir(exist_ok=True)
    r = common.run([sys.executable, SCRIPT, empty])
    assert r.returncode == 1, (r.returncode, r.stderr)
    assert "report.json" in r.stderr and "Traceback" not in r.stderr, r.stderr
    print("plots ok")


if __name__ == "__main__":
    main()
