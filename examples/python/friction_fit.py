#!/usr/bin/python3
"""A friction law from measured points: fit, solve with it from Python, compare with the table.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/friction_fit.py [--out F]

"Measurements" of the coefficient of friction at a few slips (here: points of
F(t) = 0.15 + 0.2 exp(-t / 2e-5) with 2 % noise, seeded) are fitted by a + b exp(-t / c) with
numpy alone (linear least squares for a, b over a scan of c). The fitted law goes into the paper's
brick as a Python function (fricon.FrictionLaw.function, radii integrated by adaptive
Gauss-Kronrod), and the raw points as a table law (piecewise linear, radii exact); both are
solved, and the figure shows the points, the two laws and the slips they produce.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fricon  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
PAPER_BRICK = HERE.parent / "paper-brick.toml"


def measurements(seed=1):
    t = np.array([0.0, 2e-6, 5e-6, 1e-5, 2e-5, 3e-5, 5e-5, 8e-5, 1.2e-4, 2e-4])
    truth = 0.15 + 0.2 * np.exp(-t / 2e-5)
    noise = 1.0 + 0.02 * np.random.default_rng(seed).standard_normal(t.size)
    return t, truth * noise


def fit_exponential(t, f):
    """a + b exp(-t/c): for each c of a scan, a and b by linear least squares; the best c."""
    best = None
    for c in np.geomspace(1e-6, 1e-3, 400):
        A = np.column_stack([np.ones_like(t), np.exp(-t / c)])
        coef, *_ = np.linalg.lstsq(A, f, rcond=None)
        residual = np.linalg.norm(A @ coef - f)
        if best is None or residual < best[0]:
            best = (residual, coef[0], coef[1], c)
    _, a, b, c = best
    return a, b, c


def main():
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--out", default="friction_fit.png", help="the figure")
    opts = args.parse_args()

    t, f = measurements()
    a, b, c = fit_exponential(t, f)
    print(f"fit: F(t) = {a:.4f} + {b:.4f} exp(-t / {c:.3e} m)")

    def fitted(s):
        return np.maximum(a + b * np.exp(-s / c), 0.0)

    problem = fricon.load(PAPER_BRICK)
    results = {}
    for name, law in (("fitted function", fricon.FrictionLaw.function(fitted)),
                      ("table of the points", fricon.FrictionLaw.table(t, f))):
        problem.contact.friction = law
        r = fricon.solve(problem)
        if not r.converged:
            sys.exit(f"{name}: NOT CONVERGED: {r.message}")
        results[name] = r
        rep, contact = r.report, r.report["contact"]
        print(f"{name:>20}: {rep['outer_iterations']} outer iterations, "
              f"max ||w_t|| = {rep['max_wt']:.4e} m, law {contact['friction_law']}, "
              f"radii: {contact['radius_integration']}")

    fig, (law_ax, slip_ax) = plt.subplots(1, 2, figsize=(10, 4))
    s = np.linspace(0.0, t[-1], 400)
    um = 1e6  # slips in micrometres on the axes
    law_ax.plot(um * t, f, "ko", label="measured")
    law_ax.plot(um * s, fitted(s), label="fitted a + b exp(-t/c)")
    law_ax.plot(um * s, np.interp(s, t, f), "--", label="table (piecewise linear)")
    law_ax.set(xlabel="slip t [um]", ylabel="F(t)", title="coefficient of friction")
    for name, r in results.items():
        nodes = r.contact_nodes
        slip_ax.plot(nodes["x"], um * nodes["phi"], ".", label=name)
    slip_ax.set(xlabel="x [m]", ylabel="||w_t|| [um]", title="slip on the contact surface")
    for ax in (law_ax, slip_ax):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(opts.out, dpi=120)
    print(f"figure: {opts.out}")


if __name__ == "__main__":
    main()
