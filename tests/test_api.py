"""The front door (dispersion/__init__.py, dispersion/api.py): cheap import, K/M/K_dyn,
defaults shared with dispersion.defaults, bad input refused."""
from __future__ import annotations

import subprocess
import sys
from importlib.metadata import version

import numpy as np
import pytest
import sympy

import dispersion
from dispersion import defaults
from dispersion.errors import InputError

HEAVY = ("sympy", "numpy", "scipy", "matplotlib", "mpmath", "flint")


def test_import_is_cheap():
    code = ("import sys, dispersion; "
            f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_version_from_package_metadata():
    assert dispersion.__version__ == version("dispersion-iga")
    assert dispersion.DISTRIBUTION == "dispersion-iga"


def test_public_names_and_unknown_attribute():
    for name in dispersion.__all__:
        assert getattr(dispersion, name) is not None
    assert set(dispersion.__all__) <= set(dir(dispersion))
    assert dispersion.mass_rules.mass.CONTACT_SETS  # submodules load on access
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        dispersion.nothing  # noqa: B018


def test_patch_defaults_are_the_toolkits():
    pt = dispersion.patch()
    assert (pt.p, pt.n, pt.model, pt.r, pt.mass, pt.contact, pt.gamma_s) == (
        defaults.P, defaults.N, defaults.MODEL, defaults.R, defaults.MASS, defaults.CONTACT,
        defaults.GAMMA_S)


@pytest.mark.parametrize("mass", ["consistent", "lumped", "singular", "singular-lumped"])
@pytest.mark.parametrize("model", ["bloch", "x-exact"])
def test_k_dyn_is_k_minus_omega2_m(mass, model):
    pt = dispersion.patch(model=model, mass=mass)
    Omega = sympy.Symbol("Omega")
    diff = (pt.K_dyn() - (pt.K() - Omega**2 * pt.M())).applyfunc(sympy.simplify)
    assert diff == sympy.zeros(6, 6)
    assert pt.K().is_symmetric() and pt.M().is_symmetric()


@pytest.mark.parametrize("model", ["bloch", "x-exact"])
def test_rigid_translations_cost_no_energy(model):
    # at kappa = 0 a uniform u_x or u_y (all control points moved alike) is a rigid motion
    K0 = dispersion.patch(model=model).K(kappa=0, nu=sympy.Rational(3, 10))
    ux = sympy.Matrix([1, 1, 1, 0, 0, 0])
    uy = sympy.Matrix([0, 0, 0, 1, 1, 1])
    assert K0 * ux == sympy.zeros(6, 1) and K0 * uy == sympy.zeros(6, 1)


def test_consistent_mass_positive_definite_and_singular_has_massless_rows():
    M = np.array(dispersion.patch().M(kappa=sympy.Rational(1, 3)).evalf(), dtype=float)
    assert np.linalg.eigvalsh(M).min() > 0
    assert dispersion.patch(mass="singular").plate.massless == (2, 5)


def test_exact_series_long_wave_speed():
    # S0 long-wave limit, closed form: plate modulus E / (1 - nu^2) over mu = E / (2 (1 + nu))
    # gives c^2 / c_T^2 = 2 / (1 - nu)
    nu = sympy.Symbol("nu")
    assert sympy.simplify(dispersion.series("S0", 2, exact=True)[2] - 2 / (1 - nu)) == 0


def test_patch_branches_match_the_long_wave_speed():
    kappa = 1e-2
    b = dispersion.patch().branches(np.array([kappa]), nu=0.3)
    assert b.omega["S0"][0] == pytest.approx(np.sqrt(2 / 0.7) * kappa, rel=1e-4)


def test_series_through_a_patch():
    s = dispersion.patch(mass="lumped").series("S0", 4)
    assert sorted(s) == [2, 4]


@pytest.mark.parametrize("call, match", [
    (lambda: dispersion.patch(model="x-exact", r=3), "r applies to the Bloch model only"),
    (lambda: dispersion.series("S0", 4, exact=True, mass="lumped"), "do not apply with exact=True"),
    (lambda: dispersion.patch(r="r").branches([0.1]), "r must be a number > 0"),
    (lambda: dispersion.simulate_ring(t_end=1, wobble=2), "unknown scenario fields"),
    (lambda: dispersion.patch(mass="heavy"), "mass must be one of"),
    (lambda: dispersion.patch(gamma_s=sympy.nan, mass="singular"), "gamma_s"),
])
def test_front_door_refuses(call, match):
    with pytest.raises(InputError, match=match):
        call()


def test_cli_version(capsys):
    # wired by the lead in dispersion/cli/__init__.py (see the safety branch report)
    import dispersion.cli

    assert dispersion.cli.main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"dispersion {version('dispersion-iga')}"
