"""Plate patch: symmetry, rigid modes, numeric twin, mirror split, massless DOFs."""
import numpy as np
import pytest
import sympy

from dispersion.errors import InputError
from dispersion.plate import (bloch_coefficients, dynamic_stiffness, mirror_bases,
                              numeric_pencil, plate_patch)

kappa, Omega = sympy.symbols("kappa Omega")


def test_quadratic_bloch_stencils_match_literature():
    # quadratic B-spline stencils: mass (1, 26, 66, 26, 1)/120 and stiffness
    # (-1, -2, 6, -2, -1)/6 (Cottrell, Reali, Bazilevs, Hughes 2006, sec. 3)
    c = bloch_coefficients(2)
    assert [c["00"][L] * 120 for L in range(-2, 3)] == [1, 26, 66, 26, 1]
    assert [c["11"][L] * 6 for L in range(-2, 3)] == [-1, -2, 6, -2, -1]


@pytest.mark.parametrize("kw", [dict(), dict(model="bloch", r=2), dict(p=3, n=5, mass="lumped"),
                                dict(model="bloch", r=sympy.Rational(1, 2), mass="singular")])
def test_numeric_pencil_matches_exact_dynamic_stiffness(kw):
    patch = plate_patch(**kw)
    Kd = dynamic_stiffness(patch, sympy.Rational(3, 10), sympy.Rational(7, 10), sympy.Rational(1, 4))
    K, M = numeric_pencil(patch, 0.25, [0.3])
    assert np.allclose(np.array(Kd, dtype=float), K[0] - 0.49 * M[0], atol=1e-13)
    assert np.allclose(K, K.transpose(0, 2, 1)) and np.allclose(M, M.transpose(0, 2, 1))


def test_rigid_translations_are_the_only_zero_modes_at_kappa_zero():
    K, _ = numeric_pencil(plate_patch(n=4), 0.3, [0.0])
    eig = np.linalg.eigvalsh(K[0])
    assert np.sum(np.abs(eig) < 1e-12) == 2 and eig.min() > -1e-12
    ones = np.ones(4)
    assert np.allclose(K[0] @ np.r_[ones, 0 * ones], 0) and np.allclose(K[0] @ np.r_[0 * ones, ones], 0)


def test_stiffness_positive_semidefinite_over_brillouin_zone():
    K, M = numeric_pencil(plate_patch(model="bloch", r=2), 0.3, np.linspace(0, np.pi / 2, 50))
    assert np.linalg.eigvalsh(K).min() > -1e-12 and np.linalg.eigvalsh(M).min() > 0


def test_mirror_bases_split_the_pencil():
    patch = plate_patch(model="bloch", r=2, mass="lumped")
    B = mirror_bases(patch)
    K, M = numeric_pencil(patch, 0.3, [0.4])
    assert np.allclose(B["S"].T @ K[0] @ B["A"], 0) and np.allclose(B["S"].T @ M[0] @ B["A"], 0)
    assert B["S"].shape == (6, 3) and B["A"].shape == (6, 3)


def test_one_sided_singular_mass_breaks_the_mirror_symmetry():
    top = plate_patch(mass="singular", contact="top")
    both = plate_patch(mass="singular", contact="both")
    assert mirror_bases(top) is None and top.massless == (2, 5)
    assert mirror_bases(both) is not None and both.massless == (0, 2, 3, 5)


def test_bad_input():
    for kw, msg in [(dict(n=2), "n must be >= p"), (dict(p=0), "degree p"),
                    (dict(model="bloch", r=0), "aspect ratio r"), (dict(model="fem"), "model"),
                    (dict(mass="heavy"), "mass must be")]:
        with pytest.raises(InputError, match=msg):
            plate_patch(**kw)
    with pytest.raises(InputError, match="nu must lie"):
        numeric_pencil(plate_patch(), 0.5, [0.1])
