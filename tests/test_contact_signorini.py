"""GetFEM's 1D Signorini bar: the exact solution (checked against the PDE, not a table) and
the scene solved with the bar API."""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.contact.signorini import exact_solution, signorini_1d
from dispersion.errors import InputError


@pytest.fixture(scope="module")
def ex():
    return exact_solution(9.0)


def test_exact_solution_meets_initial_and_boundary_data(ex):
    x = np.linspace(0, 1, 41)
    assert np.allclose(ex.u(x, 0.0)[0], 0.5 * (1 - x))          # u(x, 0) = (1 - x)/2
    assert np.allclose(ex.velocity(x[1:-1], 0.0)[0], 0.0)       # u_t(x, 0) = 0
    t = np.linspace(0, 9, 181)
    assert np.allclose(ex.u(np.array([1.0]), t)[:, 0], 0.0, atol=1e-14)  # clamped end


def test_exact_solution_satisfies_signorini_conditions(ex):
    t = np.linspace(0, 9, 901)
    gap = ex.u(np.array([0.0]), t)[:, 0]
    stress = ex.stress(t)
    assert gap.min() > -1e-14 and stress.min() > -1e-14
    assert np.abs(gap * stress).max() < 1e-14                    # complementarity
    assert stress.max() > 0.4                                    # there is contact


def test_exact_solution_derivatives_match_finite_differences(ex):
    # u built by integrating the invariants; its difference quotients must give u_t, u_x
    rng = np.random.default_rng(1)
    x, t, d = rng.uniform(0.05, 0.95, 30), rng.uniform(0.05, 8.9, 30), 1e-7
    for xi, ti in zip(x, t):
        ut = (ex.u(xi, ti + d) - ex.u(xi, ti - d))[0, 0] / (2 * d)
        ux = (ex.u(xi + d, ti) - ex.u(xi - d, ti))[0, 0] / (2 * d)
        assert np.isclose(ut, ex.velocity(xi, ti)[0, 0], atol=1e-6)
        assert np.isclose(ux, ex.strain(xi, ti)[0, 0], atol=1e-6)


def test_exact_solution_conserves_energy_and_has_period_three(ex):
    # energy 1/8 = (1/2) int (u_x^2) at t = 0 with u_x = -1/2
    for t in (0.3, 1.4, 2.2, 4.7):
        assert np.isclose(ex.energy(t), 0.125, rtol=1e-3)
    x = np.linspace(0, 1, 21)
    t = np.linspace(0, 5.9, 60)
    assert np.allclose(ex.u(x, t), ex.u(x, t + 3.0), atol=1e-12)


def test_singular_mass_conserves_energy_after_the_consistent_start():
    res = signorini_1d(p=1, mass="singular", dt=0.004, t_end=3.0)
    e = res.errors
    assert abs(e["energy_drift_percent"]) < 0.01
    assert e["first_step_change_percent"] == pytest.approx(0.0, abs=1e-9)
    assert e["initial_energy_change_percent"] == pytest.approx(-100 * 0.05, rel=1e-9)  # h
    assert e["min_gap"] > -1e-12


def test_singular_contact_stress_beats_lumped_and_consistent():
    errs = {m: signorini_1d(p=1, mass=m, dt=0.004, t_end=3.0).errors["stress_rel_l2"]
            for m in ("lumped", "consistent", "singular")}
    assert errs["singular"] < min(errs["lumped"], errs["consistent"])


def test_explicit_and_kane_agree_for_the_singular_mass():
    a = signorini_1d(p=1, mass="singular", scheme="kane", dt=0.004, t_end=3.0)
    b = signorini_1d(p=1, mass="singular", scheme="central", dt=0.004, t_end=3.0)
    assert abs(a.errors["stress_rel_l2"] - b.errors["stress_rel_l2"]) < 0.02


def test_history_csv_has_one_row_per_step():
    res = signorini_1d(p=1, mass="singular", dt=0.01, t_end=0.5)
    lines = [line for line in res.to_csv().splitlines() if not line.startswith("#")]
    assert lines[0] == "t [-],u0 [-],v0 [-],contact_stress [-],kinetic [-],strain [-],total [-]"
    assert len(lines) == 1 + 51


def test_bad_inputs_name_the_parameter():
    with pytest.raises(InputError, match="t_end"):
        signorini_1d(dt=0.003, t_end=1.0)
    with pytest.raises(InputError, match="dt"):
        signorini_1d(scheme="central", mass="lumped", dt=0.2, t_end=0.4)
    with pytest.raises(InputError, match="mass"):
        signorini_1d(mass="heavy")


def test_step_count_and_kept_states_are_bounded():
    with pytest.raises(InputError, match=r"t_end / dt must be <= \d+ steps"):
        signorini_1d(dt=1e-12)
    with pytest.raises(InputError, match=r"t_end / dt must be <= \d+ steps"):
        signorini_1d(t_end=1e12)
    # 10^5 elements over 10^5 steps keep about 4e10 bytes of states: over half of 24 GiB
    with pytest.raises(InputError, match=r"n_elements = 100000 .* bound of"):
        signorini_1d(n_elements=100_000, dt=1e-4, t_end=10.0)


def test_a_signorini_row_carries_the_spread_of_its_perturbed_runs():
    # issue 23: the row's errors over the runs of SIGNORINI_SPREAD_RULE (the wall moved by
    # k units of 2^-53); the k = 0 run is one of them, so it lies in each range
    from dispersion.contact.signorini import SPREAD_FIELDS, gap_ulps
    from dispersion.contact.study import _signorini

    row = _signorini((1, "lumped", "kane", 3.0, 3))
    assert row["spread"]["runs"] == 3 and gap_ulps(3) == (0.0, 2.0**-53, 2.0**-52)
    for name in SPREAD_FIELDS:
        s = row["spread"][name]
        assert s["min"] <= row[name] <= s["max"], name


def test_time_axis_is_k_dt_not_a_running_sum():
    # issue 26: the accumulated axis had t[1500] = 2.999999999999891 at dt = 0.002, so the
    # samples at the exact solution's jumps (t = 1, 3, ...) were judged on the wrong side.
    # Each t_k must be the float nearest k * dt (dt by its decimal, exact rationals here)
    from fractions import Fraction

    res = signorini_1d(mass="singular", dt=0.002, t_end=4.0)
    assert res.t[1500] == 3.0 and res.t[500] == 1.0
    assert all(t == float(k * Fraction("0.002")) for k, t in enumerate(res.t))
