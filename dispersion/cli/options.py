"""Typed number options of the command line: one grammar, bounded, each naming its range.

Every number option of every command reads its text with the claims reader
(:func:`dispersion.claims.reader.read_number`): ``0.3``, ``3/10``, ``-1e-3``, ``(1+2)/10``,
``Rational(3, 10)`` are the same forms everywhere, nothing is evaluated, and the size is
bounded before any arithmetic (at most 60 digits and a decimal exponent of at most 400, so
``--nu 1e-999999999`` is refused at once). On failure the message names the option and its
range, and argparse prints it on one line with exit status 2.

A material is read here too, once for every command (:func:`material_from_args`): a table
name, the bulk speeds, or Young's modulus, Poisson's ratio and density, with errors naming the
options.

>>> rational("nu", -1, 0.5, lo_open=True, hi_open=True)("3/10")
Fraction(3, 10)
>>> real("omega-max", 0, 200, lo_open=True)("1/2")
0.5
>>> integer("count", 2, 10)("11")
Traceback (most recent call last):
...
argparse.ArgumentTypeError: count must be an integer in [2, 10], got 11
"""
from __future__ import annotations

import argparse
import math
import re
from fractions import Fraction

from dispersion.errors import InputError, did_you_mean

__all__ = ["rational", "real", "integer", "span", "choice", "lazy_help", "length", "UNITS",
           "material_from_args", "masses_from_args", "thickness_hints", "frequencies", "given",
           "check_applies",
           "cli_words"]

#: Most digits of an integer option (the largest meaningful count has 7).
MAX_INT_DIGITS = 18


def span(lo=None, hi=None, lo_open: bool = False, hi_open: bool = False) -> str:
    """``[lo, hi]``, ``(lo, hi]``, ... as the messages write a range (None: unbounded)."""
    left = "(" if lo_open or lo is None else "["
    right = ")" if hi_open or hi is None else "]"

    def end(x):  # a float end in its short form: 1e+12, not 1000000000000.0
        return f"{x:g}" if isinstance(x, float) and len(repr(x)) > len(f"{x:g}") else x
    return f"{left}{'-inf' if lo is None else end(lo)}, {'inf' if hi is None else end(hi)}{right}"


def _exact(bound) -> Fraction:
    """A range end as a Fraction: ints, floats, "1/2", Fractions and sympy Rationals. A float
    end means the number it is written as (0.99 is 99/100, not the binary float below it,
    which would refuse ``--courant 0.99`` against the range "(0, 0.99]").

    >>> _exact(0.99) == Fraction(99, 100)
    True
    """
    if isinstance(bound, float):
        return Fraction(repr(bound))
    if isinstance(bound, (int, str, Fraction)):
        return Fraction(bound)
    return Fraction(int(bound.p), int(bound.q))  # sympy.Rational


def _in(value, lo, hi, lo_open, hi_open) -> bool:
    below = lo is not None and (value <= _exact(lo) if lo_open else value < _exact(lo))
    above = hi is not None and (value >= _exact(hi) if hi_open else value > _exact(hi))
    return not (below or above)


def _shown(q: Fraction) -> str:
    """A value in a message: an integer, else the shortest float that reads back (repr), so
    a value just outside a range never prints as its end.

    >>> _shown(Fraction(99000001, 100000000)), _shown(Fraction(10) ** -500)
    ('0.99000001', 'about 1e-500')
    """
    if q.denominator == 1 and abs(q.numerator) < 10**16:
        return str(q.numerator)
    if not Fraction(10) ** -300 < abs(q) < Fraction(10) ** 300:  # beyond the floats
        digits = len(str(abs(q.numerator))) - len(str(q.denominator))
        return f"{'-' if q < 0 else ''}about 1e{digits:+d}"
    return repr(float(q))


def rational(name: str, lo=None, hi=None, *, lo_open: bool = False, hi_open: bool = False,
             symbol: str | None = None):
    """argparse ``type``: an exact :class:`~fractions.Fraction` in the range (or ``symbol``).

    The range is checked here when given; options whose range depends on others leave it to
    the API, which raises :class:`~dispersion.errors.InputError` with the same wording.
    """
    where = "" if lo is None and hi is None else f" in {span(lo, hi, lo_open, hi_open)}"

    def parse(text: str):
        if symbol is not None and text.strip() == symbol:
            return symbol
        from dispersion.claims.reader import read_number

        try:
            value = read_number(text)
        except InputError as exc:
            or_symbol = f" or {symbol!r}" if symbol else ""
            raise argparse.ArgumentTypeError(
                f"{name} must be a number such as 0.3 or 3/10{or_symbol}{where}, got "
                f"{text[:40]!r} ({exc})") from None
        if not _in(value, lo, hi, lo_open, hi_open):
            raise argparse.ArgumentTypeError(f"{name} must lie in {span(lo, hi, lo_open, hi_open)}, "
                                             f"got {_shown(value)}")
        return value
    return parse


def real(name: str, lo=None, hi=None, *, lo_open: bool = False, hi_open: bool = False):
    """argparse ``type``: a float read exactly as :func:`rational` reads it, then rounded.

    A value beyond the floats (``1e400``) is refused rather than turned into ``inf``.
    """
    exact = rational(name, lo, hi, lo_open=lo_open, hi_open=hi_open)

    def parse(text: str) -> float:
        value = exact(text)
        try:
            return float(value)
        except OverflowError:
            raise argparse.ArgumentTypeError(f"{name} must be a finite number, got "
                                             f"{text[:40]!r}") from None
    return parse


#: Units a number may carry on the command line, by quantity: each unit's size in the base
#: unit of its kind (metres, kHz), exact. One table for every option: ``--thickness 10mm``,
#: ``--h 0.5cm``, ``--frequency 200kHz`` are read by the same rule (:func:`split_unit`).
UNITS = {
    "length": {"m": Fraction(1), "cm": Fraction(1, 100), "mm": Fraction(1, 1000),
               "um": Fraction(1, 10**6), "\u00b5m": Fraction(1, 10**6)},
    "frequency": {"Hz": Fraction(1, 1000), "kHz": Fraction(1), "MHz": Fraction(1000)},
}


def split_unit(text: str, kind: str) -> tuple[str, str | None]:
    """``text`` as (number, unit of :data:`UNITS` [kind] or None); any letter case
    (``200khz``); the unit ends the text, spaces before it allowed.

    >>> split_unit("10mm", "length"), split_unit("2e5 Hz", "frequency"), split_unit("3", "length")
    (('10', 'mm'), ('2e5', 'Hz'), ('3', None))
    """
    word = str(text).strip()
    for unit in sorted(UNITS[kind], key=len, reverse=True):
        if word.lower().endswith(unit.lower()) and len(word) > len(unit):
            number = word[:-len(unit)].rstrip()
            # "1e-3m": the number must end in a digit, a point or a bracket, never in "e"
            if number and (number[-1].isdigit() or number[-1] in ".)"):
                return number, unit
    return word, None


class Quantity(float):
    """A float read from the command line in its option's unit; ``unit`` is the unit the
    user typed (None: a bare number, taken in the option's unit)."""

    unit: str | None = None


def length(name: str, unit: str, lo=None, hi=None, *, lo_open: bool = False,
           hi_open: bool = False):
    """argparse ``type``: a length in ``unit`` (``"mm"`` or ``"m"``), with an optional unit
    of :data:`UNITS` (``10mm``, ``1cm``, ``0.003m``); the range is in ``unit``, and the
    message names both the range and the units accepted.

    >>> length("--thickness", "mm", 0, lo_open=True)("1cm"), length("--h", "m", 0)("5mm")
    (10.0, 0.005)
    >>> length("--thickness", "mm", 0, 1000, lo_open=True)("2m")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: --thickness must lie in (0, 1000] mm, got 2000 mm (2m)
    """
    units = UNITS["length"]
    scale = units[unit]
    exact = rational(name, hi_open=hi_open)  # the grammar of numbers; the range after units

    def parse(text: str) -> float:
        number, typed = split_unit(text, "length")
        try:
            value = exact(number) * (units[typed] / scale if typed else 1)
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(
                f"{name} must be a length in {unit} such as 3 or 3/10, or with a unit "
                f"({', '.join(u for u in units if u.isascii())}: 10mm), got {text[:40]!r}") from None
        if not _in(value, lo, hi, lo_open, hi_open):
            raise argparse.ArgumentTypeError(
                f"{name} must lie in {span(lo, hi, lo_open, hi_open)} {unit}, got "
                f"{_shown(value)} {unit}" + (f" ({text.strip()[:40]})" if typed else ""))
        try:
            out = Quantity(float(value))
        except OverflowError:
            raise argparse.ArgumentTypeError(f"{name} must be a finite length, got "
                                             f"{text[:40]!r}") from None
        out.unit = typed
        return out
    return parse


def integer(name: str, lo: int | None = None, hi: int | None = None, *, valid=None):
    """argparse ``type``: an integer written in decimal, in ``[lo, hi]``.

    ``valid`` (a string or a function returning one) states the range in the message
    instead, for ranges stated elsewhere (read only when a message is written).
    """
    def rule() -> str:
        if valid is not None:
            return valid() if callable(valid) else valid
        return f"in {span(lo, hi)}" if lo is not None or hi is not None else ""

    def parse(text: str) -> int:
        word = text.strip()
        if not re.fullmatch(r"[+-]?\d{1,%d}" % MAX_INT_DIGITS, word):
            raise argparse.ArgumentTypeError(f"{name} must be an integer {rule()}".rstrip()
                                             + f", got {text[:40]!r}")
        value = int(word)
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"{name} must be an integer {rule()}, got {value}")
        return value
    return parse


def choice(option: str, names):
    """argparse ``type``: one of the names ``names()`` returns (read from a registry when a
    value is checked, never copied), any letter case; otherwise the names and the nearest.

    >>> choice("--mass", lambda: ("consistent", "singular"))("Singular")
    'singular'
    >>> choice("--mass", lambda: ("consistent", "singular"))("singlar")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: --mass must be one of consistent, singular, got 'singlar'; did you mean 'singular'?
    """
    def parse(text: str) -> str:
        valid = tuple(names())
        word = text.strip()
        for name in valid:
            if name.lower() == word.lower():
                return name
        raise argparse.ArgumentTypeError(f"{option} must be one of {', '.join(valid)}, got "
                                         f"{text[:40]!r}{did_you_mean(word, valid)}")
    return parse


class _LazyHelp(str):
    """A help text whose ``{names}`` are filled in only when help is printed (argparse formats
    a help text with ``%``), so that building a parser reads no registry."""

    def __new__(cls, template: str, names):
        obj = super().__new__(cls, template.replace("{names}", "..."))
        obj.template, obj.names = template, names
        return obj

    def __mod__(self, params):
        return self.template.replace("{names}", ", ".join(self.names())) % params


def lazy_help(template: str, names) -> str:
    """Help text ``template`` with ``{names}`` replaced by ``names()`` when help is printed.

    >>> lazy_help("mass rule: {names}", lambda: ("a", "b")) % {}
    'mass rule: a, b'
    """
    return _LazyHelp(template, names)


#: Option of each input of :func:`dispersion.materials.materials.user_material` (E in GPa there).
MATERIAL_OPTIONS = {"c_L": "--cl", "c_T": "--ct", "rho": "--rho", "E": "--youngs-modulus",
                    "nu": "--nu"}


def material_from_args(args: argparse.Namespace, default: str | None = None):
    """The :class:`~dispersion.materials.materials.Material` of a command's options.

    ``--material NAME`` (a row of :data:`dispersion.materials.materials.MATERIALS`), or user values
    ``--cl/--ct[/--rho]`` (m/s, kg/m^3) or ``--youngs-modulus/--nu/--rho`` (GPa, -, kg/m^3);
    ``--nu`` counts as a material input only beside ``--youngs-modulus`` (elsewhere it is the
    dimensionless Poisson's ratio of the run). A command without some of these options simply
    lacks them. Nothing given: the table's ``default`` (None: no material). A name with user
    values, or user values that do not fix one material, are refused naming the options.

    >>> args = argparse.Namespace(material=None, cl=6000.0, ct=3000.0)
    >>> material_from_args(args).nu
    0.3333333333333333
    >>> material_from_args(argparse.Namespace(material="steel", cl=6000.0))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --material must not be combined with user values (--cl)
    >>> material_from_args(argparse.Namespace(cl=6000.0))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: material inputs (--cl) do not form one of (--youngs-modulus, nu, --rho), (--cl, --ct), (--cl, --ct, --rho)
    """
    from dispersion.materials.materials import material, user_material

    values = {key: getattr(args, opt[2:].replace("-", "_"), None)
              for key, opt in MATERIAL_OPTIONS.items()}
    if values["E"] is None:
        values["nu"] = None  # Poisson's ratio of a dimensionless run, not a material input
    given = [MATERIAL_OPTIONS[k] for k, v in values.items() if v is not None]
    name = getattr(args, "material", None)
    if name:
        if given:
            raise InputError(f"--material must not be combined with user values "
                             f"({', '.join(given)})")
        return material(name)
    if not given:
        return None if default is None else material(default)
    from dispersion.materials.unit_mixups import unit_mixups

    # valid, but likely not what was meant: said after the run (an error states them itself)
    args.unit_hints = list(getattr(args, "unit_hints", None) or ()) + [
        cli_words(h) for h in unit_mixups(c_L=values["c_L"], c_T=values["c_T"],
                                          rho=values["rho"], E_gpa=values["E"])]
    if values["E"] is not None:
        values["E"] = values["E"] * 1e9  # GPa on the command line, Pa in the API
    try:
        return user_material(**values)
    except InputError as exc:
        msg = str(exc)
        for key, opt in MATERIAL_OPTIONS.items():
            if key != "nu":  # "nu" in a message is Poisson's ratio, whichever input fixed it
                msg = re.sub(rf"\b{key}\b", opt, msg)
        raise InputError(msg) from None


def thickness_hints(args: argparse.Namespace) -> None:
    """Add to ``args.unit_hints`` a line if ``--thickness`` was a bare number that is
    implausible in mm yet plausible in another unit (``--thickness 0.003``: metres?); a value
    given with its unit (``0.003m``) is taken as written."""
    value = getattr(args, "thickness", None)
    if not isinstance(value, Quantity) or value.unit is not None:
        return
    from dispersion.materials.unit_mixups import unit_mixups

    hints = [cli_words(h) + f"; give the unit to be sure (--thickness {float(value):g}m)"
             for h in unit_mixups(thickness_mm=float(value))]
    args.unit_hints = list(getattr(args, "unit_hints", None) or ()) + hints


def masses_from_args(args: argparse.Namespace) -> list | None:
    """The mass rules of ``--mass NAME`` and ``--mass-rule FILE`` (user rules read from TOML),
    in that order; None when neither is given (the command's default rules)."""
    rules = list(getattr(args, "mass", None) or ())
    if getattr(args, "mass_rule", None):
        from dispersion.mass_rules.mass_rule_file import read_rule_file

        rules += [read_rule_file(path) for path in args.mass_rule]
    return rules or None


# ---------------------------------------------------------------------- frequency lists

#: Most frequencies of one request (a grid's COUNT included).
MAX_FREQUENCIES = 100_000
_UNITS = UNITS["frequency"]
_VALUE = re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d{1,3})?$")


def _value(text: str, option: str, units: dict | None) -> float:
    number, unit = split_unit(text, "frequency") if units else (text.strip(), None)
    if not _VALUE.match(number):
        allowed = " with an optional unit (Hz, kHz, MHz)" if units else ""
        raise InputError(f"{option} must be numbers{allowed}, lists a,b,c or grids "
                         f"START:STOP:COUNT; got {text[:40]!r}")
    out = Quantity(float(number) * (float(units[unit]) if unit else 1.0))
    out.unit = unit  # a hint reads it: a unit typed is not second-guessed
    return out


def _typed(value: float, unit: str | None) -> Quantity:
    out = Quantity(value)
    out.unit = unit
    return out


def frequencies(text: str, option: str, units: dict | None = _UNITS) -> list[float]:
    """Numbers, lists and ``START:STOP:COUNT`` grids of ``text`` (kHz unless a unit is given;
    a grid has both ends, so COUNT >= 2).

    >>> frequencies("200", "--frequency"), frequencies("0.1MHz,150", "--frequency")
    ([200.0], [100.0, 150.0])
    >>> frequencies("10kHz:1MHz:3", "--frequency")
    [10.0, 505.0, 1000.0]
    >>> frequencies("100:200:1", "--frequency")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --frequency: COUNT of START:STOP:COUNT must be an integer in [2, 100000] (both ends are included), got 1
    """
    out: list[float] = []
    for token in str(text).split(","):
        parts = token.split(":")
        if len(parts) == 1:
            out.append(_value(parts[0], option, units))
        elif len(parts) == 3:
            lo, hi = _value(parts[0], option, units), _value(parts[1], option, units)
            if not re.fullmatch(r"\s*\d{1,7}\s*", parts[2]) or not \
                    2 <= int(parts[2]) <= MAX_FREQUENCIES:
                raise InputError(f"{option}: COUNT of START:STOP:COUNT must be an integer in "
                                 f"[2, {MAX_FREQUENCIES}] (both ends are included), got "
                                 f"{parts[2].strip()[:20]}")
            if not hi > lo:
                raise InputError(f"{option}: a grid START:STOP:COUNT needs STOP > START, got "
                                 f"{token.strip()[:40]!r}")
            count = int(parts[2])
            out += [lo + (hi - lo) * i / (count - 1) for i in range(count - 1)] + [hi]
            out[-count:] = [_typed(v, lo.unit) for v in out[-count:]]
        else:
            raise InputError(f"{option} must be numbers, lists a,b,c or grids START:STOP:COUNT;"
                             f" got {token[:40]!r}")
        if len(out) > MAX_FREQUENCIES:
            raise InputError(f"{option} must give at most {MAX_FREQUENCIES} values")
    if not all(math.isfinite(v) and v > 0 for v in out):
        raise InputError(f"{option} values must be finite and > 0, got {text[:40]!r}")
    return out


# ---------------------------------------------------------------------- one grammar

def given(args: argparse.Namespace, dest: str) -> bool:
    """True if the option stored in ``dest`` was given (its default is None, False or []; a
    given 0 counts).

    >>> given(argparse.Namespace(gamma_s=0), "gamma_s"), given(argparse.Namespace(x=[]), "x")
    (True, False)
    """
    value = getattr(args, dest, None)
    return not (value is None or value is False or (isinstance(value, list) and not value))


def angles(text) -> list[float]:
    """Directions in degrees of ``--angle``: numbers, lists ``a,b,c`` and grids
    ``START:STOP:COUNT`` (both ends), each in [-360, 360], at most
    :data:`dispersion.defaults.MAX_ANGLES`.

    >>> angles("30"), angles("0:90:4"), angles("-45,0,45")
    ([30.0], [0.0, 30.0, 60.0, 90.0], [-45.0, 0.0, 45.0])
    """
    from dispersion.defaults import MAX_ANGLES

    typed = real("--angle", -360, 360)

    def value(text):
        try:
            return typed(text)
        except argparse.ArgumentTypeError as exc:   # read after parsing: one line, exit 2
            raise InputError(str(exc)) from None

    out: list[float] = []
    for token in str(text).split(","):
        parts = token.split(":")
        if len(parts) == 1:
            out.append(value(parts[0]))
        elif len(parts) == 3:
            lo, hi = value(parts[0]), value(parts[1])
            count = parts[2].strip()
            if not (count.isdigit() and len(count) <= 4 and 2 <= int(count) <= MAX_ANGLES):
                raise InputError(f"--angle: COUNT of START:STOP:COUNT must be an integer in "
                                 f"[2, {MAX_ANGLES}] (both ends are included), got {count[:20]}")
            if not hi > lo:
                raise InputError(f"--angle: a grid START:STOP:COUNT needs STOP > START, got "
                                 f"{token.strip()[:40]!r}")
            n = int(count)
            out += [lo + (hi - lo) * i / (n - 1) for i in range(n - 1)] + [hi]
        else:
            raise InputError(f"--angle must be numbers, lists a,b,c or grids START:STOP:COUNT "
                             f"in degrees; got {token[:40]!r}")
        if len(out) > MAX_ANGLES:
            raise InputError(f"--angle must give at most {MAX_ANGLES} directions")
    return out


def check_applies(args: argparse.Namespace, rules) -> None:
    """Refuse, in one line, every option given where it does not apply.

    ``rules``: ``(option, applies(args) -> bool, where it applies)`` for every option whose
    use depends on the others. The grammar test reads the same rules.

    >>> rules = [("--courant", lambda a: a.scheme is not None, "with --scheme")]
    >>> check_applies(argparse.Namespace(courant=0.5, scheme=None), rules)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --courant applies only with --scheme
    """
    for option, applies, where in rules:
        if given(args, option[2:].replace("-", "_")) and not applies(args):
            raise InputError(f"{option} applies only {where}")


#: Python parameters of the package functions and the options that set them. Names with an
#: underscore or a space are replaced wherever they stand; plain words (nu, p, material, ...)
#: only as the subject that starts a message, where they cannot be read as prose.
PARAMETER_OPTIONS = {
    "thickness_mm": "--thickness", "thickness": "--thickness",
    "frequency_khz": "--frequency", "fd_mhz_mm": "--fd",
    "kappa_min": "--kappa-min", "kappa_max": "--kappa-max", "omega_max": "--omega-max",
    "count": "--count", "courant": "--courant", "scheme": "--scheme", "gamma_s": "--gamma-s",
    "masses": "--mass", "mass": "--mass", "contact": "--contact", "model": "--model",
    "degree p": "--p", "control points n": "--n", "c_L": "--cl", "c_T": "--ct",
    "E_gpa": "--youngs-modulus", "E": "--youngs-modulus", "rho": "--rho", "nu": "--nu",
    "r": "--r", "p": "--p", "n": "--n", "material": "--material", "order": "--order",
    "branch": "--branch", "mode": "--mode-shape", "h": "--h",
}


def cli_words(message: str, options: dict | None = None) -> str:
    """``message`` of the package with its parameter names replaced by the command's options.

    >>> cli_words("kappa_max must exceed kappa_min >= 0, got [1, 1]")
    '--kappa-max must exceed --kappa-min >= 0, got [1, 1]'
    >>> cli_words("nu must not be given with a material (nu = 0.29 follows from c_L)")
    '--nu must not be given with a material (nu = 0.29 follows from --cl)'
    """
    words = PARAMETER_OPTIONS if options is None else options
    for name in sorted(words, key=len, reverse=True):
        option = words[name]
        if "_" in name or " " in name:
            message = re.sub(rf"(?<![-\w]){re.escape(name)}(?![\w])", option, message)
        elif re.match(rf"{re.escape(name)}(?![\w])", message):
            message = option + message[len(name):]
    return message


#: The mode families ``--modes`` names (S, A, SH of a symmetric plate; L, M of a layered one).
FAMILIES = ("S", "A", "SH", "L", "M")


def families(args):
    """The families of ``--modes`` (None: all)."""
    if args.modes is None:
        return None
    names = [w.strip().upper() for w in args.modes.split(",") if w.strip()]
    bad = [w for w in names if w not in FAMILIES]
    if bad or not names:
        raise InputError(f"--modes must be a comma-separated list of {', '.join(FAMILIES)}, "
                         f"got {args.modes[:40]!r}")
    return tuple(dict.fromkeys(names))
