"""The semi-discrete contact problem the time stepper integrates (paper eq 5).

Mass, internal force and tangent, a linear gap :math:`\\mathbf g = \\mathbf g_0 + \\mathbf G
\\mathbf U \\ge 0` to a rigid frictionless obstacle, and the strain energy; built by the bar
(:mod:`dispersion.contact.bar`) and the 2D patches (:mod:`dispersion.contact.problem`),
integrated by :func:`dispersion.contact.newmark.integrate`.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import scipy.sparse as sp

__all__ = ["ContactProblem"]


@dataclass(frozen=True)
class ContactProblem:
    """Mass ``M``, ``internal(u) -> (f_int, K_T)``, gap ``g0 + G u``, ``energy(u)`` (strain).

    ``f_ext`` is a constant external force (its potential ``-f_ext . u`` enters the total
    energy); ``directions`` (``(k, n)``) maps ``M v`` to momentum components; ``K`` (constant
    stiffness) marks a linear problem, ``internal(u) = (K u, K)`` and ``energy(u) =
    u.K u / 2`` (the time stepper evaluates it so), whose step matrix is factorized once; ``force(u)`` (optional) is ``f_int`` alone, cheaper than ``internal``;
    ``forces`` (optional, an :class:`~dispersion.contact.elastic_forces.ElasticForces`) gives
    ``f_int`` and ``energy(u)`` from one evaluation and stacks with other runs' operators, so
    the time stepper records each step's strain energy without evaluating it again and steps
    several runs together (:func:`~dispersion.contact.newmark.integrate_many`).
    """

    M: sp.csr_matrix
    internal: Callable
    G: sp.csr_matrix
    g0: np.ndarray
    energy: Callable
    f_ext: np.ndarray | None = None
    directions: np.ndarray | None = None
    K: sp.csr_matrix | None = None
    force: Callable | None = None
    forces: ElasticForces | None = None

    @property
    def n(self) -> int:
        return self.M.shape[0]
