"""Promise: next to every cut-off and ZGV point, every root at a given frequency is certified
to 1e-12 relative or listed (docs/promises.md, frequency-near-cutoffs-zgv; issue 34 item 7).

The plate is drawn by its speed ratio c_L/c_T (every admissible one: nu in (-1, 0.5)) and
passed as a material, so the Poisson ratio is the exact rational of its speeds, as from the
command line. The frequency is a float at a relative distance d (1e-14 .. 1e-3, log-uniform,
both signs, ends as examples) from a cut-off (S and A; the thickness-shear ones are SH
cut-offs too) or a ZGV point of the first modes. References are independent of the package's
forms: the textbook equation in p and q at 60 digits (``tests/mp_lamb.py``), its roots bracketed
by sign changes on their own grids (in kappa^2 next to a cut-off, geometric towards the ZGV
point's kappa) and closed by bisection; ZGV points solved from F = F_kappa = 0 at 60 digits.
"""
from __future__ import annotations

import math

import mpmath
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from dispersion.continuum.frequency import (FREQUENCY_OMEGA_MAX, FREQUENCY_OMEGA_MIN,
                                        modes_at_frequency, zgv_points_below)
from dispersion.materials.materials import Material, material
from dispersion.answers.mode_table import lamb_modes
from mp_lamb import (cutoffs_mp, group_velocity_mp, mp_exact, roots_in_window,
                     roots_near_zero, zgv_mp)
from promise_search import FAST_FEW, SLOW, record

RTOL = 1e-12
#: Roots with kappa below this are "next to a cut-off" (the reference scans them all).
KAPPA_NEAR = 0.05
#: First modes searched: cut-offs 1..4 of each class, ZGV points with Omega up to 12.
CUTOFFS, ZGV_OMEGA = 4, 12.0
RATIO_MIN = math.sqrt(4 / 3) * (1 + 1e-6)   # nu = -0.99999..
RATIO_MAX = 50.0                              # nu = 0.49980..


def _plate(ratio: float) -> Material:
    return Material(ratio * 1000.0, 1000.0)


def _compare(res, omega, kind, refs, inside, case, promise, nu):
    """Every returned root of ``kind`` with ``inside(kappa)`` against the references (each
    within RTOL of one, its group velocity within 1e-10 relative, or absolute in units of c_T
    below c_T), and every reference root returned: or a failure of that class at that
    frequency is listed."""
    listed = any(w == omega and k == kind for w, k, _ in res.failures)
    mine = [(lab, float(k), float(g)) for lab, k, g in zip(res.label, res.kappa, res.group)
            if lab[0] == kind and not lab.startswith("SH") and inside(float(k))]
    for lab, k, g in mine:
        assert lab[1:].isdigit() or listed, (lab, k, case)
        if listed:
            continue
        assert refs, f"{lab} kappa={k!r} has no reference root near it at {case}"
        ref = min(refs, key=lambda r: abs(r - k))
        record(promise, float(abs(k / ref - 1)), RTOL, mode=lab, kappa=k, **case)
        ref_g = group_velocity_mp(kind, ref, mpmath.mpf(omega), nu)
        record(promise + " (c_g)", float(abs(g - ref_g) / max(abs(ref_g), 1)), 1e-10,
               mode=lab, kappa=k, **case)
    for ref in refs:
        assert listed or any(abs(k / ref - 1) <= RTOL for _, k, _ in mine), \
            f"reference root {mpmath.nstr(ref, 17)} ({kind}) not returned at {case}"


def _check_cutoff(ratio, kind, n, d):
    plate = _plate(ratio)
    nu_q = plate.nu_exact
    with mpmath.workdps(60):
        nu = mp_exact(nu_q)
        wc = cutoffs_mp(kind, nu, n)[n - 1]
        omega = float(wc * (1 + mpmath.mpf(d)))
        if not FREQUENCY_OMEGA_MIN <= omega <= FREQUENCY_OMEGA_MAX:
            return
        res = modes_at_frequency(nu_q, [omega])
        W = mpmath.mpf(omega)
        case = {"ratio": ratio, "target": f"{kind}{n}", "d": d, "omega": omega}
        at = {lab[0] for _, lab in res.at_cutoff}
        for fam in ("S", "A"):   # another class's cut-off may lie next to this one too
            refs = [r for r in roots_near_zero(fam, W, nu, KAPPA_NEAR)
                    if not (fam in at and r < 1e-6)]   # a mode at its cut-off (8 eps): named
            _compare(res, omega, fam, refs, lambda k: k < KAPPA_NEAR, case,
                     "frequency roots next to a cut-off", nu)
        for lab, k in zip(res.label, res.kappa):   # SH next to its cut-off: closed form
            if lab.startswith("SH") and k < KAPPA_NEAR:
                m = int(lab[2:])
                ref = mpmath.sqrt(W**2 - (m * mpmath.pi / 2) ** 2)
                record("frequency roots next to a cut-off", float(abs(k / ref - 1)), RTOL,
                       mode=lab, **case)


def _check_zgv(ratio, which, d):
    plate = _plate(ratio)
    nu_q = plate.nu_exact
    points = zgv_points_below(float(nu_q), ZGV_OMEGA)
    if not points:
        return
    p = points[which % len(points)]
    kind = p.label[0]
    with mpmath.workdps(60):
        nu = mp_exact(nu_q)
        kz, wz = zgv_mp(kind, p.kappa, p.omega, nu)
        omega = float(wz * (1 + mpmath.mpf(d)))
        res = modes_at_frequency(nu_q, [omega])
        width = min(0.2, 50 * math.sqrt(abs(d)))
        refs = roots_in_window(kind, mpmath.mpf(omega), nu, kz, width)
        lo, hi = float(kz * (1 - width)), float(kz * (1 + width))
        case = {"ratio": ratio, "target": f"ZGV {p.label}", "d": d, "omega": omega}
        _compare(res, omega, kind, refs, lambda k: lo < k < hi, case,
                 "frequency roots next to a ZGV point", nu)


# --- the cases of issue 34, through the calculator's material route ------------------------

def _al_zgv_khz():
    al = material("aluminium")
    p = next(p for p in zgv_points_below(al.nu, 3.0) if p.label == "S1")
    with mpmath.workdps(60):
        _, wz = zgv_mp("S", p.kappa, p.omega, mp_exact(al.nu_exact))
        return float(wz * al.c_T / (mpmath.pi * 1.0) * (1 + mpmath.mpf("1e-10")))


ISSUE_34 = [  # (c_L, c_T or a table material, d mm, fd MHz mm or f kHz): what the issue saw
    ((3396.0, 1024.0), 1.0, {"fd_mhz_mm": 1.698000001698}),       # S2 1e-9 above: 1.0e-7 off
    ((3396.0, 1024.0), 1.0, {"fd_mhz_mm": 1.0239582653028525}),   # S1 1e-12 above ZGV: 3e-11
    pytest.param("aluminium", 1.0, {"frequency_khz": 3129.9},     # S1 3.2e-5 below its cut-off
                 marks=pytest.mark.slow),
    pytest.param("aluminium", 1.0, "zgv", marks=pytest.mark.slow),  # the S1 pair, f_ZGV(1+1e-10)
    ((2976.0, 2048.0), 1.0, {"fd_mhz_mm": 2.0480000000000205}),   # S2 1e-14 above: 'S?' rows
]


@pytest.mark.parametrize(("plate", "d_mm", "freq"), ISSUE_34)
def test_issue_34_roots_next_to_cutoffs_and_zgv_points(plate, d_mm, freq):
    mat = material(plate) if isinstance(plate, str) else Material(*plate)
    if freq == "zgv":
        freq = {"frequency_khz": _al_zgv_khz()}
    table = lamb_modes(mat, d_mm, **freq)
    res = table.roots
    assert not res.failures and all(lab[-1].isdigit() for lab in res.label)
    assert res.nu_exact == mat.nu_exact
    omega = float(res.omega[0])
    with mpmath.workdps(60):
        nu, W = mp_exact(mat.nu_exact), mpmath.mpf(omega)
        for lab, k in zip(res.label, res.kappa):
            if lab.startswith("SH"):
                continue
            refs = roots_in_window(lab[0], W, nu, mpmath.mpf(float(k)), 1e-3, count=40)
            ref = min(refs, key=lambda r: abs(r - k))
            assert abs(k / ref - 1) <= RTOL, (lab, k, ref)


def test_the_nearest_float_to_nu_moves_a_root_next_to_a_cut_off():
    # why the exact nu: the case above (S2 1e-9 above its cut-off) at the float nu is 1e-7 off
    mat = Material(3396.0, 1024.0)
    exact = modes_at_frequency(mat.nu_exact, [5.209398760869037], kinds=("S",), zgv=False)
    near = modes_at_frequency(mat.nu, [5.209398760869037], kinds=("S",), zgv=False)
    k_exact, k_float = (r.kappa[r.label.index("S2")] for r in (exact, near))
    assert 5e-8 < abs(k_float / k_exact - 1) < 2e-7


# --- the search ------------------------------------------------------------------------------

def _ratios():
    from dispersion.materials.materials import MATERIALS

    table = sorted(m.c_L / m.c_T for m in MATERIALS.values())
    return st.one_of(st.sampled_from(table), st.floats(RATIO_MIN, RATIO_MAX))


def _distances():
    mag = st.floats(-14.0, -3.0).map(lambda u: 10.0**u)
    return st.builds(lambda m, s: s * m, mag, st.sampled_from([1.0, -1.0]))


def _cutoff_domain(fn, full=False):
    ends = [(2.0, "S", 1, 1e-14),              # nu = 1/3: the double cut-off at pi
            (RATIO_MIN, "A", 2, -1e-14), (RATIO_MAX, "S", 1, 1e-3), (1.8, "A", 3, 1e-14),
            (2.0, "S", 2, -1e-3), (1.8708286933869707, "A", 3, 1e-14)]   # nu = 0.3
    for ex in ends if full else ends[:1]:
        fn = example(*ex)(fn)
    return given(_ratios(), st.sampled_from(["S", "A"]), st.integers(1, CUTOFFS),
                 _distances())(fn)


def _zgv_domain(fn, full=False):
    ends = [(2.0, 0, 1e-14), (1.8708286933869707, 0, 1e-3), (2.5, 0, -1e-14), (3.0, 1, 1e-12)]
    for ex in ends if full else ends[:1]:
        fn = example(*ex)(fn)
    return given(_ratios(), st.integers(0, 5), _distances())(fn)


@FAST_FEW
@_cutoff_domain
def test_roots_next_to_every_cutoff(ratio, kind, n, d):
    _check_cutoff(ratio, kind, n, d)


@pytest.mark.slow
@SLOW
@lambda fn: _cutoff_domain(fn, full=True)
def test_roots_next_to_every_cutoff_slow(ratio, kind, n, d):
    _check_cutoff(ratio, kind, n, d)


@FAST_FEW
@_zgv_domain
def test_roots_next_to_every_zgv_point(ratio, which, d):
    _check_zgv(ratio, which, d)


@pytest.mark.slow
@SLOW
@lambda fn: _zgv_domain(fn, full=True)
def test_roots_next_to_every_zgv_point_slow(ratio, which, d):
    _check_zgv(ratio, which, d)


def test_a_pair_the_zgv_kappa_does_not_split_is_found_at_the_extremum(monkeypatch):
    # 1e-14 above the S1 ZGV frequency of nu = 0.3 the pair is about 2e-7 wide (relative);
    # with the ZGV point's kappa moved 1e-5 off (so that it lies outside the pair), the pair is
    # still found, at the extremum of F located in ball arithmetic, and certified
    import dataclasses

    import dispersion.continuum.frequency as frequency

    nu_q = material("aluminium").nu_exact
    p = next(p for p in zgv_points_below(float(nu_q), 3.0) if p.label == "S1")
    moved = [dataclasses.replace(p, kappa=p.kappa * (1 + 1e-5))]
    monkeypatch.setattr(frequency, "zgv_points_below", lambda nu, top: moved)
    with mpmath.workdps(60):
        nu = mp_exact(nu_q)
        kz, wz = zgv_mp("S", p.kappa, p.omega, nu)
        omega = float(wz * (1 + mpmath.mpf("1e-14")))
        refs = roots_in_window("S", mpmath.mpf(omega), nu, kz, 1e-4)
        assert len(refs) == 2 and all(abs(r / kz - 1) < 1e-6 for r in refs)
        res = frequency.modes_at_frequency(nu_q, [omega], kinds=("S",))
        assert not res.failures
        s1 = sorted(k for lab, k in zip(res.label, res.kappa) if lab == "S1"
                    and abs(k / float(kz) - 1) < 1e-4)
        assert len(s1) == 2
        for k, ref in zip(s1, sorted(refs)):
            assert abs(k / ref - 1) <= RTOL
