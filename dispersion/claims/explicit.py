"""Claims about explicit dynamics: the critical time step and the fully discrete series.

Two claim kinds join those of :mod:`dispersion.claims` (same file, same keys for the
model and the mass)::

    [[claim]]
    name = "HRZ lets p = 2 step 2.98 times longer"
    kind = "critical_step"
    model = "bloch"                 # a plate patch (p, n, r, mass, contact, gamma_s), or "bar"
    p = 2
    mass = "hrz"
    nu = 0.3                        # plate only
    ratio = 2.9766                  # dt_crit / dt_crit(consistent), same patch
    relative_to = "consistent"      # the ratio's reference rule (optional)
    rtol = 1e-4                     # default 1e-9
    # or: omega_max = "2*sqrt(14)/3"  (largest Omega = omega h / c_T (plate) or omega h / c
    #     (bar) over the Brillouin zone, compared to rtol)

    [[claim]]
    name = "central differences lag by kappa^4 tau^2 / 12"
    kind = "fully_discrete_series"
    model = "bar"                   # or a plate patch with branch = "S0" / "A0"
    p = 1
    mass = "lumped"
    scheme = "central"              # or "average-acceleration", ... (gamma = 1/2 members)
    [claim.coefficients]            # "kappa^i*tau^j" = coefficient of Omega^2
    "kappa^4*tau^2" = "1/12"
    "kappa^4" = "-1/12"

Critical steps are those of the claim's own patch, ``r`` included
(:func:`dispersion.time_stepping.timestep.patch_omega_max`; the ratio is to the consistent mass on
the same patch) or of the periodic bar (:func:`dispersion.time_stepping.timestep.critical_step`,
exact); the series come from
:func:`dispersion.time_stepping.fully_discrete.fully_discrete_series` on the semi-discrete series of
the patch (:func:`dispersion.symbolic.power_balance.discrete_series`) or of the periodic bar
(:func:`dispersion.time_stepping.timestep.bar_omega_squared`). Series coefficients are compared
exactly (the difference cancels to zero).
"""
from __future__ import annotations

import math
import re

import sympy

from dispersion.claims.bar_model import BarModel
from dispersion.claims.claim import Claim
from dispersion.claims.claim_fields import expression
from dispersion.reader import as_sympy

__all__ = ["KINDS", "KIND_FIELDS", "step_claim", "series_claim", "task", "run", "verdict"]

KINDS = ("critical_step", "fully_discrete_series")
#: The keys of each kind (a claim of another kind refuses them,
#: :data:`dispersion.claims.schema.KIND_FIELDS`).
KIND_FIELDS = {"critical_step": ("ratio", "omega_max", "nu", "rtol", "relative_to"),
               "fully_discrete_series": ("coefficients", "scheme", "nu", "syntax")}
_KEY = re.compile(r"\s*kappa\^(\d{1,3})\s*(?:\*\s*tau\^(\d{1,3}))?\s*")


def _number(entry, key, fail, lo=0.0):
    v = entry.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= lo:
        fail(key, f"must be a finite number > {lo:g}, got {v!r}")
    return float(v)


def step_claim(entry: dict, common: dict, fail) -> Claim:
    """A ``critical_step`` claim (``common``: the fields every kind has, the model checked)."""
    given = [k for k in ("ratio", "omega_max") if k in entry]
    if len(given) != 1:
        fail("ratio", "a critical_step claim states exactly one of ratio, omega_max")
    rtol = _number(entry, "rtol", fail) if "rtol" in entry else 1e-9
    nu = None
    if not isinstance(common["model"], BarModel):
        nu = _number(entry, "nu", fail, lo=-1.0)
        if not nu < 0.5:
            fail("nu", f"must lie in (-1, 0.5), got {nu}")
    elif "nu" in entry:
        fail("nu", "not a setting of the periodic bar")
    key = given[0]
    value = expression(entry[key], key, "sympy", fail) if key == "omega_max" else \
        sympy.Float(repr(_number(entry, key, fail)), 17)
    if not value.is_number or not value.is_positive:
        fail(key, f"must be a positive number, got {entry[key]!r}")
    ref = entry.get("relative_to", "consistent")
    from dispersion.mass_rules.mass_rule import RULES

    if not isinstance(ref, str) or ref not in RULES:
        fail("relative_to", f"must name a registered rule, got {ref!r}")
    if key != "ratio" and "relative_to" in entry:
        fail("relative_to", "applies to a ratio claim only")
    return Claim(**common, printed=((key, value),) + ((("relative_to", ref),)
                                                       if ref != "consistent" else ()),
                 nu=nu, rtol=rtol, written=f"{key} = {entry[key]}"
                 + (f" (relative to {ref})" if ref != "consistent" else ""))


def series_claim(entry: dict, common: dict, fail) -> Claim:
    """A ``fully_discrete_series`` claim (``common`` as in :func:`step_claim`)."""
    from dispersion.time_stepping.time_integration import NEWMARK_MEMBERS

    scheme = entry.get("scheme", "central")
    if scheme not in NEWMARK_MEMBERS:
        fail("scheme", f"must be one of {', '.join(NEWMARK_MEMBERS)}, got {scheme!r}")
    if not isinstance(common["model"], BarModel) and common["branch"] not in ("S0", "A0"):
        fail("branch", f"must be S0 or A0, got {common['branch']!r}")
    coeffs = entry.get("coefficients")
    if not isinstance(coeffs, dict) or not coeffs:
        fail("coefficients", 'must be a table {"kappa^i*tau^j" = coefficient}')
    syntax = entry.get("syntax", "sympy")
    printed = []
    for key, text in coeffs.items():
        m = _KEY.fullmatch(str(key))
        if not m or int(m.group(1)) > 40 or int(m.group(2) or 0) > 40:
            fail(str(key), 'a power must read "kappa^i" or "kappa^i*tau^j" (i, j <= 40)')
        i, j = int(m.group(1)), int(m.group(2) or 0)
        if i % 2 or j % 2:
            fail(str(key), "powers of kappa and tau are even in Omega^2")
        printed.append(((i, j), expression(text, str(key), syntax, fail)))
    nu = entry.get("nu")
    if nu is not None:
        nu = expression(nu, "nu", "sympy", fail)
        if not (nu.is_Rational and -1 < nu < sympy.Rational(1, 2)):
            fail("nu", f"must be a rational number in (-1, 0.5), got {entry['nu']!r}")
    written = " + ".join(f"({c})*kappa^{i}*tau^{j}" for (i, j), c in printed)
    return Claim(**common, printed=(("scheme", scheme), *printed), nu=nu, written=written)


def task(claim) -> tuple:
    """The derivation a claim needs, hashable (shared between equal claims)."""
    if claim.kind == "critical_step":
        ref = dict(claim.printed[1:]).get("relative_to", "consistent")
        return ("critical_step", claim.model, claim.nu) + ((ref,) if ref != "consistent" else ())
    scheme = dict(claim.printed[:1])["scheme"]
    order = max(i for (i, _), _ in claim.printed[1:])
    return ("fully_discrete_series", claim.model, claim.branch, scheme, order, claim.nu)


def run(t: tuple):
    """Derive: ``(omega_max exact or float, ratio)`` or the series as ``{(i, j): coeff}``."""
    from dispersion.time_stepping import timestep

    model = t[1]
    if t[0] == "critical_step":
        other = t[3] if len(t) > 3 else "consistent"  # the ratio's reference rule
        if isinstance(model, BarModel):
            cs = timestep.critical_step(model.mass, model.p, model="bar", wave_speed=1.0)
            ratio = cs.ratio if other == "consistent" else float(
                timestep.bar_omega_max(other, model.p)[0]) / cs.omega_max
            return (cs.omega_max_exact, ratio)
        from dispersion.symbolic.plate import plate_patch

        w, exact, _, _ = timestep.patch_omega_max(plate_patch(model), t[2])
        ref = timestep.patch_omega_max(plate_patch(model.replace(mass=other)), t[2])[0]
        return (exact if exact is not None else w, ref / w)
    from dispersion.time_stepping.fully_discrete import fully_discrete_series, time_scheme

    _, _, branch, scheme, order, nu = t
    if isinstance(model, BarModel):
        z, k = sympy.Symbol("z"), sympy.Symbol("kappa")
        f = timestep.bar_omega_squared(model.mass, model.p).subs(z, sympy.cos(k))
        ser = sympy.series(f, k, 0, order + 1).removeO()
        semi = {i: ser.coeff(k, i) for i in range(1, order + 1)}
    else:
        from dispersion.symbolic.power_balance import discrete_series

        semi = discrete_series(branch, order, model, nu=nu)
    poly = sympy.Poly(fully_discrete_series(semi, order, time_scheme(scheme).beta),
                      sympy.Symbol("kappa"), sympy.Symbol("tau"))
    return {m: c for m, c in zip(poly.monoms(), poly.coeffs())}


def verdict(claim, derived) -> tuple[bool, str, str, str]:
    """``(holds, printed, derived, difference)`` as text."""
    if claim.kind == "critical_step":
        key, value = claim.printed[0]
        omega, ratio = derived
        got = ratio if key == "ratio" else omega
        err = abs(float(got) - float(value)) / float(value)
        holds = err <= claim.rtol
        shown = f"{key} = {got}" + (f" = {float(got):.12g}" if not isinstance(got, float) else "")
        diff = "" if holds else f"relative difference {err:.3g} > {claim.rtol:g}"
        return holds, f"{key} = {value} (rtol {claim.rtol:g})", shown, diff
    wrong = []
    shown = []
    for (i, j), c in claim.printed[1:]:
        d = derived.get((i, j), sympy.Integer(0))
        shown.append(f"({d})*kappa^{i}*tau^{j}")
        if sympy.cancel(as_sympy("printed coefficient", c) - d) != 0:
            wrong.append(f"kappa^{i}*tau^{j}: printed {c}, derived {d}")
    return not wrong, claim.written, " + ".join(shown), "; ".join(wrong)
