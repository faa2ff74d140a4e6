"""The rigid-obstacle examples (examples/obstacles) solve and agree with independent truth.

The moduli, the obstacles' radii and displacements are read back from each run's report.json
(the problem's material, the pair's "obstacle_geometry"); E* = E / (1 - nu^2).

  - ball-block: a rigid ball (kind "sphere", R = 10 mm) pressed by delta = 1 um into a steel
    block, frictionless, quarter model. Hertz for the prescribed delta:
      P = (4/3) E* sqrt(R) delta^(3/2),  a = sqrt(R delta),  p0 = 3 P / (2 pi a^2);
    the run's P is 4 x the quarter's force on the obstacle (report.json's pair "force", z; the
    bottom's reaction must equal it), its a and p0 come from a least-squares fit of
    p^2 = p0^2 (1 - r^2/a^2) over every pressed patch (state not "separated"; r the distance of
    the patch's centroid from the axis, weights the patch areas; no patch is dropped): P and a
    within 2 %, p0 within 3 %. The contact radius from the pressure's second moment
    (a^2 = 5/2 int p r^2 / int p, as check_geometry.py) is printed too.
  - cylinder-slab: a rigid cylinder (kind "cylinder", axis along y) pressed into a slab in plane
    strain, frictionless, half model. For the run's force per unit length P' (2 x the half
    model's force over the slab's thickness t, read from cylinder-slab.geo), Hertz's line
    contact b = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi b); the run's b and p0 from a fit of
    p^2 = p0^2 (1 - x^2/b^2) over the pressed patches: both within 3 %.
  - flat-punch: a flat-ended rigid punch of radius a given as a meshed surface (kind "surface"),
    pressed by delta, frictionless, quarter model: the whole force 4 x the quarter's within 3 %
    of Boussinesq's P = 2 a E* delta (a from the rigid surface's bounding box in the report).
  - obstacle.vtu of ball-block (the ball where it is, for ParaView): every point on the moved
    sphere, its triangles enclosing the ball's volume outward to 2 %.
  - ball-slide: the rigid ball pressed into a rubber block (nu = 0.48: the normal and tangential
    problems nearly decouple, examples/obstacles/ball-slide.toml) then slid along +x, Coulomb
    friction mu, half model. Every step converged; the tangential force Q (2 x steps.csv's
    tangential_force_x) rises monotonically (to 1e-3 mu P) and its last value is mu P within
    2 % (P = 2 x normal_force); where everything slides (no patch sticks) Q >= 0.98 mu P. At the
    partial-slip steps (0 < Q / (mu P) < 1 with stuck patches; at least two) the stick radius
    c = sqrt(2 A_stick / pi) (A_stick the half model's stuck area) follows Cattaneo-Mindlin,
    c / a = (1 - Q / (mu P))^(1/3), within 0.05 (a from the pressure's second moment about the
    moved ball's axis). c is short by about half a patch (the patches that the boundary of the
    stuck disc crosses count as slipping): c + d / 2, d the median diameter of the pressed
    patches, is printed and must be within 0.025 of Mindlin's. Mindlin's displacement
    s = 3 mu P (2 - nu) / (16 G a) (1 - (1 - Q / (mu P))^(2/3)) for the run's P, a and Q is
    printed beside the ball's (3.5 to 4.3 % apart), not checked: the linear tetrahedra are
    too stiff at nu = 0.48 (the run's P is 6 % above Hertz's for its delta), which makes that
    figure indicative only.
Usage: check_obstacles.py FRICON EXAMPLES_DIR OUTDIR
"""
import math
import re

import common

exe, examples, out = common.arguments(__doc__)
failures = common.Failures()


def solve(name):
    """Solves examples/obstacles/NAME.toml into OUTDIR/NAME: (folder, report, its pair)."""
    folder = out / name
    report = common.solve(exe, examples / f"{name}.toml", folder, timeout=600)
    if report["status"] != "converged":
        common.fail(f"{name}: {report['status']}: {report.get('message', '')}")
    if len(report["pairs"]) != 1:
        common.fail(f"{name}: {len(report['pairs'])} contact pairs, expected 1")
    return folder, report, report["pairs"][0]


def e_star(report):
    material = report["problem"]["material"]
    return material["young"] / (1.0 - material["poisson"] ** 2)


def compare(name, label, value, truth, tolerance, unit=""):
    """Prints value against truth with the relative error; a failure when it exceeds tolerance."""
    error = value / truth - 1.0
    print(f"{name}: {label} = {value:.4e}{unit}, expected {truth:.4e}{unit}: {100 * error:+.2f} % "
          f"(tolerance {100 * tolerance:g} %)")
    if not abs(error) <= tolerance:
        failures.add(f"{name}: {label} {value:.4e}{unit} is {100 * error:+.2f} % off "
                     f"{truth:.4e}{unit} (tolerance {100 * tolerance:g} %)")


def pressed(patches):
    return [p for p in patches if p["state"] != "separated"]


def ellipse_fit(points):
    """The weighted least-squares fit of p^2 = p0^2 (1 - s^2 / a^2) to points (s, p, weight):
    a straight line in s^2; returns (p0, a)."""
    sw = sum(w for _, _, w in points)
    sx = sum(w * s * s for s, _, w in points)
    sy = sum(w * p * p for _, p, w in points)
    sxx = sum(w * s ** 4 for s, _, w in points)
    sxy = sum(w * s * s * p * p for s, p, w in points)
    slope = (sw * sxy - sx * sy) / (sw * sxx - sx * sx)
    intercept = (sy - slope * sx) / sw
    if not (intercept > 0.0 and slope < 0.0):
        common.fail(f"the pressures are no ellipse: p^2 = {intercept:.4e} + {slope:.4e} s^2")
    return math.sqrt(intercept), math.sqrt(-intercept / slope)


def geo_value(geo, name):
    """The value of `name = VALUE;` in a .geo file."""
    m = re.search(rf"^{name}\s*=\s*([-+0-9.eE]+)\s*;", geo.read_text(), re.MULTILINE)
    if not m:
        common.fail(f"{geo}: no '{name} = ...;'")
    return float(m.group(1))


def check_ball_block():
    name = "ball-block"
    folder, report, pair = solve(name)
    sphere = pair["obstacle_geometry"]
    radius, delta = sphere["radius"], -sphere["displacement"][2]
    assert pair["obstacle"] == "sphere" and sphere["center"] == [0.0, 0.0, radius], pair
    force = -4.0 * pair["force"][2]
    bottom = 4.0 * report["reaction_force"][2]
    if not abs(bottom - force) <= 1e-6 * force:
        failures.add(f"{name}: the bottom's reaction {bottom:.6e} N is not the force on the "
                     f"obstacle {force:.6e} N")
    es = e_star(report)
    p_hertz = 4.0 / 3.0 * es * math.sqrt(radius) * delta ** 1.5
    a_hertz = math.sqrt(radius * delta)
    p0_hertz = 3.0 * p_hertz / (2.0 * math.pi * a_hertz ** 2)
    patches = common.read_patches(folder)
    on = pressed(patches)
    p0, a = ellipse_fit([(math.hypot(p["x"], p["y"]), p["lambda_n"], p["area"]) for p in on])
    load = sum(p["lambda_n"] * p["area"] for p in patches)
    moment = sum(p["lambda_n"] * p["area"] * (p["x"] ** 2 + p["y"] ** 2) for p in patches)
    a_moment = math.sqrt(2.5 * moment / load)
    print(f"{name}: R = {radius * 1e3:g} mm, delta = {delta * 1e6:g} um, E* = {es:.4e} Pa, "
          f"{report['n_primal']} unknowns, {len(on)} of {len(patches)} patches pressed; "
          f"P from the bottom's reaction {bottom:.4e} N")
    compare(name, "P", force, p_hertz, 0.02, " N")
    compare(name, "a (fit)", a, a_hertz, 0.02, " m")
    compare(name, "p0 (fit)", p0, p0_hertz, 0.03, " Pa")
    print(f"{name}: a from the second moment = {a_moment:.4e} m: "
          f"{100 * (a_moment / a_hertz - 1):+.2f} %; largest patch pressure "
          f"{100 * (max(p['lambda_n'] for p in on) / p0_hertz - 1):+.2f} % of p0")
    check_obstacle_picture(name, folder, sphere)


def check_obstacle_picture(name, folder, sphere):
    """obstacle.vtu, the ball where it is for ParaView: every point on the moved sphere, the
    triangles enclosing (outward) its volume to the tessellation's accuracy."""
    import meshio  # Debian's python3-meshio (the regression tests' reader)
    import numpy as np
    m = meshio.read(folder / "obstacle.vtu")
    centre = np.array(sphere["center"]) + np.array(sphere["displacement"])
    radius = sphere["radius"]
    off = np.abs(np.linalg.norm(m.points - centre, axis=1) - radius).max()
    t = m.cells[0].data
    p = m.points - centre
    volume = np.einsum("ij,ij->i", p[t[:, 0]], np.cross(p[t[:, 1]], p[t[:, 2]])).sum() / 6.0
    exact = 4.0 / 3.0 * math.pi * radius ** 3
    print(f"{name}: obstacle.vtu: {len(m.points)} points within {off:.1e} m of the moved ball, "
          f"volume {volume / exact - 1:+.2%} of the ball's")
    if not (off <= 1e-12 * radius and 0.0 < volume and abs(volume / exact - 1.0) <= 0.02):
        failures.add(f"{name}: obstacle.vtu is not the moved ball (off by {off:.1e} m, volume "
                     f"{volume:.4e} against {exact:.4e} m^3)")


def check_cylinder_slab():
    name = "cylinder-slab"
    folder, report, pair = solve(name)
    cylinder = pair["obstacle_geometry"]
    radius = cylinder["radius"]
    assert pair["obstacle"] == "cylinder" and cylinder["axis"] == [0.0, 1.0, 0.0], pair
    thickness = 1e-3 * geo_value(examples / "cylinder-slab.geo", "t")  # drawn in mm
    per_length = -2.0 * pair["force"][2] / thickness
    es = e_star(report)
    b_hertz = math.sqrt(4.0 * per_length * radius / (math.pi * es))
    p0_hertz = 2.0 * per_length / (math.pi * b_hertz)
    patches = common.read_patches(folder)
    on = pressed(patches)
    p0, b = ellipse_fit([(p["x"], p["lambda_n"], p["area"]) for p in on])
    print(f"{name}: R = {radius * 1e3:g} mm, t = {thickness * 1e6:g} um, E* = {es:.4e} Pa, "
          f"{report['n_primal']} unknowns, {len(on)} of {len(patches)} patches pressed; "
          f"P' = {per_length:.4e} N/m")
    compare(name, "b (fit)", b, b_hertz, 0.03, " m")
    compare(name, "p0 (fit)", p0, p0_hertz, 0.03, " Pa")


def check_flat_punch():
    name = "flat-punch"
    folder, report, pair = solve(name)
    punch = pair["obstacle_geometry"]
    assert pair["obstacle"] == "surface", pair
    box = punch["bounding_box"]  # the whole punch: x and y in [-a, a]
    radius = 0.25 * (box[3] - box[0] + box[4] - box[1])
    delta = -punch["displacement"][2]
    force = -4.0 * pair["force"][2]
    es = e_star(report)
    on = pressed(common.read_patches(folder))
    print(f"{name}: a = {radius * 1e3:g} mm, delta = {delta * 1e6:g} um, E* = {es:.4e} Pa, "
          f"{report['n_primal']} unknowns, {len(on)} patches pressed")
    compare(name, "P", force, 2.0 * radius * es * delta, 0.03, " N")


def check_ball_slide():
    name = "ball-slide"
    folder, report, pair = solve(name)
    material = report["problem"]["material"]
    shear_modulus = material["young"] / (2.0 * (1.0 + material["poisson"]))
    mu = report["problem"]["contact"]["friction"]["value"]
    rows = common.read_rows(folder / "steps.csv")
    if len(rows) != report["problem"]["loading"]["steps"] or len(rows) < 4:
        common.fail(f"{name}: {len(rows)} rows in steps.csv")
    steps = []
    for row in rows:
        k = int(float(row["step"]))
        if row["status"] != "converged":
            failures.add(f"{name}: step {k}: {row['status']}")
        patches = common.read_patches(folder / "steps", f"patches-{k:04d}.csv")
        shift = float(row["obstacle.contact_x"])  # the ball's displacement along x
        load = sum(p["lambda_n"] * p["area"] for p in patches)
        moment = sum(p["lambda_n"] * p["area"] * ((p["x"] - shift) ** 2 + p["y"] ** 2)
                     for p in patches)
        on = pressed(patches)
        diameters = sorted(2.0 * math.sqrt(p["area"] / math.pi) for p in on)
        stick = sum(p["area"] for p in patches if p["state"] == "stick")
        P = 2.0 * float(row["normal_force"])
        Q = 2.0 * float(row["tangential_force_x"])
        steps.append({"k": k, "P": P, "Q": Q, "q": Q / (mu * P), "s": shift,
                      "a": math.sqrt(2.5 * moment / load), "c": math.sqrt(2.0 * stick / math.pi),
                      "d": diameters[len(diameters) // 2], "stuck": stick > 0.0})

    for s in steps:
        print(f"{name}: step {s['k']}: s = {s['s'] * 1e6:.3f} um, P = {s['P']:.4e} N, "
              f"Q = {s['Q']:.4e} N, Q/(mu P) = {s['q']:.4f}, a = {s['a'] * 1e3:.4f} mm, "
              f"c = {s['c'] * 1e3:.4f} mm")
    for before, after in zip(steps, steps[1:]):
        if after["Q"] < before["Q"] - 1e-3 * mu * after["P"]:
            failures.add(f"{name}: Q falls from {before['Q']:.6e} N (step {before['k']}) to "
                         f"{after['Q']:.6e} N (step {after['k']})")
    last = steps[-1]
    compare(name, f"Q at the last step ({last['k']})", last["Q"], mu * last["P"], 0.02, " N")
    if abs(steps[0]["q"]) > 0.01:
        failures.add(f"{name}: step 1 presses only, yet Q/(mu P) = {steps[0]['q']:.4f}")

    partial = [s for s in steps if 0.0 < s["q"] < 1.0 and s["stuck"] and s["s"] > 0.0]
    if len(partial) < 2:
        failures.add(f"{name}: {len(partial)} partial-slip steps, expected at least 2")
    for s in partial:
        mindlin = (1.0 - s["q"]) ** (1.0 / 3.0)
        ratio, corrected = s["c"] / s["a"], (s["c"] + 0.5 * s["d"]) / s["a"]
        print(f"{name}: step {s['k']}: Q/(mu P) = {s['q']:.3f}: c/a = {ratio:.3f}, "
              f"Cattaneo-Mindlin {mindlin:.3f}: {ratio - mindlin:+.3f} (tolerance 0.05); "
              f"with half a patch (d = {s['d'] / s['a']:.3f} a): {corrected:.3f}, "
              f"{corrected - mindlin:+.3f} (tolerance 0.025)")
        if abs(ratio - mindlin) > 0.05:
            failures.add(f"{name}: step {s['k']}: c/a = {ratio:.3f}, Cattaneo-Mindlin "
                         f"{mindlin:.3f} at Q/(mu P) = {s['q']:.3f}")
        if abs(corrected - mindlin) > 0.025:
            failures.add(f"{name}: step {s['k']}: c/a + d/(2a) = {corrected:.3f}, "
                         f"Cattaneo-Mindlin {mindlin:.3f} at Q/(mu P) = {s['q']:.3f}")
        full = 3.0 * mu * s["P"] * (2.0 - material["poisson"]) / (16.0 * shear_modulus * s["a"])
        mindlin_s = full * (1.0 - (1.0 - s["q"]) ** (2.0 / 3.0))
        print(f"{name}: step {s['k']}: the ball's displacement {s['s']:.4e} m, Mindlin's for "
              f"the run's P, a and Q {mindlin_s:.4e} m ({100 * (s['s'] / mindlin_s - 1):+.1f} %, "
              f"not checked)")
    for s in steps:
        if s["s"] > 0.0 and not s["stuck"] and s["q"] < 0.98:
            failures.add(f"{name}: step {s['k']}: no patch sticks, yet Q/(mu P) = {s['q']:.4f}")


check_ball_block()
check_cylinder_slab()
check_flat_punch()
check_ball_slide()
failures.finish("obstacles: ok")
