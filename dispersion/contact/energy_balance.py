"""Energy balance of a contact run: growth beyond a stated bound, and known-unstable schemes.

A run without external work and with frictionless contact cannot gain energy: its total
energy :math:`E(t) = T + U` may only stay (conservative contact) or fall (dissipative contact).
:func:`energy_balance` measures the growth

.. math:: g = \\max_t \\frac{E(t) - E(0)}{E(0)}

and flags the run when :math:`g` exceeds :data:`GROWTH_BOUND_PERCENT` or when its
(scheme, mass) pair is in :data:`KNOWN_UNSTABLE`, whatever the growth of this particular run.
The bound is stated before any run is judged: 1 % of the initial energy, far above the Newton
tolerance of the implicit schemes (their growth is round-off) and far below the growth of an
unstable scheme (an impact of plain Newmark adds energy of the order of the impact's own).

Which schemes are stable with which masses (:data:`STABILITY_NOTE`, printed by the CLI help):

- ``kane`` (Kane's contact-modified Newmark, beta = 1/4): every mass; contact only dissipates.
- ``central`` (central differences, explicit, beta = 0, Kane's contact impulse): every mass below the
  critical time step; contact only dissipates.
- ``standard`` (plain Newmark, beta = 1/4, contact forces in the trapezoidal rule): unstable
  with a mass that has inertia at the contact nodes (``lumped``, ``consistent``): each impact
  adds energy; with the ``singular`` mass the contact nodes are massless and the scheme
  conserves energy.

>>> import numpy as np
>>> b = energy_balance(np.array([1.0, 0.99, 0.98]), "kane", "lumped")
>>> b.flagged, round(b.growth_percent, 12)
(False, 0.0)
>>> energy_balance(np.array([1.0, 1.5]), "kane", "lumped").flagged
True
>>> energy_balance(np.array([1.0, 1.0]), "standard", "lumped").reason
'plain Newmark (standard) with contact and inertia at the contact nodes (lumped mass) is known to be unstable: each impact adds energy'

References
----------
C. Kane, E. A. Repetto, M. Ortiz, J. E. Marsden, "Finite element analysis of nonsmooth
contact", Comput. Methods Appl. Mech. Engrg. 180 (1999) 1-26; H. B. Khenous, P. Laborde,
Y. Renard, "Mass redistribution method for finite element contact problems in
elastodynamics", Eur. J. Mech. A/Solids 27 (2008) 918-932.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass

from dispersion.errors import InputError

__all__ = ["GROWTH_BOUND_PERCENT", "KNOWN_UNSTABLE", "STABILITY_NOTE", "EnergyBalance",
           "energy_balance", "known_unstable", "warn"]

#: Largest growth of the total energy over its initial value (percent) that a run may show.
GROWTH_BOUND_PERCENT = 1.0

#: (scheme, mass) pairs that are unstable with contact, whatever one run's growth.
KNOWN_UNSTABLE = frozenset({("standard", "lumped"), ("standard", "consistent")})

#: One paragraph for the command-line help: which schemes are stable with which masses.
STABILITY_NOTE = (
    "Stability with contact: kane (contact-modified Newmark) is stable with every mass; "
    "central (explicit central differences) with every mass below the critical time step; standard "
    "(plain Newmark) is unstable with the lumped and consistent masses (each impact adds "
    "energy) and conserves energy only with the singular mass (massless contact nodes). "
    f"A run whose total energy grows by more than {GROWTH_BOUND_PERCENT:g} % of its initial "
    "value, or that uses a known-unstable pair, prints a warning on stderr and carries "
    "energy_flag in its JSON summary.")


def known_unstable(scheme: str, mass: str) -> str | None:
    """Why (scheme, mass) is unstable with contact, or None."""
    if (scheme, mass) in KNOWN_UNSTABLE:
        return (f"plain Newmark ({scheme}) with contact and inertia at the contact nodes "
                f"({mass} mass) is known to be unstable: each impact adds energy")
    return None


@dataclass(frozen=True)
class EnergyBalance:
    """Energy balance of one run (percentages of the initial total energy).

    ``growth_percent``: largest rise above the initial energy; ``final_change_percent``:
    end against start; ``reason``: why the run is flagged (None: not flagged).
    """

    scheme: str
    mass: str
    initial: float
    growth_percent: float
    final_change_percent: float
    bound_percent: float
    reason: str | None

    @property
    def flagged(self) -> bool:
        return self.reason is not None

    def fields(self) -> dict:
        """The JSON summary fields: growth, bound and flag (a sentence, or None)."""
        return {"energy_growth_percent": self.growth_percent,
                "energy_growth_bound_percent": self.bound_percent,
                "energy_flag": self.reason}


def energy_balance(total, scheme: str, mass: str,
                   bound_percent: float = GROWTH_BOUND_PERCENT) -> EnergyBalance:
    """Judge the total-energy history ``total`` (first entry: the initial state)."""
    import numpy as np  # not at import: the CLI help reads STABILITY_NOTE without numpy

    total = np.asarray(total, dtype=float)
    if total.ndim != 1 or total.size < 1 or not np.all(np.isfinite(total)):
        reason = "the energy history is empty or not finite (the run blew up)"
        return EnergyBalance(scheme, mass, float("nan"), float("inf"), float("inf"),
                             bound_percent, reason)
    e0 = float(total[0])
    if e0 <= 0:
        raise InputError(f"the initial total energy must be > 0 to judge growth, got {e0!r}")
    growth = float(100 * (total.max() - e0) / e0)
    final = float(100 * (total[-1] - e0) / e0)
    reasons = []
    if growth > bound_percent:
        reasons.append(f"total energy grows by {growth:.3g} % of its initial value "
                       f"(bound {bound_percent:g} %)")
    if (why := known_unstable(scheme, mass)) is not None:
        reasons.append(why)
    return EnergyBalance(scheme, mass, e0, growth, final, bound_percent,
                         "; ".join(reasons) if reasons else None)


def warn(balance: EnergyBalance, what: str, stream=None) -> bool:
    """Print one warning line about ``what`` on ``stream`` (stderr) if flagged; say if it did."""
    if not balance.flagged:
        return False
    print(f"warning: {what}: {balance.reason}; the figures of this run are not a result",
          file=stream or sys.stderr)
    return True
