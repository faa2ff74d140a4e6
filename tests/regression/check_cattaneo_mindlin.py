"""Cattaneo-Mindlin (examples/loading/hemisphere-shear.toml) against Johnson, Contact Mechanics, §7.2.

A steel hemisphere (R = 50 mm, E = 200 GPa, nu = 0.3) pressed on a steel block (the same material:
the normal and tangential problems decouple), then moved sideways in steps: Coulomb friction
(mu = 0.6) on the slip increments, half models (y >= 0). For the run's own total forces P and Q
(twice the half model's):
  - Hertz: the contact radius from the pressure's second moment is within 3 % of
    a = (3 P R / (4 E*))^(1/3), E* = E / (2 (1 - nu^2)), at every step (the pressure stays
    Hertz's while Q grows);
  - the stick radius c, from the area of the patches that stick (c = sqrt(2 A_stick / pi)),
    follows c / a = (1 - Q / (mu P))^(1/3) within 0.05 at the steps nearest Q / (mu P) = 0.25,
    0.5 and 0.75 (each within 0.05 of its target);
  - Mindlin's load-displacement curve delta(Q) = 3 mu P (2 - nu) / (8 G a) (1 - (1 - Q/(mu P))^(2/3))
    describes the displacement of the two half-spaces' distant points. The model's bodies are
    finite and the displacement is prescribed 50 mm away from the contact, where a half-space
    still moves: the prescribed displacement is Mindlin's plus a compliance of the bulk, linear
    in Q (about 11 % of it here). That compliance C is taken from the first shear step,
    C = (u_x - delta(Q)) / Q there; at every later step u_x - C Q is Mindlin's delta within 5 %
    (the curve's bend, the slip's part, is what is compared).
Usage: check_cattaneo_mindlin.py FRICON EXAMPLES_DIR OUTDIR
"""
import math

import common

exe, examples, out = common.arguments(__doc__)

E, NU, R, MU = 2.0e11, 0.3, 0.05, 0.6  # hemisphere-shear.toml, hemisphere-shear.geo
G = E / (2.0 * (1.0 + NU))
E_STAR = E / (2.0 * (1.0 - NU ** 2))
SHEAR = "displacement.dirichlet[1]_x"   # the mean x displacement of the ball's flat face [m]

folder = out / "hemisphere-shear"
report = common.solve(exe, examples / "hemisphere-shear.toml", folder, timeout=600)
if report["status"] != "converged":
    common.fail(f"hemisphere-shear: {report['message']}")
rows = common.read_rows(folder / "steps.csv")
if len(rows) != report["problem"]["loading"]["steps"]:
    common.fail(f"{len(rows)} rows in steps.csv")

steps = []
for row in rows:
    k = int(float(row["step"]))
    patches = common.read_patches(folder / "steps", f"patches-{k:04d}.csv")
    P = 2.0 * float(row["normal_force"])
    Q = -2.0 * float(row["tangential_force_x"])  # the block's friction on the ball opposes +x
    force = sum(p["lambda_n"] * p["area"] for p in patches)
    second = sum(p["lambda_n"] * p["area"] * (p["x"] ** 2 + p["y"] ** 2) for p in patches)
    a_fe = math.sqrt(2.5 * second / force)
    stick = sum(p["area"] for p in patches if p["state"] == "stick")
    a = (3.0 * P * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    steps.append({"k": k, "P": P, "Q": Q, "q": Q / (MU * P), "a": a, "a_fe": a_fe,
                  "c": math.sqrt(2.0 * stick / math.pi), "u": float(row[SHEAR])})

failures = []
for s in steps:
    err = s["a_fe"] / s["a"] - 1.0
    print(f"step {s['k']}: Q/(mu P) = {s['q']:.3f}, a = {s['a'] * 1e3:.3f} mm (Hertz), "
          f"{s['a_fe'] * 1e3:.3f} mm (second moment, {100 * err:+.2f} %), c = {s['c'] * 1e3:.3f} mm")
    if abs(err) > 0.03:
        failures.append(f"step {s['k']}: contact radius {100 * err:+.2f} % off Hertz's")

for target in (0.25, 0.5, 0.75):
    s = min(steps, key=lambda s: abs(s["q"] - target))
    if abs(s["q"] - target) > 0.05:
        failures.append(f"no step near Q/(mu P) = {target} (nearest {s['q']:.3f})")
        continue
    theory = (1.0 - s["q"]) ** (1.0 / 3.0)
    measured = s["c"] / s["a_fe"]
    print(f"Q/(mu P) = {s['q']:.3f}: c/a = {measured:.3f}, Cattaneo-Mindlin {theory:.3f} "
          f"({measured - theory:+.3f} of a)")
    if abs(measured - theory) > 0.05:
        failures.append(f"Q/(mu P) = {s['q']:.3f}: c/a = {measured:.3f}, expected {theory:.3f}")


def mindlin(s):
    return 3.0 * MU * s["P"] * (2.0 - NU) / (8.0 * G * s["a"]) * (1.0 - (1.0 - s["q"]) ** (2.0 / 3.0))


shear = [s for s in steps if s["q"] > 0.01]
first = shear[0]
bulk = (first["u"] - mindlin(first)) / first["Q"]
print(f"bulk compliance {bulk:.3e} m/N: {100 * bulk * first['Q'] / first['u']:.1f} % of the "
      f"first shear step's displacement")
for s in shear[1:]:
    ratio = (s["u"] - bulk * s["Q"]) / mindlin(s)
    print(f"step {s['k']}: (u_x - C Q) / delta_Mindlin = {ratio:.4f} (u_x / delta_Mindlin = "
          f"{s['u'] / mindlin(s):.4f})")
    if abs(ratio - 1.0) > 0.05:
        failures.append(f"step {s['k']}: load-displacement {100 * (ratio - 1):+.1f} % off Mindlin")

if failures:
    common.fail("; ".join(failures))
print("cattaneo-mindlin ok")
