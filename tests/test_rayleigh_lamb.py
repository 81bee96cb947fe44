"""Exact Rayleigh-Lamb branches: cut-offs, tracing accuracy (the float forms: test_deflated_frequency,
test_scaled_frequency)."""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from mp_lamb import mp_F

from dispersion.errors import InputError
from dispersion.continuum.rayleigh_lamb import (
    cutoff_frequencies,
    speed_ratio_squared,
)
from dispersion.continuum.exact_branches import trace_branches

DPS = 40  # digits of the mpmath references, set locally with mpmath.workdps


@pytest.fixture(autouse=True)
def _forty_digits():
    with mpmath.workdps(DPS):
        yield


def mp_root(kind, kappa, Omega0, nu):
    """High-precision root of F/Omega^2 near Omega0 (independent of the float tracer)."""
    def f(W):
        return mp_F(kind, kappa, W, nu) / W**2

    x0 = mpmath.mpf(Omega0)
    r = mpmath.findroot(f, (x0 * (1 - mpmath.mpf("1e-9")), x0 * (1 + mpmath.mpf("1e-9"))),
                        solver="anderson", verify=False)
    # certify: a sign change within 1e-25 relative brackets the root
    assert f(r * (1 - mpmath.mpf("1e-25"))) * f(r * (1 + mpmath.mpf("1e-25"))) < 0
    return r


def test_cutoffs_closed_forms():
    # kappa = 0: F_S = Omega^4 C(s Omega^2) S(Omega^2), F_A = Omega^4 S(s Omega^2) C(Omega^2)
    nu = 0.3
    s = speed_ratio_squared(nu)
    for kind in "SA":
        for w, fam in cutoff_frequencies(kind, nu, 12.0)[1:]:
            G = mp_F(kind, 0, mpmath.mpf(w), nu) / mpmath.mpf(w) ** 4
            assert abs(G) < 1e-13
            ratio = w / math.pi if fam == "T" else w * math.sqrt(s) / math.pi
            twice = 2 * ratio
            assert abs(twice - round(twice)) < 1e-12
            # symmetric: shear at m*pi, stretch at odd multiples of pi/2 (Rose 2004 ch. 8)
            expect_odd = (kind == "S") == (fam == "L")
            assert (round(twice) % 2 == 1) == expect_odd


def test_traced_roots_match_mpmath_to_1e12():
    nu = 0.3
    kappa = np.array([1e-3, 0.01, 0.1, 0.5, 1.0, 2.0, 3.7, 6.0])
    br = trace_branches(nu, kappa, 6.0)
    assert br.failures == []
    checked = 0
    for label, omega in br.omega.items():
        for k, w in zip(kappa, omega):
            if np.isnan(w):
                continue
            ref = mp_root(label[0], k, w, nu)
            assert abs(w - float(ref)) <= 1e-12 * float(ref), (label, k)
            checked += 1
    assert checked > 30


def test_s0_series_small_kappa():
    # paper eq (14): Omega^2 = 2/(1-nu) k^2 - 2 nu^2/(3 (1-nu)^3) k^4 + O(k^6)
    nu = 0.3
    kappa = np.array([0.01, 0.02, 0.04])
    w2 = trace_branches(nu, kappa, 1.0, kinds=("S",)).omega["S0"] ** 2
    series = 2 / (1 - nu) * kappa**2 - 2 * nu**2 / (3 * (1 - nu) ** 3) * kappa**4
    rem = np.abs(w2 - series) / kappa**6
    assert np.all(rem < 1.0)  # remainder is O(k^6): eq (14)'s next coefficient is ~0.02


def test_series_against_power_balance():
    from dispersion.continuum import exact_series as exact_series_mod

    nu = 0.3
    kappa = np.array([0.005, 0.01])  # truncation after k^8: relative remainder ~ k^6
    br = trace_branches(nu, kappa, 1.0)
    for label in ("S0", "A0"):
        coef = exact_series_mod.exact_series(label, 8, nu=nu)
        series = sum(float(c) * kappa**k for k, c in coef.items())
        assert np.allclose(br.omega[label] ** 2, series, rtol=1e-9, atol=0)


def test_rayleigh_wave_limit():
    # S0 and A0 tend to the Rayleigh wave: Omega/kappa -> xi with
    # (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - s xi^2)   (Rayleigh 1885), solved here in mpmath
    nu = 0.3
    s = speed_ratio_squared(nu)
    xi = mpmath.findroot(
        lambda x: (2 - x**2) ** 2 - 4 * mpmath.sqrt(1 - x**2) * mpmath.sqrt(1 - s * x**2), 0.9)
    xi = mpmath.re(xi)
    kappa = np.array([30.0])  # the S0/A0 split decays like exp(-2 kappa sqrt(1 - xi^2))
    br = trace_branches(nu, kappa, 28.0)
    for label in ("S0", "A0"):
        assert abs(br.omega[label][0] / kappa[0] - float(xi)) < 1e-7
    # A0 approaches from below, S0 from above
    assert br.omega["A0"][0] < float(xi) * 30 < br.omega["S0"][0]


def test_veering_pair_resolved():
    # nu = 0.1: S1 and S2 veer near kappa ~ 4.25, Omega ~ 6.3 with a gap ~ 0.17; a Mindlin
    # bound separates the pair, and each root must match its 40-digit reference
    nu = 0.1
    kappa = np.linspace(4.0, 4.5, 26)
    coarse = trace_branches(nu, kappa, 8.0)
    assert coarse.failures == []
    gap = coarse.omega["S2"] - coarse.omega["S1"]
    assert np.all(gap > 0) and gap.min() < 0.25
    i = int(np.argmin(gap))
    for label in ("S1", "S2"):
        w = coarse.omega[label][i]
        assert abs(w - float(mp_root("S", kappa[i], w, nu))) < 1e-12 * w


def test_coincident_cutoffs_at_nu_one_third():
    # nu = 1/3: c_L = 2 c_T, stretch cut-off pi/(2 sqrt s) = pi = first shear cut-off
    nu = 1 / 3
    cuts = [w for w, _ in cutoff_frequencies("S", nu, 3.5)]
    assert len(cuts) == 3 and abs(cuts[1] - math.pi) < 1e-14 and abs(cuts[2] - math.pi) < 1e-14
    kappa = np.array([0.0, 0.02, 0.05, 0.1])
    br = trace_branches(nu, kappa, 3.5, kinds=("S",))
    assert br.failures == []
    assert br.omega["S1"][0] == br.omega["S2"][0] == cuts[1]
    for i in range(1, kappa.size):
        w1, w2 = br.omega["S1"][i], br.omega["S2"][i]
        assert w1 < w2
        for w in (w1, w2):
            assert abs(w - float(mp_root("S", kappa[i], w, nu))) < 1e-12 * w


@pytest.mark.parametrize(
    "kwargs",
    [
        {"nu": 0.3, "kappa": [], "omega_max": 1.0},
        {"nu": 0.3, "kappa": [0.1, float("nan")], "omega_max": 1.0},
        {"nu": 0.3, "kappa": [-1.0], "omega_max": 1.0},
        {"nu": 0.3, "kappa": [1.0], "omega_max": 0.0},
        {"nu": 0.3, "kappa": [1.0], "omega_max": float("inf")},
        {"nu": 0.7, "kappa": [1.0], "omega_max": 1.0},
    ],
)
def test_bad_input(kwargs):
    with pytest.raises(InputError):
        trace_branches(**kwargs)


def test_unconverged_root_is_reported_not_hidden():
    # one solver iteration cannot close a bracket: every such root is listed, none dropped
    br = trace_branches(1 / 3, [1e-9], 3.5, kinds=("S",), max_depth=1)
    # (S2's open bracket straddles omega_max: its value is unknown, its failure is listed)
    assert {f[2].split()[0] for f in br.failures} == {"S1", "S2"}
    assert all("max_depth=1" in f[2] for f in br.failures)


def test_chunking_does_not_change_results():
    kappa = np.linspace(0, 6, 60)
    whole = trace_branches(0.3, kappa, 6.0)
    done = []
    parts = trace_branches(0.3, kappa, 6.0, chunk=7, progress=done.append)
    assert sum(done) == 2 * (kappa.size - 1)  # kappa = 0 comes from the closed forms
    assert sorted(whole.omega) == sorted(parts.omega) and parts.failures == []
    for lab, w in whole.omega.items():
        assert np.allclose(w, parts.omega[lab], rtol=1e-14, equal_nan=True)


def test_tiny_kappa_right_count_no_duplicates():
    # issue 10: at kappa in [1e-8, 1e-7], nu = 0.3 and Omega <= 8 there are 4 symmetric roots
    # (S0 and the cut-offs pi/(2 sqrt s), pi, 2 pi of cutoff_frequencies) and 5 antisymmetric
    kappa = np.linspace(1e-8, 1e-7, 10)
    br = trace_branches(0.3, kappa, 8.0)
    assert br.failures == []
    cuts = {kind: [w for w, _ in cutoff_frequencies(kind, 0.3, 8.0)] for kind in "SA"}
    for kind in "SA":
        labels = sorted((lab for lab in br.omega if lab[0] == kind), key=lambda s: int(s[1:]))
        assert len(labels) == len(cuts[kind]) == (4 if kind == "S" else 5)
        rows = np.array([br.omega[lab] for lab in labels])
        assert np.all(np.diff(rows, axis=0) > 0.1)  # distinct roots, no duplicates
        # each branch sits at its cut-off to O(kappa^2) (the fundamental one at 0)
        assert np.allclose(rows[1:, :], np.array(cuts[kind][1:])[:, None], rtol=1e-12)


@pytest.mark.parametrize("kappa", [1e-12, 1e-100, 1e-150])
def test_fundamental_branches_at_vanishing_kappa(kappa):
    # eq (14) and (16) leading terms: Omega_S0 = kappa sqrt(2/(1-nu)),
    # Omega_A0 = kappa^2 sqrt(2/(3 (1-nu))) (plate speed and Kirchhoff bending, Graff 1975)
    nu = 0.3
    br = trace_branches(nu, [kappa], 2.0)
    assert br.failures == []
    assert br.omega["S0"][0] == pytest.approx(kappa * math.sqrt(2 / (1 - nu)), rel=1e-15)
    a0 = br.omega["A0"][0]
    assert a0 / kappa / kappa == pytest.approx(math.sqrt(2 / (3 * (1 - nu))), rel=1e-15)
    assert sorted(br.omega) == ["A0", "A1", "S0"]


def test_underflow_of_a0_is_a_listed_failure():
    # Omega_A0 ~ 0.98 kappa^2 is below the smallest normal float at kappa = 1e-300
    br = trace_branches(0.3, [1e-300], 2.0)
    assert br.failures == [("A", 1e-300, br.failures[0][2])] and "underflow" in br.failures[0][2]


def test_coincident_cutoffs_resolved_not_guessed():
    # nu = 1/3: S1 and S2 leave the double cut-off pi like pi -+ (2/pi) kappa (a cone); the
    # Mindlin bound Q = pi^2 lies between them, so each is a simple, certified root. The
    # reference closes F in 40 digits in a bracket narrower than half their distance.
    kappa = np.array([1e-12, 1e-10, 1e-8])
    br = trace_branches(1 / 3, kappa, 3.5, kinds=("S",))
    assert sorted(br.omega) == ["S0", "S1", "S2"] and br.failures == []
    for i, k in enumerate(kappa):
        w1, w2 = br.omega["S1"][i], br.omega["S2"][i]
        assert w1 < math.sqrt(k * k + math.pi**2) <= w2
        half = mpmath.mpf(w2 - w1) / 4
        for w in (w1, w2):
            def f(W, k=k):
                return mp_F("S", k, W, 1 / 3)
            lo, hi = mpmath.mpf(w) - half, mpmath.mpf(w) + half
            assert f(lo) * f(hi) < 0
            ref = mpmath.findroot(f, (lo, hi), solver="anderson")
            assert abs(w - float(ref)) <= 1e-12 * float(ref)


def test_large_kappa_roots_to_1e15():
    # issue 10: A0 at kappa = 10 to 1e-15 (evanescent polish) against 40-digit roots
    nu = 0.3
    br = trace_branches(nu, [10.0], 11.0)
    assert br.failures == []
    for label in ("A0", "S0", "A1", "S1"):
        w = br.omega[label][0]
        ref = mp_root(label[0], 10.0, w, nu)
        assert abs(w - float(ref)) <= 1e-15 * float(ref), label


def test_omega_max_bounds_are_the_edges():
    # cutoff_frequencies accepts OMEGA_MAX itself (0.2 s) and refuses just past it
    from dispersion.continuum import rayleigh_lamb
    from dispersion.continuum import exact_branches as tracer

    top = rayleigh_lamb.OMEGA_MAX
    assert rayleigh_lamb.cutoff_frequencies("A", 0.3, top)[-1][0] <= top
    with pytest.raises(InputError, match="omega_max"):
        rayleigh_lamb.cutoff_frequencies("A", 0.3, top * (1 + 1e-12))
    # the tracer's scan bound: exactly MAX_SAMPLES passes the check, one kappa more does not
    omega = (tracer.MAX_SAMPLES / 4 - 1) * 0.05
    assert tracer.check_samples(4, omega) == pytest.approx(tracer.MAX_SAMPLES)
    with pytest.raises(InputError, match="omega_max"):
        trace_branches(0.3, np.linspace(0.1, 1.0, 5), omega)
