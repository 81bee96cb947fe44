"""The explicit loop: central differences on the strip, lean (CSR mat-vec, in-place updates).

With :math:`\\mathbf w_{k+1/2} = \\Delta t\\, \\mathbf v_{k+1/2}` (the leapfrog form of central
differences, Hughes 2000, 9.3),

.. math::

    \\mathbf w_{k+1/2} = \\mathbf w_{k-1/2} + \\Delta t^2 \\mathbf M_{rr}^{-1}
    (\\mathbf f_r(t_k) - \\mathbf K_{rr} \\mathbf u_{r,k} - \\mathbf K_{rm} \\mathbf u_{m,k}),
    \\qquad \\mathbf u_{r,k+1} = \\mathbf u_{r,k} + \\mathbf w_{k+1/2},

where the massless DOFs (zero rows of the mass, singular rules) obey eq (12) of the paper at
every step, :math:`\\mathbf K_{mm} \\mathbf u_{m,k} = \\mathbf f_m(t_k) - \\mathbf K_{mr}
\\mathbf u_{r,k}` (:math:`K_{mm}` factorized once). Starting at rest with a load that is zero
at t = 0, the scheme conserves exactly (to round-off) the discrete energy

.. math::

    E_{k+1/2} = \\tfrac12 \\mathbf v_{k+1/2}^T \\mathbf M \\mathbf v_{k+1/2}
              + \\tfrac12 \\mathbf u_k^T \\mathbf K \\mathbf u_{k+1}

once the load has ended (the difference of two steps telescopes for symmetric K and M).
The loop is numpy and scipy only: one CSR mat-vec per step (three with massless DOFs), a
division or a solve with the factors of :class:`~dispersion.simulation.mass_operator.MassOperator`,
and in-place vector updates; no Python work per DOF. Stations are read by a gather of the
few DOFs under them.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> from dispersion.simulation.strip_mesh import strip_mesh
>>> from dispersion.simulation.mass_operator import mass_operator
>>> mesh = strip_mesh(plan_strip(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3)))
>>> run = run_explicit(mesh, mass_operator(mesh), 0.05, np.sin(np.arange(40) * 0.05))
>>> run.records.shape, run.n_steps        # 2 stations and 2 phase stations
((41, 4), 40)

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (central differences).
T. Belytschko, W. K. Liu, B. Moran, *Nonlinear Finite Elements for Continua and Structures*,
Wiley 2000, sec. 6.2 (the explicit loop), 6.2.5 (its energy balance). Paper eqs (11)-(12).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from dispersion.errors import ConvergenceError, InputError, check_positive, check_positive_int

__all__ = ["ExplicitRun", "run_explicit", "GROWTH"]

#: Growth of the largest displacement between two chunks of the loop that is taken for an
#: instability (a bounded load on a stable scheme never grows the response by eight orders;
#: an unstable mode grows by |z| > 1 per step from round-off, so this is reached within a
#: few hundred steps even for a step a few per cent over the limit).
GROWTH = 1e8


@dataclass(frozen=True, repr=False)
class ExplicitRun:
    """Records of one explicit run: ``records[k, s]`` at station s and time ``k * dt``
    (k = 0..n_steps), the wall seconds of each of the equal ``segments`` of the loop,
    ``energy`` as ``(k, E_{k-1/2})`` rows (if asked), the final field (if asked, DOFs in
    the mesh's order) and the bytes the loop held."""

    dt: float
    n_steps: int
    records: np.ndarray
    segment_steps: tuple[int, ...]
    segment_seconds: tuple[float, ...]
    energy: np.ndarray | None
    field: np.ndarray | None
    nbytes: int

    @property
    def seconds(self) -> float:
        """Wall seconds of the whole loop."""
        return float(sum(self.segment_seconds))

    @property
    def seconds_per_step(self) -> np.ndarray:
        """Wall seconds per step in each segment (their spread is the timing's)."""
        return np.asarray(self.segment_seconds) / np.asarray(self.segment_steps)

    def __repr__(self) -> str:
        return (f"ExplicitRun({self.n_steps} steps of {self.dt:.4g}, "
                f"{self.records.shape[1]} stations, {self.seconds:.3g} s)")


class _Loop:
    """The state and the operators of one run (made once, then advanced in chunks)."""

    def __init__(self, mesh, op, dt: float, force: np.ndarray):
        import scipy.sparse.linalg as spla

        self.dt, self.force = dt, force
        self.op = op
        r_dofs = (2 * op.massive[:, None] + np.arange(2)).ravel()
        m_dofs = (2 * op.massless[:, None] + np.arange(2)).ravel()
        self.nr = r_dofs.size
        perm = np.concatenate([r_dofs, m_dofs])
        self.perm = perm
        pos = np.empty_like(perm)
        pos[perm] = np.arange(perm.size)
        K = mesh.K if m_dofs.size == 0 else mesh.K[perm][:, perm].tocsr()
        self.K = K
        nr = self.nr
        self.u = np.zeros(perm.size)
        self.w = np.zeros(nr)
        self.ur, self.um = self.u[:nr], self.u[nr:]
        load = pos[mesh.load_dofs]
        self.load_r = load[load < nr]
        self.g_r = mesh.load_values[load < nr]
        self.load_m = load[load >= nr] - nr
        self.g_m = mesh.load_values[load >= nr]
        self.st_dofs = pos[mesh.station_dofs]
        self.st_w = mesh.station_weights
        self.condensed = m_dofs.size > 0
        nbytes = K.data.nbytes + K.indices.nbytes + K.indptr.nbytes + op.nbytes
        if self.condensed:
            self.Krr = K[:nr, :nr].tocsr()
            self.Krm = K[:nr, nr:].tocsr()
            self.Kmr = K[nr:, :nr].tocsr()
            try:
                lu = spla.splu(K[nr:, nr:].tocsc(), permc_spec="NATURAL",
                               diag_pivot_thresh=0.0, options={"SymmetricMode": True})
            except RuntimeError as exc:
                raise ConvergenceError(f"the stiffness of the massless DOFs is singular ({exc})"
                                       ) from None
            self.Kmm_solve = lu.solve
            nbytes += (lu.L.nnz + lu.U.nnz) * 12
            self._solve_massless(0)
        self.diagonal = op.kind == "diagonal"
        self.dense = op.kind == "dense"
        if self.diagonal:
            m = np.repeat(op.diagonal, 2)
            self.minv = 1.0 / m
            self.c = -dt * dt / m
            self.gl = dt * dt / m[self.load_r] * self.g_r
        self.nbytes = int(nbytes + 3 * self.u.nbytes)

    def _solve_massless(self, k: int) -> None:
        s = self.Kmr @ self.ur
        np.negative(s, out=s)
        if self.load_m.size:
            s[self.load_m] += self.g_m * self.force[k] if k < self.force.size else 0.0
        self.um[:] = self.Kmm_solve(s)

    def record(self, out: np.ndarray) -> None:
        np.einsum("sj,sj->s", self.u[self.st_dofs], self.st_w, out=out)

    def advance(self, k0: int, k1: int, records: np.ndarray) -> None:
        """Steps k0 .. k1 - 1: from u_k0 to u_k1, recording u at every new step."""
        dt2, F = self.dt * self.dt, self.force
        u, w, ur = self.u, self.w, self.ur
        if self.dense:  # the rule's own explicit step: a dense M^-1 K (no massless DOFs)
            D, g = self.op.dense, self.op.dense_load * dt2
            for k in range(k0, k1):
                r = D @ u
                r *= -dt2
                r += g * F[k]
                w += r
                u += w
                np.einsum("sj,sj->s", u[self.st_dofs], self.st_w, out=records[k + 1])
            return
        if self.diagonal and not self.condensed:
            K, c, load, gl = self.K, self.c, self.load_r, self.gl
            for k in range(k0, k1):
                r = K @ u
                r *= c
                r[load] += gl * F[k]
                w += r
                u += w
                np.einsum("sj,sj->s", u[self.st_dofs], self.st_w, out=records[k + 1])
            return
        if not self.condensed:
            K, load, g, solve = self.K, self.load_r, self.g_r, self.op.solve
            for k in range(k0, k1):
                r = K @ u
                np.negative(r, out=r)
                r[load] += g * F[k]
                a = solve(r.reshape(-1, 2)).ravel()
                a *= dt2
                w += a
                u += w
                np.einsum("sj,sj->s", u[self.st_dofs], self.st_w, out=records[k + 1])
            return
        Krr, Krm, load, g = self.Krr, self.Krm, self.load_r, self.g_r
        for k in range(k0, k1):
            r = Krr @ ur
            r += Krm @ self.um
            np.negative(r, out=r)
            r[load] += g * F[k]
            if self.diagonal:
                a = r * self.minv
            else:
                a = self.op.solve(r.reshape(-1, 2)).ravel()
            a *= dt2
            w += a
            ur += w
            self._solve_massless(k + 1)
            np.einsum("sj,sj->s", u[self.st_dofs], self.st_w, out=records[k + 1])

    def energy(self, u_prev: np.ndarray, w_prev: np.ndarray, mass) -> float:
        """:math:`E` from u_k (``u_prev``), u_{k+1} (now) and w_{k+1/2} (``w_prev``)."""
        V = w_prev.reshape(-1, 2) / self.dt
        kinetic = 0.5 * float(np.sum(V * (mass @ V)))
        return kinetic + 0.5 * float(u_prev @ (self.K @ self.u))


def run_explicit(mesh, op, dt: float, force, *, segments: int = 5, energy_every: int = 0,
                 keep_field: bool = False) -> ExplicitRun:
    """Run central differences from rest for ``len(force)`` steps of ``dt``.

    Parameters
    ----------
    mesh : StripMesh
    op : MassOperator
        Of the same mesh (:func:`dispersion.simulation.mass_operator.mass_operator`).
    dt : float
        Step (units H/c_T); the caller chooses it below the critical step.
    force : array_like
        Amplitude of the end traction at :math:`t_k = k \\Delta t`, k = 0..n_steps-1.
    segments : int
        The loop is timed in this many equal chunks (the spread of the timing).
    energy_every : int
        If > 0, the discrete energy every this many steps (costs a mat-vec each).
    keep_field : bool
        Return the final displacement of every DOF (mesh order).
    """
    dt = float(check_positive("dt", dt))
    force = np.ascontiguousarray(force, dtype=float)
    if force.ndim != 1 or force.size == 0 or not np.all(np.isfinite(force)):
        raise InputError("force must be a non-empty 1-d array of finite numbers")
    segments = check_positive_int("segments", segments)
    n = force.size
    loop = _Loop(mesh, op, dt, force)
    records = np.zeros((n + 1, len(mesh.station_weights)))
    loop.record(records[0])
    every = int(energy_every)
    marks = set(np.linspace(0, n, min(segments, n) + 1).round().astype(int).tolist())
    energy_steps = set(range(every, n + 1, every)) if every > 0 else set()
    stops = sorted(marks | {k - 1 for k in energy_steps} | energy_steps)
    seconds = {}
    energies = []
    if every <= 0:
        Mrr = None
    elif op.kind == "banded":  # the mass is the inverse of the known banded one
        import scipy.sparse.linalg as spla

        S = spla.splu(mesh.mass_inverse.tocsc())

        class _Inverse:
            def __matmul__(self, V):
                return S.solve(np.ascontiguousarray(V))

        Mrr = _Inverse()
    elif loop.condensed:
        Mrr = mesh.mass[op.massive][:, op.massive].tocsr()
    else:
        Mrr = mesh.mass
    k = 0
    saved = None
    largest = 0.0
    for stop in stops[1:]:
        t0 = time.perf_counter()
        loop.advance(k, stop, records)
        elapsed = time.perf_counter() - t0
        k = stop
        now = float(np.abs(loop.u).max())
        if not np.isfinite(now) or (largest > 0 and now > GROWTH * largest):
            raise ConvergenceError(f"the explicit run blew up at step {k} (|u| grew by more "
                                   f"than {GROWTH:.0e}): the step {dt:.6g} exceeds the "
                                   "critical step")
        largest = max(largest, now)
        seconds[k] = seconds.get(k, 0.0) + elapsed
        if saved is not None and k in energy_steps:
            energies.append((k, loop.energy(saved[0], loop.w.copy(), Mrr)))
            saved = None
        if k + 1 in energy_steps:
            saved = (loop.u.copy(),)
    if not np.all(np.isfinite(records[-1])) or not np.all(np.isfinite(loop.u)):
        raise ConvergenceError("the explicit run blew up (non-finite displacements): the step "
                               "exceeds the critical step")
    seg_steps, seg_seconds = [], []
    acc, prev = 0.0, 0
    for stop in stops[1:]:
        acc += seconds[stop]
        if stop in marks:
            seg_steps.append(stop - prev)
            seg_seconds.append(acc)
            acc, prev = 0.0, stop
    field = None
    if keep_field:
        field = np.empty_like(loop.u)
        field[loop.perm] = loop.u
    nbytes = loop.nbytes + records.nbytes
    return ExplicitRun(dt, n, records, tuple(seg_steps), tuple(seg_seconds),
                       np.array(energies) if every > 0 else None, field, nbytes)
