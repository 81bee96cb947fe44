"""Size limits of text read as numbers or expressions, and what an expression would grow to,
checked on its tree.

Text from strangers (claims files, number options, a report folder's JSON, strings handed to
the API) is read by :mod:`dispersion.reader`; these rules bound the work before any
arithmetic:

* the text: at most :data:`MAX_LENGTH` characters, ASCII only, at most :data:`MAX_TOKENS`
  tokens (numbers, names, operators) and :data:`MAX_DEPTH` levels of nesting (parentheses,
  braces, calls, signs);
* a number: at most :data:`MAX_DIGITS` digits, a decimal exponent (``1e-3``) of at most
  :data:`MAX_DECIMAL_EXPONENT`;
* a power: its exponent is a written integer or fraction (``^2``, ``^{-2}``, ``**(1/2)``) of
  size at most :data:`MAX_EXPONENT` (the highest series order the toolkit derives is
  kappa^128), never an expression (``2**2**2`` is refused, so is ``9**9**9``);
* an expression (a coefficient; a series is checked coefficient by coefficient): upper
  bounds of the degree (:data:`MAX_DEGREE`), of the bits of its numbers (:data:`MAX_BITS`)
  and of its terms (:data:`MAX_TERMS`) once put over one denominator and expanded, and of
  the numbers under a root (:data:`MAX_ROOT_BITS`), computed on the tree before sympy sees
  it. The limits are a few times what the exact series to kappa^32 needs; within them
  sympy's ``factor`` and ``cancel`` of a coefficient take at most about a second.

"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from dispersion.errors import InputError

__all__ = ["MAX_LENGTH", "MAX_TOKENS", "MAX_DEPTH", "MAX_DIGITS", "MAX_DECIMAL_EXPONENT",
           "MAX_EXPONENT", "MAX_DEGREE", "MAX_BITS", "MAX_TERMS", "MAX_ROOT_BITS",
           "TextLimits", "CLAIMS_TEXT", "SERIES_TEXT", "check_size"]

#: Characters of one expression. The paper's longest series (eq 17 in LaTeX) has 170; the
#: exact S0 series to kappa^32 written out as sympy prints it has 6700.
MAX_LENGTH = 20_000
#: Tokens of one expression (numbers, names, operators): bounds the number of terms.
MAX_TOKENS = 6000
#: Nesting levels (parentheses, braces, calls, signs); the parser recurses a few frames a level.
MAX_DEPTH = 40
#: Digits of one number as written (integer and fraction part together).
MAX_DIGITS = 60
#: Largest decimal exponent of a number such as ``1e-3`` (floats end near 1e308).
MAX_DECIMAL_EXPONENT = 400
#: Largest exponent written after ``^``/``**`` (numerator and denominator of a fraction).
MAX_EXPONENT = 256
#: Largest degree (numerator plus denominator, all symbols) an expression may reach. The
#: coefficients of the exact series to kappa^32, written out, reach 61.
MAX_DEGREE = 128
#: Largest size in bits of the numbers an expression may reach (about 1200 decimal digits);
#: the exact series to kappa^32 reaches about 3000.
MAX_BITS = 4096
#: Most terms an expression (one coefficient) may expand to, numerator or denominator; the
#: exact series to kappa^32 reaches 32. Factoring is the dearest step sympy takes on a
#: printed coefficient, and it grows fast with the terms and digits of multivariate input.
MAX_TERMS = 64
#: Largest size in bits of a number under a root (``sqrt``, a fractional power): sympy looks
#: for perfect powers and small factors there, fast below this size.
MAX_ROOT_BITS = 256


@dataclass(frozen=True)
class TextLimits:
    """What the tokenizer accepts of one text: characters, tokens, digits of one number."""

    length: int
    tokens: int
    digits: int


#: Text of strangers (claims files, options, a report folder's JSON, API strings).
CLAIMS_TEXT = TextLimits(MAX_LENGTH, MAX_TOKENS, MAX_DIGITS)
#: A series coefficient as the toolkit writes it (``SeriesTable`` of ``dispersion series``),
#: read back for its LaTeX form without evaluating it: the exact series to kappa^128 (the
#: highest order derived) has coefficients of up to 25,204 characters and numbers of up to
#: 210 digits. Linear work: the tree is built unevaluated, its exponents bounded as always.
SERIES_TEXT = TextLimits(length=100_000, tokens=40_000, digits=1000)


def _fail(message: str) -> None:
    raise InputError(message)


def _bits(q: Fraction) -> int:
    return abs(q.numerator).bit_length() + q.denominator.bit_length()


def _capped_comb(n: int, k: int) -> int:
    """``C(n, k)``, capped just above :data:`MAX_TERMS` (no huge intermediate numbers)."""
    out = 1
    for i in range(min(k, n - k)):
        out = out * (n - i) // (i + 1)
        if out > MAX_TERMS:
            return MAX_TERMS + 1
    return out


def _size(node) -> tuple[int, ...]:
    """Upper bounds of ``node`` written over one denominator and expanded: ``(numerator
    degree, denominator degree, numerator bits, denominator bits, numerator terms,
    denominator terms)`` (the rule of the module doc; term counts capped at MAX_TERMS + 1)."""
    kind = node[0]
    cap = MAX_TERMS + 1
    if kind == "num":
        q = node[1]
        return 0, 0, abs(q.numerator).bit_length(), q.denominator.bit_length(), 1, 1
    if kind == "sym":
        return 1, 0, 1, 1, 1, 1
    if kind in ("neg", "sqrt", "O"):
        return _size(node[1])
    if kind == "pow":
        nd, dd, nb, db, nt, dt = _size(node[1])
        e = node[2]
        k = -(-abs(e.numerator) // e.denominator)  # ceil(|e|)
        grow = (nd + dd + 1).bit_length()  # binomial-like growth of expanded coefficients
        # an expanded sum of t terms to the power k has at most C(t + k - 1, k) terms
        nt, dt = (_capped_comb(t + k - 1, k) if t > 1 else 1 for t in (nt, dt))
        out = (nd * k, dd * k, (nb + grow) * k, (db + grow) * k, nt, dt)
        return (out[1], out[0], out[3], out[2], out[5], out[4]) if e < 0 else out
    parts = [_size(child) for _, child in node[1]]
    if kind == "mul":
        nd = dd = nb = db = 0
        nt = dt = 1
        for (op, _), (a, b, c, d, t, u) in zip(node[1], parts):
            if op == "/":
                a, b, c, d, t, u = b, a, d, c, u, t
            nd, dd, nb, db = nd + a, dd + b, nb + c, db + d
            nt, dt = min(nt * t, cap), min(dt * u, cap)
        return nd, dd, nb, db, nt, dt
    # a sum over the common denominator: each numerator times the other denominators
    dd, db = sum(p[1] for p in parts), sum(p[3] for p in parts)
    nd = max(p[0] - p[1] for p in parts) + dd
    nb = max(p[2] - p[3] for p in parts) + db + len(parts).bit_length()
    dt = 1
    for p in parts:
        dt = min(dt * p[5], cap)
    nt = min(sum(min(p[4] * dt // p[5], cap) for p in parts), cap)
    return nd, dd, nb, db, nt, dt


def check_size(tree, what: str = "the expression") -> None:
    """Refuse a tree whose degree, numbers or expanded terms exceed the limits (module doc)."""
    stack = [tree]
    while stack:  # roots first: their arguments are small numbers or symbols
        node = stack.pop()
        if node[0] == "sqrt" or (node[0] == "pow" and node[2].denominator != 1):
            _, _, nb, db, _, _ = _size(node[1])
            if nb + db > MAX_ROOT_BITS:
                _fail(f"{what} takes a root of numbers of {nb + db} bits, more than the limit "
                      f"of {MAX_ROOT_BITS}")
        if node[0] in ("add", "mul"):
            stack += [child for _, child in node[1]]
        elif node[0] in ("neg", "pow", "sqrt", "O"):
            stack.append(node[1])
    nd, dd, nb, db, nt, dt = _size(tree)
    if nd + dd > MAX_DEGREE:
        _fail(f"{what} would reach degree {nd + dd}, more than the limit of {MAX_DEGREE}")
    if nb + db > MAX_BITS:
        _fail(f"{what} would reach numbers of {nb + db} bits, more than the limit of "
              f"{MAX_BITS}")
    if max(nt, dt) > MAX_TERMS:
        _fail(f"{what} would expand to more than {MAX_TERMS} terms (write it factored, or "
              "split it)")
