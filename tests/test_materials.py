"""Materials (``dispersion.materials.materials``) and the one source of nu (issue 20)."""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dispersion
from dispersion.errors import InputError
from dispersion.materials.materials import MATERIALS, USER_COMBINATIONS, user_material
from dispersion.answers.units import ALUMINIUM, physical_branches
from dispersion.continuum.velocities import exact_velocities

NAMES = ("E", "nu", "rho", "c_L", "c_T")
VALUES = {"E": 70e9, "nu": 0.33, "rho": 2700.0, "c_L": 6320.0, "c_T": 3130.0}


def test_issue_20_nu_mismatch_raises_naming_both():
    kappa = np.linspace(0.0, 2.0, 5)
    ex = dispersion.exact_branches(kappa)           # nu = 0.3, the toolkit default
    v = exact_velocities(ex)
    with pytest.raises(InputError, match=r"nu = 0\.3 .*aluminium \(nu = 0\.337506\)"):
        physical_branches(kappa, ex.omega, v.group, ALUMINIUM, 3.0)
    ok = dispersion.exact_branches(kappa, nu=ALUMINIUM.nu)
    pb = physical_branches(kappa, ok.omega, exact_velocities(ok).group, ALUMINIUM, 3.0)
    assert pb.nu == ALUMINIUM.nu and "nu = 0.3375" in pb.title()


def test_plain_mapping_needs_nu():
    with pytest.raises(InputError, match="carry no nu"):
        physical_branches([1.0], {"S0": np.array([1.6])}, None, ALUMINIUM, 1.0)
    with pytest.raises(InputError, match="cannot be combined"):
        physical_branches([1.0], {"S0": np.array([1.6])}, None, ALUMINIUM, 1.0, nu=0.3)


def test_table_has_the_issue_materials_with_sources():
    for name in ("aluminium", "steel", "stainless-steel", "copper", "brass", "titanium",
                 "glass", "pmma"):
        m = MATERIALS[name]
        assert "CRC Handbook" in m.source and m.rho > 0
        assert 0 < m.nu < 0.5
        # plane-strain identity (c_T/c_L)^2 = (1 - 2 nu) / (2 (1 - nu)) (Achenbach, ch. 1)
        assert (m.c_T / m.c_L) ** 2 == pytest.approx((1 - 2 * m.nu) / (2 * (1 - m.nu)),
                                                      rel=1e-14)


@pytest.mark.parametrize("combo", USER_COMBINATIONS)
def test_accepted_combinations(combo):
    m = user_material(**{k: VALUES[k] for k in combo})
    assert 0 < m.nu < 0.5 and m.source.startswith("user input")


def test_every_other_combination_is_refused():
    # all 32 subsets of the five inputs: a complete search, not a sample
    accepted = [set(c) for c in USER_COMBINATIONS]
    for r in range(len(NAMES) + 1):
        for given_names in itertools.combinations(NAMES, r):
            if set(given_names) in accepted:
                continue
            with pytest.raises(InputError, match="material inputs"):
                user_material(**{k: VALUES[k] for k in given_names})


@settings(max_examples=40, deadline=None)
@given(E=st.floats(1e6, 1e12), nu=st.floats(-0.99, 0.49), rho=st.floats(1.0, 3e4))
def test_moduli_round_trip(E, nu, rho):
    # c_T^2 = E / (2 rho (1 + nu)) and nu from the speeds (Achenbach 1973, ch. 1)
    m = user_material(E=E, nu=nu, rho=rho)
    assert m.nu == pytest.approx(nu, abs=1e-12)
    assert m.rho * m.c_T**2 * 2 * (1 + nu) == pytest.approx(E, rel=1e-12)


def test_moduli_and_speeds_give_the_same_material():
    m = user_material(E=70e9, nu=0.33, rho=2700.0)
    again = user_material(c_L=m.c_L, c_T=m.c_T, rho=m.rho)
    assert again.nu == pytest.approx(0.33, rel=1e-13)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"c_L": 3000.0, "c_T": 3000.0}, "c_L must exceed"),
    ({"c_L": -1.0, "c_T": 3000.0}, "c_L must be"),
    ({"E": 70e9, "nu": 0.5, "rho": 2700.0}, "nu must lie"),
    ({"E": 70e9, "nu": 0.3, "rho": 0.0}, "rho must be"),
    ({"c_L": float("nan"), "c_T": 3000.0}, "c_L must be"),
])
def test_inconsistent_values_are_refused(kwargs, match):
    with pytest.raises(InputError, match=match):
        user_material(**kwargs)


def test_names_resolve_case_and_aliases():
    assert dispersion.material("Stainless Steel") is MATERIALS["stainless-steel"]
    assert dispersion.material("aluminum") is MATERIALS["aluminium"]
    assert list(itertools.islice(MATERIALS, 1)) == ["aluminium"]


def test_branches_keep_their_nu_through_pickling():
    # parallel sweeps pickle results: the nu tag must survive (dispersion.continuum.branch_set)
    import pickle

    ex = dispersion.exact_branches([0.5, 1.0], nu=0.25, omega_max=2.0)
    back = pickle.loads(pickle.dumps(ex))
    assert back.omega.nu == 0.25 and dict(back.omega).keys() == ex.omega.keys()
