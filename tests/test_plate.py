"""Plate patch: symmetry, rigid modes, numeric twin, mirror split, massless DOFs."""
import numpy as np
import pytest
import sympy

from dispersion.errors import InputError
from dispersion.symbolic.patch import check_size
from dispersion.symbolic.plate import (N_MAX, P_MAX, bloch_coefficients, dynamic_stiffness,
                                       mirror_bases, numeric_pencil, plate_patch)

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
    top = plate_patch(mass="singular", contact="top", gamma_s=0)
    both = plate_patch(mass="singular", contact="both", gamma_s=0)
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


@pytest.mark.parametrize("kw", [dict(model="bloch", r=2), dict(model="bloch", r=sympy.Rational(1, 2),
                                                              p=3, n=4, mass="lumped"),
                                dict(model="bloch"), dict()])
def test_x_taylor_is_the_taylor_series_of_x_functions(kw):
    # the series path's coefficients against sympy.series of the closed forms (one definition)
    from dispersion.symbolic.plate import x_functions, x_taylor

    patch = plate_patch(**kw)
    D = 4
    xf = x_functions(patch, kappa)
    taylor = x_taylor(patch, D)
    r = patch.r if patch.r is not None else 1
    for name, f in (("m", xf["m"]), ("s", xf["s"] / kappa), ("d", xf["d"]), ("mx", xf["mx"])):
        ser = sympy.series(f, kappa, 0, 2 * D + 1).removeO()
        for k, (c, e) in enumerate(taylor[name]):
            assert sympy.simplify(ser.coeff(kappa, 2 * k) - c * r**e) == 0, (name, k)


def test_mirror_bases_of_n_and_of_patch_are_the_same_split():
    B = mirror_bases(4)
    P = mirror_bases(plate_patch(n=4))
    for k in ("S", "A"):
        assert np.allclose(B[k], P[k]) and np.allclose(B[k].T @ B[k], np.eye(B[k].shape[1]))
    J = np.zeros((8, 8))  # the mirror y -> -y: u_x(i) -> u_x(n-1-i), u_y(i) -> -u_y(n-1-i)
    for i in range(4):
        J[3 - i, i], J[4 + 3 - i, 4 + i] = 1, -1
    assert np.allclose(J @ B["S"], B["S"]) and np.allclose(J @ B["A"], -B["A"])


def test_cached_matrices_cannot_be_mutated_by_a_caller():
    Y = plate_patch().Y["00"]
    with pytest.raises(TypeError):
        Y[0, 0] = 99
    E = mirror_bases(3, exact=True)["S"]
    with pytest.raises(TypeError):
        E[0, 0] = 5
    from dispersion.symbolic.plate import bloch_coefficients as bc
    bc(2)["00"][0] = 99  # a copy: the next caller still sees the true Gram integral
    assert bc(2)["00"][0] == sympy.Rational(66, 120)


@pytest.mark.parametrize("kw,msg", [
    (dict(model="bloch", r=10**400), r"aspect ratio r must lie in \[1/1000, 1000\]"),
    (dict(model="bloch", r=1e-8), r"aspect ratio r must lie in"),
    (dict(model="bloch", r=1e-200), r"aspect ratio r must lie in"),
    (dict(model="bloch", r=float("nan")), "aspect ratio r must be a finite rational"),
    (dict(model="x-exact", r=-3), r"r applies to the Bloch model only"),
    (dict(mass="singular", gamma_s=sympy.nan), "gamma_s must be a finite rational"),
])
def test_bad_aspect_ratio_and_weight_are_refused(kw, msg):
    with pytest.raises(InputError, match=msg):
        plate_patch(**kw)


def test_size_bounds_are_checked_before_the_build():
    # degree first: p = 100, n = 101 names the degree, not the points
    with pytest.raises(InputError, match=rf"degree p must be an integer in \[1, {P_MAX}\]"):
        plate_patch(p=100, n=101)
    with pytest.raises(InputError, match=rf"control points n must be an integer in \[1, {N_MAX}\]"):
        plate_patch(n=N_MAX + 1)
    assert check_size(P_MAX, P_MAX + 1) == (P_MAX, P_MAX + 1)
