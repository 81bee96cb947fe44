"""Ring benchmark: conservation laws, penetration where it is measured, lumped vs singular.

Default tests run short scenes (the default scene scaled down, :meth:`Scenario.scaled`);
the full 7200-step scene and the grids are ``slow``.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from dispersion.contact.scenario import MAX_ELEMENTS, MAX_STEPS, Scenario
from dispersion.contact.simulate import ring_problem, simulate_ring
from dispersion.contact.study import fit_rate, steps_per_impact
from dispersion.errors import InputError

SMALL = Scenario().scaled(0.0625)  # r = 9-10 m, 450 steps, about 2 steps per impact


@pytest.fixture(scope="module")
def runs():
    return {m: simulate_ring(SMALL, m) for m in ("lumped", "singular")}


def test_initial_kinetic_energy_is_half_m_v0_squared(runs):
    # every mass variant keeps the translational mass rho * area (paper sec. 1.1)
    mass = SMALL.rho * np.pi / 4 * (SMALL.r_outer**2 - SMALL.r_inner**2)
    for res in runs.values():
        assert np.isclose(res.series["kinetic"][0], 0.5 * mass * SMALL.v0**2, rtol=1e-6)


def test_horizontal_momentum_is_conserved_on_a_frictionless_plane(runs):
    # the plane pushes only along y: M v summed over x DOFs stays 0
    for res in runs.values():
        px = res.series["momentum_x"]
        assert np.abs(px).max() < 1e-8 * abs(res.series["momentum_y"][0])


def test_ring_rebounds_into_free_flight(runs):
    for res in runs.values():
        assert not res.summary["in_contact_at_end"]
        assert res.series["momentum_y"][-1] > 0  # moving away from the plane
        last = np.flatnonzero(res.series["contact_force"] > 0)[-1]
        py = res.series["momentum_y"][last + 1:]
        assert np.ptp(py) < 1e-8 * abs(py[0])


def test_greville_points_never_penetrate(runs):
    # the multipliers enforce g >= 0 exactly at the Greville points of the outer surface
    for res in runs.values():
        assert res.summary["max_penetration_greville"] < 1e-9 * SMALL.r_outer


def test_boundary_between_greville_points_dips_below_the_plane_less_than_the_gap_scale(runs):
    # between the Greville points the sampled boundary does dip (the constraint is not
    # imposed there); it stays far below the wall thickness
    thick = SMALL.r_outer - SMALL.r_inner
    for res in runs.values():
        assert 0 < res.summary["max_penetration"] < 0.05 * thick


def test_singular_mass_loses_less_energy_than_lumped_on_a_short_scene(runs):
    lumped, singular = (runs[m].summary["energy_change_percent"] for m in ("lumped", "singular"))
    assert lumped < 0 and abs(singular) < abs(lumped)


def test_standard_newmark_changes_energy_at_impacts():
    res = simulate_ring(replace(SMALL, t_end=2.0), "lumped", "standard")
    # the impacts of the first 2 s make single-step energy jumps above 1 % of E0 (the
    # standard predictor carries the contact acceleration into the step after a release);
    # the trapezoidal rule's free-flight drift before the first contact is round-off
    total = res.series["total"]
    assert np.abs(np.diff(total)).max() > 0.01 * total[0]
    first = np.flatnonzero(res.series["contact_force"] > 0)[0]
    assert np.abs(np.diff(total[:first])).max(initial=0) < 1e-9 * total[0]


def test_scaled_scene_is_the_scene_at_a_smaller_step(runs):
    # dimensional analysis: with v0 and the material fixed, a ring f times larger (radii,
    # gap, end time) at step dt is the same dimensionless problem as the ring at dt / f
    sc = Scenario().scaled(0.125)
    assert sc.scaled(0.5) == SMALL  # its run is shared with the tests above
    small = runs["singular"].summary
    coarse = simulate_ring(replace(sc, dt=sc.dt / 0.5), "singular").summary
    assert small["contact_events"] == coarse["contact_events"]
    assert np.isclose(small["energy_change_percent"], coarse["energy_change_percent"],
                      rtol=1e-6)


def test_scenario_derives_E_from_the_stated_speed_ratio():
    for sc in (Scenario(), Scenario(rho=2000.0, nu=0.2, v0=1.0)):
        assert np.isclose(sc.v0 / sc.shear_wave_speed, sc.v0_over_cT, rtol=1e-12)


def test_with_level_refines_the_instance_own_mesh():
    sc = Scenario(n_xi_elements=5, n_eta_elements=3).with_level(2)
    assert (sc.n_xi_elements, sc.n_eta_elements) == (20, 12)


def test_steps_per_impact_of_the_default_scene():
    # 2 t / (c_p dt) with t = 16 m, c_p = sqrt(E / (rho (1 - nu^2))): about 30 (docstring)
    sc = Scenario()
    c_p = np.sqrt(sc.E / (sc.rho * (1 - sc.nu**2)))
    assert np.isclose(steps_per_impact(sc), 32 / (c_p * 0.05))
    assert 29 < steps_per_impact(sc) < 31


@pytest.mark.parametrize("kwargs, name", [
    ({"gap": float("inf")}, "gap"),
    ({"theta0_deg": float("nan")}, "theta0_deg"),
    ({"t_end": 0.01}, "t_end"),
    ({"t_end": 0.07}, "t_end"),
    ({"dt": 1e-7}, "t_end / dt"),
    ({"dt": 1e-300, "t_end": 1e-299}, "dt"),
    ({"r_inner": 2.0, "r_outer": 1.0}, "r_outer"),
    ({"v0_over_cT": -1.0}, "v0_over_cT"),
])
def test_bad_scenarios_name_the_parameter(kwargs, name):
    with pytest.raises(InputError, match=name.replace("/", "/")):
        Scenario(**kwargs)


def test_step_count_limit_is_stated():
    assert MAX_STEPS >= Scenario().n_steps


def test_bad_mass_and_threshold_rejected():
    with pytest.raises(InputError, match="mass"):
        ring_problem(SMALL, "heavy")
    with pytest.raises(InputError, match="contact_threshold"):
        simulate_ring(replace(SMALL, t_end=0.1), "singular", contact_threshold=2.0)


def test_explicit_scheme_runs_the_ring_below_its_limit():
    res = simulate_ring(replace(SMALL, t_end=1.0, dt=0.01), "lumped", "central")
    assert res.summary["max_penetration_greville"] < 1e-9 * SMALL.r_outer


@pytest.mark.slow
def test_singular_loses_less_than_lumped_across_the_grid():
    # wherever an impact spans at least 3 steps, for every landing angle of the grid
    for f in (0.125, 0.25):
        for ang in (180.0, 190.0, 200.0):
            sc = replace(Scenario(), theta0_deg=ang).scaled(f)
            assert steps_per_impact(sc) >= 3
            e = {m: simulate_ring(sc, m).summary["energy_change_percent"]
                 for m in ("lumped", "singular")}
            assert abs(e["singular"]) < abs(e["lumped"]), (f, ang, e)


@pytest.mark.slow
def test_singular_energy_error_converges_in_dt_over_four_monotone_steps():
    sc = Scenario().scaled(0.125)
    dts = [sc.dt * k for k in (2.0, 1.0, 0.5, 0.25)]
    e = [simulate_ring(replace(sc, dt=dt), "singular").summary["energy_change_percent"]
         for dt in dts]
    fit = fit_rate(dts, e)
    assert fit["monotone"] and fit["points"] == 4
    assert fit["rate"] > 1


@pytest.mark.slow
def test_full_default_scene_singular_loses_far_less_than_lumped():
    e = {m: simulate_ring(Scenario(), m).summary for m in ("lumped", "singular")}
    assert abs(e["singular"]["energy_change_percent"]) < 0.1 * abs(
        e["lumped"]["energy_change_percent"])
    assert e["singular"]["force_roughness"] < e["lumped"]["force_roughness"]


def test_element_bound_admits_the_finest_cli_level_and_refuses_beyond():
    finest = Scenario().with_level(4)  # ``dispersion ring --level 4``
    assert finest.n_xi_elements * finest.n_eta_elements == MAX_ELEMENTS
    with pytest.raises(InputError, match=r"n_xi_elements x n_eta_elements must be <= "):
        Scenario(n_xi_elements=MAX_ELEMENTS // 2 + 1)
    with pytest.raises(InputError, match=r"n_xi_elements must be an integer in \[1, "):
        Scenario(n_xi_elements=10**6)


def test_memory_of_the_kept_states_is_bounded():
    finest = Scenario().with_level(4)
    # 5 floats per DOF (2 per control point of the 258 x 34 net) and kept state (7201)
    assert finest.memory_bytes == 8 * 5 * 2 * (256 + 2) * (32 + 2) * (7200 + 1)
    with pytest.raises(InputError, match=r"n_xi_elements x n_eta_elements .* bound of"):
        replace(finest, t_end=MAX_STEPS * finest.dt)
