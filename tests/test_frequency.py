"""Modes at a given frequency (``dispersion.continuum.frequency``): roots, labels, counts.

References are independent of the toolkit's formulas: the Rayleigh-Lamb equations are
written here in their textbook form (Rose 2004, eqs 8.21-8.22, multiplied out) and solved
by mpmath at 40 digits; group velocities are mpmath's implicit derivative of that form;
labels are checked against the kappa tracer's order at the root's kappa.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from dispersion.errors import InputError
from dispersion.continuum.frequency import FREQUENCY_OMEGA_MIN, modes_at_frequency
from dispersion.materials.materials import material
from dispersion.answers.mode_table import lamb_modes

#: Accuracy asked for by issue 20 (relative, kappa and velocities).
RTOL = 1e-12


def _textbook(kind, k, W, nu):
    """Rose (2004) eqs 8.21-8.22 without tan poles, divided by q (S) or p (A): real."""
    s = (1 - 2 * nu) / (2 * (1 - nu))
    p, q = mpmath.sqrt(s * W**2 - k**2), mpmath.sqrt(W**2 - k**2)
    a = (q**2 - k**2) ** 2
    if kind == "S":
        return mpmath.re(a * mpmath.cos(p) * mpmath.sinc(q) + 4 * k**2 * p * mpmath.sin(p)
                         * mpmath.cos(q))
    return mpmath.re(a * mpmath.sinc(p) * mpmath.cos(q) + 4 * k**2 * q * mpmath.sin(q)
                     * mpmath.cos(p))


def _mp_root_and_slope(kind, kappa, W, nu):
    with mpmath.workdps(40):
        nu, W = mpmath.mpf(nu), mpmath.mpf(W)
        k0 = mpmath.mpf(kappa)
        root = mpmath.findroot(lambda k: _textbook(kind, k, W, nu),
                               (k0 * (1 - mpmath.mpf("1e-8")), k0 * (1 + mpmath.mpf("1e-8"))),
                               solver="anderson")
        fk = mpmath.diff(lambda k: _textbook(kind, k, W, nu), root)
        fw = mpmath.diff(lambda w: _textbook(kind, root, w, nu), W)
        return float(root), float(-fk / fw)


CASES = [  # (material, thickness mm, f kHz): what the roots include
    ("steel", 3.0, 200.0),          # the issue's question: S0, A0, SH0 only
    ("aluminium", 1.0, 2950.0),     # S1 between its ZGV (2857 kHz) and cut-off: backward
    pytest.param("pmma", 2.0, 700.0, marks=pytest.mark.slow),     # low c_T: A1, S1
    pytest.param("titanium", 5.0, 900.0, marks=pytest.mark.slow),  # several higher modes
]


@pytest.mark.parametrize(("name", "d", "f"), CASES)
def test_roots_and_group_velocities_match_mpmath(name, d, f):
    t = lamb_modes(material(name), d, frequency_khz=[f])
    r = t.roots
    assert not r.failures
    for lab, kappa, g in zip(r.label, r.kappa, r.group):
        if lab.startswith("SH"):
            n = int(lab[2:])  # closed form Omega^2 = kappa^2 + (n pi / 2)^2 (Auld, ch. 10)
            assert kappa == pytest.approx(math.sqrt(r.omega[0] ** 2 - (n * math.pi / 2) ** 2),
                                          rel=RTOL)
            continue
        ref, slope = _mp_root_and_slope(lab[0], kappa, r.omega[0], r.nu)
        assert abs(kappa - ref) <= RTOL * ref, (lab, kappa, ref)
        assert abs(g - slope) <= 1e-10 * abs(slope), (lab, g, slope)


def test_s1_backward_branch_has_two_roots_and_negative_group_velocity():
    t = lamb_modes(material("aluminium"), 1.0, frequency_khz=[2950.0])
    s1 = [row for row in t.rows() if row["mode"] == "S1"]
    assert len(s1) == 2
    back, forward = sorted(s1, key=lambda row: row["k [rad/mm]"])
    assert back["c_g [m/s]"] < 0 < forward["c_g [m/s]"]
    zgv = [p for p in t.zgv() if p["mode"] == "S1"]
    assert zgv and zgv[0]["f [kHz]"] < 2950.0 < t.cutoffs_khz()["S1"]


def test_issue_20_aluminium_s0_at_200_khz():
    # issue 20: S0 c_p at 200 kHz in 3 mm aluminium is 5408.73 m/s at the material's nu
    # (5269.01 when nu = 0.3 is mixed in); here recomputed against mpmath at 40 digits
    t = lamb_modes(material("aluminium"), 3.0, frequency_khz=200.0)
    row = next(row for row in t.rows() if row["mode"] == "S0")
    ref, _ = _mp_root_and_slope("S", row["kappa = kh"], row["Omega = omega h / c_T"], t.nu)
    cp = row["Omega = omega h / c_T"] / ref * 3130.0
    assert row["c_p [m/s]"] == pytest.approx(cp, rel=RTOL)
    assert round(cp, 2) == 5408.73


def test_labels_follow_the_kappa_tracer():
    from dispersion.continuum.exact_branches import trace_branches

    nu = 0.3
    r = modes_at_frequency(nu, [2.8, 4.5], kinds=("S", "A"), zgv=False)
    tr = trace_branches(nu, r.kappa, 4.6)
    for i, (lab, W) in enumerate(zip(r.label, r.omega[r.index])):
        assert tr.omega[lab][i] == pytest.approx(W, rel=1e-10), (lab, r.kappa[i])


def test_sh_modes_closed_form():
    m = material("copper")
    t = lamb_modes(m, 2.0, frequency_khz=[1500.0], kinds=("SH",))
    rows = t.rows()
    assert [row["mode"] for row in rows] == ["SH0", "SH1", "SH2"]  # f_n = n c_T / (2d)
    for row in rows:
        assert row["c_p [m/s]"] * row["c_g [m/s]"] == pytest.approx(m.c_T**2, rel=1e-14)
    assert t.cutoffs_khz()["SH1"] == pytest.approx(m.c_T / (2 * 2.0), rel=1e-14)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"frequency_khz": [100.0], "fd_mhz_mm": [0.1]}, "exactly one"),
    ({}, "exactly one"),
    ({"frequency_khz": [0.0]}, "frequency_khz must lie in"),
    ({"frequency_khz": [float("nan")]}, "frequency_khz must lie in"),
    ({"fd_mhz_mm": [1e6]}, "fd_mhz_mm must lie in"),
    ({"frequency_khz": "abc"}, "frequency_khz must be"),
])
def test_bad_frequencies_are_refused(kwargs, match):
    with pytest.raises(InputError, match=match):
        lamb_modes(material("steel"), 1.0, **kwargs)


@pytest.mark.parametrize("W", [FREQUENCY_OMEGA_MIN, pytest.param(0.03, marks=pytest.mark.slow)])
def test_low_frequencies_are_accurate(W):
    # below SLOPE_OMEGA the group velocity is taken in 30 digits (the float slope loses
    # eps / Omega^2); both sides of that switch are checked
    r = modes_at_frequency(0.3, [W], kinds=("S", "A"), zgv=False)
    assert not r.failures and r.label == ("S0", "A0")
    for lab, kappa, g in zip(r.label, r.kappa, r.group):
        ref, slope = _mp_root_and_slope(lab[0], kappa, W, 0.3)
        assert abs(kappa - ref) <= RTOL * ref
        assert abs(g - slope) <= RTOL * abs(slope)


@pytest.mark.slow
def test_completeness_against_the_kappa_tracer_aluminium_to_3_mhz():
    # one quantity two ways: roots at fixed frequency against crossings of the traced
    # branches Omega_j(kappa) with the level Omega on a fine kappa grid (away from ZGV pairs)
    from dispersion.continuum.exact_branches import trace_branches

    al = material("aluminium")
    nu = al.nu
    omega = np.linspace(0.05, 3.0, 60)
    r = modes_at_frequency(nu, omega, kinds=("S", "A"))
    assert not r.failures
    kappa = np.linspace(1e-3, 4.0, 4001)
    tr = trace_branches(nu, kappa, 3.2)
    for i, W in enumerate(omega):
        found = sorted(lab for lab, j in zip(r.label, r.index) if j == i)
        crossings = []
        for lab, w in tr.omega.items():
            d = w - W
            ok = np.isfinite(d[1:]) & np.isfinite(d[:-1])
            crossings += [lab] * int(np.count_nonzero(ok & (np.sign(d[1:]) != np.sign(d[:-1]))))
        assert found == sorted(crossings), (W, found, crossings)


@pytest.mark.slow
def test_random_frequencies_certified_and_accurate():
    from hypothesis import given, settings
    from hypothesis import strategies as st

    @settings(max_examples=40, deadline=None)
    @given(nu=st.floats(0.0, 0.45), W=st.floats(0.01, 8.0))
    def check(nu, W):
        r = modes_at_frequency(nu, [W], kinds=("S", "A"))
        if r.failures:  # allowed only with a reason: a near-double root or cut-off
            assert all(reason for *_, reason in r.failures)
            return
        for lab, kappa in zip(r.label, r.kappa):
            ref, _ = _mp_root_and_slope(lab[0], kappa, W, nu)
            assert abs(kappa - ref) <= 1e-10 * ref  # 1e-12 away from ZGV points
        for fam in "SA":
            nums = sorted({int(lab[1:]) for lab in r.label if lab[0] == fam})
            assert nums == list(range(len(nums))) or (fam == "S" and 0 in nums)

    check()


@pytest.mark.parametrize(("nu", "W"), [
    (1 / 3, math.pi),
    pytest.param(0.3, math.pi, marks=pytest.mark.slow),
    pytest.param(0.3, 1.5 * math.pi, marks=pytest.mark.slow),
])
def test_frequency_exactly_at_a_cut_off(nu, W):
    # found by the property search: Omega on a cut-off (at nu = 1/3 a double one, c_L = 2 c_T)
    # leaves that mode at kappa = 0 (not propagating); the others are labelled by the count
    r = modes_at_frequency(nu, [W], kinds=("S", "A"), zgv=False)
    assert not r.failures
    assert all(lab[1:].isdigit() for lab in r.label) and np.all(r.kappa > 0)
    for lab, kappa in zip(r.label, r.kappa):
        ref, _ = _mp_root_and_slope(lab[0], kappa, W, nu)
        assert abs(kappa - ref) <= RTOL * ref


# --- promise: frequency-input roots certified to 1e-12 (docs/promises.md) ------------------
from hypothesis import example, given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from promise_search import FAST_FEW, SLOW, record  # noqa: E402


def _mp_root_and_slope(kind, kappa, omega, nu):
    """The root in kappa of the textbook equation near ``kappa`` and -F_k / F_W there, by
    mpmath alone (tests/mp_lamb.py) at 60 digits plus the cosh-sized cancellation."""
    from mp_lamb import mp_F

    with mpmath.workdps(60 + int(kappa / 2.3)):
        W, m_nu = mpmath.mpf(omega), mpmath.mpf(nu)
        k = mpmath.findroot(lambda x: mp_F(kind, x, W, m_nu), mpmath.mpf(kappa),
                            solver="newton", tol=mpmath.mpf(10) ** -50, maxsteps=200)
        g = -mpmath.diff(lambda x: mp_F(kind, x, W, m_nu), k) / \
            mpmath.diff(lambda x: mp_F(kind, k, x, m_nu), W)
        return k, g


def _check_frequency(nu, omega):
    from dispersion.continuum.frequency import modes_at_frequency

    res = modes_at_frequency(nu, [omega], kinds=("S", "A"), zgv=True)
    listed = {(w, kind) for w, kind, _ in res.failures}
    for lab, k, g in zip(res.label, res.kappa, res.group):
        if (omega, lab[0]) in listed:
            continue   # listed as a failure: allowed, never silent
        ref, ref_g = _mp_root_and_slope(lab[0], float(k), omega, nu)
        record("frequency-input kappa", abs(k / float(ref) - 1), 1e-12, nu=nu, omega=omega,
               mode=lab)
        # c_g: relative to c_T where it is small (near a ZGV point or a cut-off c_g -> 0 and
        # its relative error is that of the root times the ratio)
        record("frequency-input c_g", abs(g - float(ref_g)) / max(abs(float(ref_g)), 1.0),
               1e-10, nu=nu, omega=omega, mode=lab)


def _frequency_domain(fn, full=False):
    """Every material of the table (by its nu) and user materials (nu in (-1, 0.5)), Omega
    from the calculator's floor to its ceiling; issue 26's cases as examples."""
    from dispersion.continuum.frequency import FREQUENCY_OMEGA_MAX, FREQUENCY_OMEGA_MIN
    from dispersion.materials.materials import MATERIALS

    def omega(material, f_khz, d_mm):
        m = MATERIALS[material]
        return 2 * math.pi * f_khz * 1e3 * d_mm * 1e-3 / 2 / m.c_T, m.nu

    cases = [omega("aluminium", 3129.9, 1.0)[::-1],          # S1 backward, below its cut-off
             omega("pmma", 10.2e3, 1.0)[::-1],               # fd 10.2: A2 at kappa ~ 29
             (0.3, FREQUENCY_OMEGA_MIN),
             omega("copper", 19.5e3, 1.0)[::-1],             # fd 19.5
             (0.3, FREQUENCY_OMEGA_MAX)]
    for nu, w in cases if full else cases[:3]:   # the default run: the cheaper ends
        fn = example(nu=nu, omega=w)(fn)
    nus = st.one_of(st.sampled_from(sorted(m.nu for m in MATERIALS.values())),
                    st.floats(-0.999, 0.4999))
    return given(nu=nus, omega=st.floats(FREQUENCY_OMEGA_MIN, FREQUENCY_OMEGA_MAX))(fn)


@FAST_FEW
@_frequency_domain
def test_frequency_roots_against_mpmath(nu, omega):
    _check_frequency(nu, omega)


@pytest.mark.slow
@SLOW
@lambda fn: _frequency_domain(fn, full=True)
def test_frequency_roots_against_mpmath_slow(nu, omega):
    _check_frequency(nu, omega)


# --- promise: SH and Lamb modes at and next to every cut-off (docs/promises.md) -------------
_EPS = 2.0**-52


def _mp_cutoff(family, n, nu):
    """Cut-off Omega of a family at 50 digits: SH n pi/2; Lamb from F at kappa = 0 (S: m pi and
    (2m+1) pi / (2 sqrt s); A: (2m+1) pi / 2 and m pi / sqrt s), sqrt s = c_T / c_L."""
    with mpmath.workdps(50):
        rs = mpmath.sqrt((1 - 2 * mpmath.mpf(nu)) / (2 * (1 - mpmath.mpf(nu))))
        if family == "SH":
            return n * mpmath.pi / 2
        m, kind = divmod(n, 2)
        if family == "S":
            return (m + 1) * mpmath.pi if kind else (2 * m + 1) * mpmath.pi / (2 * rs)
        return (2 * m + 1) * mpmath.pi / 2 if kind else (m + 1) * mpmath.pi / rs


def _check_cutoff(nu, family, n, delta):
    from dispersion.continuum.frequency import FREQUENCY_OMEGA_MAX, modes_at_frequency

    wc = _mp_cutoff(family, n, nu)
    omega = float(wc * (1 + mpmath.mpf(delta)))
    if not 0.01 < omega <= FREQUENCY_OMEGA_MAX:
        return
    with mpmath.workdps(50):
        true_delta = float((mpmath.mpf(omega) - wc) / wc)
    res = modes_at_frequency(nu, [omega], kinds=(family,) if family == "SH" else ("S", "A"))
    at = {lab for _, lab in res.at_cutoff}
    fam = [lab for lab in at if lab.rstrip("0123456789") == family]
    if abs(true_delta) <= 6 * _EPS:   # at the cut-off (to rounding): named, no noise row
        assert fam, f"{family} cut-off {float(wc)} at Omega {omega} not named"
    elif abs(true_delta) >= 10 * _EPS:
        assert not fam, f"{fam} named at a relative distance {true_delta:.3g}"
    listed = {(w, kind) for w, kind, _ in res.failures}
    for lab, k, g in zip(res.label, res.kappa, res.group):
        if lab.rstrip("0123456789") != family or k > 0.1 or (omega, lab[0]) in listed:
            continue
        # every root next to a cut-off: against the textbook equation at 60 digits
        if family == "SH":
            with mpmath.workdps(60):
                m = int(lab[2:])
                ref = mpmath.sqrt(mpmath.mpf(omega) ** 2 - (m * mpmath.pi / 2) ** 2)
        else:
            ref = _mp_root_and_slope(lab[0], float(k), omega, nu)[0]
        record("kappa next to a cut-off", abs(k / float(ref) - 1), 1e-12, nu=nu,
               family=family, n=n, delta=delta, mode=lab)
        assert 2 * math.pi / k < 1e15   # never a wavelength of rounding noise
    if family == "SH" and true_delta >= 10 * _EPS:   # SH exists above its cut-off: listed
        assert f"SH{n}" in res.label


def _cutoff_domain(fn, full=False):
    """Every family's cut-offs below the ceiling, every nu (materials and user), relative
    distances from 0 (at) through a few ulp to 1e-3 on both sides; issue 26's cases."""
    from dispersion.materials.materials import MATERIALS

    nu_5900 = (1 - 2 * (3200 / 5900) ** 2) / (2 * (1 - (3200 / 5900) ** 2))
    nu_5640 = (1 - 2 * (3400 / 5640) ** 2) / (2 * (1 - (3400 / 5640) ** 2))
    ends = [(nu_5900, "SH", 11, 0.0), (nu_5640, "SH", 3, 0.0), (0.3, "S", 1, -1e-6),
            (0.3, "A", 2, 0.0), (0.3, "S", 2, 1e-12), (0.3, "SH", 1, 16 * _EPS)]
    for ex in ends if full else ends[:3]:
        fn = example(*ex)(fn)
    nus = st.one_of(st.sampled_from(sorted(m.nu for m in MATERIALS.values())),
                    st.floats(-0.99, 0.49))
    deltas = st.sampled_from([0.0, _EPS, -_EPS, 4 * _EPS, 16 * _EPS, -16 * _EPS, 1e-14,
                              -1e-12, 1e-12, 1e-10, -1e-8, 1e-8, 1e-6, -1e-3, 1e-3])
    return given(nus, st.sampled_from(["S", "A", "SH"]), st.integers(1, 18), deltas)(fn)


@FAST_FEW
@_cutoff_domain
def test_modes_at_and_next_to_every_cutoff(nu, family, n, delta):
    _check_cutoff(nu, family, n, delta)


@pytest.mark.slow
@SLOW
@lambda fn: _cutoff_domain(fn, full=True)
def test_modes_at_and_next_to_every_cutoff_slow(nu, family, n, delta):
    _check_cutoff(nu, family, n, delta)
