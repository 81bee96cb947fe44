"""Mode shapes: exact shapes are traction-free null vectors; MAC pairing picks true partners."""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.continuum.mode_shapes import _profiles, exact_mode_shape
from dispersion.discretization.discrete_mode_shapes import (
    discrete_mode_shape,
    discrete_modes,
    mac,
    pair_by_shape,
)
from dispersion.symbolic.plate import plate_patch
from dispersion.continuum.numeric_frequency import numeric_frequency_function
from dispersion.continuum.rayleigh_lamb import speed_ratio_squared
from dispersion.continuum.exact_branches import trace_branches

NU = 0.3


@pytest.mark.parametrize("kind", ["S", "A"])
def test_boundary_matrix_determinant_is_minus_f(kind):
    # the traction-free matrix of the module docstring is singular exactly where F = 0
    s = speed_ratio_squared(NU)
    rng = np.random.default_rng(3)
    for kappa, Omega in zip(rng.uniform(0.1, 4, 8), rng.uniform(0.1, 6, 8)):
        P, Q = s * Omega**2 - kappa**2, Omega**2 - kappa**2
        Phi, dPhi, Psi, dPsi = (float(v) for v in _profiles(kind, P, Q, np.array(1.0)))
        det = (2 * kappa * dPhi) * (2 * kappa * dPsi) - (kappa**2 - Q) ** 2 * Psi * Phi
        F = float(numeric_frequency_function(kind, kappa, Omega, NU))
        assert det == pytest.approx(-F, rel=1e-10, abs=1e-12)


def test_exact_shapes_have_their_parity():
    y = np.linspace(-1, 1, 11)
    ex = trace_branches(NU, [0.7], 5.0)
    for label, w in ex.omega.items():
        ux, uy = exact_mode_shape(label[0], 0.7, float(w[0]), NU, y)
        even, odd = (ux, uy) if label[0] == "S" else (uy, ux)
        assert np.allclose(even, even[::-1], atol=1e-12) and np.allclose(odd, -odd[::-1], atol=1e-12)


def test_refined_patch_modes_match_exact_shapes():
    # n = 8 control points through the thickness: MAC of the first four branches -> 1
    patch = plate_patch(n=8, model="x-exact")
    ex = trace_branches(NU, [0.05, 0.5, 1.5], 6.0)
    pb = pair_by_shape(patch, NU, ex)
    for label in ("S0", "A0", "S1", "A1"):
        assert np.all(pb.mac[label] > 0.999), label
    # coarse n = 3 shapes resemble the exact ones less than n = 8 shapes (convergence)
    coarse = pair_by_shape(plate_patch(n=3, model="x-exact"), NU, ex)
    assert np.all(coarse.mac["S1"] < pb.mac["S1"])


def test_pairing_does_not_pair_by_index():
    # issue 10: Figure 2's singular mass (Bloch r = 1/2): its second antisymmetric-like
    # discrete mode is not the exact A1 (index pairing gave ~100 % error as kappa -> 0);
    # by shape it is left unpaired (MAC < 1/2), and S0/A0 keep partners with MAC ~ 1
    patch = plate_patch(model="bloch", r=0.5, mass="singular", gamma_s=0)
    ex = trace_branches(NU, [0.02, 0.1], 4.0)
    pb = pair_by_shape(patch, NU, ex)
    assert np.all(np.isnan(pb.omega["A1"])) and np.all(pb.mac["A1"] < 0.5)
    assert np.all(pb.mac["S0"] > 0.99) and np.all(pb.mac["A0"] > 0.99)
    err = pb.relative_error(ex)
    assert np.all(np.abs(err["A0"]) < 1e-3)


def test_discrete_shape_sampled_from_control_values():
    patch = plate_patch(n=4)
    W, X = discrete_modes(patch, NU, [0.3])
    ux, uy = discrete_mode_shape(patch, X[0, :, 0], np.linspace(-1, 1, 7))
    assert np.sum(ux**2 + uy**2) == pytest.approx(1.0)
    assert mac(np.concatenate([ux, uy]), np.concatenate([ux, uy])) == pytest.approx(1.0)
