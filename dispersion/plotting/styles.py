"""One style per mass rule in every figure, derived from the rule registry.

:func:`mass_style` gives a rule its colour and marker from its place in
:data:`dispersion.mass_rules.mass_rule.RULE_NAMES`, so a rule registered tomorrow is styled in
every plot without a table to extend; a user rule (not registered) gets a style from its
name, the same in every figure of a run.

Every registered rule has a colour, a marker and a line style of its own (the colours at
least 25 apart in CIELAB, tests/test_plot_styles.py): consistent and interpolatory-nodal, or
lumped and sms, no longer share a colour in one figure.

>>> mass_style("consistent")
MassStyle(colour='C0', marker='o', linestyle='-')
>>> from dispersion.mass_rules.mass_rule import RULE_NAMES
>>> len({mass_style(r).colour for r in RULE_NAMES}) == len(RULE_NAMES)   # every rule its own
True
"""
from __future__ import annotations

import zlib
from typing import NamedTuple

__all__ = ["MassStyle", "mass_style", "COLOURS", "MARKERS", "LINESTYLES"]

#: matplotlib's default cycle, then four colours chosen as far as possible from it and from
#: each other in CIELAB (magenta, navy, black, dark goldenrod): one for each of the fourteen
#: registered rules, the closest pair as far apart as the default cycle's own closest pair.
COLOURS = (*(f"C{i}" for i in range(10)), "#ff00ff", "#00008b", "k", "#b8860b")
#: One marker per registered rule (filled and open forms are kept for the S/A families).
MARKERS = "osD^v<>pPX*hHd"
#: Line styles, in turn: neighbours in the registry never share one.
LINESTYLES = ("-", "--", "-.", ":")


class MassStyle(NamedTuple):
    """Colour, marker and line style of one mass rule (a plot that gives line styles another
    meaning, such as the sign of an error, keeps its own and uses colour and marker)."""

    colour: str
    marker: str
    linestyle: str = "-"


def mass_style(mass) -> MassStyle:
    """The style of ``mass`` (a rule name or a :class:`~dispersion.mass_rules.mass_rule.MassRule`)."""
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    name = getattr(mass, "name", mass)
    if name in RULE_NAMES:
        i = RULE_NAMES.index(name)
    else:  # a user rule: placed after the registry, by its name
        i = len(RULE_NAMES) + zlib.crc32(str(name).encode()) % (len(COLOURS) * 2)
    return MassStyle(COLOURS[i % len(COLOURS)], MARKERS[i % len(MARKERS)],
                     LINESTYLES[i % len(LINESTYLES)])
