"""dispersion.claims.reader: the whitelist expression reader, searched for counterexamples.

Two properties are tested with hypothesis: (1) a random expression tree, built directly in
sympy and rendered to plain text and to LaTeX, reads back to the same value (or to an
InputError exactly when the value is not a finite real number); (2) random text, from an
alphabet rich in what an attacker would try (quotes, escapes, dots, dunders, unicode
look-alikes), either reads to a tree of whitelisted nodes or raises InputError, never
anything else. ``max_examples`` is small in the default run; the ``slow`` tests search longer.
"""
from __future__ import annotations

import operator
import os
from fractions import Fraction

import pytest
import sympy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.claims import reader
from dispersion.claims.reader import parse, read, read_number
from dispersion.errors import InputError

nu, r, kappa = sympy.Symbol("nu"), sympy.Symbol("r", positive=True), sympy.Symbol("kappa")
QUICK = settings(max_examples=40, deadline=None, derandomize=True,
                 suppress_health_check=[HealthCheck.too_slow])
LONG = settings(max_examples=1500, deadline=None,
                suppress_health_check=[HealthCheck.too_slow])
NODES = {"num", "sym", "add", "mul", "neg", "pow", "sqrt", "O"}


# --------------------------------------------------------------------------- examples

@pytest.mark.parametrize("text, syntax, expected", [
    # reference values: the same expressions typed directly in sympy
    ("2/(1 - nu)*kappa^2", "sympy", 2 / (1 - nu) * kappa**2),
    ("2/(1 - nu)*kappa**2", "sympy", 2 / (1 - nu) * kappa**2),
    ("-2*nu^2/(3*(1-nu)^3)", "sympy", -2 * nu**2 / (3 * (1 - nu) ** 3)),
    ("Rational(3, 10) + sqrt(2)*r", "sympy", sympy.Rational(3, 10) + sympy.sqrt(2) * r),
    ("0.3 - 1e-3 + .5", "sympy", sympy.Rational(3, 10) - sympy.Rational(1, 1000) + sympy.Rational(1, 2)),
    ("nu^(1/2) * kappa^-2", "sympy", sympy.sqrt(nu) / kappa**2),
    ("--nu", "sympy", nu),
    (r"\frac{2}{1-\nu}\kappa^2", "latex", 2 / (1 - nu) * kappa**2),
    (r"\frac{2\nu^2(7\nu^2 + 10\nu - 6)}{45(1-\nu)^5}", "latex",
     2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5)),
    (r"\left(1 - \nu\right)^{-2} \cdot 3 \times r", "latex", 3 * r / (1 - nu) ** 2),
    (r"\dfrac{\sqrt{\nu}}{2}\,\kappa^{4}", "latex", sympy.sqrt(nu) / 2 * kappa**4),
    (r"2\kappa^2 + \mathcal{O}(\kappa^{4})", "latex", 2 * kappa**2 + sympy.O(kappa**4)),
])
def test_reads_what_a_paper_prints(text, syntax, expected):
    got = read(text, syntax)
    assert got.getO() == expected.getO()
    assert sympy.cancel(got.removeO() - expected.removeO()) == 0


def test_an_equation_may_start_with_omega_squared():
    # issue 19.6: a claim pasted as printed
    assert read("Omega^2 = 2/(1-nu)*kappa^2", equation=True) == 2 / (1 - nu) * kappa**2
    assert read(r"\Omega^2 = \frac{2}{1-\nu}\kappa^2", "latex", equation=True) == \
        2 / (1 - nu) * kappa**2
    with pytest.raises(InputError, match="Omega"):
        read("Omega^2 = 2/(1-nu)*kappa^2")  # not an equation field
    with pytest.raises(InputError, match="left-hand side"):
        read("kappa^2 = 2", equation=True)


@pytest.mark.parametrize("text, match", [
    ("kappa**10**9", "power of a power"),
    ("kappa^1000000000", "exponent 1000000000 out of range"),
    ("10**999999999", "exponent 999999999 out of range"),
    ("1e999999999", "decimal exponent"),
    ("9" * (reader.MAX_DIGITS + 1), "digits"),
    ("(" * (reader.MAX_DEPTH + 1) + "1" + ")" * (reader.MAX_DEPTH + 1), "nested"),
    ("+".join(["nu"] * (reader.MAX_TOKENS // 2 + 1)), "tokens"),
    ("nu" * (reader.MAX_LENGTH // 2 + 1), "characters"),
    ("(1+nu)^256*(1+nu)^256*(1+nu)^256", "degree"),
    ("(10^60)^256", "bits"),
    ("1/(nu - nu)", "division by zero"),
    ("sqrt(-1)", "not a real number"),
    ("O(nu)", "power of kappa"),
    ("(1 + nu + r)^40", "terms"),  # C(42, 2) = 861 terms once expanded
    ("(1 + nu)^100 * (1 + r)^3", "terms"),  # 101 * 4 = 404
])
def test_sizes_are_bounded_before_any_arithmetic(text, match):
    with pytest.raises(InputError, match=match):
        read(text)


def test_a_series_is_bounded_coefficient_by_coefficient():
    # a long series is many small coefficients: eq (14) to kappa^32 (16 terms, denominators
    # up to (1 - nu)^31) reads whole, each coefficient within the limits on its own
    from dispersion.continuum.exact_series import exact_series

    derived = exact_series("S0", 32)
    text = " + ".join(f"({c})*kappa^{k}" for k, c in sorted(derived.items())) + " + O(kappa^34)"
    found, order = reader.read_series(text)
    assert order == 34 and sorted(found) == sorted(derived)
    assert all(sympy.cancel(found[k] - derived[k]) == 0 for k in derived)
    with pytest.raises(InputError, match="sum of terms"):
        reader.read_series("kappa^2*(2/(1-nu) + kappa^2)")
    with pytest.raises(InputError, match="coefficient of kappa\\^2 would expand"):
        reader.read_series("(1 + nu + r)^40*kappa^2 + kappa^4")


def test_read_number_is_exact_and_bounded():
    assert read_number("3/10") == Fraction(3, 10)
    assert read_number("-1e-3") == Fraction(-1, 1000)
    assert read_number("Rational(1, 3)") == Fraction(1, 3)
    for bad in ("1/0", "nu", "sqrt(2)", "nan", "inf", "0x10", "1_000", " ", ""):
        with pytest.raises(InputError):
            read_number(bad)


def test_the_claims_package_never_evaluates_text():
    # the guarantee in the source itself: no call of an evaluating entry point anywhere in
    # dispersion.claims (sympify only with strict=True, which refuses strings)
    import ast
    from pathlib import Path

    import dispersion.claims as package

    banned = {"eval", "exec", "compile", "__import__", "parse_expr", "parse_latex", "lambdify",
              "S", "Function"}
    for path in Path(package.__file__).parent.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.Call) or getattr(
                    getattr(node.func, "value", None), "id", None) == "re":  # re.compile
                continue
            name = getattr(node.func, "id", None) or getattr(node.func, "attr", None)
            if name == "sympify":
                assert any(k.arg == "strict" and getattr(k.value, "value", None) is True
                           for k in node.keywords), (path.name, node.lineno)
            assert name not in banned, (path.name, node.lineno, name)


# --------------------------------------------------------------------------- properties

LEAVES = st.one_of(
    st.integers(0, 10**6).map(lambda n: ("int", n)),
    st.fractions(min_value=0, max_value=100, max_denominator=1000).map(lambda q: ("frac", q)),
    st.sampled_from([("sym", "nu"), ("sym", "r"), ("sym", "kappa")]),
)


def _node(children):
    return st.one_of(
        st.tuples(st.sampled_from(["+", "-", "*", "/"]), children, children),
        st.tuples(st.just("neg"), children),
        st.tuples(st.just("pow"), children, st.integers(-3, 4)),
        st.tuples(st.just("sqrt"), children),
    )


TREES = st.recursive(LEAVES, _node, max_leaves=8)


def fold(t, rules):
    """Render tree ``t`` bottom-up by ``rules``, one function per kind of node: a leaf gets its
    payload, ``pow`` its base rendered and the exponent, an operator its operands rendered;
    ``"op"`` serves the binary operators without a rule of their own."""
    kind = t[0]
    if kind in ("int", "frac", "sym"):
        return rules[kind](t[1])
    if kind == "pow":
        return rules["pow"](fold(t[1], rules), t[2])
    children = [fold(child, rules) for child in t[1:]]
    return rules[kind](*children) if kind in rules else rules["op"](kind, *children)


#: The tree built directly in sympy: the reference of the round trip.
VALUE = {"int": sympy.Integer, "frac": lambda q: sympy.Rational(q.numerator, q.denominator),
         "sym": {"nu": nu, "r": r, "kappa": kappa}.__getitem__, "neg": operator.neg,
         "pow": operator.pow, "sqrt": sympy.sqrt, "+": operator.add, "-": operator.sub,
         "*": operator.mul, "/": operator.truediv}
#: The tree as sympy text.
PLAIN = {"int": str, "frac": lambda q: f"({q.numerator}/{q.denominator})", "sym": str,
         "neg": lambda a: f"-({a})",
         "pow": lambda a, k: f"({a})^({k})" if k < 0 else f"({a})**{k}",
         "sqrt": lambda a: f"sqrt({a})", "op": lambda kind, a, b: f"({a}) {kind} ({b})"}
#: The tree as a paper prints it in LaTeX (products as juxtaposed groups).
LATEX = {"int": str, "frac": lambda q: rf"\frac{{{q.numerator}}}{{{q.denominator}}}",
         "sym": {"nu": r"\nu", "r": "r", "kappa": r"\kappa"}.__getitem__,
         "neg": lambda a: rf"-\left({a}\right)", "pow": lambda a, k: rf"\left({a}\right)^{{{k}}}",
         "sqrt": lambda a: rf"\sqrt{{{a}}}", "/": lambda a, b: rf"\frac{{{a}}}{{{b}}}",
         "*": lambda a, b: rf"\left({a}\right)\left({b}\right)",
         "op": lambda kind, a, b: rf"\left({a}\right) {kind} \left({b}\right)"}


def value(t):
    return fold(t, VALUE)


def plain(t) -> str:
    return fold(t, PLAIN)


def latex(t) -> str:
    return fold(t, LATEX)


SIZE_LIMITS = ("would reach", "would expand", "root of numbers", "nested", "tokens",
               "characters", "digits", "out of range")


def _check_round_trip(tree):
    expected = value(tree)
    finite = not expected.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo, sympy.I)
    for text, syntax in ((plain(tree), "sympy"), (latex(tree), "latex")):
        try:
            got = read(text, syntax)
        except InputError as exc:
            # the rule: refused only where the value is not a finite real number, or where
            # a stated size limit is exceeded
            assert not finite or any(w in str(exc) for w in SIZE_LIMITS), (text, str(exc))
            continue
        assert finite, (text, expected)
        assert got == expected or sympy.simplify(got - expected) == 0, (text, got, expected)


@QUICK
@given(TREES)
def test_random_trees_read_back_to_their_value(tree):
    _check_round_trip(tree)


@pytest.mark.slow
@LONG
@given(TREES)
def test_random_trees_read_back_to_their_value_long(tree):
    _check_round_trip(tree)


ATOMS = ["nu", "kappa", "r", "Omega", "sqrt", "Rational", "O", "Order", "eval", "exec",
         "__import__", "__class__", "lambda", "os", "system", "subs", "S", "Symbol", "E", "I",
         "pi", "oo", "nan", "inf", "x", "_", "'", '"', "\\", "\\137", "\\x5f", "\\u005f", ".",
         ",", ":", ";", "(", ")", "[", "]", "{", "}", "+", "-", "*", "**", "/", "^", "=", "!",
         "%", "@", "`", "$", "#", "&", "|", "~", "<", ">", "1", "2", "0", "1e5", "1e-999999",
         "3.5", " ", "\t", "\n", "\\nu", "\\kappa", "\\frac", "\\sqrt", "\\left", "\\right",
         "\\cdot", "\\input", "\\mathcal", "\x00", "\x1b[31m", "\u202e", "\uff45\uff56\uff41\uff4c",
         "\u03ba", "\u00b2", "\u2212", "\ud7ff", "\U0001f600"]
TEXTS = st.one_of(
    st.lists(st.sampled_from(ATOMS), max_size=30).map("".join),
    st.text(max_size=60),
)


def _check_whitelisted(text, syntax):
    try:
        tree = parse(text, syntax, equation=True)
    except InputError:
        return
    stack = [tree]
    while stack:  # every node of the tree is a whitelisted kind holding only data
        node = stack.pop()
        assert node[0] in NODES, node
        if node[0] == "num":
            assert isinstance(node[1], Fraction)
        elif node[0] == "sym":
            assert node[1] in ("nu", "kappa", "r", "Omega")
        elif node[0] in ("add", "mul"):
            stack += [child for _, child in node[1]]
        else:
            stack.append(node[1])
    try:
        expr = reader.to_sympy(tree)
    except InputError:
        return
    allowed = {nu, r, kappa}
    assert expr.free_symbols <= allowed
    for sub in sympy.preorder_traversal(expr):
        assert isinstance(sub, (sympy.Number, sympy.Symbol, sympy.Add, sympy.Mul, sympy.Pow,
                                sympy.Order, sympy.Tuple)) or sub is sympy.S.NegativeOne, sub


@QUICK
@given(TEXTS, st.sampled_from(reader.SYNTAXES))
def test_random_text_reads_to_whitelisted_nodes_or_raises_input_error(text, syntax):
    _check_whitelisted(text, syntax)


@pytest.mark.slow
@LONG
@given(TEXTS, st.sampled_from(reader.SYNTAXES))
def test_random_text_reads_to_whitelisted_nodes_long(text, syntax):
    cwd = os.listdir(".")
    _check_whitelisted(text, syntax)
    assert os.listdir(".") == cwd


def _check_described(tree):
    from dispersion.claims import describe_difference
    from dispersion.continuum.exact_series import exact_series

    try:
        printed = read(plain(tree))
    except InputError:
        return
    for derived in (exact_series("S0", 4)[4], sympy.Integer(0), 2 / (1 - nu) + r):
        text = describe_difference(printed, derived)
        assert isinstance(text, str) and "\n" not in text


@pytest.mark.slow
@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(TREES)
def test_any_printed_coefficient_is_described_never_raises(tree):
    # the verdict of any coefficient the reader accepts is a sentence, never an exception
    # (sympy takes ~0.1 s a comparison, so this search runs with the slow tests only)
    _check_described(tree)
