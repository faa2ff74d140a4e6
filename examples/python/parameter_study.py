#!/usr/bin/python3
"""A parameter study of the paper's brick from Python: its three friction laws and a sweep of the
slip bound g, in one figure.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/parameter_study.py [--n 4] [--out F]

For each of the paper's laws (param = 2e4, 6e4, 3e5 1/m; docs/theory.md §7) and each g, one
solve of the same problem; the figure shows the largest slip max ||w_t|| and the number of outer
iterations against g. Every solve certifies itself: a run that does not converge stops the study.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import fricon  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
PAPER_BRICK = HERE.parent / "paper-brick.toml"
PARAMS = [2.0e4, 6.0e4, 3.0e5]           # the paper's three laws [1/m]
SLIP_BOUNDS = [1.0e7, 1.5e7, 2.0e7, 2.5e7, 3.0e7]  # g [Pa]


def main():
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--n", type=int, default=4, help="mesh parameter n (3n x n x n cubes)")
    args.add_argument("--out", default="parameter_study.png", help="the figure")
    opts = args.parse_args()

    problem = fricon.load(PAPER_BRICK)
    problem.mesh.cells = [3 * opts.n, opts.n, opts.n]
    print(f"{'param [1/m]':>12} {'g [Pa]':>10} {'outer its':>9} {'n_mult':>7} "
          f"{'max|w_t| [m]':>13} {'max lambda_n [Pa]':>18}")
    rows = {}
    for param in PARAMS:
        problem.contact.friction = fricon.FrictionLaw.paper(param)
        for g in SLIP_BOUNDS:
            problem.contact.slip_bound = g
            r = fricon.solve(problem)
            if not r.converged:
                sys.exit(f"param = {param:g}, g = {g:g}: NOT CONVERGED: {r.message}")
            rep = r.report
            rows.setdefault(param, []).append((g, rep))
            print(f"{param:12.3g} {g:10.3g} {rep['outer_iterations']:9d} {rep['n_mult']:7d} "
                  f"{rep['max_wt']:13.4e} {rep['max_lambda_n']:18.4e}")

    fig, (slip, its) = plt.subplots(1, 2, figsize=(10, 4))
    for param, runs in rows.items():
        g = [x for x, _ in runs]
        slip.plot(g, [rep["max_wt"] for _, rep in runs], "o-", label=f"param {param:g}")
        its.plot(g, [rep["outer_iterations"] for _, rep in runs], "o-",
                 label=f"param {param:g}")
    slip.set(xlabel="slip bound g [Pa]", ylabel="max ||w_t|| [m]", title="largest slip")
    its.set(xlabel="slip bound g [Pa]", ylabel="outer iterations",
            title="successive approximations")
    for ax in (slip, its):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle(f"Paper brick, n = {opts.n}: the paper's three friction laws")
    fig.tight_layout()
    fig.savefig(opts.out, dpi=120)
    print(f"figure: {opts.out}")


if __name__ == "__main__":
    main()
