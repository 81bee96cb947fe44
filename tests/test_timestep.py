"""Critical time step (dispersion.time_stepping.timestep): closed forms, two ways, and the contact solver."""
from __future__ import annotations

import csv
import math

import numpy as np
import pytest
import sympy

from dispersion.contact import newmark
from dispersion.contact.bar import Bar, assemble_bar, simulate_bar
from dispersion.errors import ConvergenceError, InputError
from dispersion.mass_rules.mass_rule import user_rule
from dispersion.symbolic.plate import plate_patch
from dispersion.time_stepping.timestep import (
    bar_omega_max,
    bar_omega_squared,
    critical_step,
    matrix_critical_step,
    patch_omega_max,
)

BAR_RULES = ("consistent", "lumped", "hrz", "nodal-greville", "nodal-lobatto")


def test_p1_closed_forms():
    # literature: dt_crit = h / c lumped, h / (sqrt(3) c) consistent (Hughes 2000, 9.3)
    lumped = critical_step("lumped", 1, model="bar", h=0.1, wave_speed=5.0)
    consistent = critical_step("consistent", 1, model="bar", h=0.1, wave_speed=5.0)
    assert lumped.omega_max_exact == 2 and consistent.omega_max_exact == 2 * sympy.sqrt(3)
    assert lumped.dt == pytest.approx(0.1 / 5.0, rel=1e-15)
    assert consistent.dt == pytest.approx(0.1 / (math.sqrt(3) * 5.0), rel=1e-15)
    assert lumped.ratio == pytest.approx(math.sqrt(3), rel=1e-15)


def _quadratic_stencils():
    # independent of the package: the three pieces of the quadratic cardinal B-spline
    # (de Boor) and their Gram integrals by numpy polynomial algebra
    P = np.polynomial.Polynomial
    pieces = [P([0, 0, 0.5]), P([0.5, 1, -1]), P([0.5, -1, 0.5])]  # on [0,1], [1,2], [2,3]
    m, d = {}, {}
    for L in range(-2, 3):
        m[L] = d[L] = 0.0
        for j in range(3):
            if 0 <= j - L <= 2:
                a, b = pieces[j], pieces[j - L]
                m[L] += (a * b).integ()(1) - (a * b).integ()(0)
                d[L] += (a.deriv() * b.deriv()).integ()(1) - (a.deriv() * b.deriv()).integ()(0)
    return m, d


def test_p2_closed_forms_derived_in_the_test():
    # Cottrell, Reali, Bazilevs, Hughes 2006: consistent quadratic omega_max h/c = sqrt(10)
    m, d = _quadratic_stencils()
    theta = np.linspace(0, np.pi, 200001)
    D = sum(v * np.cos(L * theta) for L, v in d.items())
    Mc = sum(v * np.cos(L * theta) for L, v in m.items())
    assert np.sqrt((D / Mc).max()) == pytest.approx(math.sqrt(10), rel=1e-12)
    assert np.sqrt(D.max()) == pytest.approx(math.sqrt(1.5), rel=1e-9)  # lumped: m = 1
    assert bar_omega_max("consistent", 2)[0] == sympy.sqrt(10)
    exact, theta_max = bar_omega_max("lumped", 2)
    assert exact == sympy.sqrt(6) / 2 and theta_max == pytest.approx(2 * math.pi / 3)


SLOW = pytest.mark.slow


@pytest.mark.parametrize("p", [2, pytest.param(1, marks=SLOW), pytest.param(3, marks=SLOW),
                               pytest.param(4, marks=SLOW)])
@pytest.mark.parametrize("mass", BAR_RULES)
def test_exact_bar_maximum_against_a_fine_grid(p, mass):
    f = sympy.lambdify(sympy.Symbol("z"), bar_omega_squared(mass, p), "numpy")
    grid = np.sqrt(f(np.cos(np.linspace(0, np.pi, 20001))).max())
    assert float(bar_omega_max(mass, p)[0]) == pytest.approx(grid, rel=1e-7)
    assert float(bar_omega_max(mass, p)[0]) >= grid * (1 - 1e-15)


@pytest.mark.parametrize("mass", ["singular", pytest.param("consistent", marks=SLOW),
                                  pytest.param("lumped", marks=SLOW),
                                  pytest.param("singular-lumped", marks=SLOW)])
def test_plate_maximum_two_ways(mass):
    from dispersion.symbolic.plate import numeric_pencil
    from dispersion.discretization.pencil_frequencies import pencil_frequencies

    patch = plate_patch(2, 3, "bloch", 2, mass, "top", sympy.Rational(1, 2))
    w, exact, theta, method = patch_omega_max(patch, 0.3)
    # an independent dense grid: the largest batched eigenvalue on 1025 phases, no refinement
    K, M = numeric_pencil(patch, 0.3, np.linspace(0, np.pi, 1025) / 2)
    grid = float(pencil_frequencies(K, M, patch.massless).max())
    assert w >= grid * (1 - 1e-12) and w == pytest.approx(grid, rel=1e-5)
    if exact is not None:
        assert float(exact) == pytest.approx(w, rel=1e-14)


def test_finite_bar_lumped_p1_equals_bloch_and_solver():
    bar = assemble_bar(Bar(20, 1, mass="lumped"))
    h = 1 / 20
    assert matrix_critical_step(bar.problem.K, bar.problem.M) == pytest.approx(h, rel=1e-12)
    assert newmark.critical_step(bar.problem) == pytest.approx(h, rel=1e-12)


@pytest.mark.parametrize("mass,p", [("lumped", 1), ("hrz", 2),
                                    pytest.param("nodal-greville", 2, marks=SLOW),
                                    pytest.param("consistent", 1, marks=SLOW)])
def test_central_differences_blow_up_just_above_the_critical_step(mass, p, monkeypatch):
    # the solver refuses dt > dt_crit; lift that guard to watch the run: 1.01 dt_crit
    # must grow without bound, 0.99 dt_crit stays bounded (energy within a few percent)
    dtc = matrix_critical_step(*_bar_KM(mass, p))
    assert newmark.critical_step(assemble_bar(Bar(20, p, mass=mass)).problem) == \
        pytest.approx(dtc, rel=1e-10)
    with pytest.raises(InputError, match="stability limit"):
        simulate_bar(20, p, mass, dt=1.01 * dtc, scheme="central")
    ok = simulate_bar(20, p, mass, dt=0.99 * dtc, scheme="central", t_end_factor=6)
    assert abs(ok.metrics["energy_change_percent"]) < 5
    monkeypatch.setattr(newmark, "critical_step", lambda prob, u=None: math.inf)
    bad = simulate_bar(20, p, mass, dt=1.01 * dtc, scheme="central", t_end_factor=6)
    assert not abs(bad.metrics["energy_change_percent"]) < 1e3


def _bar_KM(mass, p):
    prob = assemble_bar(Bar(20, p, mass=mass)).problem
    return prob.K, prob.M


def test_user_rule_end_to_end():
    # a user callable: half consistent, half row-sum lumped (series, branches, step, contact)
    from dispersion.symbolic.power_balance import discrete_series
    from dispersion.discretization.discrete_branches import discrete_branches

    def half(space):
        from dispersion.mass_rules.mass import row_sum_lump

        return (space.M + row_sum_lump(space.M)) / 2

    rule = user_rule("half-lumped", half, x_rule="lumped")
    assert discrete_series("S0", 2, nu=sympy.Rational(3, 10), mass=rule)[2] == \
        sympy.Rational(20, 7)
    br = discrete_branches(plate_patch(2, 3, "bloch", 2, rule), 0.3, [0.1, 0.5])
    assert np.all(np.isfinite(br.omega["S0"])) and np.all(np.isfinite(br.omega["A0"]))
    cs = critical_step(rule, 2)
    lumped, consistent = critical_step("lumped", 2), critical_step("consistent", 2)
    assert consistent.dt < cs.dt < lumped.dt
    res = simulate_bar(20, 2, rule, courant=0.3, scheme="central")
    assert abs(res.metrics["energy_change_percent"]) < 5


def test_cli_timestep_prints_step_and_ratio(capsys):
    from dispersion.cli import main

    assert main(["timestep", "--mass", "hrz", "--p", "2", "--material", "steel", "--h", "1",
                 "--format", "csv"]) == 0
    out = capsys.readouterr().out
    cs = critical_step("hrz", 2, material="steel", h=1.0)
    row = next(csv.DictReader(ln for ln in out.splitlines() if not ln.startswith("#")))
    assert (row["mass"], float(row["dt_crit [s]"]), float(row["ratio to consistent"])) == \
        ("hrz", cs.dt, cs.ratio)
    # the setting once, every symbol defined (issue 28: no repeated preamble, h and H defined)
    assert out.count("# model:") == 1 and "# H: half the plate thickness" in out
    assert main(["timestep", "--model", "bar", "--mass", "singular"]) == 2
    assert "periodic bar" in capsys.readouterr().err


def test_cli_branches_fully_discrete(capsys):
    from dispersion.cli import main

    assert main(["branches", "--scheme", "central", "--courant", "0.9", "--mass", "lumped",
                 "--count", "3", "--kappa-max", "0.5", "--omega-max", "2"]) == 0
    out = capsys.readouterr().out
    assert "lumped central C=0.9" in out and "# time integration: Newmark member central" in out
    assert main(["branches", "--scheme", "central", "--courant", "1.5"]) == 2


def test_cli_user_rule_from_toml(tmp_path, capsys):
    from dispersion.cli import main

    rule = tmp_path / "rule.toml"
    rule.write_text('name = "far-quarter"\nlumped = true\n[weights]\n'
                    '"-1" = { "-2" = 0.75, "-3" = 0.25 }\n')
    assert main(["branches", "--mass-rule", str(rule), "--count", "2", "--kappa-max", "0.5",
                 "--omega-max", "1"]) == 0
    assert ",far-quarter," in capsys.readouterr().out
    assert main(["timestep", "--mass-rule", str(rule), "--p", "2", "--format", "csv"]) == 0
    assert "\nfar-quarter," in capsys.readouterr().out


@pytest.mark.slow  # the default run proves the lumped bound in the doctest
@pytest.mark.parametrize("mass", ["singular", "consistent", "nodal-lobatto"])
def test_certified_bound_holds_and_a_false_bound_is_not_proven(mass):
    # the proof can fail: 0.5 % below the numeric maximum there is a larger frequency, so no
    # cover of the zone proves it; the proven bound itself lies in [w, w (1 + rtol)]
    from dispersion.time_stepping.timestep import certified_omega_max

    patch = plate_patch(2, 3, "bloch", 2, mass, "top", sympy.Rational(1, 2))
    w = patch_omega_max(patch, 0.3, exact=False)[0]
    assert w <= certified_omega_max(patch, 0.3, w) <= w * (1 + 1e-3)
    with pytest.raises(ConvergenceError, match="is false: a frequency above it"):
        certified_omega_max(patch, 0.3, 0.995 * w, rtol=1e-3, max_cells=4000)


def test_one_critical_time_step_for_the_plate_patch():
    # the plate patch's critical step is 2 / patch_omega_max (one implementation); an
    # independent check: 2 / the largest batched eigenvalue on a grid can only be larger or
    # equal (the grid misses the refined maximum), and a zone-end maximum agrees to rounding
    from dispersion.symbolic.plate import numeric_pencil
    from dispersion.discretization.pencil_frequencies import pencil_frequencies
    from dispersion.time_stepping.timestep import critical_time_step

    patch = plate_patch(2, 3, "bloch", 2, "lumped")
    dt = critical_time_step(patch, 0.3, n_theta=33)
    K, M = numeric_pencil(patch, 0.3, np.linspace(0, np.pi, 33) / 2)
    grid = 2 / float(pencil_frequencies(K, M, patch.massless).max())
    assert dt <= grid * (1 + 1e-12)
    assert dt == pytest.approx(2 / patch_omega_max(patch, 0.3, 33)[0], rel=1e-15)
    with pytest.raises(InputError, match="n_theta"):
        critical_time_step(patch, 0.3, n_theta=2)


# --- promises of `dispersion timestep` (docs/promises.md) -----------------------------------
import mpmath  # noqa: E402
from hypothesis import example, given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from promise_search import FAST_FEW, SLOW, record  # noqa: E402


def _mp_omega_max(patch, nu, theta):
    """The largest frequency at the phase ``theta`` refined to the maximum by one Newton step
    on its slope, all in 60-digit eigenvalues of the pencil (tests/mp_pencil.py, nothing of
    the package's solvers): the slope and its derivative by central differences (step
    1e-15: truncation 1e-30, rounding 1e-45). From a phase within 1e-6 of the maximum the
    step lands within 1e-12 (quadratic convergence); at a zone end the value there, and the
    largest value of an independent float grid (plain numpy eigenvalues on 257 phases) must
    not exceed it."""
    from dispersion.symbolic.plate import numeric_pencil
    from mp_pencil import mp_frequencies

    r = mpmath.mpf(sympy.Rational(patch.r).p) / sympy.Rational(patch.r).q
    K, M = numeric_pencil(patch, nu, np.linspace(0, np.pi, 257) / float(r))
    keep = [i for i in range(M.shape[1]) if np.any(M[0, i])]
    Kh = K[:, keep][:, :, keep]
    if len(keep) < M.shape[1]:
        m = [i for i in range(M.shape[1]) if i not in keep]
        Kh = Kh - K[:, keep][:, :, m] @ np.linalg.solve(K[:, m][:, :, m], K[:, m][:, :, keep])
    Mk = M[:, keep][:, :, keep]
    grid = max(float(np.sqrt(np.max(np.linalg.eigvals(np.linalg.solve(Mk[i], Kh[i])).real)))
               for i in range(257))
    with mpmath.workdps(60):
        def top(th):
            return mp_frequencies(patch, nu, th / r, dps=60)[-1]

        th = mpmath.mpf(theta)
        if 0 < theta < math.pi:
            h = mpmath.mpf(10) ** -15
            up, mid, dn = top(th + h), top(th), top(th - h)
            th = th - ((up - dn) / (2 * h)) / ((up - 2 * mid + dn) / h**2)
        value = top(th)
    assert float(value) >= grid * (1 - 1e-12)   # no larger maximum elsewhere
    return value, th


def _check_step(mass, p, material):
    from dispersion.materials.materials import MATERIALS

    cs = critical_step(mass, p, material=material)   # never a traceback
    nu = MATERIALS[material].nu
    n = max(p + 1, 3)
    patch = plate_patch(p, n, "bloch", sympy.Rational(2, n - p), mass, "top",
                        sympy.Rational(1, 2))
    ref, where = _mp_omega_max(patch, nu, cs.theta)
    record("timestep omega_max", abs(cs.omega_max / float(ref) - 1), 1e-12, mass=mass, p=p,
           material=material)
    if 0 < where < mpmath.pi:   # an interior maximum is located too (issue 26: to 3e-8)
        record("timestep interior maximum location", abs(cs.theta - float(where)), 1e-9,
               mass=mass, p=p, material=material)
    if cs.omega_max_exact is not None:   # exact zone-end values: rational arithmetic only
        assert float(sympy.N(cs.omega_max_exact, 30)) == pytest.approx(float(ref), rel=1e-14)


def _step_domain(p_max):
    """Every rule, p = 1..p_max, every material; the crash of issue 26 (p = 4, singular, which
    also failed with copper, brass, glass, pmma, aluminium-rolled) as examples."""
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES as MASS_VARIANTS
    from dispersion.materials.materials import MATERIALS

    def decorate(fn):
        for ex in [("singular", 4, "steel")] + [("consistent", 3, "steel")] * (p_max > 3):
            fn = example(*ex)(fn)
        return given(st.sampled_from(MASS_VARIANTS), st.integers(1, p_max),
                     st.sampled_from(sorted(MATERIALS)))(fn)
    return decorate


@FAST_FEW
@_step_domain(3)
def test_critical_step_against_mpmath(mass, p, material):
    _check_step(mass, p, material)


@pytest.mark.slow
@SLOW
@_step_domain(8)
def test_critical_step_against_mpmath_slow(mass, p, material):
    _check_step(mass, p, material)


@pytest.mark.parametrize("p, mass", [(3, "consistent"), pytest.param(8, "consistent",
                                                                     marks=pytest.mark.slow)])
def test_certify_proves_the_bound_that_holds(p, mass):
    # issue 26: p = 3 printed "max_cells ... (raise rtol or max_cells)", p = 8 "does not
    # hold" for a true bound; the bound must be proven (and lie above the 60-digit maximum)
    from dispersion.materials.materials import MATERIALS

    cs = critical_step(mass, p, material="steel", certify=True)
    assert cs.failures == () and cs.omega_certified is not None
    n = max(p + 1, 3)
    patch = plate_patch(p, n, "bloch", sympy.Rational(2, n - p), mass)
    assert cs.omega_certified >= float(_mp_omega_max(patch, MATERIALS["steel"].nu, cs.theta)[0])


def test_a_proof_that_does_not_close_is_a_failure_in_words(capsys):
    # with too few cells the proof cannot close: it is listed as not proven (never "false",
    # never an option the command line does not have), in text and JSON
    import json

    from dispersion.cli import main
    from dispersion.time_stepping import omega_max_bound

    patch = plate_patch(2, 3, "bloch", 2, "lumped")
    w = patch_omega_max(patch, 0.3)[0]
    with pytest.raises(ConvergenceError, match="did not close.*not known to be false"):
        omega_max_bound.certified_omega_max(patch, 0.3, w, max_cells=2)
    real = omega_max_bound.certified_omega_max

    def few(*args, **kw):
        return real(*args, **{**kw, "max_cells": 2})

    import dispersion.time_stepping.timestep as ts
    old, ts.certified_omega_max = ts.certified_omega_max, few
    try:
        assert main(["timestep", "--p", "2", "--mass", "lumped", "--certify"]) == 0
        out = capsys.readouterr().out
        assert "no proven stable step: the proof" in out
        assert "rtol" not in out and "max_cells" not in out and "does not hold" not in out
        assert main(["timestep", "--p", "2", "--mass", "lumped", "--certify",
                     "--format", "json"]) == 0
        result = json.loads(capsys.readouterr().out)
        assert any("did not close" in f for f in result["failures"])
        assert result["rows"][0]["omega_max H / c_T proven bound"] is None
    finally:
        ts.certified_omega_max = old
