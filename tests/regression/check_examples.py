"""Every example solves, quickly, and shows what its header promises.

  - each examples/*.toml exits 0 with a complete results folder;
  - frictionless-block: no friction multiplier anywhere (lambda_t = 0 on every patch);
  - tresca-constant: the coefficient does not depend on the slip, so the second outer iteration
    repeats the first (err(2) = 0 up to rounding) and every slip bound is 0.3 g;
  - friction-table: every slip bound lies between the table's extremes 0.25 g and 0.4 g;
  - friction-expression: every slip bound lies between the formula's bounds 0.1 g and 0.5 g, and
    the report names the formula and the quadrature's tolerance;
  - paper-brick with the three params: the paper's sizes (n_p = 900, n_d = 36);
  - parameter-study.sh runs and writes one CSV line per run.
Usage: check_examples.py FRICON EXAMPLES_DIR OUTDIR
"""
import common

exe, examples, out = common.arguments(__doc__)


def solve(name):
    folder = out / name
    report = common.solve(exe, examples / f"{name}.toml", folder, timeout=120)
    assert report["status"] == "converged", name
    return folder, report


names = sorted(p.stem for p in examples.glob("*.toml"))
assert len(names) >= 6, names
reports = {name: solve(name) for name in names}

folder, _ = reports["frictionless-block"]
for p in common.read_patches(folder):
    assert p["lambda_t1"] == 0.0 and p["lambda_t2"] == 0.0 and p["radius"] == 0.0, p

folder, report = reports["tresca-constant"]
assert report["outer_iterations"] == 2 and report["err_history"][1] < 1e-12, report["err_history"]
for p in common.read_patches(folder):
    assert abs(p["radius"] - 0.3 * 2e7) <= 1e-6, p

folder, _ = reports["friction-table"]
for p in common.read_patches(folder):
    assert 0.25 * 2e7 - 1e-6 <= p["radius"] <= 0.4 * 2e7 + 1e-6, p

folder, report = reports["friction-expression"]
for p in common.read_patches(folder):
    assert 0.1 * 2e7 - 1e-6 <= p["radius"] <= 0.5 * 2e7 + 1e-6, p
assert "0.1 + 0.4*exp(-t/5e-5)" in report["contact"]["friction_law"], report["contact"]
assert "1e-10" in report["contact"]["radius_integration"], report["contact"]

for name in ["paper-brick", "paper-brick-param2e4", "paper-brick-param3e5"]:
    _, report = reports[name]
    assert report["n_primal"] == 900 and report["n_dual"] == 36, name

# Coulomb: every patch inside its friction cone with the coefficient F_R of the result, on it where
# it slips, and the report's own Coulomb certificate within its bound.
folder, report = reports["coulomb-brick"]
assert report["model"] == "coulomb" and report["state_blocks"] == ["phi", "lambda_n"], report
assert report["coulomb"]["residual"] <= report["coulomb"]["bound"], report["coulomb"]
assert all(len(b) == 2 for b in report["block_err_history"])
for p in common.read_patches(folder):
    lt = (p["lambda_t1"] ** 2 + p["lambda_t2"] ** 2) ** 0.5
    assert p["lambda_n"] >= 0 and lt <= p["F"] * p["lambda_n"] * (1 + 1e-3) + 1e-6, p
    if p["state"] == "slip":
        assert abs(lt - p["F"] * p["lambda_n"]) <= 1e-3 * p["F"] * p["lambda_n"], p

study = out / "study"
common.run_ok(["bash", examples / "parameter-study.sh", exe, study], timeout=300)
lines = (study / "summary.csv").read_text().splitlines()
assert len(lines) == 1 + 6, lines
print(f"{len(names)} examples and the parameter study checked")
