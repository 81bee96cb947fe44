"""Claims files bounded on the way in, inert on the way out; the API raises only InputError.

Issue 17 items 2, 6 and 8 (the claims part) and issue 19 item 6 (whole expressions, and
``Omega^2 =``). Derivations here are the exact S0 series to kappa^2 or kappa^4 (milliseconds).
"""
from __future__ import annotations

import json
import os
import re
import xml.etree.ElementTree as ET

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.claims import (ClaimResult, Verification, check_claim, describe_difference,
                               format_results, junit_xml, load_claims, parse_claims, plain,
                               verify_claims)
from dispersion.claims.claims_file import MAX_FILE_BYTES, MAX_NESTING
from dispersion.cli import main
from dispersion.errors import InputError
from dispersion.testing import assert_series

GOOD = '[[claim]]\nname = "bar"\nbranch = "S0"\nmodel = "rayleigh-lamb"\ncoefficients = {2 = "2/(1 - nu)"}\n'
QUICK = settings(max_examples=30, deadline=None, derandomize=True)
ESC = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def _one_line_exit_2(capsys, *argv):
    assert main(["verify", *map(str, argv)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "verify: error:" in err, err
    return err


# --------------------------------------------------------------------------- files in

def test_a_claims_file_must_be_a_regular_utf8_file_of_bounded_size(tmp_path, capsys):
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)  # opened without blocking: refused before a byte is read
    assert "not a regular file" in _one_line_exit_2(capsys, fifo)
    assert "not a regular file" in _one_line_exit_2(capsys, tmp_path)
    if os.path.exists("/dev/zero"):
        assert "not a regular file" in _one_line_exit_2(capsys, "/dev/zero")
    latin1 = tmp_path / "latin1.toml"
    latin1.write_bytes(GOOD.replace("bar", "b\xe4r").encode("latin-1"))
    assert "not UTF-8" in _one_line_exit_2(capsys, latin1)
    big = tmp_path / "big.toml"
    big.write_text(GOOD + "#" * MAX_FILE_BYTES)
    assert f"limit of {MAX_FILE_BYTES} bytes" in _one_line_exit_2(capsys, big)
    assert "cannot read" in _one_line_exit_2(capsys, tmp_path / "missing.toml")


@pytest.mark.parametrize("tail, match", [
    ("x = " + "[" * 100_000 + "]" * 100_000, "nested"),  # RecursionError inside tomllib
    ("x = " + "[" * (MAX_NESTING + 1) + "]" * (MAX_NESTING + 1), "nested"),
    ("x = {" * 3000 + "}" * 3000, "nested"),  # refused on the raw text (issue 34)
    ("x = " + "9" * 5000, "malformed TOML"),  # int() refuses more than 4300 digits
])
def test_deep_or_huge_toml_is_refused(tail, match, tmp_path, capsys):
    text = tail + "\n" + GOOD
    with pytest.raises(InputError, match=match):
        parse_claims(text)
    path = tmp_path / "c.toml"
    path.write_text(text)
    _one_line_exit_2(capsys, path)


@pytest.mark.parametrize("call", [
    lambda: parse_claims(None),
    lambda: parse_claims(b"[[claim]]"),
    lambda: parse_claims(GOOD, file=None),
    lambda: load_claims(None),
    lambda: load_claims("\x00"),
    lambda: verify_claims(None),
    lambda: verify_claims("claims.toml"),
    lambda: verify_claims([None]),
    lambda: check_claim("eq 14"),
    lambda: describe_difference("__import__('os')", 1),
    lambda: describe_difference(object(), 1),
    lambda: parse_claims(GOOD.replace('{2 = "2/(1 - nu)"}', '{2 = "1"}\nnu = "1/0"')),
    lambda: parse_claims(GOOD.replace('{2 =', '{' + "2" * 5000 + ' = "1", 2 =')),
    lambda: parse_claims(GOOD.replace("2/(1 - nu)", "1/(nu - nu)")),
    lambda: format_results([], "html"),
    lambda: format_results([], width=0),
])
def test_api_errors_are_input_errors(call):
    # issue 17.6: never TypeError, AttributeError, ZeroDivisionError or RecursionError
    with pytest.raises(InputError) as info:
        call()
    assert "\n" not in str(info.value)


def test_a_claim_may_be_pasted_with_omega_squared():
    # issue 19.6: eq (14)'s leading term as printed, in both syntaxes
    for series, syntax in (("Omega^2 = 2/(1-nu)*kappa^2", "sympy"),
                           (r"\Omega^2 = \frac{2}{1-\nu}\kappa^2", "latex")):
        text = (f'[[claim]]\nname = "a"\nbranch = "S0"\nmodel = "rayleigh-lamb"\n'
                f"syntax = '{syntax}'\nseries = '{series}'\n")
        assert check_claim(parse_claims(text)[0]).status == "holds"


@pytest.mark.parametrize("printed", ["sqrt(nu)/(1-nu)", "2/(1-nu) + sqrt(nu)", "nu^(1/3)",
                                     "(nu + sqrt(2))/(1 - nu)"])
def test_roots_in_a_printed_coefficient_are_described_not_raised(printed):
    # Poly() refuses sqrt(nu) as a term: the description falls back to whole numerators
    r = check_claim(parse_claims(GOOD.replace("2/(1 - nu)", printed))[0])
    assert r.status == "differs" and r.difference.startswith("kappa^2: ")


def test_derivations_beyond_the_engine_limits_are_refused_before_work(monkeypatch):
    import dispersion.claims.verify as verify_mod

    monkeypatch.setattr(verify_mod, "_run_task", lambda *a: pytest.fail("derivation started"))
    base = '[[claim]]\nname = "a"\nbranch = "S0"\nmodel = "bloch"\n'
    # power_balance.check_request: (2n)^2 * order <= 12000; p = 24, n = 200 of issue 17.2
    for body, field in (("p = 24\nn = 200\ncoefficients = {2 = '1'}", "'n'"),
                        ("n = 12\ncoefficients = {32 = '1'}", "'n'"),
                        ("coefficients = {34 = '1'}", "'34'"),
                        ("kind = 'error_order'\nerror_order = 32", "'error_order'")):
        with pytest.raises(InputError, match=field):
            parse_claims(base + body + "\n")


def test_the_number_of_distinct_derivations_is_bounded_before_work(monkeypatch):
    import dispersion.claims.verify as verify_mod

    monkeypatch.setattr(verify_mod, "_run_task", lambda *a: pytest.fail("derivation started"))
    n = verify_mod.MAX_DERIVATIONS + 1
    text = "".join(f'[[claim]]\nname = "v{i}"\nkind = "value"\nmodel = "rayleigh-lamb"\n'
                   f'branch = "S0"\nkappa = {i / 100}\nnu = 0.3\nomega = 1.0\nrtol = 0.1\n'
                   for i in range(n))
    with pytest.raises(InputError, match=f"{n} distinct derivations"):
        verify_claims(parse_claims(text))


def test_assert_series_text_cannot_change_the_claim():
    # name and values are written as TOML strings: quotes and newlines stay inside them
    name = 'x"\nmodel = "bloch'
    r = assert_series("S0", {2: "2/(1 - nu)"}, name=name, model="rayleigh-lamb")
    assert r.name == name and r.model == "Rayleigh-Lamb (exact)"


# --------------------------------------------------------------------------- text out

def _result(name="c", source="s", printed="p", derived="d", difference="", status="holds",
            file="f\x1b.toml"):
    return ClaimResult(name, source, "series", "S0", "Rayleigh-Lamb (exact)", file, 1,
                       printed, derived, status, status == "holds", difference)


TEXT = st.text(st.characters(), max_size=40) | st.sampled_from(
    ["\x1b[2J\x1b[31mred", "\x1b]0;title\x07", "\x9b31m", "a\x00b", "\u202eevil", "\r\n",
     "]]>", "<![CDATA[", "&amp;", "\ud800"])


@QUICK
@given(TEXT, TEXT, TEXT)
def test_junit_is_well_formed_and_text_is_inert_for_any_claim(name, source, difference):
    status = "differs" if difference else "holds"
    v = Verification(("f\x1b.toml",), (_result(name, source, "x", "y", difference, status),), 0.1)
    root = ET.fromstring(junit_xml(v).encode("utf-8"))  # an XML parser accepts it
    case = root.find(".//testcase")
    assert case is not None and root.get("tests") == "1"
    allowed = re.compile("[\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]*")
    if allowed.fullmatch(name):  # what XML can hold is kept as is
        assert case.get("name") == name
    for fmt in ("text", "markdown"):
        out = format_results(v.results, fmt, width=60)
        assert not ESC.search(out.replace("\n", "")), repr(out)
        assert "\u202e" not in out
    assert not ESC.search(plain(name + source))


def test_verify_keeps_escape_sequences_from_the_terminal(tmp_path, capsys):
    path = tmp_path / "c.toml"
    path.write_text(GOOD.replace('"bar"', '"bar\\u001b[2J\\u001b[31m"')
                    + 'source = "\\u001b]0;owned\\u0007eq 14"\n')
    junit = tmp_path / "j.xml"
    assert main(["verify", str(path), "--junit", str(junit)]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "bar" in out
    assert ET.parse(junit).getroot().find(".//testcase") is not None
    bad = tmp_path / "bad\x1b[31m.toml"
    bad.write_text("x =")
    err = _one_line_exit_2(capsys, bad)
    assert "\x1b" not in err


def test_verify_shows_whole_expressions_wrapped_to_the_width(tmp_path, capsys):
    # a long printed coefficient (the derived one is 2/(1 - nu)): shown whole, never cut
    long = " + ".join(f"{k}*nu**{k}" for k in range(1, 25))
    claims = parse_claims(GOOD.replace("2/(1 - nu)", long))
    result = verify_claims(claims, jobs=1)
    for width in (40, 60, 100):
        out = format_results(result.results, "text", width=width)
        assert max(map(len, out.splitlines())) <= width
        assert "..." not in out
        flat = "".join(out.split())
        assert "".join(result.results[0].printed.split()) in flat
        assert "".join(result.results[0].derived.split()) in flat
    path = tmp_path / "long.toml"
    path.write_text(GOOD.replace("2/(1 - nu)", long))
    assert main(["verify", str(path)]) == 1
    assert "..." not in capsys.readouterr().out


# --------------------------------------------------------------------------- schema fuzz

def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return {"nan": "nan", "inf": "inf", "-inf": "-inf"}.get(repr(value), repr(value))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(map(_toml, value)) + "]"
    return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml(v)}" for k, v in value.items()) + "}"


SCALARS = st.one_of(
    st.booleans(), st.integers(-10, 40), st.integers(), st.floats(allow_nan=True),
    st.sampled_from(["S0", "A0", "S1", "series", "value", "error_order", "bloch", "x-exact",
                     "rayleigh-lamb", "singular", "consistent", "top", "latex", "sympy",
                     "holds", "differs", "r", "1/2", "3/10", "1/0", "nan", "2/(1-nu)",
                     "2/(1-nu)*kappa^2 + O(kappa^4)", "kappa^3", "O(\"x\")", "__import__"]),
    st.text(max_size=12))
POWERS = st.sampled_from(["0", "1", "2", "4", "02"])
NESTED = st.one_of(SCALARS, st.lists(SCALARS, max_size=3),
                   st.dictionaries(POWERS, SCALARS, max_size=3))
VALUES = st.one_of(NESTED, st.lists(NESTED, max_size=3),
                   st.dictionaries(POWERS, NESTED, max_size=3))
KEYS = st.sampled_from(sorted(__import__("dispersion.claims.schema", fromlist=["x"]).CLAIM_KEYS
                              - {"name", "p", "n"}) + ["p", "n", "colour"])


@settings(max_examples=30, deadline=None, derandomize=True)
@given(st.dictionaries(KEYS, VALUES, max_size=6), st.integers(1, 6), st.integers(2, 8))
def test_any_claim_fields_parse_or_raise_input_error(fields, p, n):
    # p, n kept small: a valid patch is built once while parsing (bounded, but not free)
    fields = {k: v for k, v in fields.items() if k not in ("p", "n")}
    text = "[[claim]]\nname = \"x\"\n" + f"p = {p}\nn = {n}\n" + "".join(
        f"{k} = {_toml(v)}\n" for k, v in fields.items())
    try:
        claims = parse_claims(text, "fuzz.toml")
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc).startswith("fuzz.toml")
        return
    assert len(claims) == 1 and claims[0].name == "x"


@pytest.mark.slow
@settings(max_examples=1000, deadline=None)
@given(st.dictionaries(KEYS, VALUES, max_size=6), st.integers(1, 6), st.integers(2, 8))
def test_any_claim_fields_parse_or_raise_input_error_long(fields, p, n):
    test_any_claim_fields_parse_or_raise_input_error.hypothesis.inner_test(fields, p, n)


def test_a_comparison_that_fails_is_an_error_of_its_claim_only(monkeypatch):
    import dispersion.claims.verify as verify_mod

    calls = []
    real = verify_mod.describe_difference

    def broken_on_the_second_claim(*args):
        calls.append(args)
        if len(calls) == 2:
            raise ZeroDivisionError("inside sympy")
        return real(*args)

    claims = parse_claims(GOOD + GOOD.replace('"bar"', '"baz"'))
    monkeypatch.setattr(verify_mod, "describe_difference", broken_on_the_second_claim)
    result = verify_claims(claims, jobs=1)
    assert [r.status for r in result.results] == ["holds", "error"]
    assert "ZeroDivisionError" in result.results[1].difference and not result.passed


def test_report_json_text_is_read_never_run(tmp_path, monkeypatch):
    # `dispersion reproduce --render` re-renders the errata from reports/*.json: a forged
    # coefficient string there was sympified (run) before; now it is read by the reader
    from dispersion.claims.errata import errata_document, format_table

    monkeypatch.chdir(tmp_path)
    payload = "__import__('os').system('touch pwned')"
    with pytest.raises(InputError):
        errata_document([], eq13=[("S0", payload, "-4")])
    row = {"equation": "14", "power": 2, "printed": payload, "derived": "2/(1 - nu)",
           "status": "match", "reproduced_by": [], "printed_latex": "", "derived_latex": ""}
    with pytest.raises(InputError):
        format_table([row], "latex")
    assert list(tmp_path.iterdir()) == []
