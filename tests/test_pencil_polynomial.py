"""Characteristic polynomial path of the discrete branches: exact coefficients, certified roots,
accuracy against an independent 60-digit eigen-solve, fall-backs that never raise (issue 23
items 1 and 6, issue 17 item 6)."""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES
from dispersion.symbolic.plate import dynamic_stiffness, mirror_bases, plate_patch
from dispersion.discretization import discrete_branches as db
from dispersion.discretization import certified_roots as cr
from dispersion.discretization import extended_pencil
from dispersion.discretization import pencil_polynomial as pp
from mp_pencil import mp_frequencies, mp_group_velocity

#: Every mass rule the toolkit has (the polynomial path must serve any of them).
MASSES = BLOCH_RULE_NAMES  # the patches here are Bloch ones
#: The four masses of issue 17's 72 configurations.
ISSUE_MASSES = ("consistent", "lumped", "singular", "singular-lumped")


def _sorted_finite(br, i):
    w = np.array([v[i] for v in br.omega.values()])
    return np.sort(w[np.isfinite(w)])


@pytest.mark.parametrize("kind", ["S", "A"])
def test_coefficients_are_the_exact_determinant(kind):
    # P(u, mu) against sympy's exact det of the projected dynamic stiffness (eq 3) at rational
    # kappa = 1/3 (u = 1/9) and Omega^2 = 7/5, x-exact consistent mass
    patch = plate_patch(model="x-exact")
    E = mirror_bases(3, exact=True)[kind]
    poly = pp.pencil_polynomial(patch, 0.3, E)
    k, lam = sympy.Rational(1, 3), sympy.Rational(7, 5)
    Kd = dynamic_stiffness(patch, kappa=k, Omega=sympy.sqrt(lam), nu=sympy.Rational(3, 10))
    exact = float((E.T * Kd * E).det())
    u = float(k**2)
    value = sum(poly.coef[j, i] * u**i * float(lam) ** j
                for j in range(poly.coef.shape[0]) for i in range(poly.coef.shape[1]))
    assert value == pytest.approx(exact, rel=1e-12)


def test_bloch_shifted_table_is_the_same_polynomial():
    # the v = 2 - u table (used near the zone edge) evaluates to the same P as the u table
    poly = pp.pencil_polynomial(plate_patch(model="bloch", r=2), 0.3,
                                mirror_bases(3, exact=True)["S"])
    u = np.array([0.7, 1.3, 1.9])
    a = pp._horner_u(poly.coef, u)
    b = pp._horner_u(poly.shifted["P"], 2 - u)
    assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(a).max())


def _match_reference(model, mass, kappa):
    # issue 23 item 1: 1e-10 relative everywhere, from kappa = 1e-8 to the zone edge; the
    # reference is mpmath's eigsy of the Cholesky-reduced pencil at 60 digits (mp_pencil.py),
    # no part of the polynomial path
    patch = plate_patch(model=model, r=2 if model == "bloch" else None, mass=mass)
    br = db.discrete_branches(patch, 0.3, kappa)
    assert br.failures == []
    for i, k in enumerate(kappa):
        ref = np.array([float(v) for v in mp_frequencies(patch, 0.3, k)])
        got = _sorted_finite(br, i)
        assert got.size == ref.size
        # kappa = 0: the rigid modes are exactly 0 (the reference shows ~1e-30): absolute
        scale = np.where(ref > 1e-20, ref, 1.0) if k == 0 else ref
        assert np.all(np.abs(got - ref) / scale <= 1e-10), (k, got, ref)


@pytest.mark.parametrize("model, mass", [("bloch", "consistent"), ("x-exact", "singular")])
def test_frequencies_match_independent_60_digit_solve(model, mass):
    _match_reference(model, mass, np.array([0.0, 1e-8, 1e-4, 0.05, 0.9, 1.5]))


@pytest.mark.slow
@pytest.mark.parametrize("model", ["x-exact", "bloch"])
@pytest.mark.parametrize("mass", MASSES)
def test_frequencies_match_independent_60_digit_solve_all(model, mass):
    top = math.pi / 2 if model == "bloch" else 4.0
    _match_reference(model, mass, np.concatenate([[0.0, 1e-8, 1e-6, 1e-4, 1e-2],
                                                  np.linspace(0.1, top, 6)]))


def _certified_values_are_right(logk, mass, nu):
    # whatever the polynomial path certifies is within 1e-10 of the 60-digit reference
    patch = plate_patch(model="bloch", r=2, mass=mass)
    k = 10.0**logk
    br = db.discrete_branches(patch, nu, [k, 1.5 * k])
    for i, kk in enumerate((k, 1.5 * k)):
        if any(f[1] == kk and f[0] == "omega" for f in br.failures):
            continue
        ref = np.array([float(v) for v in mp_frequencies(patch, nu, kk)])
        got = _sorted_finite(br, i)
        assert got.size == ref.size and np.all(np.abs(got - ref) <= 1e-10 * ref), (kk, got, ref)


_KAPPA_NU_MASS = dict(logk=st.floats(-8, math.log10(math.pi / 2)), mass=st.sampled_from(MASSES),
                      nu=st.sampled_from([0.0, 0.25, 0.3, 1 / 3, 0.45, 0.4999]))


@settings(max_examples=3, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**_KAPPA_NU_MASS)
def test_property_certified_values_are_right(logk, mass, nu):
    _certified_values_are_right(logk, mass, nu)


@pytest.mark.slow
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**_KAPPA_NU_MASS)
def test_property_certified_values_are_right_long(logk, mass, nu):
    _certified_values_are_right(logk, mass, nu)


def test_eigen_path_agrees_with_polynomial_path(monkeypatch):
    # the same branches by the float eigen-solver (+ extended precision) path, forced
    patch = plate_patch(mass="singular")
    kappa = np.array([1e-5, 1e-3, 0.2, 1.0, 2.5])
    fast = db.discrete_branches(patch, 0.3, kappa)
    monkeypatch.setattr(pp, "MAX_BLOCK", 0)
    slow = db.discrete_branches(patch, 0.3, kappa)
    assert fast.symmetry == slow.symmetry
    for lab, w in fast.omega.items():
        assert np.allclose(w, slow.omega[lab], rtol=1e-10, atol=0, equal_nan=True), lab


def test_no_sympy_matrix_is_printed(monkeypatch):
    # issue 23: 167,551 Matrix.__str__ calls on the way to a cached evaluator; now none, on a
    # grid with many small kappa, on both paths
    def refuse(self):
        raise AssertionError("a sympy matrix was formatted")

    monkeypatch.setattr(sympy.matrices.MatrixBase, "__str__", refuse)
    monkeypatch.setattr(sympy.matrices.MatrixBase, "__repr__", refuse)
    kappa = np.geomspace(1e-7, 1.0, 300)
    db.discrete_branches(plate_patch(model="x-exact", mass="lumped"), 0.3, kappa)
    monkeypatch.setattr(pp, "MAX_BLOCK", 0)
    db.discrete_branches(plate_patch(model="bloch", r=2, mass="lumped"), 0.29, kappa[:40])


def test_tiny_kappa_follows_power_laws_and_reports_underflow():
    # below KAPPA_TINY: Omega = Omega(k0) (k / k0)^e; S0 ~ c_plate kappa with the plate speed
    # sqrt(2 / (1 - nu)) of the discrete patch at small kappa (eq 16 leading term), A0 ~ kappa^2
    # underflows at 1e-300 and is listed, never silently NaN
    patch = plate_patch(model="x-exact")
    br = db.discrete_branches(patch, 0.3, [0.0, 1e-300, 1e-100, 1e-30])
    s0 = br.omega["S0"]
    assert s0[0] == 0.0
    assert s0[1:] / np.array([1e-300, 1e-100, 1e-30]) == pytest.approx(math.sqrt(2 / 0.7),
                                                                      rel=1e-12)
    a0 = br.omega["A0"]
    assert np.isnan(a0[1]) and a0[0] == 0.0
    assert a0[2] / 1e-200 == pytest.approx(a0[3] / 1e-60, rel=1e-12)
    listed = {k for what, k, _ in br.failures if what == "omega"}
    assert listed == {1e-300}


def test_failing_ball_solver_is_reported_not_raised(monkeypatch):
    # issue 17 item 6: the eigen-solver never raises out of discrete_branches; forced onto the
    # eigen path, with every extended-precision solve failing as flint's acb_mat.eig can
    def broken(*args, **kwargs):
        raise ValueError("failed to isolate eigenvalues")

    monkeypatch.setattr(pp, "MAX_BLOCK", 0)
    monkeypatch.setattr(extended_pencil, "extended_frequencies", broken)
    br = db.discrete_branches(plate_patch(), 0.3, [1e-6, 0.5])
    bad = [f for f in br.failures if f[0] == "omega"]
    assert [f[1] for f in bad] == [1e-6, 1e-6]  # S and A block at the small kappa
    assert "failed" in bad[0][2]
    assert all(np.isfinite(w[1]) for w in br.omega.values())  # 0.5 needs no ball solve


CONFIGS = [(p, n, mass, nu, model)
           for p, n in ((1, 3), (2, 3), (3, 6))
           for mass in ISSUE_MASSES
           for nu in (-0.99, 0.3, 0.4999)
           for model in ("x-exact", "bloch")]


def _never_raises(p, n, mass, nu, model):
    patch = plate_patch(p=p, n=n, mass=mass, model=model, r=2 if model == "bloch" else None)
    kappa = np.array([0.0, 1e-300, 1e-100, 1e-20, 1e-12, 1e-6, 1e-3, 0.5, 1.5, 30.0, 1000.0])
    br = db.discrete_branches(patch, nu, kappa, group=True)
    listed = {k for what, k, _ in br.failures if what == "omega"}
    n_roots = 2 * n - len(patch.massless)
    for i, k in enumerate(kappa):
        got = _sorted_finite(br, i)
        assert got.size == n_roots or k in listed, (k, got)


@pytest.mark.parametrize("p, n, mass, nu, model",
                         [c for c in CONFIGS if c[0] <= 2 and c[3] != 0.3][::5])
def test_never_raises_sample(p, n, mass, nu, model):
    _never_raises(p, n, mass, nu, model)


@pytest.mark.slow
@pytest.mark.parametrize("p, n, mass, nu, model", CONFIGS)
def test_never_raises_72_configurations(p, n, mass, nu, model):
    # the 72 configurations of issue 17 item 6 (p, n, mass, nu near the limits, x-exact and
    # Bloch, kappa from 0 and 1e-300 to 1000): every kappa has all its roots or is listed
    _never_raises(p, n, mass, nu, model)


@pytest.mark.slow
def test_large_patch_at_large_kappa_never_raises():
    # issue 17: p = 23, n = 24 at kappa = 1000 raised flint's ValueError
    patch = plate_patch(p=23, n=24, mass="singular-lumped")
    br = db.discrete_branches(patch, 0.3, [1000.0])
    for w in br.omega.values():
        assert np.isfinite(w[0]) or any(f[1] == 1000.0 for f in br.failures)


def test_group_velocity_reference_helper_is_sane():
    # the reference of the velocity tests: S0 slope at small kappa is the plate speed of eq 16
    patch = plate_patch(model="x-exact")
    with mpmath.workdps(30):
        g = float(mp_group_velocity(patch, 0.3, 1e-4, 1))
    assert g == pytest.approx(math.sqrt(2 / 0.7), rel=1e-7)


# --- the certificate itself (issue 23 item 1): a finite radius always encloses the root ---

def _block_reference(patch, nu, kappa, block):
    """``mu = Omega^2 m_x`` of the roots of one block in extended precision (mp_pencil.py: the
    eigen-solve of the Cholesky-reduced pencil, nothing of the polynomial path), as floats,
    and the float m_x the polynomial path multiplies by."""
    basis = None if block.kind is None else mirror_bases(patch.n, exact=True)[block.kind]
    # digits: 40 beyond the spread of the roots (A0 ~ kappa^4 beside roots of order one)
    dps = 40 + int(4 * max(0.0, -math.log10(kappa)))
    with mpmath.workdps(dps):
        W = mp_frequencies(patch, nu, kappa, dps, basis)
        r = float(patch.r) if patch.model == "bloch" else None
        u, v, _ = pp.u_of_kappa(patch.model, r, np.array([kappa]))
        mx = float(pp.mass_factor(block.poly, u, v)[0, 0])
        return np.array([float(w * w * mx) for w in W]), u, v


def _certificate_holds(p, n, mass, nu, kappa, rel_shift):
    # the rule, stated before looking: |mu - mu_ref| <= rad + 8 eps mu, the 8 eps covering
    # the reference's conversion to float and the float m_x it is multiplied by (a few ulp)
    patch = plate_patch(p=p, n=n, model="bloch", r=2, mass=mass)
    for block in db._plan(patch, nu):
        if block.poly is None:
            continue
        ref, u, v = _block_reference(patch, nu, kappa, block)
        # start off the root by rel_shift: the certificate may not rely on Newton converging
        mu, rad = cr.certified_roots(block.poly, u, v, (ref * (1 + rel_shift))[None, :],
                                     iterations=0, kappa=np.array([kappa]))
        finite = np.isfinite(rad[0])
        err = np.abs(mu[0] - ref)
        assert np.all(err[finite] <= rad[0][finite] + 8 * np.finfo(float).eps * ref[finite]), \
            (block.kind, kappa, mu[0], ref, rad[0])


_EDGE = math.pi / 2   # zone edge pi/r of the Bloch patch with r = 2
_KAPPA = st.one_of(st.floats(1e-12, 1e-4), st.floats(1e-4, _EDGE),
                   st.sampled_from([1e-20, 1e-8, _EDGE, math.nextafter(_EDGE, 0),
                                    _EDGE * (1 - 1e-9), _EDGE / 2]))


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kappa=_KAPPA, mass=st.sampled_from(ISSUE_MASSES),
       nu=st.sampled_from([0.0, 0.3, 0.45]), rel_shift=st.floats(-1e-3, 1e-3))
def test_property_certificate_encloses_the_root(kappa, mass, nu, rel_shift):
    _certificate_holds(2, 3, mass, nu, kappa, rel_shift)


@pytest.mark.slow
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kappa=_KAPPA, mass=st.sampled_from(ISSUE_MASSES), rel_shift=st.floats(-1e-3, 1e-3))
def test_property_certificate_encloses_the_root_p3_n6(kappa, mass, rel_shift):
    # the 12 x 12 mixed pencil of the singular masses: degree 10 in mu, 36 in u, the
    # centred Taylor tables and the Kantorovich radius
    _certificate_holds(3, 6, mass, 0.3, kappa, rel_shift)


def _p3_values_are_right(kappa, mass):
    # whatever discrete_branches returns for p = 3, n = 6 (any route) is within 1e-10 of the
    # 60-digit reference, or the kappa is listed
    patch = plate_patch(p=3, n=6, model="bloch", r=2, mass=mass)
    br = db.discrete_branches(patch, 0.3, kappa)
    for i, kk in enumerate(kappa):
        if any(f[1] == kk and f[0] == "omega" for f in br.failures):
            continue
        dps = 40 + int(4 * max(0.0, -math.log10(kk))) if kk > 0 else 60  # as above
        ref = np.array([float(v) for v in mp_frequencies(patch, 0.3, kk, dps)])
        got = _sorted_finite(br, i)
        scale = np.where(ref > 1e-20, ref, 1.0) if kk == 0 else ref
        assert got.size == ref.size and np.all(np.abs(got - ref) <= 1e-10 * scale), (kk, got, ref)


@pytest.mark.slow
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kappa=st.lists(_KAPPA, min_size=1, max_size=3), mass=st.sampled_from(ISSUE_MASSES))
def test_property_p3_n6_values_are_right(kappa, mass):
    _p3_values_are_right(np.array(kappa), mass)


def test_p3_n6_zone_edge_and_zero_are_right():
    # the hard points of the race grids: kappa = 0, 1e-6 and the zone edge itself
    _p3_values_are_right(np.array([0.0, 1e-6, 1.0, _EDGE]), "singular-lumped")


def test_routes_count_every_kappa_once():
    # every kappa of the grid is counted on exactly one route; the tiny ones on the power law
    patch = plate_patch(p=3, n=6, model="bloch", r=2, mass="singular-lumped")
    kappa = np.concatenate([[0.0, 1e-30], np.linspace(0.01, _EDGE, 300)])
    br = db.discrete_branches(patch, 0.3, kappa)
    assert set(br.routes) == set(db.ROUTES)
    assert sum(br.routes.values()) == kappa.size
    assert br.routes["power law"] == 2


def test_taylor_tables_are_the_same_polynomial():
    # the centred tables are exact Taylor shifts of P: their value at (u, mu) equals that of
    # the table in u, evaluated at 50 digits (mpmath); the rule: within 1e-9 of the u-table's
    # bar sum sum |a_jk| u^k |mu|^j (both tables are the exact P rounded coefficient-wise)
    # the singular-lumped mass of the test above: the same exact polynomial (cached)
    patch = plate_patch(p=3, n=6, model="bloch", r=2, mass="singular-lumped")
    poly = db._plan(patch, 0.3)[0].poly
    assert poly.centres == pp.taylor_centres(poly.coef.shape[1] - 1) == 4
    rng = np.random.default_rng(1)
    u = rng.uniform(0, 2, 40)
    mu = rng.uniform(0, 50, (1, 40))
    c = cr._tables(poly, u, 2 - u)[0]
    p, _ = pp._horner_mu(c, mu)
    J, D = poly.coef.shape
    with mpmath.workdps(50):
        for i in range(u.size):
            uu, m = mpmath.mpf(u[i]), mpmath.mpf(mu[0, i])
            ref = sum(mpmath.mpf(poly.coef[j, k]) * uu**k * m**j for j in range(J)
                      for k in range(D))
            bar = sum(abs(poly.coef[j, k]) * u[i]**k * mu[0, i]**j for j in range(J)
                      for k in range(D))
            assert abs(p[0, i] - float(ref)) <= 1e-9 * bar, (u[i], p[0, i], float(ref))
