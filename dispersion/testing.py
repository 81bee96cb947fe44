"""Pytest helpers: hold a manuscript's equations in a test suite.

Each helper derives a claim (:mod:`dispersion.claims`) and raises ``AssertionError`` with
the printed and the derived form and the difference if it does not hold as recorded.

>>> assert_series("A0", {4: "2/(3*(1 - nu))"}, model="rayleigh-lamb").status
'holds'
>>> try:
...     assert_series("A0", {4: "2/(1 - nu)"}, model="rayleigh-lamb", name="typo")
... except AssertionError as exc:
...     print(str(exc).splitlines()[0])
claim 'typo' (<string>:1) differs
"""
from __future__ import annotations

import json

from dispersion.claims import (Claim, ClaimResult, check_claim, load_claims, parse_claims,
                               plain)

__all__ = ["assert_claim", "assert_series", "assert_claims_file", "claims_in", "failure_message"]


def failure_message(result: ClaimResult) -> str:
    """Printed vs derived, term by term, for an assertion message (control sequences from
    the claims file escaped, see :func:`dispersion.claims.report.plain`)."""
    lines = [f"claim {result.name!r} ({result.file}:{result.line}) {result.status}",
             f"  source:     {result.source or '-'}", f"  model:      {result.model}"]
    if result.terms:
        for t in result.terms:
            mark = "ok " if t.holds else "BAD"
            lines.append(f"  {mark} kappa^{t.power}: printed {t.printed}  derived {t.derived}"
                         + (f"  ({t.difference})" if t.difference else ""))
    else:
        lines += [f"  printed:    {result.printed}", f"  derived:    {result.derived}"]
    if result.difference:
        lines.append(f"  difference: {result.difference}")
    return plain("\n".join(lines), newlines=True)


def assert_claim(claim: Claim) -> ClaimResult:
    """Check one claim; return its result, or raise ``AssertionError`` showing the mismatch."""
    result = check_claim(claim)
    if not result.passed:
        raise AssertionError(failure_message(result))
    return result


def _toml(value) -> str:
    """``value`` as TOML: a JSON string is a TOML basic string (every character escaped that
    must be), so no text given here can change the structure of the claim."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml(v)}"
                               for k, v in value.items()) + "}"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    return json.dumps(str(value))


def assert_series(branch: str, coefficients, *, name: str = "series", **fields) -> ClaimResult:
    """Assert a series claim written inline: ``coefficients`` is ``{power: expression}`` or
    the whole series as text; ``fields`` are claim keys (``model``, ``mass``, ``r``, ...)."""
    body = {"name": name, "branch": branch, **fields}
    key = "coefficients" if isinstance(coefficients, dict) else "series"
    body[key] = ({str(k): str(v) for k, v in coefficients.items()} if key == "coefficients"
                 else coefficients)
    text = "[[claim]]\n" + "\n".join(f"{json.dumps(str(k))} = {_toml(v)}"
                                     for k, v in body.items()) + "\n"
    return assert_claim(parse_claims(text)[0])


def claims_in(path) -> list[Claim]:
    """The claims of a file, e.g. for ``pytest.mark.parametrize(..., ids=lambda c: c.name)``."""
    return load_claims(path)


def assert_claims_file(path) -> list[ClaimResult]:
    """Assert every claim of a file; the message lists each one that does not hold."""
    results = [check_claim(c) for c in load_claims(path)]
    bad = [r for r in results if not r.passed]
    if bad:
        raise AssertionError("\n".join(failure_message(r) for r in bad))
    return results
