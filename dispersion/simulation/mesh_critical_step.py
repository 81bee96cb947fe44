"""The critical step of the assembled strip: the finite patch's proven step, beside the lattice's.

Central differences are stable for :math:`\\omega_{max} \\Delta t \\le 2` with
:math:`\\omega_{max}^2` the largest eigenvalue of :math:`\\hat K x = \\omega^2 M_{rr} x`
(massless DOFs condensed, :math:`\\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}`, as the loop
solves them). The strip is a finite patch (:func:`~dispersion.simulation.strip_mesh.strip_patch`)
and its largest frequency is the patch's
(:func:`dispersion.time_stepping.mesh_step.mesh_omega_max`): a Lanczos estimate, then a
*proven* upper bound by a verified Cholesky factorization of :math:`\\sigma M - K` (Rump
2006), the two narrowed by bisection on the inertia. The step the simulation takes is
``courant`` times :math:`2/\\omega_{max}`, with :math:`\\omega_{max}` the proven bound
rounded *up* to six significant digits (the stable side, and the same step on every machine
unless the maximum sits on a rounding boundary).

The toolkit's lattice step (:func:`dispersion.time_stepping.timestep.patch_omega_max`) is that of the
periodic Bloch patch with the strip's thickness mesh, aspect ratio and rule: for p = 1 the
two agree (the strip's maximum approaches the periodic one), for p >= 2 the open mesh's
boundary functions raise :math:`\\omega_{max}` above it (the "outliers" of Cottrell et al.
2006), so the mesh's own step is the smaller. Both are reported; the tests check the value
against the toolkit's dense :func:`dispersion.time_stepping.timestep.matrix_critical_step` on a small
strip.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> from dispersion.simulation.strip_mesh import strip_mesh
>>> from dispersion.simulation.mass_operator import mass_operator
>>> mesh = strip_mesh(plan_strip(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3)))
>>> step = mesh_critical_step(mesh, mass_operator(mesh))
>>> 0 < step.dt_crit <= 2 / step.omega_proven <= 2 / step.omega_lanczos
True

References
----------
S. M. Rump, BIT 46 (2006) 433-452. R. B. Lehoucq, D. C. Sorensen, C. Yang, *ARPACK Users'
Guide*, SIAM 1998. J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, CMAME 195 (2006)
5257-5296 (outlier frequencies of open meshes).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

from dispersion.errors import ConvergenceError

__all__ = ["MeshCriticalStep", "mesh_critical_step", "LANCZOS_TOL", "round_up"]

#: Relative residual of the Lanczos estimate (:data:`dispersion.time_stepping.mesh_step.ESTIMATE_TOL`).
#: The Ritz value is a Rayleigh quotient, below the maximum; the proven bound and the
#: bisection on the inertia then narrow the bracket to 1e-9, whatever the residual.
LANCZOS_TOL = 1e-8


@dataclass(frozen=True)
class MeshCriticalStep:
    """``omega_lanczos`` (the estimate: the best Rayleigh quotient, a lower bound),
    ``omega_max`` (the proven bound rounded up to 6 digits), ``dt_crit = 2 / omega_max``;
    ``omega_bloch`` and ``dt_bloch`` the toolkit's periodic patch (None if not asked);
    ``iterations``: Lanczos operator applications; ``seconds``: the proven largest frequency
    (what a run pays for its step); ``bloch_seconds``: the toolkit's Bloch-patch step beside
    it (a comparison, not needed to run); ``omega_proven`` the proven upper bound itself
    (:func:`dispersion.time_stepping.mesh_step.mesh_omega_max`)."""

    omega_lanczos: float
    omega_max: float
    dt_crit: float
    omega_bloch: float | None
    dt_bloch: float | None
    iterations: int
    seconds: float
    #: Why the toolkit has no Bloch-patch step for this rule (None: it has one, or not asked).
    bloch_failure: str | None = None
    bloch_seconds: float = 0.0
    #: The proven upper bound on the largest frequency (unrounded).
    omega_proven: float | None = None

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


def mesh_critical_step(mesh, op=None, *, bloch: bool = False, tol: float = LANCZOS_TOL
                       ) -> MeshCriticalStep:
    """Largest frequency of the assembled strip, proven (and the Bloch patch's if ``bloch``).

    Parameters
    ----------
    mesh : StripMesh
    op : MassOperator
        Kept for the callers; the finite patch's pencil carries the same mass.
    bloch : bool
        Also the toolkit's periodic-patch value (:func:`dispersion.time_stepping.timestep.patch_omega_max`).
    tol : float
        Relative residual of the Lanczos estimate (the bracket is then narrowed to 1e-9).
    """
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.time_stepping.mesh_step import mesh_omega_max

    t0 = time.perf_counter()
    pen = mesh_pencil(mesh.patch, mesh.matrices)
    w = mesh_omega_max(pen, tol=tol)
    if w.omega_proven is None:
        raise ConvergenceError(f"the strip's largest frequency was not proven: {w.failure}")
    omega_max = round_up(w.omega_proven)
    seconds = time.perf_counter() - t0
    t0 = time.perf_counter()
    omega_b = dt_b = why = None
    if bloch:
        from dispersion.errors import InputError

        try:
            omega_b, dt_b = bloch_step(mesh.plan)
        except InputError as exc:  # a rule the Bloch plate patch does not model
            why = exc.reason  # the fact, without advice the strip cannot follow
    return MeshCriticalStep(w.omega, omega_max, 2.0 / omega_max, omega_b, dt_b, w.applications,
                            seconds, why, time.perf_counter() - t0, w.omega_proven)


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
