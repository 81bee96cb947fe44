"""Cost-accuracy study and its report section (dispersion.studies.cost_accuracy)."""
from __future__ import annotations

import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.results import jsonable
from dispersion.studies.cost_accuracy import cost_accuracy, pareto_front


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 10), st.floats(0, 10)), min_size=1, max_size=12))
def test_pareto_front_is_exactly_the_undominated_points(pts):
    cost, err = np.array(pts).T
    front = pareto_front(cost, err)
    for i in range(len(pts)):
        dominated = any(cost[j] <= cost[i] and err[j] <= err[i]
                        and (cost[j] < cost[i] or err[j] < err[i]) for j in range(len(pts)))
        assert front[i] == (not dominated)


def test_study_points_and_render(tmp_path):
    from dispersion.report.cost_accuracy import render

    res = cost_accuracy((2,), ("consistent", "lumped"))
    by = {pt.mass: pt for pt in res.points}
    # the lumped mass allows the longer step, hence the cheaper run
    assert by["lumped"].tau_crit > by["consistent"].tau_crit
    assert by["lumped"].cost < by["consistent"].cost
    for pt in res.points:  # central differences raise every frequency: 2 asin(x/2) > x
        assert pt.error_S0 > pt.semi_error_S0 and pt.error_A0 > pt.semi_error_A0
    data = json.loads(json.dumps(jsonable(res)))
    md = render(data, tmp_path)
    assert (tmp_path / "cost_accuracy.png").stat().st_size > 0
    assert "p = 2 lumped" in md and "| 2 | consistent |" in md



def test_a_mass_that_needs_a_solve_is_not_counted_as_cheap_as_a_division():
    """The modelled cost counts the solve of a non-diagonal mass (it was free before issue 30):
    at every p the step of a rule that states a solve costs more work per DOF than a diagonal
    one's, and more than the same stiffness product alone."""
    from dispersion.mass_rules.mass_rule import get_rule

    res = cost_accuracy((1, 2, 3, 4), ("consistent", "lumped"))
    by = {(pt.p, pt.mass): pt for pt in res.points}
    for p in (1, 2, 3, 4):
        assert get_rule("consistent").explicit_cost.mass == "solve"
        assert by[(p, "consistent")].work > by[(p, "lumped")].work
