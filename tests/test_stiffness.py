"""The 6x6 elastic law (dispersion/materials/stiffness.py): rotation, factories, validity."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.materials.stiffness import (isotropic, orthotropic, transversely_isotropic,
                                            voigt)
from dispersion.materials.materials import ply

_PLY = transversely_isotropic(E1=142e9, E2=10.3e9, G12=7.2e9, nu12=0.27, nu23=0.54)


@settings(max_examples=25, deadline=None, derandomize=True)
@given(angle=st.floats(-360, 360))
def test_rotation_keeps_the_invariants_and_turns_back(angle):
    C = _PLY.array()
    R = _PLY.rotated(angle)
    # the trace of the Kelvin form and its eigenvalues are invariants of a rotation
    w = np.array([1, 1, 1, 2 ** 0.5, 2 ** 0.5, 2 ** 0.5])
    eig = np.linalg.eigvalsh(C * w[:, None] * w)
    eig_r = np.linalg.eigvalsh(R.array() * w[:, None] * w)
    assert np.allclose(eig, eig_r, rtol=1e-12)
    assert np.allclose(R.rotated(-angle).array(), C, rtol=0, atol=1e-12 * C.max())
    # a rotation about the normal keeps x3 -> -x3 symmetry (monoclinic about the plane)
    assert R.mirror_normal()


def test_quarter_turn_swaps_the_in_plane_axes():
    R = _PLY.rotated(90).array()
    C = _PLY.array()
    assert np.isclose(R[0, 0], C[1, 1]) and np.isclose(R[1, 1], C[0, 0])
    assert np.isclose(R[3, 3], C[4, 4]) and np.isclose(R[4, 4], C[3, 3])
    assert _PLY.rotated(90).mirror_transverse() and not _PLY.rotated(30).mirror_transverse()


def test_isotropic_law_is_unchanged_by_any_rotation_and_agrees_with_engineering_constants():
    iso = isotropic(E=200e9, nu=0.25)
    assert np.allclose(iso.rotated(37).array(), iso.array(), atol=1e-3)
    lam, mu = iso.lame()
    assert np.isclose(mu, 80e9) and np.isclose(lam, 80e9)
    assert iso.is_isotropic() and not _PLY.is_isotropic()


def test_transversely_isotropic_constants_invert_the_compliance():
    S = np.linalg.inv(_PLY.array())
    assert np.isclose(1 / S[0, 0], 142e9) and np.isclose(1 / S[1, 1], 10.3e9)
    assert np.isclose(-S[0, 1] / S[0, 0], 0.27) and np.isclose(1 / S[5, 5], 7.2e9)
    # the table's ply: C44 = (C22 - C23) / 2, transversely isotropic about the fibres
    C = ply("T800/913").stiffness.array()
    assert np.isclose(C[3, 3], (C[1, 1] - C[1, 2]) / 2)


def test_damping_makes_energy_leave_and_bad_laws_are_refused():
    d = _PLY.with_loss(0.02)
    assert not d.lossless and np.allclose(d.array(), _PLY.array() * (1 - 0.02j))
    with pytest.raises(InputError, match="lose energy"):
        voigt(_PLY.array() * (1 + 0.02j))
    with pytest.raises(InputError, match="positive definite"):
        orthotropic(1, 2, 0, 1, 0, 1, 1, 1, 1)
    with pytest.raises(InputError, match="symmetric"):
        C = _PLY.array().copy()
        C[0, 1] *= 2
        voigt(C)
    with pytest.raises(InputError, match="eta must lie"):
        _PLY.with_loss(1.5)


def test_plane_strain_law_is_the_x1_x3_block():
    law = _PLY.plane_strain_law()
    C = _PLY.array()
    m = law.float_moduli()
    assert np.isclose(m["D11"], C[0, 0] / C[4, 4]) and np.isclose(m["D22"], C[2, 2] / C[4, 4])
    with pytest.raises(InputError):
        _PLY.rotated(30).plane_strain_law()


def test_the_gfrp_ply_and_epoxy_give_back_their_sources_constants():
    """The table's GFRP ply is built from engineering constants; its compliance must give them
    back (E1 = 1/S11, E2 = 1/S22, G12 = 1/S66, nu12 = -S12 E1, nu23 = -S23 E2), and epoxy's
    speeds must give the source's Poisson ratio 0.392 and modulus 3.941 GPa."""
    from dispersion.materials.materials import material, ply

    S = np.linalg.inv(ply("TVR380/M12R").stiffness.array())
    E1, E2 = 1 / S[0, 0], 1 / S[1, 1]
    assert np.allclose([E1, E2, 1 / S[5, 5], -S[0, 1] * E1, -S[1, 2] * E2],
                       [46.43e9, 14.92e9, 5.233e9, 0.27, 0.3], rtol=1e-12)
    epoxy = material("epoxy")
    E = 2 * epoxy.rho * epoxy.c_T**2 * (1 + epoxy.nu)
    assert abs(epoxy.nu - 0.392) < 5e-4 and abs(E / 3.941e9 - 1) < 5e-4
