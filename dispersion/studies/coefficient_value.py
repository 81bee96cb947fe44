"""Exact value of a series coefficient written as text, at a rational nu (no ``eval``).

The race against Maxima (:mod:`dispersion.studies.series_race`) compares every coefficient of
both programs exactly: ours and Maxima's linear syntax (integers, ``nu``, ``+ - * / ^ **``,
parentheses, integer exponents) are read by a whitelist recursive-descent parser over
:class:`fractions.Fraction`. Maxima's coefficients at kappa^64 have numbers of hundreds of
digits, beyond the bounds of the claims reader (:mod:`dispersion.claims.reader`), so this
reader bounds only the nesting and the exponents.
"""
from __future__ import annotations

import re
from fractions import Fraction

from dispersion.errors import InputError

__all__ = ["coefficient_value"]

_VALUE_TOKEN = re.compile(r"\s*(?:(\d+)|(nu)|(\*\*|[-+*/^()]))")
#: Bounds of a coefficient text: nesting of parentheses and the size of an exponent.
_VALUE_DEPTH = 100
_VALUE_EXPONENT = 1024


def coefficient_value(text: str, nu: Fraction) -> Fraction:
    """Exact value of a coefficient string (ours or Maxima's linear syntax) at a rational nu.

    Read by a whitelist recursive-descent parser over exact fractions (integers, ``nu``,
    ``+ - * / ^ **`` and parentheses; integer exponents); nothing is ``eval``-ed. Anything
    else is an :class:`InputError` naming the position.

    >>> coefficient_value("-2/(nu-1)", Fraction(3, 10))
    Fraction(20, 7)
    >>> coefficient_value("2*nu^2 - (1 - nu)^-1", Fraction(1, 2))
    Fraction(-3, 2)
    >>> coefficient_value("__import__('os')", Fraction(0))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: unexpected text at position 0 of a coefficient: "__import__('"
    """
    return _ValueReader(text, nu).read()


class _ValueReader:
    """expr := term (('+'|'-') term)*; term := unary (('*'|'/') unary)*;
    unary := ('+'|'-') unary | power; power := atom (('^'|'**') signed integer)?;
    atom := integer | nu | '(' expr ')'."""

    def __init__(self, text: str, nu: Fraction):
        self.nu, self.tokens, pos = nu, [], 0
        if not isinstance(text, str):
            raise InputError(f"a coefficient must be text, got {type(text).__name__}")
        while pos < len(text):
            m = _VALUE_TOKEN.match(text, pos)
            if m is None or m.end() == pos:
                if text[pos:].strip() == "":
                    break
                raise InputError(f"unexpected text at position {pos} of a coefficient: "
                                 f"{text[pos:pos + 12]!r}")
            self.tokens.append((m.group(1) or m.group(2) or m.group(3), m.start(m.lastindex),
                                m.group(1)))
            pos = m.end()
        self.i, self.depth = 0, 0

    def _peek(self):
        return self.tokens[self.i][0] if self.i < len(self.tokens) else None

    def _fail(self, what: str):
        where = (f"at position {self.tokens[self.i][1]}" if self.i < len(self.tokens)
                 else "at the end")
        raise InputError(f"{what} {where} of a coefficient")

    def read(self) -> Fraction:
        if not self.tokens:
            raise InputError("empty coefficient")
        value = self._expr()
        if self.i != len(self.tokens):
            self._fail(f"unexpected {self._peek()!r}")
        return value

    def _expr(self) -> Fraction:
        value = self._term()
        while self._peek() in ("+", "-"):
            op = self.tokens[self.i][0]
            self.i += 1
            value = value + self._term() if op == "+" else value - self._term()
        return value

    def _term(self) -> Fraction:
        value = self._unary()
        while self._peek() in ("*", "/"):
            op = self.tokens[self.i][0]
            self.i += 1
            x = self._unary()
            if op == "/":
                if x == 0:
                    self._fail("division by zero")
                value /= x
            else:
                value *= x
        return value

    def _unary(self) -> Fraction:
        sign = 1
        while self._peek() in ("+", "-"):
            sign = -sign if self.tokens[self.i][0] == "-" else sign
            self.i += 1
        return sign * self._power()

    def _power(self) -> Fraction:
        base = self._atom()
        if self._peek() not in ("^", "**"):
            return base
        self.i += 1
        sign = 1
        paren = self._peek() == "("
        self.i += paren
        while self._peek() in ("+", "-"):
            sign = -sign if self.tokens[self.i][0] == "-" else sign
            self.i += 1
        if self.i >= len(self.tokens) or self.tokens[self.i][2] is None:
            self._fail("an integer exponent is required")
        e = sign * int(self.tokens[self.i][0])
        self.i += 1
        if paren:
            if self._peek() != ")":
                self._fail("')' expected")
            self.i += 1
        if abs(e) > _VALUE_EXPONENT:
            self._fail(f"exponent {e} out of range [-{_VALUE_EXPONENT}, {_VALUE_EXPONENT}]")
        if base == 0 and e < 0:
            self._fail("division by zero")
        return base ** e

    def _atom(self) -> Fraction:
        tok = self._peek()
        if tok is None:
            self._fail("unexpected end")
        if tok == "nu":
            self.i += 1
            return self.nu
        if self.tokens[self.i][2] is not None:
            self.i += 1
            return Fraction(int(tok))
        if tok == "(":
            self.depth += 1
            if self.depth > _VALUE_DEPTH:
                self._fail(f"nesting deeper than {_VALUE_DEPTH}")
            self.i += 1
            value = self._expr()
            if self._peek() != ")":
                self._fail("')' expected")
            self.i += 1
            self.depth -= 1
            return value
        self._fail(f"unexpected {tok!r}")
