"""The elastic law travels with the plate patch (issue 28 item 6; docs/promises.md).

Promise: the discrete plate of an orthotropic law (:class:`Orthotropic`, K from its plane-strain
D) has the frequencies of its own pencil K - Omega^2 M to RTOL (or lists the kappa as a
failure), over the law's whole domain (C11, C22, C66 > 0, C12^2 < C11 C22, ratios to C66 in
[1e-6, 1e6]), every mass rule's kind (consistent, lumped, singular), both models. The
reference is independent: the pencil assembled in mpmath at 50 digits from the constants
themselves (tests/mp_pencil.py: no characteristic polynomial, no float eigen-solver).
And an orthotropic law with isotropic constants is the isotropic plate: the same D exactly,
the same branches.
"""
from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import example, given, settings
from hypothesis import strategies as st
from mp_pencil import mp_frequencies

from dispersion.errors import InputError
from dispersion.patch_model import PatchModel
from dispersion.materials.elastic_law import ElasticLaw, Isotropic, Orthotropic
from dispersion.symbolic.patch import Patch
from dispersion.symbolic.plate import plate_patch
from dispersion.symbolic.power_balance import discrete_series
from dispersion.discretization.discrete_branches import RTOL, discrete_branches

#: Poisson's ratio over its whole open range (-1, 1/2), as three-digit decimals: what a float
#: route reads is then the same rational (ends as explicit examples).
NU = st.integers(-999, 499).map(lambda k: sympy.Rational(k, 1000))
#: log10 of a stiffness over C66, across the law's range [1e-6, 1e6].
LOG_RATIO = st.floats(-6, 6, allow_nan=False)


def _isotropic_constants(nu, mu):
    """C11 = C22 = lambda + 2 mu, C12 = lambda, C66 = mu of Poisson's ratio ``nu`` (plane
    strain, shear modulus ``mu``): written out here, not taken from the code."""
    lam = 2 * mu * nu / (1 - 2 * nu)
    return lam + 2 * mu, lam + 2 * mu, lam, mu


@settings(max_examples=30, deadline=None)
@given(nu=NU, mu=st.fractions(Fraction(1, 1000), 1000))
@example(nu=sympy.Rational(-999, 1000), mu=Fraction(1))
@example(nu=sympy.Rational(499, 1000), mu=Fraction(1000))
@example(nu=sympy.Rational(0), mu=Fraction(1, 1000))
def test_isotropic_constants_give_the_isotropic_D(nu, mu):
    ortho = Orthotropic(*_isotropic_constants(nu, sympy.Rational(mu)))
    assert ortho.moduli() == Isotropic(nu).moduli()
    assert ortho.rational_moduli() == Isotropic(nu).rational_moduli()


@settings(max_examples=6, deadline=None)
@given(nu=NU, model=st.sampled_from(["x-exact", "bloch"]),
       mass=st.sampled_from(["consistent", "lumped", "singular"]))
@example(nu=sympy.Rational(-999, 1000), model="bloch", mass="singular")
@example(nu=sympy.Rational(499, 1000), model="x-exact", mass="consistent")
def test_isotropic_constants_give_the_isotropic_branches(nu, model, mass):
    kappa = [0.0, 1e-4, 0.3, 1.1]
    iso = discrete_branches(plate_patch(model=model, mass=mass), float(nu), kappa)
    ortho = discrete_branches(
        plate_patch(model=model, mass=mass, law=Orthotropic(*_isotropic_constants(nu, 1))),
        None, kappa)
    assert sorted(iso.omega) == sorted(ortho.omega)
    for label in iso.omega:
        np.testing.assert_allclose(ortho.omega[label], iso.omega[label], rtol=1e-11,
                                   atol=1e-300)


def _law(logs, c12_share):
    """An orthotropic law from log10 C11/C66, C22/C66 and C12 as a share of sqrt(C11 C22)."""
    c11, c22 = (Fraction(10.0**x).limit_denominator(10**9) for x in logs)
    c11, c22 = (max(c, Fraction(1, 10**6)) for c in (c11, c22))
    bound = Fraction(float(np.sqrt(float(c11 * c22)))).limit_denominator(10**9)
    c12 = Fraction(c12_share).limit_denominator(1000) * bound
    if c12 and not Fraction(1, 10**6) <= abs(c12) <= 10**6:
        c12 = Fraction(0)
    return Orthotropic(c11, c22, c12, 1)


def _check_against_mpmath(law, model, mass, kappa):
    patch = plate_patch(model=model, mass=mass, law=law)
    br = discrete_branches(patch, None, [kappa])
    if br.failures:   # listed (never silent): allowed by the promise
        return
    got = sorted(float(w[0]) for w in br.omega.values() if np.isfinite(w[0]))
    with mpmath.workdps(50):
        ref = [float(w) for w in mp_frequencies(patch, law, kappa, dps=50)]
    assert len(got) == len(ref), (law, model, mass, kappa, got, ref)
    top = max(ref)
    for g, r in zip(got, ref):
        # each root to RTOL of itself, or of the largest where it cancels below it
        assert abs(g - r) <= 10 * RTOL * max(r, 1e-8 * top) + 1e-300, (law, model, mass,
                                                                         kappa, g, r)


@settings(max_examples=8, deadline=None)
@given(logs=st.tuples(st.floats(-2, 2), st.floats(-2, 2)), c12_share=st.floats(-0.95, 0.95),
       model=st.sampled_from(["x-exact", "bloch"]),
       mass=st.sampled_from(["consistent", "lumped", "singular"]),
       kappa=st.floats(0.0, 3.0))
@example(logs=(0.0, 0.0), c12_share=0.0, model="bloch", mass="consistent", kappa=0.0)
@example(logs=(1.0, -1.0), c12_share=0.95, model="x-exact", mass="singular", kappa=3.0)
def test_orthotropic_branches_against_mpmath(logs, c12_share, model, mass, kappa):
    _check_against_mpmath(_law(logs, c12_share), model, mass, kappa)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(logs=st.tuples(LOG_RATIO, LOG_RATIO), c12_share=st.floats(-0.999, 0.999),
       model=st.sampled_from(["x-exact", "bloch"]),
       mass=st.sampled_from(["consistent", "lumped", "singular"]),
       kappa=st.floats(0.0, 6.0))
@example(logs=(-6.0, -6.0), c12_share=0.0, model="bloch", mass="lumped", kappa=1.5)
@example(logs=(6.0, 6.0), c12_share=0.999, model="x-exact", mass="consistent", kappa=6.0)
@example(logs=(6.0, -6.0), c12_share=-0.999, model="bloch", mass="singular", kappa=0.0)
def test_orthotropic_branches_against_mpmath_whole_domain(logs, c12_share, model, mass,
                                                         kappa):
    _check_against_mpmath(_law(logs, c12_share), model, mass, kappa)


def test_law_travels_with_the_patch():
    law = Orthotropic(sympy.Rational(1657, 10), sympy.Rational(1657, 10),
                      sympy.Rational(639, 10), sympy.Rational(796, 10))
    spec = Patch(law=law)
    assert spec.law == law and spec.nu is None and not spec.isotropic
    assert Patch.from_dict(spec.as_dict()) == spec
    assert ElasticLaw.from_dict(law.as_dict()) == law
    assert "orthotropic" in spec.title() and "C66 = 398/5" in " ".join(spec.header_lines())
    assert plate_patch(spec).law == law
    # the isotropic plate as before: nu names its law; the dict has no law key
    assert Patch(nu=0.3).law == Isotropic(sympy.Rational(3, 10))
    assert "law" not in Patch(nu=0.3).as_dict()
    # the numeric front door takes the patch's law
    br = PatchModel(spec).branches([0.5])
    direct = discrete_branches(plate_patch(spec), None, [0.5])
    assert {k: v.tolist() for k, v in br.omega.items()} == \
        {k: v.tolist() for k, v in direct.omega.items()}


@pytest.mark.parametrize("call, words", [
    (lambda: Patch(nu=0.3, law=Orthotropic(3, 2, 1, 1)), "give nu or law"),
    (lambda: Orthotropic(1, 1, 2, 1), "positive definite"),
    (lambda: Orthotropic(1, 1, 0, 0), "C66 must be > 0"),
    (lambda: Orthotropic(10**7, 1, 0, 1), "[1e-6, 1e6]"),
    (lambda: discrete_branches(plate_patch(law=Orthotropic(3, 2, 1, 1)), 0.3, [0.5]),
     "nu applies to an isotropic plate"),
    (lambda: discrete_branches(plate_patch(), None, [0.5]), "give the patch a number"),
    (lambda: Orthotropic(3, 2, 1, 1).poisson_ratio("exact Rayleigh-Lamb branches"),
     "need an isotropic plate"),
    (lambda: ElasticLaw.from_dict({"kind": "layered"}), "law kind must be one of"),
    (lambda: Patch(law=0.3), "law must be an ElasticLaw"),
])
def test_bad_laws_are_refused_in_words(call, words):
    with pytest.raises(InputError, match=None) as info:
        call()
    assert words in str(info.value)


@settings(max_examples=6, deadline=None)
@given(c11=st.fractions(Fraction(1, 100), 100, max_denominator=100),
       c22=st.fractions(Fraction(1, 100), 100, max_denominator=100),
       share=st.fractions(Fraction(-99, 100), Fraction(99, 100), max_denominator=100),
       model=st.sampled_from(["x-exact", "bloch"]),
       mass=st.sampled_from(["consistent", "lumped", "singular"]))
@example(c11=Fraction(100), c22=Fraction(1, 100), share=Fraction(-99, 100), model="bloch",
         mass="singular")
@example(c11=Fraction(1, 100), c22=Fraction(100), share=Fraction(99, 100), model="x-exact",
         mass="lumped")
def test_orthotropic_s0_starts_at_the_extensional_speed(c11, c22, share, model, mass):
    # long waves stretch the plate with sigma_yy = 0: Omega^2 = (C11 - C12^2 / C22) / C66
    # kappa^2 + O(kappa^4) (a closed form written here; C66 = 1 in these units)
    c12 = share * min(c11, c22)   # |C12| < sqrt(C11 C22): positive definite
    law = Orthotropic(c11, c22, c12, 1)
    series = discrete_series("S0", 2, Patch(model=model, mass=mass, law=law))
    assert series[2] == sympy.Rational(c11 - c12**2 / c22)
