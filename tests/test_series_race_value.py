"""The race's coefficient reader (series_race._value -> coefficient_value): exact,
whitelist-only, no eval.

Reference values are computed independently in the test: each random expression tree is
evaluated directly with Fractions and rendered to text in both syntaxes (ours: ``**``,
Maxima's linear syntax: ``^``) before the reader sees the text.
"""
from __future__ import annotations

import ast
import inspect
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.errors import InputError
from dispersion.studies import series_race
from dispersion.studies.series_race import _value
from dispersion.studies import coefficient_value as _reader

NU = st.fractions(min_value=-5, max_value=5, max_denominator=20)


def _tree(max_leaves=12):
    leaf = st.one_of(st.integers(0, 10**30).map(lambda v: ("num", v)), st.just(("nu",)))
    return st.recursive(
        leaf,
        lambda kids: st.one_of(
            st.tuples(st.sampled_from("+-*/"), kids, kids),
            st.tuples(st.just("neg"), kids),
            st.tuples(st.just("pow"), kids, st.integers(-4, 6))),
        max_leaves=max_leaves)


def _eval(t, nu):
    kind = t[0]
    if kind == "num":
        return Fraction(t[1])
    if kind == "nu":
        return nu
    if kind == "neg":
        return -_eval(t[1], nu)
    if kind == "pow":
        base = _eval(t[1], nu)
        if base == 0 and t[2] < 0:
            raise ZeroDivisionError
        return base ** t[2]
    a, b = _eval(t[1], nu), _eval(t[2], nu)
    if kind == "/" and b == 0:
        raise ZeroDivisionError
    return {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else None}[kind]


def _text(t, caret: bool) -> str:
    kind = t[0]
    if kind == "num":
        return str(t[1])
    if kind == "nu":
        return "nu"
    if kind == "neg":
        return f"-({_text(t[1], caret)})"
    if kind == "pow":
        e = str(t[2]) if t[2] >= 0 else f"({t[2]})" if caret else str(t[2])
        return f"({_text(t[1], caret)}){'^' if caret else '**'}{e}"
    return f"({_text(t[1], caret)}) {kind} ({_text(t[2], caret)})"


def _fast_and_full(fast: int, full: int):
    """The example count of a search: ``fast`` in the default run, ``full`` in the slow run."""
    return pytest.mark.parametrize("examples", [
        pytest.param(fast, id="fast"), pytest.param(full, id="full", marks=pytest.mark.slow)])


@_fast_and_full(60, 300)
def test_value_equals_direct_fraction_evaluation(examples):
    settings(max_examples=examples, deadline=None)(
        given(_tree(), NU, st.booleans())(_value_equals_direct_fraction_evaluation))()


def _value_equals_direct_fraction_evaluation(tree, nu, caret):
    text = _text(tree, caret)
    try:
        expected = _eval(tree, nu)
    except ZeroDivisionError:
        try:
            _value(text, nu)
        except InputError as exc:
            assert "division by zero" in str(exc)
        else:
            raise AssertionError(f"{text!r} divides by zero at nu = {nu} but was read")
        return
    assert _value(text, nu) == expected


@_fast_and_full(100, 500)
def test_value_refuses_with_input_error_only(examples):
    settings(max_examples=examples, deadline=None)(given(
        st.text(alphabet=st.sampled_from(list("0123456789nu+-*/^() .eE_[]'\"abcdxyzos,;:")),
                max_size=40), NU)(_value_refuses_with_input_error_only))()


def _value_refuses_with_input_error_only(text, nu):
    # fuzz: any text either reads to a Fraction or is refused as InputError, nothing else
    try:
        assert isinstance(_value(text, nu), Fraction)
    except InputError:
        pass


def test_injections_are_refused():
    for text in ("__import__('os').system('true')", "nu.__class__", "(lambda: 1)()",
                 "open('x')", "1 if 1 else 2", "[1]", "1e3", "nu^nu", "2^(1/2)",
                 "(" * 150 + "1" + ")" * 150, "2^100000"):
        try:
            _value(text, Fraction(1, 3))
        except InputError:
            continue
        raise AssertionError(f"{text!r} was read")


def test_no_eval_in_the_race_or_the_reader():
    for module in (series_race, _reader):
        tree = ast.parse(inspect.getsource(module))
        names = {n.func.id for n in ast.walk(tree)
                 if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
        assert not names & {"eval", "exec", "compile"}, module.__name__
