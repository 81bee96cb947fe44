"""The critical step of the assembled strip: its largest frequency by Lanczos, beside the toolkit's.

Central differences are stable for :math:`\\omega_{max} \\Delta t \\le 2` with
:math:`\\omega_{max}^2` the largest eigenvalue of :math:`\\hat K x = \\omega^2 M_{rr} x`
(massless DOFs condensed, :math:`\\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}`, as the loop
solves them). It is found by the implicitly restarted Lanczos method (ARPACK through
``scipy.sparse.linalg.eigsh``, largest algebraic, fixed start vector): on
:math:`D^{-1/2} \\hat K D^{-1/2}` for a diagonal mass, else in ARPACK's generalized mode with
the mass operator's factors. The Ritz value is a Rayleigh quotient, so it lies below the
true maximum by at most the residual ``tol`` relative; the step the simulation takes is
``courant`` times :math:`2/\\omega_{max}`, with :math:`\\omega_{max}` rounded *up* to six
significant digits (the stable side, and the same step on every machine unless the maximum
sits on a rounding boundary).

The toolkit's step (:func:`dispersion.waves.timestep.patch_omega_max`) is that of the
periodic Bloch patch with the strip's thickness mesh, aspect ratio and rule: for p = 1 the
two agree (the strip's maximum approaches the periodic one), for p >= 2 the open mesh's
boundary functions raise :math:`\\omega_{max}` above it (the "outliers" of Cottrell et al.
2006), so the mesh's own step is the smaller. Both are reported; the tests check the Lanczos
value against the toolkit's dense :func:`dispersion.waves.timestep.matrix_critical_step` on a
small strip.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> from dispersion.simulation.strip_mesh import strip_mesh
>>> from dispersion.simulation.mass_operator import mass_operator
>>> mesh = strip_mesh(plan_strip(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3)))
>>> step = mesh_critical_step(mesh, mass_operator(mesh))
>>> 0 < step.dt_crit <= 2 / step.omega_lanczos
True

References
----------
R. B. Lehoucq, D. C. Sorensen, C. Yang, *ARPACK Users' Guide*, SIAM 1998 (implicitly
restarted Lanczos, generalized mode 2). J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R.
Hughes, CMAME 195 (2006) 5257-5296 (outlier frequencies of open meshes).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from dispersion.errors import ConvergenceError

__all__ = ["MeshCriticalStep", "mesh_critical_step", "LANCZOS_TOL", "round_up"]

#: Relative residual of the Lanczos Ritz pair. The Ritz value is a Rayleigh quotient, below the
#: maximum; on the strips of the study it lies within 1e-7 of it (checked against the dense
#: solution in the tests), and the top of the spectrum is so clustered (relative gaps of 1e-6
#: for p = 1) that a tighter residual costs thousands of iterations for no change in the step.
LANCZOS_TOL = 1e-6


@dataclass(frozen=True)
class MeshCriticalStep:
    """``omega_lanczos`` (the Ritz value's root), ``omega_max`` (rounded up to 6 digits),
    ``dt_crit = 2 / omega_max``; ``omega_bloch`` and ``dt_bloch`` the toolkit's periodic
    patch (None if not asked); ``iterations``: Lanczos operator applications; ``seconds``."""

    omega_lanczos: float
    omega_max: float
    dt_crit: float
    omega_bloch: float | None
    dt_bloch: float | None
    iterations: int
    seconds: float
    #: Why the toolkit has no Bloch-patch step for this rule (None: it has one, or not asked).
    bloch_failure: str | None = None

    @property
    def ratio_to_bloch(self) -> float | None:
        """:math:`\\Delta t_{mesh} / \\Delta t_{Bloch}` (< 1: the open mesh's outliers)."""
        return None if self.dt_bloch is None else self.dt_crit / self.dt_bloch


def round_up(x: float, digits: int = 6) -> float:
    """``x > 0`` rounded up to ``digits`` significant digits.

    >>> round_up(3.14159265), round_up(2.0)
    (3.1416, 2.0)
    """
    e = math.floor(math.log10(x)) - digits + 1
    up = float(f"{math.ceil(x / 10.0**e - 1e-9)}e{e}")
    return up if up >= x else float(f"{math.ceil(x / 10.0**e) + 1}e{e}")


def _operator(mesh, op):
    """(A, M, Minv) of the pencil on the massive DOFs, counting applications of A."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    r_dofs = (2 * op.massive[:, None] + np.arange(2)).ravel()
    m_dofs = (2 * op.massless[:, None] + np.arange(2)).ravel()
    K = mesh.K
    count = [0]
    if m_dofs.size:
        Krr = K[r_dofs][:, r_dofs].tocsr()
        Krm = K[r_dofs][:, m_dofs].tocsr()
        Kmm = spla.splu(K[m_dofs][:, m_dofs].tocsc())

        def kmul(x):
            return Krr @ x - Krm @ Kmm.solve(Krm.T @ x)
    else:
        def kmul(x):
            return K @ x
    n = r_dofs.size
    if op.kind in ("banded", "dense"):  # M^-1 K, similar to a symmetric matrix: real spectrum
        def step(x):
            count[0] += 1
            return op.solve(kmul(np.ravel(x)).reshape(-1, 2)).ravel()

        return spla.LinearOperator((n, n), matvec=step, dtype=float), "nonsymmetric", None, count
    if op.kind == "diagonal":
        s = 1.0 / np.sqrt(np.repeat(op.diagonal, 2))

        def scaled(x):
            count[0] += 1
            return s * kmul(s * np.ravel(x))

        return spla.LinearOperator((n, n), matvec=scaled, dtype=float), None, None, count
    M = sp.kron(mesh.mass[op.massive][:, op.massive], sp.identity(2), format="csr")

    def counted(x):
        count[0] += 1
        return kmul(np.ravel(x))

    Minv = spla.LinearOperator((n, n), matvec=lambda b: op.solve(np.reshape(b, (-1, 2))).ravel(),
                               dtype=float)
    return spla.LinearOperator((n, n), matvec=counted, dtype=float), M, Minv, count


def mesh_critical_step(mesh, op, *, bloch: bool = False, tol: float = LANCZOS_TOL
                       ) -> MeshCriticalStep:
    """Largest frequency of the assembled strip by Lanczos (and the Bloch patch's if ``bloch``).

    Parameters
    ----------
    mesh : StripMesh
    op : MassOperator
    bloch : bool
        Also the toolkit's periodic-patch value (:func:`dispersion.waves.timestep.patch_omega_max`).
    tol : float
        Relative residual of the Lanczos Ritz pair.
    """
    import scipy.sparse.linalg as spla

    t0 = time.perf_counter()
    A, M, Minv, count = _operator(mesh, op)
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])
    try:
        if isinstance(M, str):  # the product of the banded inverse mass with K: Arnoldi
            vals = spla.eigs(A, k=1, which="LR", tol=tol, v0=v0,
                             ncv=min(A.shape[0] - 1, 60), maxiter=5000,
                             return_eigenvectors=False).real
        else:
            vals = spla.eigsh(A, k=1, M=M, Minv=Minv, which="LA", tol=tol, v0=v0,
                              ncv=min(A.shape[0] - 1, 60), maxiter=5000,
                              return_eigenvectors=False)
    except spla.ArpackNoConvergence as exc:
        raise ConvergenceError(f"Lanczos did not converge on the strip's largest frequency "
                               f"({exc})") from None
    w2 = float(vals[-1])
    if not w2 > 0:
        raise ConvergenceError(f"the strip's largest eigenvalue is {w2}, not positive")
    omega = math.sqrt(w2)
    omega_max = round_up(omega)
    omega_b = dt_b = why = None
    if bloch:
        from dispersion.errors import InputError

        try:
            omega_b, dt_b = bloch_step(mesh.plan)
        except InputError as exc:  # a rule the Bloch plate patch does not model
            why = str(exc)
    return MeshCriticalStep(omega, omega_max, 2.0 / omega_max, omega_b, dt_b, count[0],
                            time.perf_counter() - t0, why)


def bloch_step(plan) -> tuple[float, float]:
    """The toolkit's largest frequency and critical step of the Bloch patch of ``plan``."""
    import sympy

    from dispersion.symbolic.plate import plate_patch
    from dispersion.time_stepping.timestep import patch_omega_max

    s = plan.strip
    patch = plate_patch(s.p, plan.n, "bloch", sympy.Rational(plan.r.numerator, plan.r.denominator),
                        s.mass, s.contact, sympy.Rational(repr(s.gamma_s)))
    w = patch_omega_max(patch, plan.nu, n_theta=17, exact=False)[0]
    return float(w), 2.0 / float(w)
