"""Damped layered plates (dispersion/continuum/layered/damped_modes.py): complex wavenumbers and the
attenuation, against closed forms and the 40-digit transfer matrix with complex moduli."""
from __future__ import annotations

import cmath
import math

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


def _case(names, thick, etas, W, samples=300):
    mats = [material(n) for n in names]
    plate = layered_plate([(m.solid().with_loss(e), t) for m, t, e in zip(mats, thick, etas)])
    ours = damped_modes(plate, [W])
    assert not ours.failures, ours.failures
    sc = plate.scaled()
    w = W * sc.c_ref / sc.h_m

    def layers(scale):   # loss factors scaled by `scale`/eta_max: the homotopy
        top = max(etas)
        return [(m.c_L * cmath.sqrt(1 - 1j * e * scale / top),
                 m.c_T * cmath.sqrt(1 - 1j * e * scale / top), m.rho, t * 1e-3)
                for m, t, e in zip(mats, thick, etas)]

    undamped = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in zip(mats, thick)]
    plain = layered_modes(lossless_twin(plate), [W])
    start_of = dict(zip(plain.label, plain.kappa))
    springs = [None] * (len(names) - 1)
    for fam in ("L", "SH"):
        mine = {lab: k for lab, k in zip(ours.label, ours.kappa)
                if lab.startswith("SH") == (fam == "SH")}
        ref0 = roots_at_frequency(undamped, springs, w,
                                  (1.3 * max(start_of.values()) + 0.5) / sc.h_m, fam, samples)
        assert len(ref0) == len(mine), (fam, mine, ref0)
        for lab, k in mine.items():
            # the 40-digit root of the undamped plate with this name, continued as the loss
            # grows (the reference's own homotopy)
            start = min(ref0, key=lambda x: abs(float(x) * sc.h_m - start_of[lab]))
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
def test_damped_plate_against_the_40_digit_transfer_matrix_slow(a, b, share, W, eta):
    _case((a, b), (share, 1 - share), (eta, eta / 3), W, 300)


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
