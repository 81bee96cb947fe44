"""Claims files (dispersion.claims): parsing, exact verification, difference descriptions."""
from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest
import sympy

from dispersion.claims import (KAPPA, MAX_JOBS, check_claim, describe_difference, junit_xml, parse_claims,
                               paper_claims_path, verify_claims, verify_file)
from dispersion.errors import InputError

nu = sympy.Symbol("nu")


@pytest.fixture(scope="module")
def paper():
    return verify_file(paper_claims_path(), jobs=1)


def one(text):
    return check_claim(parse_claims(text)[0])


def test_paper_file_fails_exactly_on_eqs_17_and_19(paper):
    # eq 17 kappa^6 and eq 19 kappa^4 are the known misprints (tests/test_power_balance.py
    # derives both independently); everything else holds for the stated models
    status = {r.name: r.status for r in paper.results}
    assert {n for n, s in status.items() if s == "differs"} == {"eq 17", "eq 19"}
    assert not paper.passed
    assert status["eq 20, gamma_s = 1/2"] == "differs (expected)"
    assert all(s == "holds" for n, s in status.items()
               if n not in ("eq 17", "eq 19", "eq 20, gamma_s = 1/2"))
    diff = {r.name: r.difference for r in paper.results}
    # printed eq 17 kappa^6 is -1/2 of the derived term; printed eq 19 kappa^4 has its sign flipped
    assert diff["eq 17"] == "kappa^6: factor: printed = -1/2 * derived"
    assert diff["eq 19"] == "kappa^4: sign: printed = -(derived)"


@pytest.mark.parametrize("printed, derived, expected", [
    (-2 / (1 - nu), 2 / (1 - nu), "sign: printed = -(derived)"),
    (3 / (1 - nu), 2 / (1 - nu), "factor: printed = 3/2 * derived"),
    ((nu**2 + 11 * nu) / (1 - nu), (nu**2 + 10 * nu) / (1 - nu), "numerator term 10*nu -> 11*nu (same denominator 1 - nu)"),
    (1 / (1 + nu), 1 / (1 - nu), "denominator: printed nu + 1, derived 1 - nu"),
    (nu, sympy.Integer(0), "extra term: printed nu, derived 0"),
    (sympy.Integer(0), nu, "missing term: derived nu"),
])
def test_difference_is_described_simply(printed, derived, expected):
    assert describe_difference(printed, derived).startswith(expected)
    assert describe_difference(derived, derived) == ""


def test_whole_series_claims_every_even_power_up_to_the_order_term():
    # "+ O(kappa^6)" claims the kappa^4 coefficient too: here zero, but eq 14 has -2 nu^2/(3(1-nu)^3)
    r = one('[[claim]]\nname = "x"\nmodel = "rayleigh-lamb"\nbranch = "S0"\n'
            'series = "2/(1-nu)*kappa^2 + O(kappa^6)"\n')
    assert r.status == "differs" and [t.power for t in r.terms] == [2, 4]
    assert r.difference.startswith("kappa^4: missing term")


def test_latex_and_sympy_text_give_the_same_claim():
    sym = parse_claims('[[claim]]\nname = "a"\nbranch = "A0"\nmodel = "rayleigh-lamb"\n'
                       'series = "2/(3*(1-nu))*kappa^4 + 2*(7*nu - 17)/(45*(1-nu)^2)*kappa^6"\n')
    tex = parse_claims('[[claim]]\nname = "a"\nbranch = "A0"\nmodel = "rayleigh-lamb"\n'
                       'syntax = "latex"\nseries = \'\\frac{2}{3(1-\\nu)}\\kappa^4 + '
                       '\\frac{2 \\cdot (7\\nu - 17)}{45(1-\\nu)^2}\\kappa^6 + O(\\kappa^8)\'\n')
    assert [k for k, _ in tex[0].printed] == [4, 6]
    for (k1, a), (k2, b) in zip(sym[0].printed, tex[0].printed):
        assert k1 == k2 and sympy.cancel(a - b) == 0


def test_error_order_exact_and_as_a_bound():
    # consistent mass S0: eqs 14 and 17 first differ at kappa^6 (tests/test_power_balance.py)
    base = '[[claim]]\nname = "e"\nkind = "error_order"\nbranch = "S0"\nmass = "consistent"\n'
    assert one(base + "error_order = 6\n").status == "holds"
    wrong = one(base + "error_order = 4\n")
    assert wrong.status == "differs" and "leading error O(kappa^6)" in wrong.difference
    assert one(base + "error_order = 4\nbound = true\n").status == "holds"


def test_value_claim_against_the_long_wave_closed_form():
    # Omega from eq (14) to kappa^4 at kappa = 0.01: the kappa^6 term is ~1e-8 relative
    k, v = 0.01, 0.3
    omega = float(sympy.sqrt(2 / (1 - v) * k**2 - 2 * v**2 / (3 * (1 - v) ** 3) * k**4))
    body = f'[[claim]]\nname = "v"\nkind = "value"\nmodel = "rayleigh-lamb"\nbranch = "S0"\n' \
           f"kappa = {k}\nnu = {v}\nrtol = 1e-6\n"
    assert one(body + f"omega = {omega!r}\n").status == "holds"
    assert one(body + f"omega = {omega * 1.001!r}\n").status == "differs"


def test_numeric_nu_with_tolerance():
    # eq 14 leading term at nu = 3/10: 2/(1 - 0.3) = 2.857142857...
    body = '[[claim]]\nname = "n"\nbranch = "S0"\nmodel = "rayleigh-lamb"\nnu = "3/10"\n'
    assert one(body + 'coefficients = {2 = "20/7"}\n').status == "holds"
    assert one(body + 'rtol = 1e-9\ncoefficients = {2 = 2.857142857143}\n').status == "holds"
    assert one(body + 'rtol = 1e-9\ncoefficients = {2 = 2.8571}\n').status == "differs"


def test_expected_difference_that_holds_is_a_failure():
    r = one('[[claim]]\nname = "x"\nmodel = "rayleigh-lamb"\nbranch = "S0"\nexpect = "differs"\n'
            'coefficients = {2 = "2/(1-nu)"}\n')
    assert r.status == "holds (unexpected)" and not r.passed


@pytest.mark.parametrize("text, where", [
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncolour = "red"\n', ":4: claim 'a': field 'colour'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "2/(1-nu"}\n',
     ":4: claim 'a': field '2'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "2/(1-mu)"}\n',
     ":4: claim 'a': field '2': unknown name 'mu'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\nn = 2\ncoefficients = {2 = "1"}\n',
     ":4: claim 'a': field 'n': the toolkit cannot build"),
    ('[[claim]]\nname = "a"\nbranch = "S3"\ncoefficients = {2 = "1"}\n',
     ":3: claim 'a': field 'branch'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {3 = "1"}\n',
     ":4: claim 'a': field '3'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "1"}\n'
     '[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "1"}\n',
     ":6: claim 'a': field 'name'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "1"\n', "malformed TOML"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\nmodel = "rayleigh-lamb"\nr = 2\n'
     'coefficients = {2 = "1"}\n', ":5: claim 'a': field 'r'"),
])
def test_bad_input_names_file_line_entry_and_field(text, where):
    with pytest.raises(InputError) as info:
        parse_claims(text, "f.toml")
    msg = str(info.value)
    assert msg.startswith("f.toml") and where in msg and "\n" not in msg


def test_malformed_toml_names_the_line():
    with pytest.raises(InputError, match=r"f\.toml: malformed TOML: .*line 4"):
        parse_claims('[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {2 = "1"\n', "f.toml")


def test_junit_has_one_case_per_claim_and_failures_for_the_misprints(paper):
    root = ET.fromstring(junit_xml(paper))
    cases = root.findall(".//testcase")
    assert len(cases) == len(paper.results) == int(root.get("tests"))
    failed = {c.get("name") for c in cases if c.find("failure") is not None}
    assert failed == {"eq 17", "eq 19"} and root.get("failures") == "2"
    eq17 = next(c for c in cases if c.get("name") == "eq 17")
    assert "printed:" in eq17.find("failure").text and "derived:" in eq17.find("failure").text


def test_each_distinct_derivation_is_shared():
    claims = parse_claims('[[claim]]\nname = "a"\nmodel = "rayleigh-lamb"\nbranch = "A0"\n'
                          'coefficients = {4 = "2/(3*(1-nu))"}\n'
                          '[[claim]]\nname = "b"\nmodel = "rayleigh-lamb"\nbranch = "A0"\n'
                          'coefficients = {6 = "2*(7*nu - 17)/(45*(1-nu)^2)"}\n')
    assert [r.status for r in verify_claims(claims, jobs=1).results] == ["holds", "holds"]


def test_parallel_verification_agrees_with_serial(paper):
    par = verify_file(paper_claims_path(), jobs=2)
    assert [(r.name, r.status, r.difference) for r in par.results] == \
        [(r.name, r.status, r.difference) for r in paper.results]


def test_kappa_symbol_is_not_allowed_in_a_coefficient():
    with pytest.raises(InputError, match="field '2'"):
        parse_claims(f'[[claim]]\nname = "a"\nbranch = "S0"\ncoefficients = {{2 = "{KAPPA}"}}\n')


def test_a_derivation_that_fails_marks_its_claim_as_error(monkeypatch):
    import dispersion.claims.verify as claims_mod
    from dispersion.errors import DispersionError

    def broken(*args):
        raise DispersionError("characteristic function vanishes identically near the origin")

    monkeypatch.setattr(claims_mod, "_series", broken)
    claims = parse_claims('[[claim]]\nname = "a"\nmodel = "rayleigh-lamb"\nbranch = "A0"\n'
                          'coefficients = {4 = "2/(3*(1-nu))"}\n')
    result = verify_claims(claims, jobs=1)
    assert not result.passed and result.results[0].status == "error"
    assert "vanishes identically" in result.results[0].difference
    root = ET.fromstring(junit_xml(result))
    assert root.get("errors") == "1" and root.find(".//testcase/error") is not None


@pytest.mark.parametrize("jobs", [0, MAX_JOBS + 1, 2.5, "2", True])
def test_jobs_out_of_range_is_refused_before_any_derivation(monkeypatch, jobs):
    import dispersion.claims.verify as claims_mod

    def must_not_run(*args):
        raise AssertionError("derivation started")

    monkeypatch.setattr(claims_mod, "_run_task", must_not_run)
    claims = parse_claims('[[claim]]\nname = "a"\nmodel = "rayleigh-lamb"\nbranch = "A0"\n'
                          'coefficients = {4 = "2/(3*(1-nu))"}\n')
    with pytest.raises(InputError, match=rf"jobs must be an integer in \[1, {MAX_JOBS}\]"):
        verify_claims(claims, jobs=jobs)
