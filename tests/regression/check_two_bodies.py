"""The two-body examples (examples/two-bodies) solve and agree with independent truth.

  - hertz-spheres: two identical frictionless spheres (R = 50 mm, E = 20 GPa, nu = 0.3, quarter
    models) pressed together by a total approach h = 4 mm of their flat faces (Code_Aster's
    SSNV104 setup). By symmetry the interface stays the plane z = 0: the answer is that of the
    upper sphere alone pressed by h / 2 on a rigid frictionless plane. That problem, solved on
    the same upper mesh (the same file with the pair's obstacle made the plane z = 0), gives the
    same total force to 0.5 %, contact radius to 1 % and peak patch pressure to 1.5 % (the
    lower mesh does not match the upper one, and the patches differ). Against Hertz for the
    approach (one sphere of radius R/2 on a plane, E* = E / (2 (1 - nu^2)): a = sqrt(R h / 2) =
    10 mm and p0 = E / (pi (1 - nu^2)) sqrt(2 h / R) = 2798 MPa): the contact radius from the
    pressure's second moment (a^2 = 5/2 int p r^2 / int p for Hertz's p) and the largest patch
    pressure within 6 %; both come out 4-5 % above, unchanged by refinement and equal to the
    one-sphere-on-a-plane answer (for the run's own force they are within about 1 % of Hertz's:
    bench/hertz_bench.py --problem two-spheres): Hertz's half-spaces are not the model's hemispheres, whose
    flat faces, where h is prescribed, lie at R from the contact (a / R_eff = 0.4).
    The reactions balance (the contact forces on the two bodies cancel, to 1e-6 of the force),
    and the master covers the contact surface (coverage 1 to 1e-3).
  - sphere-on-block: a frictionless steel hemisphere (R = 50 mm, E1 = 200 GPa, nu1 = 0.3) on an
    aluminium block (E2 = 70 GPa, nu2 = 0.33), quarter models with non-matching meshes, pressed
    by 0.45 mm. Hertz for the run's total force P (four times the quarter's) with the pair's
    modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (E* = 57.87 GPa): a = (3 P R / (4 E*))^(1/3),
    p0 = 3 P / (2 pi a^2). The contact radius from the pressure's second moment is within 5 % of
    a and the largest patch pressure within 5 % of p0 (both come out within 2 %: -1.4 % and
    +0.8 %; at 0.7 x the element sizes -0.8 % and +2.1 %); the master covers the contact surface.
  - sphere-on-block-quadratic: the same with 10-node tetrahedra on both bodies, twice as coarse:
    the contact radius and the peak within 2 % (they come out -0.7 % and -0.1 %), the master
    covers the contact surface and the reactions balance as above.
  - sheared-blocks: Coulomb friction between two blocks; the certificate passes, the tangential
    force of the pair is at most mu times its normal force, small sliding holds, and the
    reactions of the clamped lower block balance the force on the upper block's top.
  - sheared-blocks along a loading path of 3 steps, the top pressed and slid 2 mm at step 2
    (two thirds of the master's mean edge of 3 mm, beyond the half that small sliding allows)
    and back to exactly zero at step 3: the path converges (released to zero, lambda = 0 is the exact answer, and the
    Coulomb certificate is relative to the path's pressures), the last step carries no force,
    and small sliding is flagged at step 2 although step 3 ends unslid: in report.json
    (`small_sliding`, `max_slip_step`, `warnings`), in the summary (WARNING) and on stderr.
    The examples that keep to small sliding, with the finer surface as the slave, warn of
    nothing.
  - stacked-blocks: two pairs (block on block, block on plane); report.json lists both, and
    patches.csv, contact_nodes.csv and solution.vtu carry the pair and body indices, and
    `fricon plot` draws the maps of each pair.
Usage: check_two_bodies.py FRICON EXAMPLES_DIR OUTDIR
"""
import math

import meshio
import numpy as np

import common

exe, examples, out = common.arguments(__doc__)

E, NU, R, H = 2.0e10, 0.3, 0.05, 4.0e-3  # hertz-spheres.toml, hertz-spheres.geo
# sphere-on-block.toml, sphere-on-block.geo: steel ball, aluminium block, radius
E_BALL, NU_BALL, E_BLOCK, NU_BLOCK, R_BALL = 2.0e11, 0.3, 7.0e10, 0.33, 0.05
MU_SHEARED = 0.3                         # sheared-blocks.toml


def solve(name, *sets):
    folder = out / name
    report = common.solve(exe, examples / f"{name}.toml", folder, *sets, timeout=300)
    assert report["status"] == "converged", name
    return folder, report


def hertz_measures(patches):
    """Force, contact radius from the pressure's second moment, and peak of a quarter model."""
    force = sum(p["lambda_n"] * p["area"] for p in patches)
    second = sum(p["lambda_n"] * p["area"] * (p["x"] ** 2 + p["y"] ** 2) for p in patches)
    return force, math.sqrt(2.5 * second / force), max(p["lambda_n"] for p in patches)


def on_the_plane(toml, copy):
    """The problem file with its pair's master replaced by the rigid plane z = 0 (normal +z,
    towards the upper body) and the mesh file's path made absolute."""
    text = toml.read_text()
    body = 'obstacle = { kind = "body", boundary = "lower_contact" }'
    assert body in text, toml
    text = text.replace(body, 'obstacle = { kind = "plane", point = [0.0, 0.0, 0.0], '
                              'normal = [0.0, 0.0, 1.0] }')
    text = "\n".join(line for line in text.splitlines()
                     if not line.startswith("search_distance")) + "\n"
    text = text.replace('file = "hertz-spheres.geo"',
                        f'file = "{(toml.parent / "hertz-spheres.geo").resolve()}"')
    copy.parent.mkdir(parents=True, exist_ok=True)
    copy.write_text(text)
    return copy


def solve_against(name, master, coverage_tolerance):
    """Solves an example of one pair against the body surface `master`; checks that the master
    covers the contact surface and that small sliding holds. Returns the report, the patches and
    the pair's report."""
    folder, report = solve(name)
    [pair] = report["pairs"]
    assert pair["obstacle"] == "body" and pair["master"] == master, pair
    assert abs(pair["master_coverage"] - 1.0) < coverage_tolerance, pair["master_coverage"]
    assert pair["small_sliding"], pair
    assert pair["master_kept_out"], pair
    assert report["warnings"] == [], report["warnings"]
    return report, common.read_patches(folder), pair


def check_hertz():
    # Curved surfaces projected along the patches' averaged normals: covered up to slivers.
    report, patches, pair = solve_against("hertz-spheres", "lower_contact", 1e-3)
    # Quarter model: four times the force, the pressure's moments about the pole.
    force, a_h, peak = hertz_measures(patches)
    # The symmetric problem: the upper sphere alone on the plane z = 0.
    plane_toml = on_the_plane(examples / "hertz-spheres.toml", out / "hertz-on-plane.toml")
    plane_report = common.solve(exe, plane_toml, out / "hertz-on-plane", timeout=300)
    assert plane_report["status"] == "converged"
    f_plane, a_plane, peak_plane = hertz_measures(common.read_patches(out / "hertz-on-plane"))
    print(f"hertz-spheres: two bodies against one on the plane: force {force / f_plane - 1:+.3%}, "
          f"a {a_h / a_plane - 1:+.3%}, peak {peak / peak_plane - 1:+.3%}")
    assert abs(force / f_plane - 1.0) <= 0.005, (force, f_plane)
    assert abs(a_h / a_plane - 1.0) <= 0.01, (a_h, a_plane)
    assert abs(peak / peak_plane - 1.0) <= 0.015, (peak, peak_plane)
    a_approach = math.sqrt(R * H / 2.0)
    p0_approach = E / (math.pi * (1.0 - NU ** 2)) * math.sqrt(2.0 * H / R)
    print(f"hertz-spheres: P = {4.0 * force:.4e} N; a = {a_h * 1e3:.3f} mm against "
          f"{a_approach * 1e3:.2f} mm ({a_h / a_approach - 1:+.2%}), peak {peak / 1e6:.1f} MPa "
          f"against p0 = {p0_approach / 1e6:.1f} MPa ({peak / p0_approach - 1:+.2%})")
    assert abs(a_h / a_approach - 1.0) <= 0.06, (a_h, a_approach)
    assert abs(peak / p0_approach - 1.0) <= 0.06, (peak, p0_approach)
    # The contact forces on the two bodies cancel: the reactions of the pressed faces and of
    # the symmetry planes balance each other (in z, the flat faces alone).
    assert abs(pair["normal_force"] - force) <= 1e-9 * force
    assert abs(report["reaction_force"][2]) <= 1e-6 * force, report["reaction_force"]


def check_sphere_on_block(name="sphere-on-block", tolerance=0.05):
    report, patches, pair = solve_against(name, "block_top", 1e-6)
    # Quarter model: four times the force; Hertz for that force with the pair's modulus.
    force = sum(p["lambda_n"] * p["area"] for p in patches)
    assert abs(pair["normal_force"] - force) <= 1e-9 * force, (pair["normal_force"], force)
    total = 4.0 * force
    e_star = 1.0 / ((1.0 - NU_BALL ** 2) / E_BALL + (1.0 - NU_BLOCK ** 2) / E_BLOCK)
    a = (3.0 * total * R_BALL / (4.0 * e_star)) ** (1.0 / 3.0)
    p0 = 3.0 * total / (2.0 * math.pi * a * a)
    second = sum(p["lambda_n"] * p["area"] * (p["x"] ** 2 + p["y"] ** 2) for p in patches)
    a_h = math.sqrt(2.5 * second / force)
    peak = max(p["lambda_n"] for p in patches)
    print(f"{name}: E* = {e_star / 1e9:.2f} GPa, P = {total:.4e} N; a = "
          f"{a_h * 1e3:.3f} mm against Hertz's {a * 1e3:.3f} mm ({a_h / a - 1:+.2%}), peak "
          f"{peak / 1e6:.1f} MPa against p0 = {p0 / 1e6:.1f} MPa ({peak / p0 - 1:+.2%})")
    assert abs(a_h / a - 1.0) <= tolerance, (a_h, a)
    assert abs(peak / p0 - 1.0) <= tolerance, (peak, p0)
    # The contact forces on the two bodies cancel: in z, the reactions of the ball's face and of
    # the block's bottom balance each other.
    assert abs(report["reaction_force"][2]) <= 1e-6 * force, report["reaction_force"]


def check_sheared():
    folder, report = solve("sheared-blocks")
    [pair] = report["pairs"]
    assert report["coulomb"]["residual"] <= report["coulomb"]["bound"], report["coulomb"]
    tangential = math.hypot(*pair["tangential_force"])
    print(f"sheared-blocks: normal force {pair['normal_force']:.4e} N, tangential "
          f"{tangential:.4e} N = {tangential / pair['normal_force']:.4f} of it; "
          f"{pair['patch_states']}")
    assert tangential <= MU_SHEARED * pair["normal_force"] * (1 + 1e-6), (tangential, pair)
    assert pair["patch_states"]["slip"] > 0 and pair["patch_states"]["stick"] > 0, pair
    assert pair["small_sliding"], pair
    assert report["equilibrium_residual"] <= 1e-8, report["equilibrium_residual"]


SLIDE = 2.0e-3  # [m], the sliding path's slide at its step 2


def pair_patches(report):
    return sum(p["n_patches"] for p in report["pairs"])


def check_sliding_path():
    folder = out / "sheared-blocks-path"
    r = common.run_ok([exe, "solve", examples / "sheared-blocks.toml", "--out", folder,
                       "--set", "loading.steps=3", "--set", "dirichlet.1.path=[0, 1, 0]",
                       "--set", f"dirichlet.1.value=[{SLIDE}, 0, -2e-5]"], timeout=300)
    report = common.read_report(folder)
    assert report["status"] == "converged", report["message"]
    steps = report["steps"]
    assert len(steps) == 3
    pressed = steps[1]["normal_force"]
    # Released to zero: lambda = 0, to the accuracy of the example's tolerances (qp_rtol 1e-6 of
    # the QP's data, outer_tol 1e-4); the QP stops at a residual, not at 0 itself.
    assert pressed > 0 and abs(steps[2]["normal_force"]) <= 1e-5 * pressed, steps
    assert steps[2]["patch_states"]["separated"] == pair_patches(report), steps[2]
    [pair] = report["pairs"]
    limit = 0.5 * pair["master_element_size"]
    print(f"sliding path: max slip {pair['max_slip']:.3e} m at step {pair['max_slip_step']} "
          f"(limit {limit:.3e} m); warnings {report['warnings']}")
    assert pair["max_slip_step"] == 2 and pair["max_slip"] > limit, pair
    assert not pair["small_sliding"], pair
    [warning] = report["warnings"]
    assert "at step 2" in warning and "small sliding" in warning, warning
    assert f"WARNING       {warning}" in r.stdout, r.stdout
    assert f"fricon: warning: {warning}" in r.stderr, r.stderr


def check_stacked():
    folder, report = solve("stacked-blocks")
    pairs = report["pairs"]
    assert [p["obstacle"] for p in pairs] == ["body", "plane"], pairs
    assert all(p["normal_force"] > 0 for p in pairs), pairs
    for name in ("patches.csv", "contact_nodes.csv"):
        rows = common.read_rows(folder / name)
        assert {float(r["pair"]) for r in rows} == {0.0, 1.0}, name
    mesh = meshio.read(folder / "solution.vtu")
    bodies = np.unique(np.concatenate(mesh.cell_data["body"]))
    assert list(bodies) == [0, 1], bodies
    assert report["equilibrium_residual"] <= 1e-8, report["equilibrium_residual"]
    # fricon plot draws each pair's maps, seen along its own normal.
    common.run_ok([str(exe), "plot", str(folder)], timeout=120)
    for pair in (0, 1):
        for name in ("contact_maps", "friction_circles"):
            assert (folder / "plots" / f"{name}-pair{pair}.png").is_file(), (name, pair)


check_hertz()
check_sphere_on_block()
check_sphere_on_block("sphere-on-block-quadratic", 0.02)
check_sheared()
check_sliding_path()
check_stacked()
print("two bodies: passed")
