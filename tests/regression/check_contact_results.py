"""Solve the paper's brick (n = 4) with the fricon program and check every result file.

Checks facts that hold independently of the solver's internals:
  - report.json has the documented keys, MPGP steps by kind that add up to qp_iterations, the paper's sizes (n_p = 900, n_d = 36), a converged
    outer loop whose last err(k) is below outer_tol, and KKT residuals at the QP tolerance;
  - report.json's geometry: one region "body" of the brick's volume, the obstacle z = 0 with
    normal e3 (not given: the plane of the bottom), the basis n = -e3, t1 = e1, t2 = e2;
  - patches.csv: centroids on the bottom (z = 0), lambda_n >= 0 and ||lambda_t|| <= radius on every patch (feasibility), and
    sum(lambda_n * area) equals the report's total_normal_force;
  - contact_nodes.csv: nodes on the bottom (z = 0) at zero initial gap, w_n = -w_3 on the bottom (n = -e3), phi = ||w_t||, F in [0.2, 0.3] (the
    paper's law), the maxima equal the report's;
  - contact.vtu and solution.vtu open in meshio, and the displacement of the contact surface
    equals that of the body at the same points; contact.vtu has the gap (0) per node and
    solution.vtu the region (0) per tetrahedron.
Usage: check_contact_results.py FRICON PROBLEM.toml OUTDIR
"""
import csv

import meshio
import numpy as np

import common

exe, problem, out = common.arguments(__doc__)
report = common.solve(exe, problem, out, quiet=False)
for key in ["n_primal", "n_dual", "outer_iterations", "n_mult", "err_history", "time_s", "timings",
            "wn_pos_l2", "wn_pos_inf", "max_neg_wn", "max_wt", "max_lambda_n", "max_lambda_t",
            "total_normal_force", "kkt"]:
    assert key in report, f"report.json lacks {key}"
assert report["status"] == "converged"
# The MPGP steps by kind add up to the steps.
steps = report["qp_steps"]
assert steps["cg"] + steps["expansion"] + steps["proportioning"] == report["qp_iterations"], steps
assert report["n_primal"] == 900 and report["n_dual"] == 36
assert report["err_history"][-1] <= report["problem"]["solver"]["outer_tol"]
assert len(report["err_history"]) == report["outer_iterations"]
# The certificate: the final KKT residuals within the stated bound, 100 x qp_rtol.
assert report["termination"] == "converged", report["termination"]
assert report["kkt"]["bound"] == 100 * report["problem"]["solver"]["qp_rtol"]
assert report["kkt"]["max"] <= report["kkt"]["bound"], report["kkt"]
assert report["kkt"]["max"] == max(report["kkt"][k] for k in
                                   ("feasibility", "stationarity", "complementarity"))
# MPGP's monotonicity: reported per QP and in all, 0 with alpha_bar = 1.95 / ||Q||.
history = report["contact"]["history"]
assert report["n_objective_increases"] == sum(h["n_objective_increases"] for h in history) == 0
for k in ["feasibility", "stationarity", "complementarity"]:
    assert report["kkt"][k] < 1e-5, (k, report["kkt"][k])

# The geometry: one region, the obstacle the bottom's own plane z = 0, the paper's basis.
assert report["n_regions"] == 1, report["n_regions"]
assert len(report["regions"]) == 1 and report["regions"][0]["name"] == "body", report["regions"]
assert report["regions"][0]["n_tets"] == report["n_tets"]
lengths = report["problem"]["mesh"]["size"]
assert abs(report["regions"][0]["volume"] - np.prod(lengths)) <= 1e-12 * np.prod(lengths)
assert report["obstacle"]["given"] is False
assert report["obstacle"]["point"][2] == 0.0 and report["obstacle"]["normal"] == [0, 0, 1]
for axis, e in [("n", [0, 0, -1]), ("t1", [1, 0, 0]), ("t2", [0, 1, 0])]:
    assert np.allclose(report["contact_basis"][axis], e, rtol=0, atol=1e-15), report["contact_basis"]
assert "partition_note" not in report  # the chessboard is stable as built

def read_csv(path, header):
    """The numeric columns of a CSV whose header starts with `header`, and all its rows."""
    with open(path) as f:
        rows = list(csv.reader(f))
    assert rows[0][:len(header)] == header, rows[0]
    return np.array([r[:len(header)] for r in rows[1:]], dtype=float), rows

PATCH_COLUMNS = ["x", "y", "z", "area", "lambda_n", "lambda_t1", "lambda_t2", "radius", "F",
                 "ratio"]
P, rows = read_csv(out / "patches.csv", PATCH_COLUMNS)
assert rows[0] == PATCH_COLUMNS + ["state", "pair"], rows[0]
assert all(row[11] == "0" for row in rows[1:]), "one contact pair: pair 0 everywhere"
assert P.shape == (12, 10)
X, Y, Z, AREA, LN, LT1, LT2, RADIUS, F_R, RATIO = range(10)
assert np.all(P[:, Z] == 0.0), "a patch centroid off the brick's bottom"
# The state column: slip exactly where ||lambda_t|| reaches the radius (to 1e-6), else stick.
for p, row in zip(P, rows[1:]):
    on_circle = np.hypot(p[LT1], p[LT2]) >= (1 - 1e-6) * p[RADIUS]
    assert row[10] == ("slip" if on_circle else "stick"), (row, p)
    if p[LN] > 0:
        assert abs(p[RATIO] - np.hypot(p[LT1], p[LT2]) / p[LN]) <= 1e-12 * p[RATIO], p
    else:  # Tresca friction without contact pressure (lift-off)
        assert p[RATIO] == (np.inf if np.hypot(p[LT1], p[LT2]) > 0 else 0), p
assert np.all(P[:, LN] >= 0)
lt = np.hypot(P[:, LT1], P[:, LT2])
assert np.all(lt <= P[:, RADIUS] * (1 + 1e-12)), "a friction multiplier exceeds its slip bound"
assert np.all((P[:, RADIUS] >= 0.2 * 2e7 - 1) & (P[:, RADIUS] <= 0.3 * 2e7 + 1))
total = report["total_normal_force"]
assert abs((P[:, AREA] * P[:, LN]).sum() - total) <= 1e-9 * total
assert abs(P[:, LN].max() - report["max_lambda_n"]) <= 1e-9 * report["max_lambda_n"]
assert abs(lt.max() - report["max_lambda_t"]) <= 1e-9 * report["max_lambda_t"]

NODE_COLUMNS = ["x", "y", "z", "gap", "w_n", "w_t1", "w_t2", "phi", "F"]
N, rows = read_csv(out / "contact_nodes.csv", NODE_COLUMNS)
assert rows[0] == NODE_COLUMNS + ["pair"], rows[0]
assert all(row[9] == "0" for row in rows[1:]), "one contact pair: pair 0 everywhere"
assert N.shape == (13 * 5, 9)
X, Y, Z, GAP, WN, WT1, WT2, PHI, F = range(9)
assert np.all(N[:, Z] == 0.0), "a contact node off the brick's bottom"
assert np.all(N[:, GAP] == 0.0), "the paper's brick rests on the foundation: zero gap"
assert np.allclose(N[:, PHI], np.hypot(N[:, WT1], N[:, WT2]), rtol=1e-12, atol=0)
assert np.all((N[:, F] >= 0.2 - 1e-15) & (N[:, F] <= 0.3 + 1e-15))
assert abs(N[:, PHI].max() - report["max_wt"]) <= 1e-12 * report["max_wt"]
assert abs((-N[:, WN]).max() - report["max_neg_wn"]) <= 1e-12 * report["max_neg_wn"]
assert abs(np.maximum(N[:, WN], 0).max() - report["wn_pos_inf"]) <= 1e-12 * report["wn_pos_inf"]

body = meshio.read(out / "solution.vtu")
surface = meshio.read(out / "contact.vtu")
assert "triangle" in surface.cells_dict and surface.cells_dict["triangle"].shape == (96, 3)
index = {tuple(np.round(p, 12)): i for i, p in enumerate(body.points)}
ub = body.point_data["displacement"]
us = surface.point_data["displacement"]
for i, p in enumerate(surface.points):
    j = index[tuple(np.round(p, 12))]
    assert np.allclose(us[i], ub[j], rtol=0, atol=1e-15 + 1e-12 * abs(ub[j]).max())
    assert abs(surface.point_data["w_n"][i] + ub[j][2]) <= 1e-15 + 1e-12 * abs(ub[j][2])
for name in ["lambda_n", "lambda_t", "radius", "norm_lambda_t"]:
    assert name in surface.cell_data, name
assert np.all(surface.point_data["gap"] == 0.0)
region = np.asarray(body.cell_data["region"][0])
assert np.issubdtype(region.dtype, np.integer) and np.all(region == 0), region.dtype
print("paper brick: report.json, patches.csv, contact_nodes.csv, contact.vtu checked")
