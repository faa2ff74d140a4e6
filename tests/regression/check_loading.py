"""The loading-path examples (examples/loading) run and show what their headers promise.

Both (from steps.csv, report.json and the files of each step):
  - the run converges, steps.csv and report.json's "steps" have one row per step of the path, and
    every step converged with a global equilibrium residual of at most 1e-8;
  - solution.pvd is the time series: 2 datasets per step (the body and the contact surface), each
    file it names present, and steps/solution-NNNN.vtu, steps/contact-NNNN.vtu and
    steps/patches-NNNN.csv exist for every step;
  - Coulomb's bound on the whole: the tangential force is at most mu N (1 + 1e-8) at every step.
brick-hysteresis (Coulomb, constant mu = 0.3; the top pressed, then pushed along x to and fro):
  - a step slides along the push when every patch slips and the contact surface moved in that
    step along the push at every node: the increment of w_t1 has the push's sign and
    |increment of w_t2| <= 1.4e-3 |increment of w_t1| (steps/contact-NNNN.vtu). Each patch's
    friction is mu lambda_n against its mean slip increment, so there the force's part along x
    is mu N to within 1 - 1/sqrt(1 + 1.4e-3^2) < 1e-6: it must be |tangential_force_x| =
    0.3 normal_force within 1e-6 (relative), with the sign opposite to the push's motion. (The
    first sliding steps of a plateau still slip slightly across y, the brick's Poisson effect:
    the criterion leaves them out, and asks for at least one such step in each monotone part
    of the push.) On every step where all patches slip the force opposes the push's motion;
  - on the first step after each reversal of the push (two at least) no patch slips, and the
    stuck steps that follow a reversal share one stick slope d(tangential_force_x)/d(push)
    (negative; within 1e-6): the straight sides of the loop;
  - `fricon plot` writes plots/force_displacement.png and plots/stick_slip_steps.png.
slip-weakening (Coulomb with the paper's F of the accumulated slip, a block pushed along x):
  - the ratio -tangential_force_x / normal_force (the plane's force opposes the push) reaches
    0.28 or more, never increases after its peak by more than 1e-7, and ends at 0.2 within 1e-6
    (relative), with every patch's coefficient F at 0.2 (the slip past the law's fall).
Step files chosen by [output] (issue 33, the feature "path output that can be thinned"), on
brick-hysteresis on a coarse mesh:
  - step_files_every = 3: steps/ holds the files of the steps k with k % 3 == 0 and of the last
    step, and no others; solution.pvd names exactly those steps (body and contact surface);
    steps.csv still has one row per step;
  - step_files = [1, 2]: the files of steps 1, 2 and the last;
  - both keys at once, a step beyond the path and an unordered list are refused (exit 1, the
    key named).
Stale files (issue 33, item 7): the paper's brick solved with --plot into brick-hysteresis's
folder (which holds a path's steps/, steps.csv and plots/force_displacement.png) leaves none of
the path's files: no steps/, no steps.csv, no force_displacement.png or stick_slip_steps.png.
Usage: check_loading.py FRICON EXAMPLES_DIR OUTDIR
"""
import math
import xml.etree.ElementTree as ET

import meshio
import numpy as np

import common

exe, examples, out = common.arguments(__doc__)

MU = 0.3                  # brick-hysteresis.toml: [contact.friction] value
ACROSS = 1.4e-3           # sliding along the push: |dw_t2| <= ACROSS |dw_t1| at every node
RATIO_TOL = 1e-6          # mu N on the plateaus, 0.2 at the end of slip-weakening (relative)
SLOPE_TOL = 1e-6          # the stick slopes after the reversals (relative)
EQUILIBRIUM_TOL = 1e-8    # steps.csv equilibrium_residual
KINETIC = 0.2             # the paper's F after its fall
PEAK = 0.28               # the least peak of the slip-weakening ratio

failures = common.Failures(separator="\n")


def solve(name):
    """Solves examples/loading/NAME.toml into OUTDIR/NAME; returns (folder, report, steps), steps
    one dict per row of steps.csv (numbers as floats, "status" as text)."""
    folder = out / name
    report = common.solve(exe, examples / f"{name}.toml", folder, timeout=120)
    if report["status"] != "converged":
        common.fail(f"{name}: {report['status']}: {report['message']}")
    rows = common.read_rows(folder / "steps.csv")
    steps = [{k: (v if k == "status" else float(v)) for k, v in row.items()} for row in rows]
    return folder, report, steps


def check_path_files(name, folder, report, steps):
    """What every loading path writes: steps.csv and report.json's steps, every step converged
    and in equilibrium, the per-step files and solution.pvd as their time series."""
    n = report["problem"]["loading"]["steps"]
    if len(steps) != n or len(report["steps"]) != n:
        failures.add(f"{name}: {len(steps)} rows in steps.csv and {len(report['steps'])} in "
                     f"report.json's steps, for a path of {n} steps")
    for k, row in enumerate(steps, start=1):
        if int(row["step"]) != k:
            failures.add(f"{name}: row {k} of steps.csv is step {row['step']:g}")
        if row["status"] != "converged":
            failures.add(f"{name}: step {k} {row['status']}")
        if not row["equilibrium_residual"] <= EQUILIBRIUM_TOL:
            failures.add(f"{name}: step {k}: equilibrium residual {row['equilibrium_residual']:.2e}"
                         f" > {EQUILIBRIUM_TOL:g}")
    for s in report["steps"]:
        if s["status"] != "converged":
            failures.add(f"{name}: report.json step {s['step']}: {s['status']}: {s['message']}")
    for k in range(1, n + 1):
        for base in (f"solution-{k:04d}.vtu", f"contact-{k:04d}.vtu", f"patches-{k:04d}.csv"):
            if not (folder / "steps" / base).is_file():
                failures.add(f"{name}: steps/{base} is missing")
    datasets = ET.parse(folder / "solution.pvd").getroot().iter("DataSet")
    datasets = [(d.get("timestep"), d.get("part"), d.get("file")) for d in datasets]
    if len(datasets) != 2 * n:
        failures.add(f"{name}: solution.pvd has {len(datasets)} datasets, expected 2 x {n} steps")
    for _, _, file in datasets:
        if not (folder / file).is_file():
            failures.add(f"{name}: solution.pvd names {file}, which is missing")
    times = sorted({float(t) for t, _, _ in datasets})
    if times != [float(k) for k in range(1, n + 1)]:
        failures.add(f"{name}: the timesteps of solution.pvd are {times}, expected 1 to {n}")


def check_coulomb_bound(name, steps, mu):
    for row in steps:
        t = math.sqrt(sum(row[f"tangential_force_{c}"] ** 2 for c in "xyz"))
        if t > mu * row["normal_force"] * (1.0 + 1e-8):
            failures.add(f"{name}: step {row['step']:g}: tangential force {t:.6e} N above "
                         f"{mu} x normal force {row['normal_force']:.6e} N")


def push_column(report):
    """The steps.csv column of the x displacement of the [[dirichlet]] entry with a path."""
    entries = [i for i, d in enumerate(report["problem"]["dirichlet"]) if d.get("path")]
    if len(entries) != 1:
        common.fail(f"expected one [[dirichlet]] entry with a path, found {len(entries)}")
    return f"displacement.dirichlet[{entries[0]}]_x"


def sign(x):
    return (x > 0) - (x < 0)


# ---------------------------------------------------------------------------------------------
# brick-hysteresis
# ---------------------------------------------------------------------------------------------
name = "brick-hysteresis"
folder, report, steps = solve(name)
check_path_files(name, folder, report, steps)
check_coulomb_bound(name, steps, MU)
push = [row[push_column(report)] for row in steps]
# The push's direction of motion in each step (0 for the first, pressed only).
motion = [0] + [sign(push[k] - push[k - 1]) for k in range(1, len(push))]
n_patches = [int(row["n_stick"] + row["n_slip"] + row["n_separated"]) for row in steps]
basis = report["contact_basis"]
t1, t2 = np.array(basis["t1"]), np.array(basis["t2"])
w = [meshio.read(folder / "steps" / f"contact-{k:04d}.vtu").point_data["displacement"]
     for k in range(1, len(steps) + 1)]

# Monotone parts of the push: a new one starts at each reversal.
reversals = [k for k in range(2, len(steps))
             if motion[k] and motion[k - 1] and motion[k] != motion[k - 1]]
segment = []
part = 0
for k in range(len(steps)):
    if k in reversals:
        part += 1
    segment.append(part if motion[k] else None)
sliding_parts = set()

for k in range(1, len(steps)):
    row, step = steps[k], k + 1
    tx, normal = row["tangential_force_x"], row["normal_force"]
    all_slip = row["n_slip"] == n_patches[k] and row["n_slip"] > 0
    if all_slip and sign(tx) != -motion[k]:
        failures.add(f"{name}: step {step}: every patch slips but tangential_force_x = {tx:.6e} N "
                     f"does not oppose the push's motion ({motion[k]:+d})")
    if not all_slip:
        continue
    d = w[k] - w[k - 1]
    along, across = d @ t1, d @ t2
    if not (np.all(np.sign(along) == motion[k])
            and np.all(np.abs(across) <= ACROSS * np.abs(along))):
        continue  # every patch slips, but not yet along the push alone
    sliding_parts.add(segment[k])
    ratio = abs(tx) / (MU * normal)
    print(f"{name}: step {step}: slides along the push ({push[k]:+.2e} m), |T_x| / (mu N) - 1 = "
          f"{ratio - 1.0:+.2e}, max |dw_t2/dw_t1| = {np.max(np.abs(across / along)):.1e}")
    if abs(ratio - 1.0) > RATIO_TOL:
        failures.add(f"{name}: step {step}: slides along the push but |tangential_force_x| = "
                     f"{abs(tx):.9e} N is {ratio:.9f} x mu N (N = {normal:.9e} N)")
missing = sorted(set(s for s in segment if s is not None) - sliding_parts)
if missing:
    failures.add(f"{name}: no step slides along the push in the monotone part(s) {missing} of the "
                 f"path (parts split at the reversals, steps {reversals})")

if len(reversals) < 2:
    failures.add(f"{name}: {len(reversals)} reversals of the push, expected 2 (0 -> + -> - -> +)")
slopes = []
for k in reversals:
    if steps[k]["n_slip"] != 0:
        failures.add(f"{name}: step {k + 1}, the first after a reversal of the push, has "
                     f"{steps[k]['n_slip']:g} slipping patches: it should stick again")
    j = k
    while j < len(steps) and steps[j]["n_slip"] == 0 and steps[j]["n_separated"] == 0:
        slope = ((steps[j]["tangential_force_x"] - steps[j - 1]["tangential_force_x"])
                 / (push[j] - push[j - 1]))
        slopes.append((j + 1, slope))
        j += 1
print(f"{name}: reversals at steps {[k + 1 for k in reversals]}, stick slopes "
      + ", ".join(f"step {s}: {v:.6e} N/m" for s, v in slopes))
if slopes:
    reference = slopes[0][1]
    for s, v in slopes:
        if not v < 0 or abs(v / reference - 1.0) > SLOPE_TOL:
            failures.add(f"{name}: step {s}: stick slope {v:.9e} N/m, the first reversal's "
                         f"{reference:.9e} N/m (the same, negative, expected)")

plots = folder / "plots"
common.run_ok([exe, "plot", folder], timeout=180)
for figure in ("force_displacement.png", "stick_slip_steps.png"):
    path = plots / figure
    if not path.is_file() or path.read_bytes()[:8] != b"\x89PNG\r\n\x1a\n":
        failures.add(f"{name}: `fricon plot` wrote no PNG {path}")

# ---------------------------------------------------------------------------------------------
# slip-weakening
# ---------------------------------------------------------------------------------------------
name = "slip-weakening"
folder, report, steps = solve(name)
check_path_files(name, folder, report, steps)
check_coulomb_bound(name, steps, MU)
ratios = [-row["tangential_force_x"] / row["normal_force"] for row in steps]
peak = int(np.argmax(ratios))
print(f"{name}: -T_x / N peaks at {ratios[peak]:.6f} (step {peak + 1}), ends at {ratios[-1]:.9f} "
      f"(step {len(steps)}); max accumulated slip {steps[-1]['max_accumulated_slip']:.3e} m")
if ratios[peak] < PEAK:
    failures.add(f"{name}: the ratio -tangential_force_x / normal_force peaks at "
                 f"{ratios[peak]:.6f} (step {peak + 1}), below {PEAK}")
for k in range(peak + 1, len(steps)):
    if ratios[k] > ratios[k - 1] + 1e-7:
        failures.add(f"{name}: step {k + 1}: the ratio rises again after its peak "
                     f"({ratios[k - 1]:.9f} -> {ratios[k]:.9f})")
if abs(ratios[-1] / KINETIC - 1.0) > RATIO_TOL:
    failures.add(f"{name}: the ratio ends at {ratios[-1]:.9f}, expected {KINETIC} within "
                 f"{RATIO_TOL:g}")
last = common.read_patches(folder / "steps", f"patches-{len(steps):04d}.csv")
for p in last:
    if p["state"] != "slip" or abs(p["F"] - KINETIC) > 1e-12:
        failures.add(f"{name}: last step: patch at ({p['x']:g}, {p['y']:g}) is {p['state']} with "
                     f"F = {p['F']:.12f}, expected slip at F = {KINETIC}")

# ---------------------------------------------------------------------------------------------
# [output] step_files_every / step_files: which steps' files are written
# ---------------------------------------------------------------------------------------------
COARSE = "mesh.cells=[6,2,2]"


def written_steps(folder):
    """The step numbers of steps/solution-NNNN.vtu in the folder, sorted."""
    return sorted(int(p.stem.split("-")[1]) for p in (folder / "steps").glob("solution-*.vtu"))


def pvd_steps(folder):
    """{part: sorted timesteps} of the datasets of solution.pvd."""
    parts = {}
    for d in ET.parse(folder / "solution.pvd").getroot().iter("DataSet"):
        parts.setdefault(d.get("part"), []).append(int(float(d.get("timestep"))))
        if not (folder / d.get("file")).is_file():
            failures.add(f"{folder.name}: solution.pvd names {d.get('file')}, which is missing")
    return {k: sorted(v) for k, v in parts.items()}


problem = examples / "brick-hysteresis.toml"
for label, setting, chosen in [
        ("every-3", "output.step_files_every=3", lambda k, n: k % 3 == 0 or k == n),
        ("list-1-2", "output.step_files=[1,2]", lambda k, n: k in (1, 2) or k == n)]:
    folder = out / f"step-files-{label}"
    common.solve(exe, problem, folder, COARSE, setting, timeout=120)
    n = len(common.read_rows(folder / "steps.csv"))
    expected = [k for k in range(1, n + 1) if chosen(k, n)]
    if n < 6:
        failures.add(f"{label}: steps.csv has {n} rows, expected every step of the path (> 5)")
    if written_steps(folder) != expected:
        failures.add(f"{label}: steps/ holds the files of steps {written_steps(folder)}, "
                     f"expected {expected}")
    for base in ("contact", "patches"):
        ext = ".csv" if base == "patches" else ".vtu"
        have = sorted(int(p.stem.split("-")[1]) for p in (folder / "steps").glob(f"{base}-*{ext}"))
        if have != expected:
            failures.add(f"{label}: steps/{base}-NNNN{ext} of steps {have}, expected {expected}")
    if pvd_steps(folder) != {"0": expected, "1": expected}:
        failures.add(f"{label}: solution.pvd lists {pvd_steps(folder)}, expected {expected} "
                     "for the body (part 0) and the contact surface (part 1)")

for setting, fragments in [
        (["output.step_files=[1,2]", "output.step_files_every=2"], ["step_files_every"]),
        (["output.step_files=[1,500]"], ["output.step_files[1]", "beyond"]),
        (["output.step_files=[3,2]"], ["output.step_files[1]", "increasing"])]:
    cmd = [exe, "solve", problem, "--quiet", "--out", out / "refused", "--set", COARSE]
    for s_ in setting:
        cmd += ["--set", s_]
    r = common.run(cmd, timeout=60)
    if r.returncode != 1 or not all(f in r.stderr for f in fragments):
        failures.add(f"{setting}: exit {r.returncode}, expected 1 naming {fragments}:\n{r.stderr}")

# ---------------------------------------------------------------------------------------------
# A static run into a path's folder leaves none of the path's files (issue 33, item 7)
# ---------------------------------------------------------------------------------------------
folder = out / "brick-hysteresis"
stale = [folder / "steps", folder / "steps.csv", folder / "plots" / "force_displacement.png",
         folder / "plots" / "stick_slip_steps.png"]
if not all(p.exists() for p in stale):
    failures.add(f"the path's folder lacks one of {stale} before the static rerun")
common.solve(exe, examples.parent / "paper-brick.toml", folder, timeout=120, extra=["--plot"])
for p in stale:
    if p.exists():
        failures.add(f"a static run with --plot into a path's folder kept the path's {p}")
if not (folder / "plots" / "convergence.png").is_file():
    failures.add("the static rerun with --plot drew no plots/convergence.png")

failures.finish("loading paths ok")
