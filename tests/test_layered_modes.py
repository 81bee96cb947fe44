"""Every mode of a layered plate at a frequency (dispersion/continuum/layered/layered_modes.py), against
references computed here and independently: the Rayleigh-Lamb calculator for one layer, the
Thomson-Haskell transfer matrix at 40 digits (tests/mp_layered.py) for isotropic stacks, and
closed forms of the literature for the [0/90]s laminate (classical lamination theory at low
frequency; the thickness resonances of a three-layer stack)."""
from __future__ import annotations

import math

import mpmath
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from mp_layered import anisotropic_function, anisotropic_roots, group_velocity, roots_at_frequency
from promise_search import SLOW, record

from dispersion.continuum.layered.layered_modes import ROOT_RTOL, layered_modes
from dispersion.continuum.layered.layered_plate import SpringInterface, laminate, layered_plate
from dispersion.continuum.frequency import modes_at_frequency
from dispersion.materials.materials import MATERIALS, material, ply

ROOT_BOUND = 1e-12   # the README's promise (relative)
GROUP_BOUND = 1e-10  # c_g, relative to c_ref where below it


def _compare_one_layer(name, W):
    m = material(name)
    ours = layered_modes(layered_plate([(m, 1.0)]), [W])
    ref = modes_at_frequency(m.nu, [W])
    assert not ours.failures and not ref.failures
    a = sorted(zip(ours.label, ours.kappa, ours.group))
    b = sorted(zip(ref.label, ref.kappa, ref.group))
    assert [x[0] for x in a] == [x[0] for x in b]
    err = max(abs(x[1] / y[1] - 1) for x, y in zip(a, b))
    gerr = max(abs(x[2] - y[2]) / max(1.0, abs(y[2])) for x, y in zip(a, b))
    record("layered-one-layer", err, 2 * ROOT_BOUND, material=name, omega=W)
    record("layered-one-layer-group", gerr, GROUP_BOUND, material=name, omega=W)


def test_one_isotropic_layer_has_the_rayleigh_lamb_modes():
    # the backward S1 pair near its ZGV point (Omega 2.7303 at nu 0.29)
    _compare_one_layer("steel", 2.75)


@pytest.mark.slow
@SLOW
@given(name=st.sampled_from(sorted(MATERIALS)), W=st.floats(2e-3, 30.0))
@example(name="steel", W=2e-3)
@example(name="steel", W=30.0)
@example(name="pmma", W=0.05)
def test_one_isotropic_layer_has_the_rayleigh_lamb_modes_slow(name, W):
    _compare_one_layer(name, W)


def _haskell_case(names, thick, springs, W, samples):
    mats = [material(n) for n in names]
    faces = tuple(None if s is None else SpringInterface(*s) for s in springs)
    plate = layered_plate(list(zip(mats, thick)), interfaces=faces)
    ours = layered_modes(plate, [W])
    assert not ours.failures, ours.failures
    sc = plate.scaled()
    layers = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in zip(mats, thick)]
    mp_springs = [None if s is None else (s[0], s[1]) for s in springs]
    w = W * sc.c_ref / sc.h_m
    k_max = (1.3 * max(ours.kappa) + 0.5) / sc.h_m
    for fam in ("L", "SH"):
        # a stack that is its own mirror image (a == b, share 0.5) names its Lamb modes S, A
        mine = sorted((k, g) for k, g, f in zip(ours.kappa, ours.group, ours.family)
                      if (f == "SH") == (fam == "SH"))
        # the reference's sign-change scan steps over roots closer than its spacing (steel on
        # stainless steel: pairs 5e-3 apart): it refines while it finds fewer than ours, up
        # to 64 times; a root of ours it never finds, or one too many, still fails
        n = samples
        ref = roots_at_frequency(layers, mp_springs, w, k_max, fam, n)
        while len(ref) < len(mine) and n < 64 * samples:
            n *= 4
            ref = roots_at_frequency(layers, mp_springs, w, k_max, fam, n)
        assert len(mine) == len(ref), (fam, mine, ref)
        err = max((abs(a / float(b * sc.h_m) - 1) for (a, _), b in zip(mine, ref)), default=0.0)
        record("layered-haskell", err, ROOT_BOUND, names=",".join(names), omega=W, family=fam)
        # c_g relative to c_ref where it is below it (absolute in units of c_ref)
        gerr = max((abs(g - float(group_velocity(layers, mp_springs, b, w, fam)) / sc.c_ref)
                    / max(1.0, abs(g)) for (_, g), b in zip(mine, ref)), default=0.0)
        record("layered-haskell-group", gerr, GROUP_BOUND, names=",".join(names), omega=W,
               family=fam)


def test_bilayer_against_a_40_digit_transfer_matrix():
    # the bonded bilayer of GEWtool's test (0.71 + 0.29 mm), steel on aluminium here, with
    # spring interface as well
    _haskell_case(("steel", "aluminium"), (0.71, 0.29), (None,), 0.9, 60)


@pytest.mark.slow
@SLOW
@given(a=st.sampled_from(sorted(MATERIALS)), b=st.sampled_from(sorted(MATERIALS)),
       share=st.floats(0.1, 0.9), W=st.floats(0.05, 8.0),
       spring=st.one_of(st.none(), st.floats(1e13, 1e16)))
@example(a="steel", b="aluminium", share=0.71, W=4.0, spring=5e14)
@example(a="pmma", b="steel", share=0.5, W=6.0, spring=None)
@example(a="steel", b="stainless-steel", share=0.7729732377262142, W=5.084930709444274,
         spring=1e16)   # close pairs (a CI draw)
def test_bilayer_against_a_40_digit_transfer_matrix_slow(a, b, share, W, spring):
    springs = (None,) if spring is None else ((spring, spring / 2),)
    _haskell_case((a, b), (share, 1 - share), springs, W, 400)


# ------------------------------------------------------------------ the [0/90]s laminate

def _clt(plate):
    """Classical lamination theory (Jones 1999, sec. 4.2): A11, A66, D11 of the reduced
    stiffnesses Q_ij = C_ij - C_i3 C_j3 / C33 (plane stress) and the mass per area."""
    A11 = A66 = D11 = mass = 0.0
    z = -plate.total_thickness_mm * 1e-3 / 2
    for layer, C in zip(plate.layers, plate.wave_frame_stiffness()):
        C = C.array()
        Q11 = C[0, 0] - C[0, 2] ** 2 / C[2, 2]
        t = layer.thickness_mm * 1e-3
        A11 += Q11 * t
        A66 += C[5, 5] * t
        D11 += Q11 * ((z + t) ** 3 - z**3) / 3
        mass += layer.solid.rho * t
        z += t
    return A11, A66, D11, mass


def test_laminate_meets_lamination_theory_at_low_frequency():
    plate = laminate("[0/90]s", ply("T800/913"), 0.125)
    A11, A66, D11, mass = _clt(plate)
    sc = plate.scaled()
    errors = {}
    for W in (0.004, 0.002):
        r = layered_modes(plate, [W])
        assert not r.failures
        rows = dict(zip(r.label, r.kappa))
        w = W * sc.c_ref / sc.h_m
        k = {lab: kap / sc.h_m for lab, kap in rows.items()}
        errors[W] = (abs((w / k["S0"]) / math.sqrt(A11 / mass) - 1),
                     abs((w / k["SH0"]) / math.sqrt(A66 / mass) - 1),
                     abs(w / k["A0"] ** 2 / math.sqrt(D11 / mass) - 1))
    # every error vanishes at the rate of the first neglected term: S0 as Omega^2, A0
    # (Kirchhoff: shear and rotary inertia neglected) as kappa^2 ~ Omega; SH0 is exact (every
    # ply has the same C66 / rho, so u2 uniform through the thickness is a solution)
    rates = [math.log2(e1 / e2) for e1, e2 in zip(errors[0.004], errors[0.002])]
    assert 1.8 < rates[0] < 2.2 and 0.8 < rates[2] < 1.2, rates
    assert errors[0.002][0] < 1e-6
    # SH0 is exact: within the accuracy every root is certified to
    assert errors[0.004][1] < ROOT_RTOL and errors[0.002][1] < ROOT_RTOL


def _thickness_resonance(mu_mid, mu_out, rho, a, b, odd):
    """The closed forms of a symmetric three-layer stack at kappa = 0 (middle layer of half
    thickness a, outer layer b, free faces): even fields
    mu_o q_o tan(q_o b) + mu_m q_m tan(q_m a) = 0, odd fields
    mu_o q_o tan(q_o b) tan(q_m a) = mu_m q_m, q = omega sqrt(rho / mu)."""
    def f(w):
        qm, qo = w * mpmath.sqrt(rho / mu_mid), w * mpmath.sqrt(rho / mu_out)
        if odd:
            return (mu_out * qo * mpmath.sin(qo * b) * mpmath.sin(qm * a)
                    - mu_mid * qm * mpmath.cos(qo * b) * mpmath.cos(qm * a))
        return (mu_out * qo * mpmath.sin(qo * b) * mpmath.cos(qm * a)
                + mu_mid * qm * mpmath.sin(qm * a) * mpmath.cos(qo * b))
    return f


@pytest.mark.parametrize("W", [pytest.param(4.0), pytest.param(12.0, marks=pytest.mark.slow)])
def test_laminate_cutoffs_are_the_closed_form_thickness_resonances(W):
    plate = laminate("[0/90]s", ply("T800/913"), 0.125)
    sc = plate.scaled()
    r = layered_modes(plate, [W], families=("SH",))
    C0, C90 = plate.wave_frame_stiffness()[0].array(), plate.wave_frame_stiffness()[1].array()
    rho = ply("T800/913").rho
    a, b = 0.125e-3, 0.125e-3
    checked = 0
    with mpmath.workdps(40):
        # SH: u2 with C44; even (SH0, SH2, ...) and odd (SH1, SH3, ...)
        for label, w_dimless in r.cutoffs.items():
            if not label.startswith("SH") or w_dimless == 0:
                continue
            n = int(label[2:])
            f = _thickness_resonance(C90[3, 3], C0[3, 3], rho, a, b, odd=n % 2 == 1)
            w = w_dimless * sc.c_ref / sc.h_m
            lo, hi = f(mpmath.mpf(w) * (1 - 1e-12)), f(mpmath.mpf(w) * (1 + 1e-12))
            assert lo * hi < 0, (label, w)
            checked += 1
    assert checked >= 2


def test_modes_come_in_the_classes_of_the_plate():
    from dispersion.continuum.layered.dynamic_stiffness import mode_classes

    lam = laminate("[0/90]s", ply("T800/913"), 0.125)
    assert [c.name for c in mode_classes(lam)] == ["S", "A", "SHS", "SHA"]
    assert [c.name for c in mode_classes(lam.turned(30))] == ["S", "A"]
    bi = layered_plate([(material("steel"), 0.5), (material("copper"), 0.5)])
    assert [c.name for c in mode_classes(bi)] == ["L", "SH"]
    r = layered_modes(bi, [0.5], families=("SH",))
    assert r.label == ("SH0",) and r.family == ("SH",)


def _laminate_case(layup, direction, W, samples):
    plate = laminate(layup, ply("T800/913"), 0.125, direction=direction)
    ours = layered_modes(plate, [W])
    assert not ours.failures, ours.failures
    sc = plate.scaled()
    layers = [(C.matrix, layer.solid.rho, layer.thickness_mm * 1e-3)
              for C, layer in zip(plate.wave_frame_stiffness(), plate.layers)]
    ref = anisotropic_roots(layers, W * sc.c_ref / sc.h_m, (1.3 * max(ours.kappa) + 0.5)
                            / sc.h_m, samples)
    mine = sorted(ours.kappa)   # every family at once: the reference does not split them
    # the reference's scan can step over two close roots ([0/90]s at 13 deg, Omega 6: 9 of
    # 11 at 400 samples, found): it refines, 4x at a time up to 16x, while it counts fewer
    # than our certified count; a root of ours it never finds still fails
    top, more = (1.3 * max(ours.kappa) + 0.5) / sc.h_m, samples
    w = W * sc.c_ref / sc.h_m
    while len(ref) < len(mine) and more < 16 * samples:
        more *= 4
        ref = anisotropic_roots(layers, w, top, more)
    if len(ref) < len(mine):
        # a pair closer than the finest scan ([0/90]s at 21.7 deg, Omega 5: 8 of 10 at 6400
        # samples, the pair 1e-5 apart): each of ours the scan did not find must be a zero of
        # the reference function inside +-ROOT_BOUND of it to be counted: its values there of
        # opposite signs (after the phase of one) and larger than at our root (a zero, not a
        # pole); a root of ours that is not, still fails
        for a in mine:
            if any(abs(a / float(b * sc.h_m) - 1) < 1e-6 for b in ref):
                continue
            with mpmath.workdps(40):
                k0 = mpmath.mpf(a) / sc.h_m
                lo = anisotropic_function(layers, k0 * (1 - mpmath.mpf(ROOT_BOUND)), w)
                hi = anisotropic_function(layers, k0 * (1 + mpmath.mpf(ROOT_BOUND)), w)
                mid = anisotropic_function(layers, k0, w)
                turn = mpmath.conj(hi) / abs(hi)
                assert mpmath.re(lo * turn) < 0 < mpmath.re(hi * turn), (a, lo, hi)
                assert abs(mid) < min(abs(lo), abs(hi)), (a, lo, mid, hi)
                ref.append(k0)
        ref = sorted(ref)
    assert len(mine) == len(ref), (mine, [float(x * sc.h_m) for x in ref])
    err = max(abs(a / float(b * sc.h_m) - 1) for a, b in zip(mine, ref))
    record("layered-laminate", err, ROOT_BOUND, layup=layup, direction=direction, omega=W)


@pytest.mark.slow
@SLOW
@given(layup=st.sampled_from(["[0/90]s", "[0/45/-45/90]", "[0/90]"]),
       direction=st.floats(0, 90), W=st.floats(0.05, 6.0))
@example(layup="[0/90]s", direction=0.0, W=2.0)
@example(layup="[0/90]s", direction=45.0, W=6.0)
@example(layup="[0/90]s", direction=13.0, W=6.0)  # two close roots the scan stepped over
@example(layup="[0/90]s", direction=21.711231891145797, W=5.0)   # closer still (a CI draw)
def test_laminate_against_partial_waves_in_ball_arithmetic_slow(layup, direction, W):
    # an independent route: eigenvalues and eigenvectors of each layer's first-order system
    # (python-flint's eigen-solver at 160 bits), the product of the transfer matrices, the
    # 3x3 determinant of the free faces, scanned and closed at 40 digits
    _laminate_case(layup, direction, W, 400)
