"""The friction law given as a formula: the paper's brick solved with law = "expression" holding
the paper's law (and its kinks) gives the same solution as law = "paper".

Runs `fricon solve` on the paper's brick at n = 4 and n = 8 (qp_rtol = 1e-11) both ways and
compares the outer iterations and every patch's radius and multipliers (patches.csv) to 1e-8
relative, and checks that the report names the quadrature. The radii are then computed by
adaptive Gauss-Kronrod quadrature instead of exactly (docs/theory.md §2.6).
Usage: check_expression_law.py FRICON PROBLEM.toml OUTDIR
"""
import math

import common

exe, problem, out = common.arguments(__doc__)
PAPER_FORMULA = "max(0.2, min(0.3, 0.3 - 0.05*6e4*(t - 1e-5)))"
KINKS = "[1e-5, 4.3333333333333335e-5]"  # t0 and t0 + 2/param
# Relative tolerances: the radii agree to rounding; the multipliers go through QPs stopped at
# qp_rtol = 1e-11, which amplify those differences (and err(k), a difference of iterates, more).
RTOL = {"radius": 1e-9, "lambda_n": 5e-8, "lambda_t1": 5e-8, "lambda_t2": 5e-8}
ERR_RTOL = 1e-5


def solve(folder, cells, extra):
    report = common.solve(exe, problem, folder, f"mesh.cells={cells}", "solver.qp_rtol=1e-11",
                          *extra)
    return report, common.read_rows(folder / "patches.csv")


failures = common.Failures(separator="\n")
for cells in ["[12,4,4]", "[24,8,8]"]:
    ref, ref_rows = solve(out / f"{cells}-paper", cells, [])
    got, rows = solve(out / f"{cells}-expression", cells,
                      ["contact.friction.law=expression",
                       f'contact.friction.expression="{PAPER_FORMULA}"',
                       f"contact.friction.kinks={KINKS}"])
    if got["outer_iterations"] != ref["outer_iterations"]:
        failures.add(f"{cells}: {got['outer_iterations']} outer iterations, "
                     f"law paper took {ref['outer_iterations']}")
    if "Gauss-Kronrod" not in got["contact"]["radius_integration"]:
        failures.add(f"{cells}: radius_integration is {got['contact']['radius_integration']!r}")
    if not got["contact"]["friction_law"].startswith("expression("):
        failures.add(f"{cells}: friction_law is {got['contact']['friction_law']!r}")
    for k, (a, b) in enumerate(zip(got["err_history"], ref["err_history"])):
        if abs(a - b) > ERR_RTOL * b:
            failures.add(f"{cells}: err({k + 1}) = {a}, law paper gave {b}")
    assert len(rows) == len(ref_rows)
    for col, rtol in RTOL.items():
        diff = math.sqrt(sum((float(a[col]) - float(b[col])) ** 2 for a, b in zip(rows, ref_rows)))
        norm = math.sqrt(sum(float(b[col]) ** 2 for b in ref_rows))
        print(f"{cells}: {col}: {diff / norm:.3g} relative")
        if diff > rtol * norm:
            failures.add(f"{cells}: {col} differs by {diff / norm:.3g} relative")
failures.finish("law = \"expression\" with the paper's formula gives the paper's solution")
