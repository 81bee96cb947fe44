"""Claims about a finite mesh: its largest frequency, its outliers and what a removal wins.

One claim kind joins those of :mod:`dispersion.claims` (same file, same model keys; the
model is the bar of degree ``p`` and rule ``mass``, here on a finite mesh)::

    [[claim]]
    name = "the boundary penalty lets p = 4 step sqrt(5/2) times longer"
    kind = "mesh_step"
    model = "bar"                   # the claim's model: the finite bar below (h = 1, c = 1)
    p = 4
    mass = "consistent"
    elements = 100                  # the mesh: N elements, open knot vectors
    ends = "fixed"                  # free, fixed or periodic
    removal = "penalty"             # an outlier-removal method (optional)
    quantity = "gain"               # what is claimed (below)
    value = "sqrt(5/2)"
    rtol = 0.01                     # default 1e-9; "outliers" is compared exactly

``quantity`` is one of

* ``omega_max``: the mesh's largest :math:`\\omega h / c` (with the removal, if any);
* ``ratio``: that over the periodic lattice's of the same rule (1: no outlier);
* ``gain``: the step with the removal over the step without, i.e. the largest frequency
  without over with (needs ``removal``);
* ``outliers``: how many frequencies lie above the lattice's largest (a whole number).

The derivation is :func:`dispersion.time_stepping.mesh_step.mesh_omega_max` (the proven
upper bound is the value compared: the step a user would take) and, for ``outliers``,
:func:`dispersion.discretization.finite_mesh.outlier_numbers.outliers`.
"""
from __future__ import annotations

import math

import sympy

from dispersion.claims.claim import Claim
from dispersion.claims.claim_fields import expression

__all__ = ["KINDS", "KIND_FIELDS", "QUANTITIES", "MAX_ELEMENTS", "mesh_claim", "task", "run",
           "verdict"]

KINDS = ("mesh_step",)
KIND_FIELDS = {"mesh_step": ("elements", "ends", "removal", "quantity", "value", "rtol")}
QUANTITIES = ("omega_max", "ratio", "gain", "outliers")
#: Most elements of a claim's mesh (every frequency is computed for ``outliers``: the dense
#: solver of 2000 DOFs takes seconds).
MAX_ELEMENTS = 2000


def mesh_claim(entry: dict, common: dict, fail) -> Claim:
    """A ``mesh_step`` claim (``common``: the fields every kind has, the model checked)."""
    from dispersion.claims.bar_model import BarModel
    from dispersion.defaults import MESH_ENDS
    from dispersion.discretization.finite_mesh.outlier_removal import REMOVALS

    model = common["model"]
    if not isinstance(model, BarModel):
        fail("model", "a mesh_step claim is about the bar (model = 'bar') on a finite mesh")
    n = entry.get("elements")
    if type(n) is not int or not 1 <= n <= MAX_ELEMENTS:
        fail("elements", f"must be an integer in [1, {MAX_ELEMENTS}], got {n!r}")
    ends = entry.get("ends", "free")
    if ends not in MESH_ENDS or ends == "sliding":
        fail("ends", f"must be free, fixed or periodic, got {ends!r}")
    removal = entry.get("removal")
    if removal is not None and removal not in REMOVALS:
        fail("removal", f"must be one of {', '.join(REMOVALS)}, got {removal!r}")
    quantity = entry.get("quantity")
    if quantity not in QUANTITIES:
        fail("quantity", f"must be one of {', '.join(QUANTITIES)}, got {quantity!r}")
    if quantity == "gain" and removal is None:
        fail("removal", "a gain is the step with a removal method over the step without")
    if "value" not in entry:
        fail("value", "required: the claimed number")
    value = expression(entry["value"], "value", "sympy", fail)
    if not value.is_number or not value.is_real or value.is_negative:
        fail("value", f"must be a real number >= 0, got {entry['value']!r}")
    if quantity == "outliers" and not value.is_integer:
        fail("value", f"a count of outliers is a whole number, got {entry['value']!r}")
    rtol = entry.get("rtol", 1e-9)
    if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) or not (
            math.isfinite(rtol) and 0 < rtol < 1):
        fail("rtol", f"must be a number in (0, 1), got {rtol!r}")
    if quantity == "outliers" and "rtol" in entry:
        fail("rtol", "a count of outliers is compared exactly")
    from dispersion.discretization.finite_mesh.finite_patch import finite_bar
    from dispersion.errors import InputError

    try:  # the claim is about this mesh: the model the reports name
        mesh = finite_bar(model.p, n, ends=ends, mass=model.mass_name, removal=removal,
                          length=float(n))
    except InputError as exc:
        fail("elements", f"the toolkit cannot build this mesh: {exc}")
    printed = (("quantity", quantity), ("value", value))
    written = f"{quantity} = {entry['value']}" + (f" (rtol {rtol:g})" if quantity !=
                                                   "outliers" else "")
    return Claim(**{**common, "model": mesh}, printed=printed, rtol=float(rtol),
                 written=written)


def task(claim) -> tuple:
    """The derivation a claim needs, hashable (shared between equal claims): the mesh (the
    claim's model, a :class:`~dispersion.discretization.finite_mesh.finite_patch.FinitePatch` with h = 1)
    and whether its outliers are counted."""
    return ("mesh_step", claim.model, dict(claim.printed)["quantity"] == "outliers")


def run(t: tuple) -> dict:
    """``{"omega_max", "plain", "lattice", "outliers"}`` of the mesh (h = 1, c = 1)."""
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max
    from dispersion.time_stepping.mesh_step import mesh_omega_max

    _, patch, count = t
    if count:  # every frequency, counted against the lattice's
        from dispersion.discretization.finite_mesh.outlier_numbers import outliers

        return {"outliers": outliers(patch, limit=False).count}
    out = {"omega_max": mesh_omega_max(patch).omega_proven,
           "lattice": lattice_omega_max(patch)}
    if patch.removal is not None:
        out["plain"] = mesh_omega_max(patch.replace(removal=None)).omega_proven
    return out


def verdict(claim, derived) -> tuple[bool, str, str, str]:
    """``(holds, printed, derived, difference)`` as text."""
    d = dict(claim.printed)
    quantity, value = d["quantity"], d["value"]
    if quantity == "outliers":
        got = derived["outliers"]
        holds = got == int(value)
        return holds, claim.written, f"outliers = {got}", "" if holds else \
            f"{got} frequencies above the lattice, claimed {value}"
    if derived.get("omega_max") is None:
        return False, claim.written, "no proven bound", "the mesh's bound did not close"
    got = {"omega_max": derived["omega_max"],
           "ratio": derived["omega_max"] / derived["lattice"],
           "gain": derived.get("plain", math.nan) / derived["omega_max"]}[quantity]
    target = float(sympy.N(value, 20))
    err = abs(got - target) / target if target else abs(got)
    holds = err <= claim.rtol
    return holds, claim.written, f"{quantity} = {got:.10g}", "" if holds else \
        f"relative difference {err:.3g} > {claim.rtol:g}"
