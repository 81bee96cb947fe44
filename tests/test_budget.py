"""The cost rules of dispersion/budget.py: each request is refused just above its bound,
before any work (the function doing the work is replaced by one that fails the test), and
accepted at the bound; the rules reach every entry point (API, claims, command line).
"""
from __future__ import annotations

import itertools

import pytest
import sympy

from dispersion import budget
from dispersion.claims import parse_claims
from dispersion.cli import main
from dispersion.errors import InputError


def _never(*args, **kwargs):
    raise AssertionError("the work started")


def test_series_work_counts_the_terms_of_the_full_expansions():
    # independent count: the monomials of (x_1 + ... + x_k)^j are the multisets of size j
    for k in range(1, 6):
        for m in range(1, 6):
            brute = sum(len(set(itertools.combinations_with_replacement(range(k), j)))
                        for j in range(1, m + 1))
            assert budget.series_work(k, m) == brute
    assert budget.series_work(40, 40) == budget.SERIES_WORK_MAX + 1  # capped, not computed


@pytest.mark.parametrize("p", [budget.BAR_P_MAX + 1, 24])
def test_the_bar_degree_is_refused_above_its_bound_before_work(monkeypatch, p, capsys):
    import dispersion.time_stepping.timestep as ts

    monkeypatch.setattr(ts, "_coefficients", _never)
    for call in (lambda: ts.bar_omega_squared("hrz", p), lambda: ts.bar_omega_max("lumped", p),
                 lambda: ts.critical_step("consistent", p, model="bar", wave_speed=1.0)):
        with pytest.raises(InputError, match=f"at most p = {budget.BAR_P_MAX}"):
            call()
    assert main(["timestep", "--model", "bar", "--p", str(p)]) == 2
    assert f"at most p = {budget.BAR_P_MAX}" in capsys.readouterr().err


def test_the_bar_degree_at_its_bound_is_computed():
    from dispersion.time_stepping.timestep import bar_omega_squared

    assert bar_omega_squared("nodal-lobatto", budget.BAR_P_MAX).has(sympy.Symbol("z"))


def test_fully_discrete_series_bounds_both_of_its_costs(monkeypatch):
    import dispersion.time_stepping.fully_discrete as fd

    with pytest.raises(InputError, match="128"):
        fd.time_series(budget.TIME_TERMS_MAX + 1)
    monkeypatch.setattr(fd, "time_series", _never)
    with pytest.raises(InputError, match="128"):
        fd.fully_discrete_series({2: 1}, 2 * budget.TIME_TERMS_MAX + 2)
    nu = sympy.Symbol("nu")
    symbolic = {2 * i: 1 / (1 - nu) ** i for i in range(1, 6)}  # k = 5, m = 5: 251 products
    with pytest.raises(InputError, match="symbolic coefficients.*give nu a value"):
        fd.fully_discrete_series(symbolic, 10)
    numeric = {2 * i: sympy.Rational(1, i) for i in range(1, 13)}  # k = m = 12
    with pytest.raises(InputError, match="numeric coefficients"):
        fd.fully_discrete_series(numeric, 24)


def test_fully_discrete_series_within_its_bounds_is_computed():
    from dispersion.time_stepping.fully_discrete import fully_discrete_series

    nu = sympy.Symbol("nu")
    # k = 4, m = 4: 69 products, the largest symbolic work within the bound
    assert budget.series_work(4, 4) <= budget.SYMBOLIC_SERIES_WORK_MAX
    out = fully_discrete_series({2: 1, 4: nu, 6: 0, 8: 1}, 4)
    assert out.has(nu)


def _claim(kind: str, body: str, model: str = 'model = "bar"\np = 2\nmass = "hrz"\n') -> str:
    return f'[[claim]]\nname = "c"\nkind = "{kind}"\n{model}{body}'


@pytest.mark.parametrize("text, bound", [
    (_claim("critical_step", "ratio = 1.5\n",
            f'model = "bar"\np = {budget.BAR_P_MAX + 1}\nmass = "hrz"\n'),
     f"at most p = {budget.BAR_P_MAX}"),
    (_claim("fully_discrete_series", '[claim.coefficients]\n"kappa^18" = "1"\n'),
     r"at most kappa\^16"),
    (_claim("fully_discrete_series", 'branch = "S0"\n[claim.coefficients]\n"kappa^10" = "1"\n',
            'model = "bloch"\n'), "give nu a value"),
    (_claim("fully_discrete_series", 'branch = "S0"\nnu = "3/10"\n[claim.coefficients]\n'
                                     '"kappa^24" = "1"\n', 'model = "bloch"\n'),
     "numeric coefficients"),
])
def test_claims_beyond_a_bound_are_refused_when_read(monkeypatch, text, bound):
    import dispersion.claims.explicit as explicit

    monkeypatch.setattr(explicit, "run", _never)
    with pytest.raises(InputError, match=bound) as info:
        parse_claims(text)
    assert "field 'p'" in str(info.value)


@pytest.mark.parametrize("text", [
    _claim("critical_step", "ratio = 1.5\n",
           f'model = "bar"\np = {budget.BAR_P_MAX}\nmass = "hrz"\n'),
    _claim("fully_discrete_series", '[claim.coefficients]\n"kappa^16" = "1"\n'),
    _claim("fully_discrete_series", 'branch = "S0"\n[claim.coefficients]\n"kappa^8" = "1"\n',
           'model = "bloch"\n'),
    _claim("fully_discrete_series", 'branch = "A0"\nnu = "3/10"\n[claim.coefficients]\n'
                                    '"kappa^24" = "1"\n', 'model = "bloch"\n'),
])
def test_claims_within_the_bounds_are_read(text):
    assert len(parse_claims(text)) == 1


def test_phases_are_bounded_by_memory_before_the_pencil(monkeypatch):
    import dispersion.time_stepping.timestep as ts
    from dispersion.symbolic.plate import plate_patch

    monkeypatch.setattr(ts, "float_pencil", _never)
    patch = plate_patch(2, 3, "bloch", 2, "consistent")
    most = budget.PHASE_WORK_MAX // (2 * patch.n) ** 2
    for call in (ts.critical_time_step, ts.patch_omega_max):
        with pytest.raises(InputError, match=f"at most n_theta = {most}"):
            call(patch, 0.3, n_theta=most + 1)
    with pytest.raises(AssertionError, match="the work started"):  # at the bound: the work
        ts.patch_omega_max(patch, 0.3, n_theta=most)


def test_jobs_are_bounded_per_usable_cpu():
    assert budget.check_jobs(budget.max_jobs()) == budget.max_jobs()
    for bad in (0, budget.max_jobs() + 1, 1.0, True, "2"):
        with pytest.raises(InputError, match=r"jobs must be an integer in \[1, "):
            budget.check_jobs(bad)
