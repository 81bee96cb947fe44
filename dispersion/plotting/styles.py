"""One style per mass rule in every figure, derived from the rule registry.

:func:`mass_style` gives a rule its colour and marker from its place in
:data:`dispersion.symbolic.mass_rule.RULE_NAMES`, so a rule registered tomorrow is styled in
every plot without a table to extend; a user rule (not registered) gets a style from its
name, the same in every figure of a run.

>>> mass_style("consistent")
MassStyle(colour='C0', marker='o')
>>> from dispersion.mass_rules.mass_rule import RULE_NAMES
>>> len({mass_style(r) for r in RULE_NAMES}) == len(RULE_NAMES)   # every rule its own
True
"""
from __future__ import annotations

import zlib
from typing import NamedTuple

__all__ = ["MassStyle", "mass_style", "COLOURS", "MARKERS"]

#: matplotlib's default cycle, then markers for rules beyond its ten colours.
COLOURS = tuple(f"C{i}" for i in range(10))
MARKERS = "osD^v<>pPX*h"


class MassStyle(NamedTuple):
    """Colour and marker of one mass rule."""

    colour: str
    marker: str


def mass_style(mass) -> MassStyle:
    """The style of ``mass`` (a rule name or a :class:`~dispersion.symbolic.mass_rule.MassRule`)."""
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    name = getattr(mass, "name", mass)
    if name in RULE_NAMES:
        i = RULE_NAMES.index(name)
    else:  # a user rule: placed after the registry, by its name
        i = len(RULE_NAMES) + zlib.crc32(str(name).encode()) % (len(COLOURS) * 2)
    return MassStyle(COLOURS[i % len(COLOURS)], MARKERS[i % len(MARKERS)])
