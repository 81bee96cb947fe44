"""Claims files: what a manuscript prints about a dispersion branch, checked against the derivation.

A *claim* is what a paper, a manuscript or a textbook states about a branch of a model: its
power series (eqs 14-20 of the paper are such claims), the leading order of its error, or its
value at one wavenumber. A claims file is TOML::

    title = "My manuscript"           # optional
    [defaults]                        # optional: keys every claim inherits
    model = "bloch"

    [[claim]]
    name = "S0 bar speed"             # required, unique in the file
    source = "Smith 2024, eq (3)"     # optional: paper and equation
    branch = "S0"                     # S0 or A0 (value claims: S0, S1, ..., A0, A1, ...)
    model = "rayleigh-lamb"           # or a patch: "bloch" / "x-exact" with the keys below
    [claim.coefficients]              # Omega^2 = sum of coefficient * kappa^power
    2 = "2/(1 - nu)"

Keys of a claim (``[defaults]`` may set any of them except ``name``):

``kind``
    ``"series"`` (default), ``"error_order"`` or ``"value"``; the explicit-dynamics kinds
    ``"critical_step"`` and ``"fully_discrete_series"`` (:mod:`~dispersion.claims.explicit`);
    the leading-error-term kinds ``"order_range"`` and ``"leading_term"``
    (:mod:`~dispersion.claims.orders`). An ``order_range`` claim compares a rule with a
    reference over a range of degrees, either exactly (``same_leading_term_as``: power and
    coefficient) or as a bound (``at_least_order_of``: the power is never lower). The old
    key ``same_order_as`` is read as the deprecated name of ``at_least_order_of`` (it meant
    "at least that order", so claims with it held by default against weaker rules); the
    result's text names the deprecation. A ``leading_term`` claim states the term c x^k
    itself (``power``, ``coefficient``, exact in nu on the plate).
``model``
    ``"rayleigh-lamb"`` (the exact plate, eq 13 in its standard form) or a plate patch,
    ``"bloch"`` or ``"x-exact"`` with ``p``, ``n``, ``r`` (number, ``"1/2"`` or ``"r"`` for
    the symbol), ``mass``, ``contact``, ``gamma_s`` and ``weights`` (a table
    ``{contact index: {neighbour index: weight}}``): the claim holds that
    :class:`dispersion.symbolic.patch.Patch` (``claim.model``), its unset fields the
    toolkit's defaults (:mod:`dispersion.defaults`).
``coefficients`` or ``series`` (series claims)
    Either a table power -> coefficient of :math:`\\Omega^2` (each power listed is claimed),
    or the whole expression in ``kappa``, e.g. ``"2/(1-nu)*kappa^2 + O(kappa^4)"``, a sum
    of terms, each a coefficient times a power of kappa, and an optional order term: every
    even power from the branch's first up to the order term (or the highest power written)
    is claimed, a missing one as zero. Powers are even, from the branch's first up to the
    highest the toolkit derives (kappa^32 for a patch, kappa^128 exact).
``syntax``
    ``"sympy"`` (default: sympy text, ``^`` or ``**`` for powers, symbols ``nu``, ``kappa``,
    ``r``) or ``"latex"`` (``\\nu``, ``\\kappa``, ``\\frac``, ``O(\\kappa^8)``, as printed in a
    paper). Both are read by the whitelist reader :mod:`dispersion.claims.reader`: numbers,
    ``+ - * / ^ **``, parentheses, the symbols and ``sqrt``, ``Rational``, ``O``, nothing
    else; the text is never evaluated. A series may start with ``Omega^2 =`` (LaTeX:
    ``\\Omega^2 =``). Use TOML literal strings (single quotes) so that backslashes stay as
    written.
``nu``, ``rtol``
    Series claims may substitute a number for nu (``nu = "3/10"``); with ``rtol`` as well,
    the coefficients are compared to that relative tolerance instead of exactly.
``error_order``, ``bound``
    Error-order claims: the leading power of kappa of :math:`\\Omega_h^2 - \\Omega^2` (the
    patch's series minus the exact Rayleigh-Lamb series). Exact by default; with
    ``bound = true`` the claim is "O(kappa^error_order)", i.e. that power or a higher one.
``kappa``, ``nu``, ``omega``, ``rtol``
    Value claims: :math:`\\Omega` of the branch at :math:`\\kappa` and nu, within ``rtol``.
``expect``
    ``"holds"`` (default) or ``"differs"``: a recorded finding that the claim does *not*
    hold under these settings (like pytest's strict ``xfail``: it fails if it holds).
``source``, ``note``
    Free text shown in the reports.

Every number field (``nu``, ``r``, ``gamma_s``, ``kappa``, ``omega``, ``rtol``, weights,
coefficients) is a TOML number or a string such as ``"3/10"`` read by the same reader; NaN
and infinities are refused, so are odd or repeated powers (``02`` and ``2``). A file must be
a regular UTF-8 file of at most 1 MiB; sizes and derivations are bounded before any work
(:mod:`dispersion.claims.schema`). A bad file is one :class:`~dispersion.errors.InputError`
naming file, line, claim and field.

Comparisons are exact: the printed minus the derived coefficient, cancelled over QQ(nu[, r]),
must be zero. A mismatch is described as simply as possible: a sign, a constant factor, a
changed term of the numerator, or the difference itself.

>>> from dispersion.claims import check_claim, parse_claims
>>> claims = parse_claims('''
... [[claim]]
... name = "A0 leading"
... branch = "A0"
... model = "rayleigh-lamb"
... coefficients = {4 = "2/(3*(1 - nu))"}
... ''')
>>> check_claim(claims[0]).status
'holds'

The package is split by what each part holds: :mod:`~dispersion.claims.reader` (the
expression reader) with :mod:`~dispersion.claims.limits` (its size rules),
:mod:`~dispersion.claims.claims_file` (the file as text and TOML, within limits),
:mod:`~dispersion.claims.schema` (TOML to :class:`~dispersion.claims.claim.Claim` values,
field by field, with :mod:`~dispersion.claims.claim_fields`),
:mod:`~dispersion.claims.claim_model` (the model keys to one :class:`~dispersion.symbolic.patch.Patch`, or the
:mod:`~dispersion.claims.exact_model` or the :mod:`~dispersion.claims.bar_model`),
:mod:`~dispersion.claims.explicit` (the explicit-dynamics kinds),
:mod:`~dispersion.claims.orders` (the leading-error-term kinds),
:mod:`~dispersion.claims.verify` (derivations, scheduling, verdicts),
:mod:`~dispersion.claims.report` (text, Markdown, JUnit XML) and
:mod:`~dispersion.claims.errata` (the paper's errata table).

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (13)-(20).
"""
from __future__ import annotations

import importlib

#: Public names and the module of the package that holds each. They are imported on first
#: use, so that ``dispersion.claims.reader`` (the CLI's number options) loads without sympy.
_HOMES = {
    "EXACT": "exact_model", "ExactModel": "exact_model", "BarModel": "bar_model",
    "KINDS": "schema", "KAPPA": "schema", "Claim": "claim", "parse_claims": "schema",
    "load_claims": "schema", "paper_claims_path": "claims_file",
    "Term": "verify", "ClaimResult": "verify", "Verification": "verify",
    "check_claim": "verify", "verify_claims": "verify", "verify_file": "verify",
    "describe_difference": "verify", "MAX_JOBS": "verify", "check_jobs": "verify",
    "KIND_RULES": "verify",
    "format_results": "report", "junit_xml": "report", "plain": "report",
}
__all__ = list(_HOMES)


def __getattr__(name: str):
    if name in _HOMES:
        value = getattr(importlib.import_module(f"{__name__}.{_HOMES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOMES))
