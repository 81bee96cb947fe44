"""How many round-off-perturbed runs a spread has, and why that many: a fixed count and its statistic.

A contact history is chaotic: a perturbation of round-off size (the initial velocity by
1e-12, the wall by a few units in the last place) changes which steps are in contact, so a
reported figure is one draw of a spread. The ring study and the 1D Signorini rows report
each chaotic figure as its range over :data:`SPREAD_RUNS` runs (the unperturbed one and
``SPREAD_RUNS - 1`` perturbed ones), the same count for every spread, stated with its
reason (:data:`SPREAD_RULE`) before any figure is seen.

The reason is the comparison that judges a reproduction (``dispersion reproduce``): a new
figure must lie in the reference's range widened by its width on each side, at least by a
floor (:data:`RING_FLOORS`, :data:`SIGNORINI_FLOOR`). Under exchangeable runs a further run
falls outside the bare range of n runs with probability 2/(n + 1), whatever the
distribution; outside the widened band, for n = 8, with probability 0.5 % (normal) or
0.2 % (uniform), and one of n = 8 new runs with 3 % (normal) or 0.8 % (uniform) (Monte
Carlo, :func:`band_miss`; checked in the tests). Four runs, the ring's former count,
missed the band with 6 % and 16 % (normal).

>>> SPREAD_RUNS
8
>>> round(band_miss(8, "normal", samples=200_000, seed=1), 3)
0.005
"""
from __future__ import annotations

import numpy as np

__all__ = ["SPREAD_RUNS", "RING_FLOORS", "SIGNORINI_FLOOR", "SPREAD_RULE", "band_miss"]

#: Runs of every round-off spread (the unperturbed one included).
SPREAD_RUNS = 8
#: Floors of the ring's spread figures: 1e-6 percentage points of energy change, one
#: contact event (the ``abs`` of the ring report's comparison rules).
RING_FLOORS = {"energy_change_percent": 1e-6, "contact_events": 1}
#: Floor of every error of a 1D Signorini row (relative errors and percentages alike).
SIGNORINI_FLOOR = 1e-6

#: The rule in words, as the reports show it.
SPREAD_RULE = (
    f"Every round-off spread has {SPREAD_RUNS} runs (the unperturbed one and "
    f"{SPREAD_RUNS - 1} perturbed), the same count for the ring and every Signorini row, "
    "set before any figure by the comparison that judges a reproduction: a new figure must "
    "lie in the reference's range widened by its width on each side, and with 8 "
    "exchangeable runs a further run misses that band with probability 0.5 % (normal "
    "figures; 0.2 % uniform), one of 8 new runs with 3 % (0.8 %); with the ring's former "
    "4 runs these were 6 % and 16 %.")


def band_miss(n: int, distribution: str = "normal", *, every: bool = False,
              samples: int = 1_000_000, seed: int = 0) -> float:
    """Probability that a further run (``every``: any of n further runs) of a figure drawn
    from ``distribution`` (``"normal"`` or ``"uniform"``) falls outside the range of ``n``
    runs widened by that range's width on each side: Monte Carlo over ``samples`` draws."""
    rng = np.random.default_rng(seed)
    draw = rng.standard_normal if distribution == "normal" else rng.random
    x = draw((samples, n))
    y = draw((samples, n if every else 1))
    lo, hi = x.min(axis=1), x.max(axis=1)
    width = hi - lo
    return float(((y.min(axis=1) < lo - width) | (y.max(axis=1) > hi + width)).mean())
