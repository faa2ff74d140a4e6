"""User-defined friction laws from Python: a callable, and law = "expression"."""
import numpy as np
import pytest

import fricon
from conftest import PAPER_BRICK

PARAM = 6.0e4          # the paper's law of Table 1 [1/m]
T0 = 1.0e-5            # where it starts to fall [m]
KINKS = [T0, T0 + 2.0 / PARAM]
PAPER_EXPRESSION = f"t <= {T0} ? 0.3 : max(0.3 - 0.05*{PARAM}*(t - {T0}), 0.2)"


def paper_law(t):
    """The paper's law (docs/theory.md §7), written independently of the library's."""
    return np.where(t <= T0, 0.3, np.maximum(0.3 - 0.05 * PARAM * (t - T0), 0.2))


def tight(problem):
    problem.solver.qp_rtol = 1e-10
    problem.solver.outer_tol = 1e-8
    return problem


def solve_with(law):
    p = tight(fricon.load(PAPER_BRICK))
    p.contact.friction = law
    r = fricon.solve(p, threads=1)
    assert r.converged, r.message
    return r


@pytest.fixture(scope="module")
def reference():
    return solve_with(fricon.FrictionLaw.paper(PARAM))


def relative(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)).max() / np.abs(np.asarray(b)).max()


@pytest.mark.parametrize("law", [
    fricon.FrictionLaw.function(paper_law, kinks=KINKS),
    fricon.FrictionLaw.expression(PAPER_EXPRESSION, kinks=KINKS),
], ids=["callable", "expression"])
def test_the_paper_law_written_by_the_user_gives_the_papers_answer(law, reference):
    r = solve_with(law)
    assert r.report["outer_iterations"] == reference.report["outer_iterations"]
    for column in ("lambda_n", "lambda_t1", "lambda_t2", "radius"):
        assert relative(r.patches[column], reference.patches[column]) < 1e-8, column
    assert relative(r.displacement, reference.displacement) < 1e-8
    contact = r.report["contact"]
    assert ("paper_law" if law.function else "expression") in contact["friction_law"]
    assert "rtol" in contact["radius_integration"]


def test_a_smooth_law_converges_as_the_quadrature_is_tightened():
    def smooth(t):
        return 0.1 + 0.4 * np.exp(-t / 5e-5)

    radii = {}
    for rtol in (1e-2, 1e-4, 1e-6, 1e-12):
        radii[rtol] = solve_with(fricon.FrictionLaw.function(smooth, quadrature_rtol=rtol)
                                 ).patches["radius"]
    errors = [relative(radii[rtol], radii[1e-12]) for rtol in (1e-2, 1e-4, 1e-6)]
    assert errors[0] >= errors[1] >= errors[2]
    assert errors[2] < 1e-6
    # The same law as an expression, at the same accuracy, agrees.
    by_expression = solve_with(fricon.FrictionLaw.expression("0.1 + 0.4*exp(-t/5e-5)",
                                                             quadrature_rtol=1e-12))
    assert relative(by_expression.patches["radius"], radii[1e-12]) < 1e-8


def test_the_callable_sees_arrays_of_slips_a_few_times_per_iteration():
    calls = []

    def law(t):
        calls.append(len(t))
        return paper_law(t)

    r = solve_with(fricon.FrictionLaw.function(law, kinks=KINKS))
    assert len(calls) <= 20 * r.report["outer_iterations"]
    assert max(calls) > 100  # many slips per call


def test_a_negative_coefficient_is_an_input_error_naming_the_slip():
    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.function(lambda t: 0.3 - 1e4 * t)
    with pytest.raises(fricon.InputError, match=r"t = .*must be finite and >= 0"):
        fricon.solve(p)


def test_a_wrong_number_of_values_is_an_input_error():
    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.function(lambda t: np.array([0.3, 0.2]))
    with pytest.raises(fricon.InputError, match="returned 2 values"):
        fricon.solve(p)


def test_an_exception_in_the_callable_propagates_unchanged():
    class LawError(Exception):
        pass

    def law(t):
        raise LawError("no data beyond 1 mm")

    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.function(law)
    with pytest.raises(LawError, match="no data beyond 1 mm"):
        fricon.solve(p)
    assert fricon.solve(PAPER_BRICK).converged


def test_an_expression_with_a_syntax_error_names_the_key():
    p = fricon.load(PAPER_BRICK)
    with pytest.raises(fricon.InputError, match="contact.friction.expression"):
        p.contact.friction = fricon.FrictionLaw.expression("0.1 + * t")
    assert p.contact.friction.law == "paper"


def test_a_law_of_a_file_replaces_a_function():
    p = fricon.load(PAPER_BRICK)
    p.contact.friction = fricon.FrictionLaw.function(paper_law, kinks=KINKS)
    p.contact.friction = fricon.FrictionLaw.constant(0.25)
    assert p.contact.friction.to_dict() == {"law": "constant", "value": 0.25}
