"""One claim of a claims file, as a value: what is claimed, about which model, where it stands.

``model`` is what the claim is about, built once where the file is read
(:func:`dispersion.claims.claim_model.claim_model`) and passed down whole: a
:class:`dispersion.symbolic.patch.Patch`, the exact plate
(:class:`dispersion.claims.exact_model.ExactModel`) or the periodic bar
(:class:`dispersion.claims.bar_model.BarModel`); reports show ``model.label()``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from dispersion.claims.claim_model import ClaimModel

__all__ = ["Claim"]


@dataclass(frozen=True)
class Claim:
    """One claim of a claims file (see :mod:`dispersion.claims` for its fields)."""

    name: str
    kind: str
    branch: str
    model: ClaimModel
    file: str = "<string>"
    line: int = 0
    source: str | None = None
    note: str | None = None
    printed: tuple = ()  # series: ((power, coefficient), ...)
    written: str = ""  # the claim as written in the file
    nu: object = None
    rtol: float | None = None
    error_order: int | None = None
    bound: bool = False
    kappa: float | None = None
    omega: float | None = None
    expect: str = "holds"

    @property
    def order(self) -> int:
        """Highest power of kappa the derivation must reach."""
        from dispersion.symbolic.power_balance import BRANCHES

        if self.kind == "error_order":
            return self.error_order + 2
        return max((k for k, _ in self.printed), default=2 * BRANCHES[self.branch][1])
