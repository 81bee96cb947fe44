"""The time integrators by name and their parameters: Kane's contact-modified Newmark
(paper eqs 6-10), standard Newmark, central differences (``beta = 0``, explicit).

>>> newmark_for("central").explicit, SCHEME_TEXT["kane"]
(True, "Kane's contact-modified Newmark")
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from dispersion.errors import InputError, check_positive, check_positive_int

__all__ = ["CONTACT_TREATMENTS", "CONTACT_SCHEMES", "SCHEME_TEXT", "DENSE_MAX", "Newmark", "newmark_for"]

#: Largest step matrix factorized with dense LAPACK; sparse SuperLU above. Chosen by
#: measurement (``python benchmarks/bench_ring.py``, table 1, 2-core machine): at the ring's
#: 144 DOFs the two factorize within 2x of each other when the machine is quiet, and
#: threaded LAPACK is up to 20x slower when it is loaded; from 408 DOFs on SuperLU wins
#: outright (0.74 vs 1.6 ms, 12 vs 74 ms at 1320). Dense stays for the bar's few dozen DOFs.
DENSE_MAX = 64

#: How an implicit Newmark step treats contact: Kane's contact-modified update or the
#: standard one (:class:`Newmark` ``scheme``).
CONTACT_TREATMENTS = ("kane", "standard")


@dataclass(frozen=True)
class Newmark:
    """Newmark parameters (``beta``, ``gamma``), ``scheme`` and Newton controls.

    ``beta = 0`` (with ``gamma = 1/2``) is the explicit central-difference scheme. ``tol``
    bounds the total residual (force residual and complementarity) relative to
    ``max(|inertia|, |f_int|, |f_ext|)`` of the step; ``solver`` is ``"auto"`` (dense up to
    ``dense_max`` unknowns), ``"dense"`` or ``"sparse"``. ``reuse_tangent=False`` rebuilds
    and refactors the tangent at every Newton iteration (full Newton: the speed baseline).
    """

    beta: float = 0.25
    gamma: float = 0.5
    scheme: str = "kane"
    tol: float = 1e-8
    max_iter: int = 25
    solver: str = "auto"
    dense_max: int = DENSE_MAX
    reuse_tangent: bool = True

    def __post_init__(self):
        if not (math.isfinite(self.beta) and 0 <= self.beta <= 0.5):
            raise InputError(f"beta must lie in [0, 0.5] (0: explicit), got {self.beta}")
        check_positive("gamma", self.gamma)
        if self.scheme not in CONTACT_TREATMENTS:
            raise InputError(f"scheme must be one of {', '.join(CONTACT_TREATMENTS)}; got {self.scheme!r}")
        if self.explicit and (self.gamma != 0.5 or self.scheme != "kane"):
            raise InputError("beta = 0 (explicit) needs gamma = 0.5 and scheme 'kane', got "
                             f"gamma = {self.gamma}, scheme {self.scheme!r}")
        if self.solver not in ("auto", "sparse", "dense"):
            raise InputError(f"solver must be 'auto', 'sparse' or 'dense', got {self.solver!r}")
        check_positive("tol", self.tol)
        check_positive_int("max_iter", self.max_iter)
        check_positive_int("dense_max", self.dense_max, minimum=0)

    @property
    def explicit(self) -> bool:
        return self.beta == 0


#: Time integrators of contact problems by name: Kane's contact-modified Newmark, standard
#: Newmark, central differences (beta = 0, explicit, Kane's contact impulse; the same member
#: is "central" in :data:`dispersion.time_stepping.time_integration.NEWMARK_MEMBERS`).
CONTACT_SCHEMES = ("kane", "standard", "central")
#: How pages and figures name them.
SCHEME_TEXT = {"kane": "Kane's contact-modified Newmark", "standard": "standard Newmark",
               "central": "explicit central differences"}


def newmark_for(scheme: str, **kwargs) -> Newmark:
    """:class:`Newmark` of the scheme named ``scheme`` (see :data:`CONTACT_SCHEMES`)."""
    if scheme not in CONTACT_SCHEMES:
        raise InputError(f"scheme must be one of {', '.join(CONTACT_SCHEMES)}; got {scheme!r}")
    if scheme == "central":
        return Newmark(beta=0.0, gamma=0.5, scheme="kane", **kwargs)
    return Newmark(scheme=scheme, **kwargs)
