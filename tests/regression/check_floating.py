"""The floating-body examples (examples/floating) solve and agree with independent truth: a body
held by contact alone must be balanced by its contact forces, whatever the mesh.

  - free-block: a free steel brick 0.2 x 0.1 x 0.05 m (no [[dirichlet]]) on the rigid plane,
    1 MPa on its top (N = 1e6 * 0.2 * 0.1 = 20 kN) and 0.8 MPa along +x on its back face
    (T = 8e5 * 0.1 * 0.05 = 4 kN), Coulomb F = 0.3. Equilibrium alone fixes the contact's
    resultants: its normal force is 20 kN and its tangential force 4 kN along -x (0 along y), to
    1e-5 of N (the balance is as precise as the QP's tolerance, qp_rtol = 1e-6, lets it be: a
    run under load, with other threads, differs by a few 1e-6); T <= F N as a whole and
    |lambda_t| <= F lambda_n on every patch (to the Coulomb
    certificate's tolerance times the largest pressure). The body is reported
    floating in all six rigid motions, none undetermined (friction holds them), and the dual
    QP's equality G lambda = e is met within its bound.
  - the same block frictionless (F = 0) and without the push: the contact holds it in z and
    against tilting, nothing in x, y and about z. The solution is determined only up to those
    three motions: report.json names them ("undetermined") and fricon returns the solution of
    least norm in them, so their amplitudes are zero (|a| <= 1e-12 max |u|, a rotation times the
    body's diagonal). The normal force is still 20 kN, the tangential force zero.
  - nafems-punch-frictionless and nafems-punch-coulomb (F = 0.1): the punch (quarter model,
    symmetry planes only) floats in exactly one motion, "translation z"; the foundation is held.
    The contact's z force on the punch equals the load on its top (report.json's
    applied_force, the 100 MPa on the facetted quarter disc: within 0.1 % of p pi R^2 / 4) to
    1e-5. With Coulomb friction the pair's tangential force is at most 0.1 times its normal force
    and |lambda_t| <= F lambda_n on every patch.
  - free-block with the paper's slip-dependent F(s) (F(0) = 0.3): friction carries the push
    exactly (1e-5 of N), and the Coulomb certificate passes.
  - free-block along a loading path of 4 steps (the push 0, 0.5, 1 and 1.4 times the example's):
    every step converges, the contact carries N and friction exactly the step's push (1e-5 of N).
  - sphere-between-blocks: the ball and the upper block float in "translation z" only; the lower
    block is held. The upper block rests on pair (b) alone and the ball on pair (a) alone, so
    both pairs carry the 8 kN on the upper block's top, to 1e-5, and the lower block's reaction
    is that force too.
    (The ball is the slave of both pairs: a slave whose patches reach past the master's edge,
    here the upper block's bottom against the quarter ball at the symmetry planes, gives the
    master less force than it takes, 8e-5 of it.)
Every check runs; the failures are reported together at the end.
Usage: check_floating.py FRICON EXAMPLES_DIR OUTDIR
"""
import math
import time

import common

exe, examples, out = common.arguments(__doc__)

ALL_MOTIONS = ["translation x", "translation y", "translation z",
               "rotation about x", "rotation about y", "rotation about z"]
# free-block.toml: the brick, its loads, its friction.
BLOCK = (0.2, 0.1, 0.05)                                 # m
PRESSURE, PUSH, MU_BLOCK = 1.0e6, 8.0e5, 0.3             # Pa, Pa, -
N_BLOCK = PRESSURE * BLOCK[0] * BLOCK[1]                 # 20 kN on the top
T_BLOCK = PUSH * BLOCK[1] * BLOCK[2]                     # 4 kN on the back face x = 0
# nafems-punch-*.toml: 100 MPa on the top of a quarter punch of radius 50 mm.
P_PUNCH, R_PUNCH, MU_PUNCH = 1.0e8, 0.05, 0.1
# sphere-between-blocks.toml: 5 MPa on the upper block's quarter top, 40 x 40 mm.
LOAD_SPHERE = 5.0e6 * 0.04 * 0.04                        # 8 kN

failures = common.Failures()


def check(name, function):
    """Runs one check; a failed assertion or run becomes a failure and the next check runs."""
    start = time.monotonic()
    try:
        function()
    except (AssertionError, SystemExit) as e:  # SystemExit: a run that failed (common.run_ok)
        failures.add(f"{name}: {e}")
        print(f"FAIL {name} ({time.monotonic() - start:.1f} s)", flush=True)
        return
    print(f"ok   {name} ({time.monotonic() - start:.1f} s)", flush=True)


def solve(name, *sets, problem=None):
    folder = out / name
    report = common.solve(exe, examples / f"{problem or name}.toml", folder, *sets, timeout=300)
    assert report["status"] == "converged", (name, report["status"], report["message"])
    return folder, report


def close(value, expected, rtol, what):
    assert abs(value - expected) <= rtol * abs(expected), (
        f"{what}: {value!r}, expected {expected!r} to {rtol:g} (off by "
        f"{abs(value - expected) / abs(expected):.2e})")


def body(report, region):
    """The report's entry of the body of `region`."""
    [b] = [b for b in report["bodies"] if f'(region "{region}"' in b["description"]]
    return b


def check_body(report, region, motions):
    """The body of `region` floats in exactly `motions` (held when there are none)."""
    b = body(report, region)
    assert b["floating"] == bool(motions), (region, b)
    assert b["free_motions"] == motions, (region, b["free_motions"], motions)
    assert len(b["amplitudes"]) == len(motions), (region, b)


def check_balance(report):
    """The floating bodies' equality G lambda = e holds within its bound."""
    balance = report["balance"]
    assert balance["equality_residual"] <= balance["bound"], balance


def check_coulomb_patches(folder, report, mu):
    """|lambda_t| <= mu lambda_n on every patch (Coulomb's law with the final pressures), to the
    Coulomb certificate's tolerance times the largest pressure."""
    patches = common.read_patches(folder)
    scale = max(p["lambda_n"] for p in patches)
    worst = max(math.hypot(p["lambda_t1"], p["lambda_t2"]) - mu * p["lambda_n"] for p in patches)
    bound = report["coulomb"]["bound"] * scale
    assert worst <= bound, f"|lambda_t| - {mu} lambda_n reaches {worst:.3e} Pa > {bound:.3e} Pa"


def tangential(report):
    """The sum over the pairs of their tangential forces [N]."""
    return [sum(p["tangential_force"][i] for p in report["pairs"]) for i in range(3)]


def check_free_block():
    folder, report = solve("free-block")
    # The applied loads as the program read them.
    close(report["applied_force"][0], T_BLOCK, 1e-12, "applied force x")
    close(report["applied_force"][2], -N_BLOCK, 1e-12, "applied force z")
    normal = sum(p["normal_force"] for p in report["pairs"])
    force_z = sum(p["force"][2] for p in report["pairs"])
    t = tangential(report)
    print(f"free-block: normal force {normal:.9e} N, tangential ({t[0]:.9e}, {t[1]:.3e}) N, "
          f"T / N = {math.hypot(*t) / normal:.4f}")
    close(normal, N_BLOCK, 1e-5, "normal force")
    close(force_z, N_BLOCK, 1e-5, "contact force z")
    assert abs(t[0] + T_BLOCK) <= 1e-5 * N_BLOCK, f"tangential force x {t[0]!r} (-{T_BLOCK})"
    assert abs(t[1]) <= 1e-5 * N_BLOCK, f"tangential force y {t[1]!r}"
    assert math.hypot(*t) <= MU_BLOCK * normal, (t, normal)
    check_coulomb_patches(folder, report, MU_BLOCK)
    assert report["coulomb"]["residual"] <= report["coulomb"]["bound"], report["coulomb"]
    assert report["reaction_force"] == [0.0, 0.0, 0.0], report["reaction_force"]
    check_body(report, "body", ALL_MOTIONS)
    assert body(report, "body")["undetermined"] == [], body(report, "body")
    check_balance(report)


def check_frictionless_block():
    folder, report = solve("free-block-frictionless", "contact.friction.value=0.0",
                           "traction.1.value=[0.0, 0.0, 0.0]", problem="free-block")
    close(report["applied_force"][2], -N_BLOCK, 1e-12, "applied force z")
    assert report["applied_force"][:2] == [0.0, 0.0], report["applied_force"]
    normal = sum(p["normal_force"] for p in report["pairs"])
    close(normal, N_BLOCK, 1e-5, "normal force")
    t = tangential(report)
    assert math.hypot(*t) <= 1e-12 * N_BLOCK, f"tangential force {t}"
    check_body(report, "body", ALL_MOTIONS)
    check_balance(report)
    b = body(report, "body")
    undetermined = ["translation x", "translation y", "rotation about z"]
    assert sorted(b["undetermined"]) == sorted(undetermined), b["undetermined"]
    # The solution of least norm in the undetermined motions: none of them in u.
    u_max = report["max_displacement"]
    diagonal = math.hypot(*BLOCK)  # [m], a rotation's largest displacement per radian
    for motion in undetermined:
        a = b["amplitudes"][b["free_motions"].index(motion)]
        size = abs(a) * (diagonal if motion.startswith("rotation") else 1.0)
        print(f"free-block frictionless: {motion} amplitude {a:.3e} ({size / u_max:.1e} of "
              f"max |u| = {u_max:.3e} m)")
        assert size <= 1e-12 * u_max, (motion, a, u_max)


def check_punch(name, mu):
    folder, report = solve(name)
    applied = report["applied_force"]
    # The facetted quarter disc of the top is a little smaller than the quarter circle.
    close(-applied[2], P_PUNCH * math.pi * R_PUNCH ** 2 / 4.0, 1e-3, "applied force z")
    [pair] = report["pairs"]
    print(f"{name}: load {-applied[2]:.6e} N, contact z force on the punch "
          f"{pair['force'][2]:.6e} N ({pair['force'][2] / -applied[2] - 1:+.1e}), tangential "
          f"{math.hypot(*pair['tangential_force']) / pair['normal_force']:.4f} of the normal force")
    close(pair["force"][2], -applied[2], 1e-5, "contact z force on the punch")
    check_body(report, "punch", ["translation z"])
    check_body(report, "foundation", [])
    check_balance(report)
    if mu > 0.0:
        assert math.hypot(*pair["tangential_force"]) <= mu * pair["normal_force"], pair
        check_coulomb_patches(folder, report, mu)
        assert report["coulomb"]["residual"] <= report["coulomb"]["bound"], report["coulomb"]


def check_sphere(name, *sets):
    folder, report = solve(name, *sets, problem="sphere-between-blocks")
    close(-report["applied_force"][2], LOAD_SPHERE, 1e-12, "applied force z")
    pairs = report["pairs"]
    forces = [p["force"][2] for p in pairs]
    coverage = [p["master_coverage"] for p in pairs]
    print(f"{name}: pair z forces {', '.join(f'{f:.6e}' for f in forces)} N against "
          f"{LOAD_SPHERE:.6e} N ({', '.join(f'{abs(f) / LOAD_SPHERE - 1:+.1e}' for f in forces)}); "
          f"master coverage {', '.join(f'{c:.6f}' for c in coverage)}")
    # The slave of each pair is the body above it: the force on it is up, the load, in both.
    for p in pairs:
        close(abs(p["force"][2]), LOAD_SPHERE, 1e-5, f"pair {p['key']} ({p['boundary']} on "
                                                     f"{p['master']}) z force")
    close(report["reaction_force"][2], LOAD_SPHERE, 1e-5, "the lower block's reaction z")
    check_body(report, "ball", ["translation z"])
    check_body(report, "upper", ["translation z"])
    check_body(report, "lower", [])
    check_balance(report)


def check_block_path():
    """free-block.toml along a loading path: pressed, then pushed by 0, 0.5, 1 and 1.4 times the
    example's push (up to 5.6 kN < mu N = 6 kN): at every step the contact carries the 20 kN and
    friction exactly the step's push (equilibrium of the floating block), to 1e-5 of N."""
    factors = [0.0, 0.5, 1.0, 1.4]
    folder, report = solve("free-block-path", "loading.steps=4",
                           "traction[0].path=[1.0,1.0,1.0,1.0]",
                           f"traction[1].path=[{','.join(map(str, factors))}]",
                           problem="free-block")
    steps = common.read_rows(folder / "steps.csv")
    assert len(steps) == len(factors), steps
    for step, factor in zip(steps, factors):
        assert step["status"] == "converged", step
        close(float(step["normal_force"]), N_BLOCK, 1e-5, f"step {step['step']} normal force")
        assert abs(float(step["tangential_force_x"]) + factor * T_BLOCK) <= 1e-5 * N_BLOCK, (
            step["step"], step["tangential_force_x"], factor * T_BLOCK)


def check_block_slip_weakening():
    """free-block.toml with the paper's slip-dependent coefficient F(s) (param 6e4 1/m; F(0) =
    0.3, the same as the example's constant, falling with the slip): it still sticks as a whole,
    friction carrying exactly the push (1e-5 of N), and the Coulomb certificate passes."""
    _, report = solve("free-block-paper-law", 'contact.friction={law="paper", param=6.0e4}',
                      problem="free-block")
    t = tangential(report)
    assert abs(t[0] + T_BLOCK) <= 1e-5 * N_BLOCK, f"tangential force x {t[0]!r} (-{T_BLOCK})"
    assert report["coulomb"]["residual"] <= report["coulomb"]["bound"], report["coulomb"]
    check_balance(report)


start = time.monotonic()
check("free-block", check_free_block)
check("free-block with a slip-dependent coefficient", check_block_slip_weakening)
check("free-block along a loading path", check_block_path)
check("free-block frictionless", check_frictionless_block)
check("nafems-punch-frictionless", lambda: check_punch("nafems-punch-frictionless", 0.0))
check("nafems-punch-coulomb", lambda: check_punch("nafems-punch-coulomb", MU_PUNCH))
check("sphere-between-blocks", lambda: check_sphere("sphere-between-blocks"))
failures.finish(f"floating bodies: passed ({time.monotonic() - start:.0f} s)")
