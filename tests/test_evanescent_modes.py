"""The evanescent modes (dispersion/continuum/layered/evanescent_modes.py) against independent
40-digit computations: the textbook Rayleigh-Lamb equations at complex kappa (one isotropic
layer) and the Thomson-Haskell transfer matrix at complex k (two layers), roots by findroot
from a grid of starts, their number by the argument principle, both in mpmath
(tests/mp_complex.py, tests/mp_layered.py); closed forms of the literature (SH, the
Papkovich-Fadle roots of the static strip)."""
from __future__ import annotations

import math

import mpmath
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from mp_complex import count_in_rectangle, is_zero_near, rayleigh_lamb, roots_in_rectangle
from mp_layered import anisotropic_function, dispersion_function
from promise_search import SLOW, record

from dispersion.continuum.layered.evanescent_modes import (DECAY_RANGE, ROOT_RTOL,
                                                          evanescent_modes, im_max_of)
from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.errors import InputError
from dispersion.materials.materials import MATERIALS, Material, material

#: Agreement of a listed root with the 40-digit one: the certified radius, with room for
#: the float polish (the radius is ROOT_RTOL |kappa|).
MATCH = 10 * ROOT_RTOL


def _plate_of_nu(nu):
    ct = 3000.0
    cl = ct * math.sqrt(2 * (1 - nu) / (1 - 2 * nu))
    return layered_plate([(Material(cl, ct, 7800.0, "test", "test"), 1.0)])


def _compare(ours, reference_f, family, R, im_max, case):
    """Our roots of one family (complex, Re >= 0) against the 40-digit roots of the
    reference function(s) in [0, R] x (0, im_max], the reference's list checked complete by
    its own count."""
    mp_roots = []
    im_lo = None
    for f in reference_f:
        found = roots_in_rectangle(f, R, mpmath.mpf("1e-12"), im_max)
        im_lo = min([0.01] + [float(z.imag) / 2 for z in found]
                    + [k.imag / 2 for k in ours]) if im_lo is None else im_lo
        counted = count_in_rectangle(f, R, im_lo, im_max)
        inside = [z for z in found if z.imag > im_lo]
        expected = sum(1 if abs(z.real) < 1e-30 else 2 for z in inside)
        # the grid of starts refines (x2, up to 8x) while the reference's own count finds
        # more roots than its list (titanium/epoxy 0.797, Omega 5.41, 92.7 dB: 2 of 4)
        n_re, n_im = 8, 5
        while counted != expected and n_re < 64:
            n_re, n_im = 2 * n_re, 2 * n_im
            found = roots_in_rectangle(f, R, mpmath.mpf("1e-12"), im_max, n_re, n_im)
            inside = [z for z in found if z.imag > im_lo]
            expected = sum(1 if abs(z.real) < 1e-30 else 2 for z in inside)
        assert counted == expected, (f"{family}: the 40-digit grid search found {expected} "
                                     f"roots (with mirrors), the count says {counted}: {case}")
        mp_roots += found
    assert len(ours) == len(mp_roots), (f"{family}: listed {len(ours)}, 40 digits "
                                        f"{len(mp_roots)}: {[complex(z) for z in mp_roots]} "
                                        f"vs {ours}: {case}")
    worst = 0.0
    for k in ours:
        err = min(abs(complex(z) - k) / abs(k) for z in mp_roots)
        worst = max(worst, err)
        z = min(mp_roots, key=lambda q: abs(complex(q) - k))
        assert (k.real == 0) == (abs(z.real) < 1e-30), f"{family}: kind of {k}: {case}"
    record("evanescent-roots", worst, MATCH, family=family, **case)


def _isotropic_case(nu, Omega, decay, families=("S", "A", "SH")):
    im_max = im_max_of(decay)
    r = evanescent_modes(_plate_of_nu(nu), [Omega], im_max=im_max, families=families)
    case = {"nu": nu, "Omega": Omega, "decay": decay}
    assert r.failures == (), (r.failures, case)
    fams = {"S": ("S",), "A": ("A",), "SH": ("SHS", "SHA")}
    for family in families:
        ours = [complex(k) for k, f in zip(r.kappa, r.family) if f == family]
        R = max(max(r.region[(0, c)] for c in fams[family]), 6.0)
        _compare(ours, [rayleigh_lamb(c, nu, Omega) for c in fams[family]], family, R,
                 im_max, case)


def test_one_isotropic_layer_against_the_40_digit_rayleigh_lamb_equations():
    """Mindlin's nu = 0.31 between the A1 and S1 cut-offs (the slow twin searches the
    domain)."""
    _isotropic_case(0.31, 2.0, 40.0, families=("A",))


@pytest.mark.slow
@SLOW
@given(nu=st.floats(-0.9, 0.49), Omega=st.floats(2e-3, 10.0),
       decay=st.floats(1.0, DECAY_RANGE[1]))
@example(nu=-0.9, Omega=2e-3, decay=DECAY_RANGE[1])
@example(nu=0.49, Omega=10.0, decay=1.0)
@example(nu=0.25, Omega=1.8, decay=60.0)
@example(nu=0.31, Omega=30.0 / 8, decay=DECAY_RANGE[1])
@example(nu=0.0, Omega=2e-3, decay=173.34340880055274)   # a CI draw: S0's pair at +-0.0014
@example(nu=0.0, Omega=2e-3, decay=2.0)   # A0's four roots 0.055 below the count's top edge
def test_one_isotropic_layer_against_the_40_digit_rayleigh_lamb_equations_slow(nu, Omega,
                                                                                 decay):
    _isotropic_case(nu, Omega, decay)


def _bilayer_case(lower, upper, share, Omega, decay):
    im_max = im_max_of(decay)
    plate = layered_plate([(material(lower), share), (material(upper), 1.0 - share)])
    r = evanescent_modes(plate, [Omega], im_max=im_max)
    case = {"lower": lower, "upper": upper, "share": share, "Omega": Omega, "decay": decay}
    assert r.failures == (), (r.failures, case)
    st_ = plate.scaled()
    h = st_.h_m
    w = Omega * st_.c_ref / h
    layers = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in
              ((material(lower), share), (material(upper), 1.0 - share))]
    for family, cls in (("L", "L"), ("SH", "SH")):
        def f(kap, family=family):
            return dispersion_function(layers, [None], kap / h, w, family)
        ours = [complex(k) for k, fam in zip(r.kappa, r.family) if fam == family]
        _compare(ours, [f], family, max(r.region[(0, cls)], 6.0), im_max, case)


def test_bilayer_roots_are_zeros_of_the_40_digit_transfer_matrix():
    """The README's bilayer at 500 kHz: each listed root is a 40-digit zero of the
    Thomson-Haskell function (the slow twin also finds them all and counts them)."""
    plate = layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)])
    st_ = plate.scaled()
    Omega = 2 * math.pi * 500e3 * st_.h_m / st_.c_ref
    r = evanescent_modes(plate, [Omega], im_max=im_max_of(40.0))
    assert r.failures == () and len(r.kappa) >= 2
    layers = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in
              ((material("steel"), 0.71), (material("aluminium"), 0.29))]
    w = Omega * st_.c_ref / st_.h_m
    for k, family in zip(r.kappa, r.family):
        def f(kap, family=family):
            return dispersion_function(layers, [None], kap / st_.h_m, w, family)
        assert is_zero_near(f, complex(k), MATCH), (family, k)


@pytest.mark.slow
@SLOW
@given(lower=st.sampled_from(sorted(MATERIALS)), upper=st.sampled_from(sorted(MATERIALS)),
       share=st.floats(0.1, 0.9), Omega=st.floats(0.05, 6.0), decay=st.floats(1.0, 100.0))
@example(lower="steel", upper="aluminium", share=0.1, Omega=0.05, decay=100.0)
@example(lower="steel", upper="aluminium", share=0.9, Omega=6.0, decay=1.0)
@example(lower="titanium", upper="epoxy", share=0.7966841231493176, Omega=5.4073443418034985,
         decay=92.71726224419108)   # the reference's grid missed two roots (a CI draw)
def test_bilayer_against_the_40_digit_transfer_matrix_slow(lower, upper, share, Omega, decay):
    _bilayer_case(lower, upper, share, Omega, decay)


def test_sh_roots_are_the_closed_form():
    """SH_n of one layer: Q = n pi / 2, kappa = i sqrt((n pi / 2)^2 - Omega^2) below its
    cut-off (Graff 1975, sec. 8.1)."""
    Omega, decay = 1.0, 100.0
    r = evanescent_modes(layered_plate([(material("steel"), 1.0)]), [Omega],
                         im_max=im_max_of(decay), families=("SH",))
    expected = [math.sqrt((n * math.pi / 2) ** 2 - Omega**2) for n in range(1, 8)]
    expected = [x for x in expected if x <= im_max_of(decay)]
    assert list(r.label) == [f"SH-e{n}" for n in range(1, len(expected) + 1)]
    for k, x in zip(r.kappa, expected):
        assert k.real == 0 and abs(k.imag - x) <= 1e-12 * x


def test_static_limit_is_the_papkovich_fadle_strip():
    """At Omega -> 0 the complex roots of one layer tend to kappa = i gamma with
    sin 2 gamma + 2 gamma = 0 (S, extension) and sin 2 gamma - 2 gamma = 0 (A, bending),
    the Papkovich-Fadle eigenvalues of the elastic strip (G. A. Johnson, R. W. Little,
    Quart. Appl. Math. 22 (1965) 335), each 40-digit root found from the asymptotic start
    2 gamma ~ x + i ln(2 x), x = (2n + 3/2) pi (S) and (2n + 5/2) pi (A), n = 0, 1, ..."""
    Omega = 2e-3
    r = evanescent_modes(layered_plate([(material("steel"), 1.0)]), [Omega],
                         im_max=im_max_of(80.0), families=("S", "A"))
    assert r.failures == ()
    with mpmath.workdps(40):
        for family, sign, start in (("S", 1, 1.5), ("A", -1, 2.5)):
            ours = sorted((complex(k) for k, f, kind in zip(r.kappa, r.family, r.kind)
                           if f == family and kind == "complex"), key=lambda q: q.imag)
            assert ours, family
            for n, k in enumerate(ours):
                x = (2 * n + start) * math.pi
                z = mpmath.findroot(lambda z: mpmath.sin(z) + sign * z,
                                    mpmath.mpc(x, math.log(2 * x)))
                gamma = complex(z) / 2
                kap = complex(abs(gamma.imag), abs(gamma.real))   # i gamma, mirrored
                assert abs(k - kap) <= 1e-4 * abs(kap), (family, n, k, kap)


def test_out_of_range_bounds_and_damped_plates_are_refused():
    plate = layered_plate([(material("steel"), 1.0)])
    for bad in (0.0, -1.0, im_max_of(DECAY_RANGE[1]) * 1.001, float("nan")):
        with pytest.raises(InputError, match="im_max"):
            evanescent_modes(plate, [1.0], im_max=bad)
    with pytest.raises(InputError, match="damped"):
        evanescent_modes(layered_plate([(material("steel"), 1.0)], damping=0.01), [1.0],
                         im_max=1.0)
    with pytest.raises(InputError, match="at most"):
        evanescent_modes(plate, [1.0] * 21, im_max=1.0)
    with pytest.raises(InputError, match="estimated work"):   # budget rule 7, before work
        evanescent_modes(plate, [30.0] * 7, im_max=im_max_of(60.0))


def test_the_table_gives_the_decay_in_db_per_metre_and_per_thickness():
    """decay = 20 log10(e) Im k (dB/m) and times d (dB per thickness); k = kappa / h (a
    root set by hand: the table's arithmetic alone)."""
    import numpy as np

    from dispersion.answers.evanescent_mode_table import EvanescentModeTable
    from dispersion.continuum.layered.evanescent_modes import EvanescentRoots

    plate = layered_plate([(material("steel"), 2.0)])
    kap = 0.75 + 1.25j
    roots = EvanescentRoots(plate, np.array([1.0]), 2.0, np.array([0]), ("S-e1",), ("S",),
                            ("complex",), np.array([kap]), (), ("S",), {(0, "S"): 3.0},
                            {(0, "S"): (4, 4)})
    (row,) = EvanescentModeTable(plate, np.array([300.0]), roots, 40.0).rows()
    h_m = 1e-3
    assert row["Re k [rad/mm]"] == 0.75 and row["Im k [1/mm]"] == 1.25
    assert math.isclose(row["decay [dB/m]"], 20 * math.log10(math.e) * 1.25 / h_m,
                        rel_tol=1e-14)
    assert math.isclose(row["decay [dB/thickness]"], row["decay [dB/m]"] * 2 * h_m,
                        rel_tol=1e-14)


@pytest.mark.parametrize("argv, says", [
    (["--evanescent", "--material", "steel", "--thickness", "1", "--decay-max", "0"],
     "--decay-max must lie in (0, 200]"),
    (["--evanescent", "--material", "steel", "--thickness", "1", "--decay-max", "201"],
     "--decay-max must lie in (0, 200]"),
    (["--material", "steel", "--thickness", "1", "--decay-max", "30"],
     "--decay-max applies only with --evanescent"),
    (["--evanescent", "--cl", "5960", "--ct", "3235", "--thickness", "1"], "needs --rho"),
    (["--evanescent", "--layup", "steel:1", "--zgv"], "--zgv"),
    (["--evanescent", "--layup", "steel:1", "--damping", "0.01"], "--damping"),
    (["--evanescent", "--layup", "steel:1", "--angle", "0,30"], "several --angle"),
    (["--evanescent", "--material", "steel", "--thickness", "1", "--mode-shape", "A0"],
     "--mode-shape"),
])
def test_the_command_refuses_in_one_line_before_work(argv, says, capsys):
    from dispersion.cli import main

    assert main(["branches", "--exact", "--frequency", "500", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and says in err, err


@pytest.mark.slow
def test_a_complex_branch_leaves_the_s1_zgv_point_slow():
    """Mindlin's spectrum (nu = 0.31): below the S1 zero-group-velocity frequency the
    backward S2 and forward S1 roots meet and go on as a complex pair, whose real part starts
    at the ZGV point's kappa and whose imaginary part grows as sqrt(Omega_zgv - Omega)
    (R. D. Mindlin 1960, the complex branch of the frequency spectrum; I. Tolstoy, E. Usdin,
    JASA 29 (1957) 37). The ZGV point is the isotropic calculator's."""
    from dispersion.continuum.frequency import zgv_points_below

    nu = 0.31
    (zgv,) = [p for p in zgv_points_below(nu, 3.0) if p.label == "S1"]
    ims = []
    for eps in (1e-4, 4e-4):
        r = evanescent_modes(_plate_of_nu(nu), [zgv.omega * (1 - eps)], im_max=1.0,
                             families=("S",))
        assert r.failures == ()
        near = [complex(k) for k in r.kappa if abs(k.real - zgv.kappa) < 0.05 * zgv.kappa]
        assert len(near) == 1 and 0 < near[0].imag < 0.1, (eps, r.kappa)
        ims.append(near[0].imag)
    assert abs(ims[1] / ims[0] - 2.0) < 0.05    # sqrt(4) = 2: a square-root branch point
    above = evanescent_modes(_plate_of_nu(nu), [zgv.omega * (1 + 1e-4)], im_max=1.0,
                             families=("S",))
    assert above.failures == ()
    assert not [k for k in above.kappa if abs(k.real - zgv.kappa) < 0.05 * zgv.kappa]


@pytest.mark.slow
def test_laminate_against_the_partial_wave_determinant_slow():
    """[0/90]s of T800/913 at 1 MHz, waves along 0 and 30 deg: each listed root is a
    40-digit zero of the free plate's 3x3 determinant of partial-wave transfer matrices
    (python-flint's eigen-solver at 160 bits, tests/mp_layered.py: no Stroh exponential, no
    dynamic stiffness), and that determinant's own count in [-R, R] x (im_lo, im_max] (every
    family at once) is the number of listed roots there with their mirror images."""
    from dispersion.api import layup

    for angle in (0.0, 30.0):
        plate = layup("[0/90]s", ply="T800/913", ply_thickness_mm=0.125, direction=angle)
        sc = plate.scaled()
        Omega = 2 * math.pi * 1e6 * sc.h_m / sc.c_ref
        im_max = im_max_of(40.0)
        r = evanescent_modes(plate, [Omega], im_max=im_max)
        assert r.failures == (), r.failures
        layers = [(C.matrix, layer.solid.rho, layer.thickness_mm * 1e-3)
                  for C, layer in zip(plate.wave_frame_stiffness(), plate.layers)]
        w = Omega * sc.c_ref / sc.h_m

        def f(kap):
            return anisotropic_function(layers, kap / sc.h_m, w)

        for k in r.kappa:
            assert is_zero_near(f, complex(k), MATCH), (angle, k)
        R = min(r.region.values())
        ours = [complex(k) for k in r.kappa if k.real <= R]
        im_lo = min([0.01] + [k.imag / 2 for k in ours])
        expected = sum(1 if k.real == 0 else 2 for k in ours)
        assert count_in_rectangle(f, R, im_lo, im_max, first=120) == expected, angle
