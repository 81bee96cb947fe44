"""Modes of layered plates through the thickness (dispersion/continuum/layered/
layered_mode_shapes.py): against the exact isotropic shapes, the free faces, Biot's theorem
and the angular derivative of the frequency."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from mp_layered import group_velocity, roots_at_frequency
from promise_search import SLOW, record

from dispersion.continuum.layered.layered_branches import layered_branches
from dispersion.continuum.layered.layered_mode_shapes import energy_velocities, mode_shape
from dispersion.continuum.layered.layered_modes import layered_modes
from dispersion.continuum.layered.layered_plate import laminate, layered_plate
from dispersion.continuum.mode_shapes import exact_mode_shape
from dispersion.materials.materials import MATERIALS, material, ply

STEEL = material("steel")


@pytest.mark.parametrize("W, label", [(1.0, "A0"), (3.0, "S1")])
def test_one_layer_has_the_exact_rayleigh_lamb_shape(W, label):
    s = mode_shape(layered_plate([(STEEL, 1.0)]), W, label)
    ux, uy = exact_mode_shape(label[0], s.kappa, W, STEEL.nu, s.z)
    ours = np.abs(s.u[[0, 2]])
    exact = np.abs(np.array([ux, uy]))
    assert np.allclose(ours, exact / exact.max(), atol=1e-9)
    assert np.abs(s.u[1]).max() == 0.0            # no SH part in a Lamb mode


CASES = [
    (layered_plate([(STEEL, 0.71), (material("aluminium"), 0.29)]), 2.0, "L1"),
    (laminate("[0/90]s", ply("T800/913"), 0.125, direction=30), 1.0, "A0"),
    pytest.param(laminate("[0/90]s", ply("T800/913"), 0.125, direction=30), 1.0, "S0",
                 marks=pytest.mark.slow),
    pytest.param(laminate("[0/90/45/-45]", ply("T800/913"), 0.125, direction=20), 1.0, "M1",
                 marks=pytest.mark.slow),
]


@pytest.mark.parametrize("plate, W, label", CASES)
def test_energy_flows_at_the_group_velocity_from_free_faces(plate, W, label):
    """Biot: the energy velocity along the wave is d Omega / d kappa (computed from the
    stiffness's derivatives, another route); the tractions vanish on both faces."""
    s = mode_shape(plate, W, label)
    assert abs(s.energy_velocity[0] / s.group - 1) < 1e-10
    scale = np.abs(s.stress).max()
    faces = np.abs(s.stress[[2, 3, 4]][:, [0, -1]])
    assert faces.max() < 1e-9 * scale


@pytest.mark.slow
@pytest.mark.parametrize("direction, W, label", [(30.0, 1.0, "A0"), (30.0, 1.0, "S0"),
                                                 (20.0, 4.0, "S1")])
def test_the_skew_is_the_angular_derivative_of_the_frequency(direction, W, label):
    """Across the wave the energy flows at (1/kappa) dOmega/dtheta at fixed kappa (the
    group velocity's other component), by a 4-point difference over +-2e-3 deg."""
    s = mode_shape(laminate("[0/90]s", ply("T800/913"), 0.125, direction=direction), W, label)
    d = 1e-3
    W_at = []
    for dt in (-2 * d, -d, d, 2 * d):
        b = layered_branches(laminate("[0/90]s", ply("T800/913"), 0.125,
                                      direction=direction + dt), [s.kappa], 1.5 * W)
        W_at.append([w for w, lab in zip(b.omega, b.label) if lab == label][0])
    dW = (-W_at[3] + 8 * W_at[2] - 8 * W_at[1] + W_at[0]) / (12 * math.radians(d))
    assert abs(s.energy_velocity[1] - dW / s.kappa) < 1e-7 * abs(s.group)


ENERGY_BOUND = 1e-10   # the README's promise: c_e along the waves = c_g, relative (c_ref below)


def _energy_case(names, thick, W, samples=300):
    """Every mode of an isotropic bilayer at Omega: the energy velocity along the waves
    (power over energy through the thickness) against -F_k / F_omega of the Thomson-Haskell
    transfer matrix at 40 digits (tests/mp_layered.py) at the 40-digit roots; across the
    waves it vanishes (an isotropic stack)."""
    mats = [material(n) for n in names]
    plate = layered_plate(list(zip(mats, thick)))
    roots = layered_modes(plate, [W])
    assert not roots.failures, roots.failures
    c_e = energy_velocities(plate, roots)
    sc = plate.scaled()
    layers = [(m.c_L, m.c_T, m.rho, t * 1e-3) for m, t in zip(mats, thick)]
    w = W * sc.c_ref / sc.h_m
    k_max = (1.3 * max(roots.kappa) + 0.5) / sc.h_m
    for fam in ("L", "SH"):
        # a stack that is its own mirror image names its Lamb modes S and A, else L
        mine = sorted((k, c[0], c[1]) for k, c, f in zip(roots.kappa, c_e, roots.family)
                      if (f == "SH") == (fam == "SH"))
        for n in (samples, 4 * samples):   # a finer scan where two roots share a step
            ref = roots_at_frequency(layers, [None], w, k_max, fam, n)
            if len(ref) == len(mine):
                break
        assert len(mine) == len(ref), (fam, mine, ref)
        for (_, along, across), k_ref in zip(mine, ref):
            g = float(group_velocity(layers, [None], k_ref, w, fam)) / sc.c_ref
            record("layered-energy-velocity", abs(along - g) / max(1.0, abs(g)), ENERGY_BOUND,
                   names=",".join(names), omega=W, family=fam)
            assert abs(across) <= ENERGY_BOUND * max(1.0, abs(g))


def test_energy_velocity_is_the_40_digit_group_velocity():
    # the bonded bilayer of GEWtool's example: L0, SH0 and L1 (the slow twin searches the rest)
    _energy_case(("steel", "aluminium"), (0.71, 0.29), 1.2, samples=60)


@pytest.mark.slow
@SLOW
@given(a=st.sampled_from(sorted(MATERIALS)), b=st.sampled_from(sorted(MATERIALS)),
       share=st.floats(0.1, 0.9), W=st.floats(0.05, 8.0))
@example(a="steel", b="aluminium", share=0.1, W=0.05)
@example(a="pmma", b="steel", share=0.9, W=8.0)
@example(a="glass", b="epoxy", share=0.6063710957794048, W=7.877284575109775)  # close roots
@example(a="aluminium", b="aluminium", share=0.5, W=1.0)   # symmetric: S and A, not L
def test_energy_velocity_is_the_40_digit_group_velocity_slow(a, b, share, W):
    _energy_case((a, b), (share, 1 - share), W)
