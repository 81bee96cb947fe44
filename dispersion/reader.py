"""The whitelist reader of numbers and expressions: text -> syntax tree -> Fraction or sympy,
never evaluated.

Text from strangers reaches the toolkit by many roads: claims files (``dispersion verify``
runs in CI on pull requests), number options of the command line, the JSON of a report folder
(``dispersion reproduce --render`` on a fork's ``reports/``), strings handed to the API
(``dispersion.patch(r="1/2")``). All of it is read here, by a whitelist, not by Python: a
tokenizer and a recursive-descent parser accept numbers, ``+ - * / ^ **``, parentheses, the
names ``nu``, ``kappa``, ``r`` (and ``Omega`` on the left of ``Omega^2 =``) and calls of
``sqrt``, ``Rational`` and ``O`` only; anything else is an
:class:`~dispersion.errors.InputError` naming the position. Nothing is ``eval``-ed,
``sympify``-ed from a string or handed to sympy's parsers; sympy sees only numbers and symbols
built here. LaTeX (``syntax = "latex"``) is read by the same parser: ``\\nu``, ``\\kappa``,
``\\Omega``, ``\\frac{a}{b}``, ``\\sqrt{x}``, ``\\left( \\right)``, ``\\cdot``, ``\\times``,
``\\mathcal{O}``, braces for grouping and products by juxtaposition (``2\\nu^2(1-\\nu)``).

Sizes are bounded before any arithmetic by the rules of :mod:`dispersion.reader_limits`
(length, tokens, nesting, digits, exponents, and what an expression would grow to).
:func:`rational` is the one door by which a value of the API or of a file becomes an exact
number (an int, a float by its shortest decimal, a Fraction, a sympy Rational, or text read
here).

>>> read("2/(1 - nu)*kappa^2 + O(kappa^4)")
2*kappa**2/(1 - nu) + O(kappa**4)
>>> read(r"\\frac{2}{3(1-\\nu)}\\kappa^4", syntax="latex")
2*kappa**4/(3 - 3*nu)
>>> read("__import__")
Traceback (most recent call last):
...
dispersion.errors.InputError: unknown name '__import__' at position 1 (allowed: nu, kappa, r, sqrt, Rational, O)
>>> read('O("kappa")')
Traceback (most recent call last):
...
dispersion.errors.InputError: unexpected character '"' at position 3
>>> read_number("3/10")
Fraction(3, 10)
"""
from __future__ import annotations

import re
from fractions import Fraction

from dispersion.errors import InputError
from dispersion.reader_limits import (CLAIMS_TEXT, MAX_BITS, MAX_DECIMAL_EXPONENT, MAX_DEGREE,
                                      MAX_DEPTH, MAX_DIGITS, MAX_EXPONENT, MAX_LENGTH,
                                      MAX_ROOT_BITS, MAX_TERMS, MAX_TOKENS, SERIES_TEXT,
                                      TextLimits, check_size)

__all__ = ["MAX_LENGTH", "MAX_TOKENS", "MAX_DEPTH", "MAX_DIGITS", "MAX_DECIMAL_EXPONENT",
           "MAX_EXPONENT", "MAX_DEGREE", "MAX_BITS", "MAX_TERMS", "MAX_ROOT_BITS", "SYNTAXES",
           "TextLimits", "CLAIMS_TEXT", "SERIES_TEXT", "parse", "check_size", "series_terms", "read",
           "read_series", "read_number", "to_sympy", "to_fraction", "symbols", "rational", "as_sympy"]

SYNTAXES = ("sympy", "latex")

_NAMES = ("nu", "kappa", "r", "Omega")
_FUNCTIONS = ("sqrt", "Rational", "O")
_LATEX_NAMES = {r"\nu": "nu", r"\kappa": "kappa", r"\Omega": "Omega"}
_LATEX_SPACE = {r"\,", r"\;", r"\:", r"\!", "\\ ", r"\quad", r"\qquad", r"\left", r"\right",
                r"\big", r"\Big", r"\bigg", r"\Bigg"}
_LATEX_TIMES = {r"\cdot", r"\times"}
_LATEX_FRAC = {r"\frac", r"\dfrac", r"\tfrac"}
_LATEX_FONT = {r"\mathcal", r"\mathrm", r"\operatorname"}  # only as \mathcal{O}

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<cmd>\\(?:[A-Za-z]+|[,;:! ]))
  | (?P<op>\*\*|[-+*/^(){}\[\],=])
""", re.VERBOSE)


def _fail(message: str) -> None:
    raise InputError(message)


# --------------------------------------------------------------------------- tokens

def _tokens(text: str, latex: bool,
            limits: TextLimits = CLAIMS_TEXT) -> list[tuple[str, str, int]]:
    """``(kind, text, position)`` tokens; position counts from 1 for the messages."""
    if not isinstance(text, str):
        _fail(f"an expression must be text (a string), got {type(text).__name__}")
    if len(text) > limits.length:
        _fail(f"text of {len(text)} characters, more than the limit of {limits.length}")
    bad = next((i for i, ch in enumerate(text) if not (" " <= ch <= "~" or ch in "\t\n\r")),
               None)
    if bad is not None:
        _fail(f"character U+{ord(text[bad]):04X} at position {bad + 1} is not allowed "
              "(printable ASCII only)")
    out, pos = [], 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            _fail(f"unexpected character {text[pos]!r} at position {pos + 1}")
        kind, word = m.lastgroup, m.group()
        if kind == "num":
            _check_number_text(word, pos + 1, limits.digits)
        elif kind == "name" and latex:
            # LaTeX letters are one-letter symbols: split "Or" into "O", "r"
            out += [("name", ch, pos + 1 + j) for j, ch in enumerate(word)]
            kind = "space"
        elif kind == "cmd" and not latex:
            _fail(f"LaTeX command {word!r} at position {pos + 1} in sympy text "
                  "(set syntax = \"latex\")")
        if kind != "space":
            out.append((kind, word, pos + 1))
        if len(out) > limits.tokens:
            _fail(f"has more than {limits.tokens} tokens (numbers, names and operators)")
        pos = m.end()
    return out


def _check_number_text(word: str, pos: int, max_digits: int = MAX_DIGITS) -> None:
    mantissa, _, exponent = word.lower().partition("e")
    digits = sum(ch.isdigit() for ch in mantissa)
    if digits > max_digits:
        _fail(f"number at position {pos} has {digits} digits, more than the limit of "
              f"{max_digits}")
    if exponent:
        e = exponent.lstrip("+-").lstrip("0")
        if len(e) > len(str(MAX_DECIMAL_EXPONENT)) or (e and int(e) > MAX_DECIMAL_EXPONENT):
            _fail(f"number at position {pos}: decimal exponent {exponent} out of range "
                  f"(at most {MAX_DECIMAL_EXPONENT} in size)")


def _number(word: str) -> Fraction:
    mantissa, _, exponent = word.lower().partition("e")
    whole, _, frac = mantissa.partition(".")
    value = Fraction(int((whole or "0") + frac), 10 ** len(frac))
    if exponent:
        value *= Fraction(10) ** int(exponent)
    return value


# --------------------------------------------------------------------------- tree
# Nodes are tuples: ("num", Fraction), ("sym", name), ("add", ((sign, node), ...)),
# ("mul", ((op, node), ...)) with op "*" or "/", ("neg", node), ("pow", node, Fraction),
# ("sqrt", node), ("O", node): the tree is data, never code.

class _Parser:
    def __init__(self, text: str, latex: bool, names: tuple[str, ...] = (),
                 limits: TextLimits = CLAIMS_TEXT):
        self.latex = latex
        self.names = _NAMES + tuple(names)
        self.toks = _tokens(text, latex, limits)
        self.i = 0
        self.depth = 0

    # -- helpers
    def peek(self, ahead: int = 0):
        j = self.i + ahead
        return self.toks[j] if j < len(self.toks) else ("end", "", None)

    def where(self) -> str:
        kind, word, pos = self.peek()
        return "at the end" if kind == "end" else f"{word!r} at position {pos}"

    def take(self):
        tok = self.peek()
        self.i += 1
        return tok

    def skip_space(self):
        while self.latex and self.peek()[0] == "cmd" and self.peek()[1] in _LATEX_SPACE:
            self.i += 1

    def is_op(self, *words) -> bool:
        self.skip_space()
        kind, word, _ = self.peek()
        return (kind == "op" and word in words) or (
            self.latex and kind == "cmd" and "*" in words and word in _LATEX_TIMES)

    def expect(self, word: str):
        if not self.is_op(word):
            _fail(f"expected {word!r}, found {self.where()}")
        self.take()

    def enter(self):
        self.depth += 1
        if self.depth > MAX_DEPTH:
            _fail(f"nested more than {MAX_DEPTH} levels deep")

    def leave(self):
        self.depth -= 1

    # -- grammar
    def top(self, equation: bool):
        tree = self.expr()
        if equation and self.is_op("="):
            self.take()
            if tree != ("pow", ("sym", "Omega"), Fraction(2)):
                _fail("the left-hand side of '=' must be Omega^2")
            tree = self.expr()
        elif self.is_op("="):
            _fail("an equation (Omega^2 = ...) is allowed only as a whole series, not here")
        if self.peek()[0] != "end":
            _fail(f"unexpected {self.where()}")
        return tree

    def expr(self):
        self.enter()
        terms = []
        sign = 1
        while self.is_op("+", "-"):  # leading signs
            sign *= -1 if self.take()[1] == "-" else 1
        terms.append((sign, self.term()))
        while self.is_op("+", "-"):
            sign = -1 if self.take()[1] == "-" else 1
            while self.is_op("+", "-"):
                sign *= -1 if self.take()[1] == "-" else 1
            terms.append((sign, self.term()))
        self.leave()
        return terms[0][1] if len(terms) == 1 and terms[0][0] == 1 else ("add", tuple(terms))

    def term(self):
        factors = [("*", self.unary())]
        while True:
            if self.is_op("*", "/"):
                op = "/" if self.take()[1] == "/" else "*"
                factors.append((op, self.unary()))
            elif self.latex and self.starts_atom():
                if factors[-1][1][0] == "num" and self.peek()[0] == "num":
                    _fail(f"two numbers side by side: {self.where()}")
                factors.append(("*", self.power()))
            else:
                break
        return factors[0][1] if len(factors) == 1 else ("mul", tuple(factors))

    def starts_atom(self) -> bool:
        self.skip_space()
        kind, word, _ = self.peek()
        if kind in ("num", "name"):
            return True
        if kind == "op":
            return word in "({"
        return kind == "cmd" and word not in _LATEX_TIMES

    def unary(self):
        if self.is_op("+", "-"):
            self.enter()
            neg = self.take()[1] == "-"
            inner = self.unary()
            self.leave()
            return ("neg", inner) if neg else inner
        return self.power()

    def power(self):
        base = self.atom()
        if self.is_op("^", "**"):
            self.take()
            exponent = self.exponent()
            if self.is_op("^", "**"):
                _fail(f"a power of a power needs parentheses: {self.where()}")
            if base[0] == "sym" and base[1] == "Omega" and exponent != 2:
                _fail("Omega may appear only as Omega^2 on the left of '='")
            return ("pow", base, exponent)
        return base

    def exponent(self) -> Fraction:
        """A written integer or fraction: ``2``, ``-2``, ``{2}``, ``(1/2)``, ``{-1/2}``."""
        close = None
        if self.is_op("(") or (self.latex and self.is_op("{")):
            close = ")" if self.take()[1] == "(" else "}"
        sign = 1
        while self.is_op("+", "-"):
            sign *= -1 if self.take()[1] == "-" else 1
        if self.latex and close is None and len(self.peek()[1]) > 1 and self.peek()[0] == "num":
            _fail(f"a LaTeX exponent of more than one digit needs braces (^{{10}}), found "
                  f"{self.where()}")
        value = self.integer("exponent")
        if close is not None and self.is_op("/"):
            self.take()
            den = self.integer("exponent")
            if den == 0:
                _fail("division by zero in an exponent")
            value = Fraction(value, den)
        if close is not None:
            self.expect(close)
        value = sign * Fraction(value)
        if max(abs(value.numerator), value.denominator) > MAX_EXPONENT:
            _fail(f"exponent {value} out of range (at most {MAX_EXPONENT} in size)")
        return value

    def integer(self, what: str) -> int:
        self.skip_space()
        kind, word, _ = self.peek()
        if kind != "num" or not word.isdigit():
            _fail(f"{what} must be a written integer or fraction, found {self.where()}")
        self.take()
        return int(word)

    def atom(self):
        self.skip_space()
        kind, word, pos = self.peek()
        if kind == "num":
            self.take()
            return ("num", _number(word))
        if kind == "op" and word in "({":
            if word == "{" and not self.latex:
                _fail(f"unexpected {self.where()}")
            self.take()
            inner = self.expr()
            self.expect(")" if word == "(" else "}")
            return inner
        if kind == "name":
            self.take()
            if self.latex:
                if word == "r":
                    return ("sym", "r")
                if word == "O":
                    return self.call("O")
                _fail(f"unknown symbol {word!r} at position {pos} (use \\nu, \\kappa, r, "
                      "\\Omega, O)")
            if word in self.names:
                return ("sym", word)
            if word in _FUNCTIONS:
                return self.call(word)
            _fail(f"unknown name {word!r} at position {pos} (allowed: nu, kappa, r, sqrt, "
                  "Rational, O)")
        if kind == "cmd":
            self.take()
            if word in _LATEX_NAMES:
                return ("sym", _LATEX_NAMES[word])
            if word in _LATEX_FRAC:
                num = self.group()
                den = self.group()
                return ("mul", (("*", num), ("/", den)))
            if word == r"\sqrt":
                if self.is_op("["):
                    _fail(f"\\sqrt[n] is not supported: {self.where()}")
                return ("sqrt", self.group())
            if word in _LATEX_FONT:
                self.expect("{")
                self.skip_space()
                if self.peek()[:2] != ("name", "O"):
                    _fail(f"{word} is allowed only as {word}{{O}}, found {self.where()}")
                self.take()
                self.expect("}")
                return self.call("O")
            _fail(f"LaTeX command {word!r} at position {pos} is not allowed (use \\nu, "
                  "\\kappa, \\Omega, \\frac, \\sqrt, \\cdot, \\times, \\left, \\right)")
        _fail(f"unexpected {self.where()}")

    def group(self):
        """A LaTeX argument: ``{...}`` or a single digit or symbol (``\\frac12``)."""
        self.skip_space()
        if self.is_op("{"):
            self.take()
            self.enter()
            inner = self.expr()
            self.leave()
            self.expect("}")
            return inner
        kind, word, _ = self.peek()
        if kind == "num" and len(word) > 1:  # \frac12 = 1/2: the first digit only
            _fail(f"write the argument in braces (\\frac{{1}}{{2}}), found {self.where()}")
        return self.atom()

    def call(self, name: str):
        self.expect("(")
        self.enter()
        if name == "Rational":
            num = self.signed_integer()
            self.expect(",")
            den = self.signed_integer()
            if den == 0:
                _fail("Rational(p, 0): division by zero")
            node = ("num", Fraction(num, den))
        else:
            arg = self.expr()
            if name == "O" and not _is_kappa_power(arg):
                _fail("O(...) takes a power of kappa, e.g. O(kappa^8)")
            node = (name, arg)
        self.leave()
        self.expect(")")
        return node

    def signed_integer(self) -> int:
        sign = 1
        while self.is_op("+", "-"):
            sign *= -1 if self.take()[1] == "-" else 1
        return sign * self.integer("an argument of Rational")


def _is_kappa_power(node) -> bool:
    if node == ("sym", "kappa"):
        return True
    return (node[0] == "pow" and node[1] == ("sym", "kappa") and node[2].denominator == 1
            and node[2] > 0)


def parse(text: str, syntax: str = "sympy", *, equation: bool = False,
          names: tuple[str, ...] = (), limits: TextLimits = CLAIMS_TEXT):
    """The syntax tree of ``text`` (nested tuples): length, tokens, depth, digits and exponents
    bounded (:func:`check_size` bounds what the tree would grow to; :func:`read` applies it).

    ``equation`` accepts a leading ``Omega^2 =`` (``\\Omega^2 =`` in LaTeX); ``names`` are
    further plain symbols allowed (lower-case identifiers, e.g. ``("w",)``); ``limits`` the
    bounds of the text (:data:`~dispersion.reader_limits.CLAIMS_TEXT` for text of strangers).

    >>> parse("nu^2 + 1")
    ('add', ((1, ('pow', ('sym', 'nu'), Fraction(2, 1))), (1, ('num', Fraction(1, 1)))))
    """
    if syntax not in SYNTAXES:
        _fail(f"syntax must be one of {', '.join(SYNTAXES)}, got {syntax!r}")
    if isinstance(text, str) and not text.strip():
        _fail("empty expression")
    for name in names:
        if not (isinstance(name, str) and re.fullmatch(r"[a-z]\w{0,15}", name)) or \
                name in _FUNCTIONS:
            _fail(f"names must be lower-case identifiers other than the functions, got {name!r}")
    return _Parser(text, syntax == "latex", tuple(names), limits).top(equation)


# --------------------------------------------------------------------------- series

def _has_kappa(node) -> bool:
    stack = [node]
    while stack:
        n = stack.pop()
        if n == ("sym", "kappa") or n[0] == "O":
            return True
        if n[0] in ("add", "mul"):
            stack += [child for _, child in n[1]]
        elif n[0] in ("neg", "pow", "sqrt"):
            stack.append(n[1])
    return False


def _kappa_term(node) -> tuple[int, list]:
    """``(power of kappa, [(op, factor), ...])`` of one term ``c * kappa^k``; kappa may stand
    only as a factor of the term's product, never inside a sum, a quotient or a root."""
    power, factors, stack = 0, [], [("*", node)]
    while stack:
        op, n = stack.pop()
        if op == "*" and n[0] == "neg":
            factors.append(("*", ("num", Fraction(-1))))
            stack.append(("*", n[1]))
        elif op == "*" and n[0] == "mul":
            stack += list(reversed(n[1]))
        elif op == "*" and n == ("sym", "kappa"):
            power += 1
        elif op == "*" and n[0] == "pow" and n[1] == ("sym", "kappa") and n[2].denominator == 1 \
                and n[2] > 0:
            power += int(n[2])
        elif _has_kappa(n):
            _fail("write the series as a sum of terms, each a coefficient times a power of "
                  "kappa (kappa^k), and the order term as + O(kappa^k)")
        else:
            factors.append((op, n))
    return power, factors


def series_terms(tree) -> tuple[dict[int, tuple], int | None]:
    """The coefficient trees of a series ``sum c_k kappa^k + O(kappa^m)`` and ``m`` (or None).

    Terms of equal power are added; each coefficient is checked by :func:`check_size`.
    """
    terms = tree[1] if tree[0] == "add" else ((1, tree),)
    found: dict[int, list] = {}
    order = None
    for sign, term in terms:
        if term[0] == "O":
            if order is not None:
                _fail("more than one order term O(...)")
            arg = term[1]
            order = 1 if arg == ("sym", "kappa") else int(arg[2])
            continue
        power, factors = _kappa_term(term)
        coef = ("mul", (("*", ("num", Fraction(sign))), *factors))
        found.setdefault(power, []).append((1, coef))
    out = {}
    for power, parts in sorted(found.items()):
        coef = parts[0][1] if len(parts) == 1 else ("add", tuple(parts))
        check_size(coef, f"the coefficient of kappa^{power}")
        out[power] = coef
    return out, order


# --------------------------------------------------------------------------- values

def to_fraction(tree) -> Fraction:
    """The exact value of a tree without symbols, calls or irrational powers (a rational)."""
    kind = tree[0]
    if kind == "num":
        return tree[1]
    if kind == "neg":
        return -to_fraction(tree[1])
    if kind == "pow":
        base, e = to_fraction(tree[1]), tree[2]
        if e.denominator != 1:
            _fail("not a rational number (fractional power)")
        if base == 0 and e < 0:
            _fail("division by zero")
        return base ** int(e)
    if kind == "add":
        return sum((sign * to_fraction(t) for sign, t in tree[1]), Fraction(0))
    if kind == "mul":
        value = Fraction(1)
        for op, t in tree[1]:
            x = to_fraction(t)
            if op == "/":
                if x == 0:
                    _fail("division by zero")
                value /= x
            else:
                value *= x
        return value
    if kind == "sym":
        _fail(f"a number is required here, not the symbol {tree[1]!r}")
    _fail(f"a rational number is required here ({kind}(...) is not allowed)")


def to_sympy(tree, *, evaluate: bool = True):
    """The sympy expression of a tree, built from sympy numbers and symbols only.

    ``evaluate=False`` keeps the tree's form (``2/(3*(nu - 1))`` stays so, for LaTeX); it
    does no arithmetic, so its work is linear in the tree.
    Raises :class:`InputError` for a division by zero or a non-real value (``sqrt(-1)``).
    """
    import sympy

    expr = _build(tree, sympy) if evaluate else _form(tree, sympy)
    if expr.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo):
        _fail("division by zero")
    if expr.has(sympy.I):
        _fail("not a real number (square root of a negative number)")
    return expr


def symbols() -> dict:
    """The sympy symbols of the names the reader knows, defined here once: ``nu``, ``r`` (the
    aspect ratio b/h, positive), ``kappa``, ``Omega``.

    >>> symbols()["r"].is_positive
    True
    """
    import sympy

    return {"nu": sympy.Symbol("nu"), "r": sympy.Symbol("r", positive=True),
            "kappa": sympy.Symbol("kappa"), "Omega": sympy.Symbol("Omega")}


def _symbols(sympy) -> dict:
    return symbols()


def _negate(x, sympy):
    """``-x`` without arithmetic: a number's sign, a product's leading number, else -1 * x."""
    if x.is_Number:
        return -x
    if x.is_Mul and x.args and x.args[0].is_Number:
        return sympy.Mul(-x.args[0], *x.args[1:], evaluate=False)
    return sympy.Mul(sympy.Integer(-1), x, evaluate=False)


def _form(node, sympy):
    """:func:`_build` without evaluation: sums and products flattened as written."""
    kind = node[0]
    if kind in ("num", "sym"):
        return _build(node, sympy)
    if kind == "neg":
        return _negate(_form(node[1], sympy), sympy)
    if kind == "sqrt":
        return sympy.Pow(_form(node[1], sympy), sympy.Rational(1, 2), evaluate=False)
    if kind == "O":
        return sympy.Order(_form(node[1], sympy))
    if kind == "pow":
        e = node[2]
        return sympy.Pow(_form(node[1], sympy), sympy.Rational(e.numerator, e.denominator),
                         evaluate=False)
    if kind == "add":
        terms = []
        for sign, t in node[1]:
            x = _form(t, sympy)
            x = _negate(x, sympy) if sign < 0 else x
            terms += list(x.args) if x.is_Add else [x]
        return terms[0] if len(terms) == 1 else sympy.Add(*terms, evaluate=False)
    factors = []
    for op, t in node[1]:
        x = _form(t, sympy)
        if op == "/":
            factors.append(sympy.Pow(x, sympy.Integer(-1), evaluate=False))
        else:
            factors += list(x.args) if x.is_Mul else [x]
    return factors[0] if len(factors) == 1 else sympy.Mul(*factors, evaluate=False)


def _build(node, sympy):
    kind = node[0]
    if kind == "num":
        return sympy.Rational(node[1].numerator, node[1].denominator)
    if kind == "sym":
        if node[1] == "Omega":
            _fail("Omega may appear only as Omega^2 on the left of '='")
        known = _symbols(sympy)
        return known[node[1]] if node[1] in known else sympy.Symbol(node[1])
    if kind == "neg":
        return -_build(node[1], sympy)
    if kind == "sqrt":
        return sympy.sqrt(_build(node[1], sympy))
    if kind == "O":
        return sympy.Order(_build(node[1], sympy))
    if kind == "pow":
        e = node[2]
        return sympy.Pow(_build(node[1], sympy), sympy.Rational(e.numerator, e.denominator))
    if kind == "add":
        return sympy.Add(*[s * _build(t, sympy) for s, t in node[1]])
    out = sympy.Integer(1)
    for op, t in node[1]:
        x = _build(t, sympy)
        out = out / x if op == "/" else out * x
    return out


def read(text: str, syntax: str = "sympy", *, equation: bool = False,
         names: tuple[str, ...] = ()):
    """``text`` (plain sympy-like text or LaTeX) as one sympy expression, its size checked by
    :func:`check_size` as a whole; see the module doc."""
    tree = parse(text, syntax, equation=equation, names=names)
    check_size(tree)
    return to_sympy(tree)


def read_series(text: str, syntax: str = "sympy") -> tuple[dict, int | None]:
    """A series ``[Omega^2 =] sum c_k kappa^k [+ O(kappa^m)]`` as ``({k: c_k}, m or None)``.

    Each coefficient is checked by :func:`check_size` on its own (a long series is many
    small coefficients) and built in sympy only then.

    >>> read_series(r"\\Omega^2 = \\frac{2}{1-\\nu}\\kappa^2 + O(\\kappa^4)", "latex")
    ({2: 2/(1 - nu)}, 4)
    """
    coefficients, order = series_terms(parse(text, syntax, equation=True))
    return {k: to_sympy(c) for k, c in coefficients.items()}, order


def read_number(text: str) -> Fraction:
    """A rational number written as ``0.3``, ``3/10``, ``-1e-3`` or ``Rational(3, 10)``.

    >>> read_number("1e-999999999")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: number at position 1: decimal exponent -999999999 out of range (at most 400 in size)
    """
    tree = parse(text)
    check_size(tree)
    return to_fraction(tree)


def _shown(value, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def rational(name: str, value):
    """``value`` as an exact sympy Rational, or an :class:`InputError` naming ``name``.

    The one door by which a number of the API or of a file becomes exact: ints, Fractions
    and sympy Rationals as they are; floats (also numpy's) by their shortest decimal
    (0.3 is 3/10); text by the whitelist (:func:`read_number`: ``"1/2"``, ``"0.3"``,
    ``"Rational(3, 10)"``), never by ``sympify``. NaN, infinities, bools, symbols, surds and
    any other object are refused.

    >>> rational("nu", 0.3), rational("r", "1/2")
    (3/10, 1/2)
    >>> rational("r", "__import__('os').system('touch pwned') or 2")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: r must be a finite rational number, got "__import__('os').system('touch pwned') or 2" (unexpected character "'" at position 12)
    """
    import math
    import numbers

    import sympy

    def bad(why: str = ""):
        return InputError(f"{name} must be a finite rational number, got {_shown(value)}"
                          + (f" ({why})" if why else ""))

    if isinstance(value, bool):
        raise bad()
    if isinstance(value, sympy.Basic):
        if value.is_Rational:
            return value
        raise bad()
    if isinstance(value, numbers.Integral):
        return sympy.Integer(int(value))
    if isinstance(value, numbers.Rational):  # Fraction
        return sympy.Rational(int(value.numerator), int(value.denominator))
    if isinstance(value, numbers.Real):
        x = float(value)
        if not math.isfinite(x):
            raise bad()
        q = Fraction(repr(x))  # the shortest decimal: bounded text (at most 17 digits)
        return sympy.Rational(q.numerator, q.denominator)
    if isinstance(value, str):
        try:
            q = read_number(value)
        except InputError as exc:
            raise bad(str(exc)) from None
        return sympy.Rational(q.numerator, q.denominator)
    raise bad()


def as_sympy(name: str, value):
    """``value`` as a sympy object when it is a finite number (int, float, Fraction, complex,
    numpy's) or already a sympy expression; anything else (text, a list, a tuple, a dict, a
    set, NaN, an infinity) is an :class:`InputError` naming ``name``.

    ``sympy.sympify(x, strict=True)`` refuses text but not containers: a tuple, a dict or a set
    becomes a sympy container whose items are sympified without ``strict``, so a string inside
    one is parsed (``sympify(("__import__('os')...",), strict=True)`` runs it). Here sympy sees
    numbers only.

    >>> as_sympy("kappa", 0.5), as_sympy("kappa", 2)
    (0.500000000000000, 2)
    >>> as_sympy("kappa", ("__import__('os').system('touch pwned')",))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: kappa must be a number or a sympy expression, got tuple
    """
    import cmath
    import numbers

    import sympy

    if isinstance(value, sympy.Basic):
        return value
    if isinstance(value, numbers.Number) and not isinstance(value, bool):
        if not isinstance(value, numbers.Rational) and not cmath.isfinite(complex(value)):
            raise InputError(f"{name} must be a finite number, got {value!r}")
        return sympy.sympify(value, strict=True)  # a number: never text, never a container
    raise InputError(f"{name} must be a number or a sympy expression, got "
                     f"{type(value).__name__}")
