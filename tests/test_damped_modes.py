"""Damped layered plates (dispersion/continuum/layered/damped_modes.py): complex wavenumbers and the
attenuation, against closed forms and the 40-digit transfer matrix with complex moduli."""
from __future__ import annotations

import cmath
import math
from collections import Counter

import mpmath
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from mp_layered import damped_root, roots_at_frequency
from promise_search import SLOW, record

from dispersion.continuum.layered.damped_modes import ROOT_RTOL, damped_modes, lossless_twin
from dispersion.continuum.layered.layered_modes import layered_modes
from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.materials.materials import MATERIALS, material


def test_sh0_of_a_damped_plate_is_the_closed_form():
    # uniform hysteretic damping: SH0 is u2 uniform through the thickness, k = omega / c_T*
    # with c_T* = c_T sqrt(1 - i eta) (time dependence exp(-i omega t))
    eta = 0.02
    r = damped_modes(layered_plate([(material("steel"), 1.0)], damping=eta), [1.5],
                     families=("SH",))
    assert not r.failures
    k = dict(zip(r.label, r.kappa))["SH0"]
    exact = 1.5 / cmath.sqrt(1 - 1j * eta)
    assert abs(k / exact - 1) < 1e-13
    assert k.imag > 0   # the wave decays along +x


def _case(names, thick, etas, W, samples=300, failures_allowed=False):
    """Every damped root against the 40-digit transfer matrix; with ``failures_allowed`` a
    mode the code lists as a failure (its root moved far from the undamped one, near a
    cut-off at large loss: the README's "or listed") counts as present, never as missing."""
    mats = [material(n) for n in names]
    plate = layered_plate([(m.solid().with_loss(e), t) for m, t, e in zip(mats, thick, etas)])
    ours = damped_modes(plate, [W])
    assert failures_allowed or not ours.failures, ours.failures
    # the failures that stand for a mode without a row (one each): no damped root near the
    # undamped one, or several undamped modes leading to one damped root
    dropped = [why.split()[0].rstrip(":") for _, _, why in ours.failures
               if "no damped root" in why or "lead to one damped root" in why]
    sc = plate.scaled()
    w = W * sc.c_ref / sc.h_m

    def layers(scale):   # loss factors scaled by `scale`/eta_max: the homotopy
        top = max(etas)
        return [(m.c_L * cmath.sqrt(1 - 1j * e * scale / top),
                 m.c_T * cmath.sqrt(1 - 1j * e * scale / top), m.rho, t * 1e-3)
                for m, t, e in zip(mats, thick, etas)]

    undamped = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in zip(mats, thick)]
    plain = layered_modes(lossless_twin(plate), [W])
    springs = [None] * (len(names) - 1)
    for fam in ("L", "SH"):
        mine = [(lab, k) for lab, k in zip(ours.label, ours.kappa)   # a list: a backward
                if lab.startswith("SH") == (fam == "SH")]                # pair shares a name
        ref0 = roots_at_frequency(undamped, springs, w,
                                  (1.3 * max(plain.kappa) + 0.5) / sc.h_m, fam, samples)
        named = [lab for lab in dropped if lab.startswith("SH") == (fam == "SH")]
        assert len(ref0) == len(mine) + len(named), (fam, mine, named, ref0)
        for lab, k in mine:
            # the 40-digit root of the undamped plate with this name (of a backward pair, the
            # one nearest the damped root), continued as the loss grows (the reference's own
            # homotopy)
            near = [kap for name, kap in zip(plain.label, plain.kappa) if name == lab]
            kap0 = min(near, key=lambda x: abs(x - k.real))
            start = min(ref0, key=lambda x: abs(float(x) * sc.h_m - kap0))
            refk = complex(damped_root(layers, springs, w, start, fam, max(etas))) * sc.h_m
            record("damped-roots", abs(k / refk - 1), ROOT_RTOL, names=",".join(names),
                   omega=W, family=fam, mode=lab)


@pytest.mark.slow
def test_damped_plate_against_the_40_digit_transfer_matrix():
    # a lossy polymer on steel (loss factors 0.05 and 0.002), two Lamb modes 3 % apart
    # (L0, L1 at Omega 1.2): complex moduli in both routes, names by continuation in both
    _case(("steel", "pmma"), (0.6, 0.4), (0.002, 0.05), 1.2)


@pytest.mark.slow
@SLOW
@given(a=st.sampled_from(sorted(MATERIALS)), b=st.sampled_from(sorted(MATERIALS)),
       share=st.floats(0.2, 0.8), W=st.floats(0.1, 5.0), eta=st.floats(1e-4, 0.1))
@example(a="steel", b="pmma", share=0.6, W=4.0, eta=0.1)
@example(a="aluminium", b="aluminium", share=0.8, W=3.0, eta=0.0625)   # L3 listed (CI draw)
def test_damped_plate_against_the_40_digit_transfer_matrix_slow(a, b, share, W, eta):
    _case((a, b), (share, 1 - share), (eta, eta / 3), W, 300, failures_allowed=True)


def test_attenuation_in_db_per_metre_is_twenty_log10_e_times_im_k(capsys):
    from dispersion.cli import main

    assert main(["branches", "--exact", "--layup", "steel:1", "--damping", "0.01",
                 "--frequency", "500", "--modes", "SH", "--format", "json"]) == 0
    import json

    row = json.loads(capsys.readouterr().out)["rows"][0]
    h = 0.5e-3
    k = 2 * math.pi * 500e3 * h / material("steel").c_T / cmath.sqrt(1 - 0.01j)
    assert row["mode"] == "SH0"
    assert abs(row["attenuation [dB/m]"] / (20 / math.log(10) * k.imag / h) - 1) < 1e-12
    assert "c_g [m/s]" not in row


# ------------------------------------------- one damped layer: the textbook equations, 40 digits

def _rayleigh_lamb(kind, k, W, r, s):
    """The Rayleigh-Lamb function of a plate of half thickness 1 at Omega = omega h / c_T,
    speeds c_L = r sqrt(s), c_T = sqrt(s) in units of c_T (s = 1 - i eta: hysteretic complex
    moduli; Graff 1975, eq. 8.1.25-26): symmetric (q^2 - k^2)^2 cos p sin(q)/q
    + 4 k^2 p sin p cos q, antisymmetric (q^2 - k^2)^2 sin(p)/p cos q + 4 k^2 q cos p sin q
    (divided by q, resp. p: entire in k, no branch of the square roots to choose)."""
    p = mpmath.sqrt(W**2 / (r**2 * s) - k**2)
    q = mpmath.sqrt(W**2 / s - k**2)
    sinc = (lambda x: mpmath.sin(x) / x if x != 0 else mpmath.mpf(1))
    if kind == "S":
        return (q**2 - k**2) ** 2 * mpmath.cos(p) * sinc(q) + 4 * k**2 * p * mpmath.sin(p) * mpmath.cos(q)
    return (q**2 - k**2) ** 2 * sinc(p) * mpmath.cos(q) + 4 * k**2 * q * mpmath.cos(p) * mpmath.sin(q)


def _one_layer_reference(name, eta, W, steps=8):
    """Every mode of one layer of ``name`` with loss factor ``eta`` at ``W`` from references
    outside the layered code: the undamped modes (names and starts) from the isotropic
    calculator (certified against mpmath, tests/test_frequency_promises.py), each Lamb root
    continued in the loss factor by the secant method on the Rayleigh-Lamb function at 40
    digits; SH_n in closed form, kappa^2 = Omega^2 / (1 - i eta) - (n pi / 2)^2."""
    from dispersion.continuum.frequency import modes_at_frequency

    m = material(name)
    r = mpmath.mpf(m.c_L) / mpmath.mpf(m.c_T)
    plain = modes_at_frequency(m.nu_exact, [W])
    assert not plain.failures
    out = {}
    with mpmath.workdps(40):
        for lab, k0 in zip(plain.label, plain.kappa):
            if lab.startswith("SH"):
                n = int(lab[2:])
                out[lab] = complex(mpmath.sqrt(mpmath.mpf(W) ** 2 / (1 - 1j * mpmath.mpf(eta))
                                               - (n * mpmath.pi / 2) ** 2))
                continue
            k = mpmath.mpf(k0)
            for j in range(steps + 1):
                s = 1 - 1j * mpmath.mpf(eta) * j / steps
                f = (lambda x, s=s: _rayleigh_lamb(lab[0], x, mpmath.mpf(W), r, s))
                k = mpmath.findroot(f, (k, k * (1 + mpmath.mpf(10) ** -8)), solver="secant",
                                    tol=mpmath.mpf(10) ** -70, maxsteps=200, verify=False)
            assert abs(f(k)) < mpmath.mpf(10) ** -25 * max(1, abs(k)) ** 4
            out.setdefault(lab, []).append(complex(k))
    return {lab: v for lab, v in out.items()}


def _one_layer_case(name, eta, W, failures_allowed=True):
    """Every row is the reference's root of its name to ROOT_RTOL; a mode the code could not
    certify (a root that moved far from the undamped one: near a cut-off, at large loss) is
    listed by name among the failures, as the README promises, never silently missing."""
    plate = layered_plate([(material(name), 1.0)], damping=eta)
    ours = damped_modes(plate, [W])
    assert failures_allowed or not ours.failures, ours.failures
    ref = _one_layer_reference(name, eta, W)
    mine = {}
    for lab, k in zip(ours.label, ours.kappa):
        mine.setdefault(lab, []).append(complex(k))
    listed = Counter(why.split(":")[0] for _, _, why in ours.failures)
    count = Counter({lab: len(v) if isinstance(v, list) else 1 for lab, v in ref.items()})
    assert Counter({lab: len(v) for lab, v in mine.items()}) + listed == count, \
        (mine, listed, ref)
    for lab, ks in mine.items():
        want = ref[lab] if isinstance(ref[lab], list) else [ref[lab]]
        for k in ks:   # the reference root of its name nearest to it (two: a backward pair)
            k_ref = min(want, key=lambda z: abs(z - k))
            record("damped-one-layer", abs(k / k_ref - 1), ROOT_RTOL, material=name, eta=eta,
                   omega=W, mode=lab)


def test_one_damped_layer_is_the_rayleigh_lamb_equation_at_complex_speeds():
    # 1 mm steel, eta 0.01 (the README's plate) at 3 MHz, 20 kHz above the S1 cut-off:
    # S0, S1, A0, A1, SH0, SH1 (the README's 500 kHz: an example of the slow twin)
    _one_layer_case("steel", 0.01, 2 * math.pi * 3000e3 * 0.5e-3 / 3235.0,
                    failures_allowed=False)


@pytest.mark.slow
@SLOW
@given(name=st.sampled_from(sorted(MATERIALS)), eta=st.floats(1e-4, 0.1),
       W=st.one_of(st.floats(2e-3, 0.1), st.floats(0.1, 5.0)))
@example(name="steel", eta=1e-4, W=0.1)
@example(name="steel", eta=1e-4, W=2e-3)   # the tables' lowest Omega (OMEGA_RANGE)
@example(name="pmma", eta=0.1, W=2e-3)
@example(name="pmma", eta=0.1, W=5.0)
@example(name="steel", eta=0.1, W=2.75)   # the backward S1 pair of the undamped plate
@example(name="steel", eta=0.01, W=2 * math.pi * 500e3 * 0.5e-3 / 3235.0)   # the README's
def test_one_damped_layer_is_the_rayleigh_lamb_equation_at_complex_speeds_slow(name, eta, W):
    _one_layer_case(name, eta, W)


@pytest.mark.slow
def test_a_root_the_float_secant_leaves_short_is_refined_and_certified():
    # 1 mm steel, eta 1e-4, 2.1 kHz: S0 (kappa 1.2e-3) was listed "not certified (winding 0)"
    # before the ball-value refinement; now every root is certified and is the reference's
    _one_layer_case("steel", 1e-4, 2 * math.pi * 2.1e3 * 0.5e-3 / 3235.0, failures_allowed=False)
