"""The internal force and stored energy of St.Venant-Kirchhoff patches, of one or many at once.

The gradient map ``BF`` of a discretization (:class:`~.assembly.Discretization`) takes the
DOFs to the displacement gradient at every Gauss point; then, by components,

.. math::

    \\mathbf F = \\mathbf I + \\nabla \\mathbf u, \\qquad
    \\mathbf E = \\tfrac12 (\\mathbf F^T \\mathbf F - \\mathbf I), \\qquad
    \\mathbf S = \\bar\\lambda \\, \\mathrm{tr}(\\mathbf E) \\mathbf I + 2 \\mu \\mathbf E, \\qquad
    \\mathbf f = \\mathbf{BF}^T (w \\, \\mathbf F \\mathbf S), \\qquad
    W = \\sum_g w_g \\big(\\tfrac{\\bar\\lambda}{2} \\mathrm{tr}(\\mathbf E)^2 +
        \\mu \\, \\mathbf E : \\mathbf E\\big),

one evaluation giving the force and the energy. :meth:`ElasticForces.stack` joins K
operators into one block-diagonal operator, so K runs of a time stepper (K patches, K
states) take one sparse product and one set of array operations per evaluation instead of
K: a small patch's force is dominated by the fixed cost of each array operation, not by its
arithmetic. Each run's numbers are those of its own operator (the block-diagonal product
sums each row exactly as the single product does).

>>> from dispersion.contact.assembly import discretize
>>> from dispersion.contact.material import StVenantKirchhoff
>>> from dispersion.splines.nurbs import quarter_ring
>>> op = ElasticForces.of(discretize(quarter_ring(1.0, 2.0, 2, 1)), StVenantKirchhoff(1.0, 0.3))
>>> two = ElasticForces.stack([op, op])
>>> u = np.linspace(0, 1e-3, op.n)
>>> f, W = two.force_energy(np.stack([u, 2 * u]))
>>> bool(np.array_equal(f[0], op.force_energy(u)[0])), f.shape, W.shape
(True, (2, 24), (2,))
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import scipy.sparse as sp

__all__ = ["ElasticForces"]


@dataclass(frozen=True, eq=False)
class ElasticForces:
    """``K`` patches' force operator: block-diagonal gradient map ``BF`` (``4 ng K`` x
    ``n K``, rows by component, run, Gauss point) and its transpose, and per Gauss point
    (``(K, ng)``) the quadrature weight ``w`` times the material's moduli:
    ``lam_w`` :math:`= \\bar\\lambda w`, ``mu_w`` :math:`= \\mu w`."""

    BF: sp.csr_matrix
    BFT: sp.csr_matrix
    lam_w: np.ndarray
    mu_w: np.ndarray

    @property
    def K(self) -> int:
        return self.lam_w.shape[0]

    @property
    def n(self) -> int:
        """DOFs of one patch."""
        return self.BF.shape[1] // self.K

    @classmethod
    def of(cls, disc, mat) -> ElasticForces:
        """The operator of one discretization ``disc`` with material ``mat``."""
        w = disc.wdet.reshape(1, -1)
        return cls(disc.BF, disc.BFT, mat.lam_bar * w, mat.mu * w)

    @classmethod
    def stack(cls, ops: list[ElasticForces]) -> ElasticForces:
        """One operator for the runs of ``ops`` side by side (block-diagonal maps, their
        rows ordered by gradient component, then run, then Gauss point)."""
        if len(ops) == 1:
            return ops[0]
        import scipy.sparse as sp

        BF = sp.block_diag([o.BF for o in ops], format="csr")
        ng = ops[0].lam_w.shape[1]
        order = np.arange(BF.shape[0]).reshape(len(ops), 4, ng).transpose(1, 0, 2).ravel()
        BF = BF[order]
        return cls(BF, BF.T.tocsr(), np.concatenate([o.lam_w for o in ops]),
                   np.concatenate([o.mu_w for o in ops]))

    def restrict(self, free: np.ndarray) -> ElasticForces:
        """The operator on the DOFs ``free`` of one patch (the others held at zero)."""
        return ElasticForces(self.BF[:, free].tocsr(), self.BFT[free].tocsr(), self.lam_w,
                             self.mu_w)

    def force(self, U: np.ndarray):
        """Forces at displacements ``U`` (``(K, n)``, or one run's ``(n,)``) and the strains
        they came from (:meth:`energy` turns them into stored energies)."""
        U = np.asarray(U, dtype=float)
        K, ng = self.lam_w.shape
        Fv = (self.BF @ U.reshape(-1)).reshape(4, K, ng)  # (F00 - 1, F01, F10, F11 - 1)
        F01, F10 = Fv[1], Fv[2]
        F00, F11 = Fv[0] + 1.0, Fv[3] + 1.0
        E00 = 0.5 * (F00 * F00 + F10 * F10 - 1.0)
        E11 = 0.5 * (F01 * F01 + F11 * F11 - 1.0)
        E01 = 0.5 * (F00 * F01 + F10 * F11)
        tr = E00 + E11
        ltw = self.lam_w * tr
        m2w = 2 * self.mu_w
        S00, S11, S01 = m2w * E00 + ltw, m2w * E11 + ltw, m2w * E01
        # f_ak = sum_g sum_J P_kJ dR_aJ: the transpose of the gradient map applied to P
        P = np.concatenate((F00 * S00 + F01 * S01, F00 * S01 + F01 * S11,
                            F10 * S00 + F11 * S01, F10 * S01 + F11 * S11))
        f = self.BFT @ P.reshape(-1)
        return (f if U.ndim == 1 else f.reshape(K, -1)), (tr, E00, E11, E01)

    def energy(self, strains) -> np.ndarray:
        """Stored energies ``(K,)`` of the strains :meth:`force` returned."""
        tr, E00, E11, E01 = strains
        W = 0.5 * self.lam_w * tr * tr + self.mu_w * (E00 * E00 + E11 * E11 + 2 * E01 * E01)
        return np.add.reduce(W, axis=1)

    def force_energy(self, U: np.ndarray):
        """Forces and stored energies at displacements ``U``: ``(K, n)`` gives ``(K, n)`` and
        ``(K,)``; one run's ``(n,)`` gives ``(n,)`` and a float."""
        f, strains = self.force(U)
        W = self.energy(strains)
        return (f, float(W[0])) if np.ndim(U) == 1 else (f, W)
