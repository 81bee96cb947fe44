"""The parameters of the literature's rule families, as rules: reproduction degree, beta.

The registry holds one member of each family under its name (``dual-lumped``: full
reproduction, ``sms``: beta = 1/2, :mod:`dispersion.mass_rules.lumping_rules`); these factories
give any other member as a :class:`~dispersion.mass_rules.mass_rule.MassRule` object, accepted
wherever a rule is (the periodic bar, the patch, claims through the API).

>>> from dispersion.time_stepping.timestep import bar_omega_max
>>> bar_omega_max(approximate_dual_rule(0), 1)[0]     # q = 0: the row-sum lumped bar, 2
2
>>> bar_omega_max(sms_rule(1), 1)[0]                  # 4 / (1 + 4 beta) = 4/5
2*sqrt(5)/5

A member of the reproduction-degree family also has a name that text can carry (a claims
file, the CLI): ``dual-lumped-q<q>`` is read by :func:`family_rule`, through
:func:`dispersion.mass_rules.mass_rule.get_rule`, so ``mass = "dual-lumped-q1"`` works
wherever a registered name does.

>>> family_rule("dual-lumped-q1") is approximate_dual_rule(1), family_rule("dual-lumped-qx")
(True, None)
"""
from __future__ import annotations

from dispersion.mass_rules.lumping_rules import approximate_dual_entry, sms_entry
from dispersion.mass_rules.mass_rule import (FAMILY_NAMES, MassRule, family_rule,
                                           literature_rule)

__all__ = ["FAMILY_NAMES", "approximate_dual_rule", "family_rule", "sms_rule"]


def approximate_dual_rule(q: int) -> MassRule:
    """``dual-lumped-q<q>``: approximate-dual lumping with reproduction degree ``q`` (capped at
    the degree p of the space along x; a space of degree below q is refused). For q <= 8 the
    one object of its name (:func:`~dispersion.mass_rules.mass_rule.family_rule`), so equal
    names give equal rules."""
    member = family_rule(f"dual-lumped-q{q}") if isinstance(q, int) else None
    return member or literature_rule(f"dual-lumped-q{q}", dict(approximate_dual_entry(q),
                                                               x_rule="dual-lumped"))


def sms_rule(beta) -> MassRule:
    """``sms-<beta>``: selective mass scaling with parameter ``beta`` in [0, 100]."""
    e = sms_entry(beta)
    return literature_rule(f"sms-{e['description'].rsplit('= ', 1)[1]}", dict(e, x_rule="sms"))
