"""One guided-wave simulation, measured: :func:`simulate` a :class:`~.strip.Strip`.

The steps, in order (each timed):

1. plan and bound: :func:`~.strip.plan_strip`, then :func:`~.run_cost.estimate_cost` refuses
   in one line what could not finish, before anything is assembled;
2. assemble (:func:`~.strip_mesh.strip_mesh`; a rule the strip cannot run is refused with
   the reason) and prepare the mass (:func:`~.mass_operator.mass_operator`: divide or factorize
   once);
3. the mesh's own critical step by Lanczos, beside the toolkit's Bloch-patch step
   (:func:`~.mesh_critical_step.mesh_critical_step`); the step is ``courant`` times it; the
   cost is checked again with the true step count;
4. the explicit loop (:func:`~.central_difference.run_explicit`), timed in five segments;
5. the reference at every station, continued from the reference station by the exact branch
   (:func:`~.modal_synthesis.continue_signal`), and the errors
   (:func:`~.signal_error.signal_error`);
6. the prediction of the dispersion analysis (:func:`~.dispersion_prediction.predict`: at the
   carrier; :func:`~.dispersion_prediction.band_arrival_error`: the energy arrival over the
   band, weighted by the spectrum received at the reference station).

The result, :class:`WaveRun`, carries the strip it was computed from and renders its own
title, header lines (inputs in words, with units), CSV columns and rows (the signals and
their references), JSON and failures.

>>> run = simulate(Strip(p=1, mass="lumped", travel=1, stations=2, elements_per_wavelength=3,
...                      kappa_c=1.0))
>>> run.n_steps > 0, len(run.errors)
(True, 1)
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from dispersion.rendering import Rendered
from dispersion.simulation.strip import Strip

__all__ = ["WaveRun", "simulate", "Strip"]


@dataclass(frozen=True, repr=False)
class WaveRun(Rendered):
    """A simulated burst with its reference, errors, prediction, costs and failures.

    It renders itself (:class:`dispersion.rendering.Rendered`): its rows are the signals
    (every station's record and reference, CSV and JSON), its text and Markdown forms the
    errors, the prediction and the cost.

    ``records[k, s]`` is the particle velocity (v_x for S0, v_y for A0, on the mid-plane, per
    unit traction over mu, in units of c_T) at station s and time ``times[k]`` (the half steps
    :math:`(k + 1/2)\\Delta t` of central differences); ``reference`` the exact continuation
    of station 0's record (band-limited) to each station. ``errors[s - 1]`` are those of
    station s against its reference. Times in H/c_T.
    """

    strip: Strip
    plan: object
    dofs: int
    massless_points: int
    mass_kind: str
    mass_why: str
    step: object
    dt: float
    n_steps: int
    records: np.ndarray = field(repr=False)
    reference: np.ndarray = field(repr=False)
    errors: tuple
    prediction: object
    seconds: dict
    seconds_per_step: tuple[float, float, float]
    nbytes: int
    failures: tuple[str, ...] = ()
    #: False if the carrier phase could not be followed from the reference station (its
    #: 2 pi branch, and so the phase errors, are then uncertain; the arrival times stand).
    phase_certain: bool = True
    #: The energy arrival error the fully discrete branch predicts over the burst's band
    #: (:func:`~.dispersion_prediction.band_arrival_error`), or None.
    band_prediction: float | None = None

    @property
    def times(self) -> np.ndarray:
        """The half steps :math:`(k + 1/2)\\Delta t` of the records (H/c_T)."""
        return (np.arange(self.n_steps) + 0.5) * self.dt

    # ----------------------------------------------------------------- costs
    @property
    def seconds_per_time(self) -> float:
        """Measured cost: wall seconds of the loop per simulated H/c_T (median segment rate)."""
        return self.seconds_per_step[1] / self.dt

    @property
    def modelled_cost(self) -> float:
        """The chart's first model: steps per unit time x DOFs (DOF-steps per H/c_T)."""
        return self.dofs / self.dt

    @property
    def modelled_work(self) -> float | None:
        """Today's chart's model (:mod:`dispersion.studies.cost_accuracy`): steps per unit
        time x DOFs x the rule's modelled multiply-adds per DOF and step (its stated
        ``explicit_cost``, two dimensions), or None for a rule that states none."""
        from dispersion.mass_rules.mass_rule import get_rule

        cost = getattr(get_rule(self.strip.mass), "explicit_cost", None)
        if cost is None:
            return None
        return self.modelled_cost * cost.work_per_dof(self.strip.p, 2, dofs=self.dofs)

    @property
    def far(self):
        """The errors at the far station (the travel of ``strip.travel`` wavelengths)."""
        return self.errors[-1]

    # ----------------------------------------------------------------- rendering
    def title(self) -> str:
        return (f"{self.strip.mode} burst over {self.strip.travel:g} wavelengths: "
                f"{self.strip.label()}")

    def header_lines(self) -> list[str]:
        from dispersion.materials.materials import MATERIALS

        s, pl = self.strip, self.plan
        mat = MATERIALS[s.material]
        f_khz = pl.omega_c / (2 * math.pi) / pl.time_unit_us * 1e3
        lines = [
            f"material: {mat.name} (c_L {mat.c_L:g} m/s, c_T {mat.c_T:g} m/s, nu {pl.nu:.4g}), "
            f"plane strain, thickness d = {s.thickness_mm:g} mm (H = d/2)",
            f"burst: {s.cycles}-cycle Hann-windowed tone burst, {s.mode}, carrier kappa_c = "
            f"k H = {s.kappa_c:g}, Omega_c = omega H / c_T = {pl.omega_c:.6g} "
            f"({f_khz:.4g} kHz), wavelength {pl.wavelength:.6g} H",
            f"load: uniform end traction at x = 0 along {'x' if s.kind == 'S' else 'y'} "
            f"({'symmetric' if s.kind == 'S' else 'antisymmetric'}); record: "
            f"particle velocity {'v_x' if s.kind == 'S' else 'v_y'} on the mid-plane (the "
            "difference of displacements over a step: central differences' own velocity)",
            f"mesh: B-splines of degree p = {s.p}, {pl.n_elements_x} x {pl.n_elements_y} "
            f"elements ({s.elements_per_wavelength:g} per wavelength along x, element "
            f"length {pl.element_length:.6g} H), n = {pl.n} control points through the "
            f"thickness, {self.dofs} DOFs ({self.massless_points} massless points)",
            f"mass: {s.mass} ({self.mass_kind}: {self.mass_why})"
            + (f", contact set {s.contact}, gamma_s = {s.gamma_s:g}"
               if self.massless_points else ""),
            f"strip: length {pl.length:.6g} H ({pl.length / pl.wavelength:.4g} wavelengths), "
            f"stations at {', '.join(f'{x / pl.wavelength:.4g}' for x in pl.stations)} "
            "wavelengths",
            f"time: central differences, dt = {self.dt:.6g} H/c_T = {s.courant:g} x the mesh's "
            f"critical step {self.step.dt_crit:.6g} (Lanczos)"
            + (f"; Bloch patch's step {self.step.dt_bloch:.6g}" if self.step.dt_bloch
               else f"; no Bloch-patch step ({self.step.bloch_failure})"
               if self.step.bloch_failure else "")
            + f"; {self.n_steps} steps to t = {self.n_steps * self.dt:.6g} H/c_T "
            f"({self.n_steps * self.dt * pl.time_unit_us:.4g} us)",
            f"reference: the first station's record band-limited to Omega in "
            f"[{pl.band[0]:.4g}, {pl.band[1]:.4g}] and continued by the exact {s.mode} branch",
        ]
        return lines

    def columns(self) -> tuple[str, ...]:
        cols = ["t [H/c_T]", "t [us]"]
        for x in self.plan.stations:
            lam = x / self.plan.wavelength
            cols += [f"v({lam:.4g} wavelengths) [c_T]",
                     f"reference({lam:.4g} wavelengths) [c_T]"]
        return tuple(cols)

    def rows(self) -> list[dict]:
        cols = self.columns()
        t = self.times
        data = [t, t * self.plan.time_unit_us]
        for s in range(len(self.plan.stations)):
            data += [self.records[:, s], self.reference[:, s]]
        block = np.column_stack(data)
        return [dict(zip(cols, map(float, row))) for row in block]

    def summary(self) -> dict:
        """The run without its signals (plain data: the study stores these)."""
        from dispersion.results import jsonable

        e = self.far
        return jsonable({
            "strip": self.strip, "n": self.plan.n, "n_elements_x": self.plan.n_elements_x,
            "n_elements_y": self.plan.n_elements_y, "dofs": self.dofs,
            "massless_points": self.massless_points, "mass_kind": self.mass_kind,
            "dt": self.dt, "n_steps": self.n_steps, "t_end": self.n_steps * self.dt,
            "omega_max_lanczos": self.step.omega_lanczos, "omega_max": self.step.omega_max,
            "dt_crit": self.step.dt_crit, "dt_bloch": self.step.dt_bloch,
            "lanczos_iterations": self.step.iterations,
            "arrival_error": e.arrival_error,
            "phase_error": e.phase_error if self.phase_certain else None,
            "phase_velocity_error": e.phase_velocity_error if self.phase_certain else None,
            "phase_certain": self.phase_certain, "l2_error": e.l2_error,
            "energy_arrival_error": e.energy_arrival_error,
            "out_of_band": e.out_of_band, "errors": self.errors,
            "prediction": self.prediction, "band_prediction": self.band_prediction,
            "seconds": self.seconds, "seconds_per_step": self.seconds_per_step,
            "seconds_per_time": self.seconds_per_time, "modelled_cost": self.modelled_cost,
            "modelled_work": self.modelled_work,
            "nbytes": self.nbytes, "failures": self.failures,
        })

    def json_extra(self) -> dict:
        """The run without its signals beside them (:meth:`summary`)."""
        return {"summary": self.summary()}

    def station_lines(self) -> list[str]:
        """The errors at every station and the prediction, one line each (text forms)."""
        lines = []
        for x, e in zip(self.plan.stations[1:], self.errors):
            lam = (x - self.plan.stations[0]) / self.plan.wavelength
            phase = (f"phase {e.phase_error:+.4g} rad (phase velocity "
                     f"{100 * e.phase_velocity_error:+.4g} %)" if self.phase_certain
                     else "phase not followed")
            lines.append(f"after {lam:.4g} wavelengths: arrival {100 * e.arrival_error:+.4g} % "
                         f"(peak), {100 * e.energy_arrival_error:+.4g} % (energy); {phase}; "
                         f"L2 {e.l2_error:.4g}")
        pred = self.prediction
        if pred is not None and pred.failure is None:
            band = ("" if self.band_prediction is None else
                    f", {100 * self.band_prediction:+.4g} % (energy, over the band)")
            lines.append(f"predicted by the fully discrete branch: arrival "
                         f"{100 * pred.arrival_error:+.4g} % (carrier){band}; phase "
                         f"{pred.phase_error:+.4g} rad (phase velocity "
                         f"{100 * pred.phase_velocity_error:+.4g} %)")
        lo, med, hi = self.seconds_per_step
        lines.append(f"cost: {med * self.n_steps:.3g} s for {self.n_steps} steps of "
                     f"{self.dofs} DOFs ({med:.3g} s per step, {lo:.3g} to {hi:.3g} over the "
                     f"timed segments; {self.seconds_per_time / self.plan.time_unit_us:.3g} s "
                     f"per simulated us); modelled: {self.modelled_cost:.4g} DOF-steps per H/c_T"
                     + ("" if self.modelled_work is None else
                        f", {self.modelled_work:.4g} multiply-adds per H/c_T")
                     + f"; {self.nbytes / 1e6:.3g} MB")
        return lines

    def to_text(self, digits: int = 7) -> str:
        """Title, the errors at every station, the prediction and the cost, the inputs and
        the failures (the signals themselves are in the CSV and JSON forms)."""
        lines = [self.title(), "", *self.station_lines(), "", *self.header_lines()]
        lines += ([""] + [f"failure: {f}" for f in self.failures] if self.failures else [])
        return "\n".join(lines)

    def to_markdown(self, digits: int = 7) -> str:
        parts = [f"**{self.title()}**", "\n".join(f"- {x}" for x in self.station_lines()),
                 "\n".join(f"- {x}" for x in self.header_lines())]
        if self.failures:
            parts.append("\n".join(f"- failure: {f}" for f in self.failures))
        return "\n\n".join(parts)


def simulate(strip: Strip, *, bloch: bool = True, predict: bool = True, segments: int = 5,
             energy_every: int = 0, cost_limit: int | None = None) -> WaveRun:
    """Run one simulation of ``strip`` and measure it (module docstring).

    ``bloch``: also the toolkit's Bloch-patch step; ``predict``: the dispersion analysis's
    prediction; ``cost_limit``: a DOF-step bound below :data:`~.run_cost.MAX_DOF_STEPS`.
    """
    from dispersion.simulation.central_difference import run_explicit
    from dispersion.simulation.dispersion_prediction import predict as prediction
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.mesh_critical_step import mesh_critical_step
    from dispersion.simulation.modal_synthesis import continue_signal, exact_branch, fft_length
    from dispersion.simulation.run_cost import (MAX_DOF_STEPS, RunCost, check_cost,
                                                estimate_cost)
    from dispersion.simulation.signal_error import (carrier_phase, envelope_centroid,
                                                    envelope_peak, signal_error)
    from dispersion.simulation.strip import plan_strip
    from dispersion.simulation.strip_mesh import strip_mesh
    from dispersion.simulation.tone_burst import ToneBurst

    if not isinstance(strip, Strip):
        raise TypeError("strip must be a Strip")
    limit = MAX_DOF_STEPS if cost_limit is None else min(int(cost_limit), MAX_DOF_STEPS)
    seconds = {}
    t0 = time.perf_counter()
    plan = plan_strip(strip)
    what = f"simulation ({strip.label()})"
    check_cost(estimate_cost(plan), what, limit)
    seconds["plan"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    mesh = strip_mesh(plan)
    seconds["assembly"] = time.perf_counter() - t0
    op = mass_operator(mesh)
    seconds["factorization"] = op.seconds
    step = mesh_critical_step(mesh, op, bloch=bloch)
    seconds["critical_step"] = step.seconds
    dt = strip.courant * step.dt_crit
    n_steps = math.ceil(plan.t_end / dt)
    check_cost(RunCost(mesh.n_dofs, n_steps, False, mesh.step_kind[0] == "dense"), what, limit)
    burst = ToneBurst(strip.cycles, plan.omega_c)
    force = burst.signal(np.arange(n_steps) * dt)
    run = run_explicit(mesh, op, dt, force, segments=segments, energy_every=energy_every)
    seconds["loop"] = run.seconds
    t0 = time.perf_counter()
    x_rec = np.diff(run.records, axis=0) / dt  # velocity at the half steps
    nfft = fft_length(x_rec.shape[0])
    bins = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
    bins = bins[(bins >= plan.band[0]) & (bins <= plan.band[1])]
    kappa_b, group_b = exact_branch(strip.kind, plan.nu, bins)  # one certified solve

    def wavenumber(omega):  # the band's bins, solved above
        return kappa_b if omega.shape == bins.shape else exact_branch(strip.kind, plan.nu,
                                                                      omega)[0]

    n_user = len(plan.stations)
    x = np.asarray(plan.stations + plan.phase_stations)
    rec = x_rec
    ref = continue_signal(rec[:, 0], dt, x - x[0], wavenumber, plan.band)
    # the carrier phase error followed from zero at x0, one wavelength at a time
    wrapped = [carrier_phase(rec[:, j], ref[:, j], dt, plan.band, plan.omega_c)
               for j in range(n_user, x.size)]
    unwrapped = np.unwrap(wrapped)
    phase_x = x[n_user:]
    failures = []
    # (at x0 the phase is that of a record against itself band-limited: zero up to the
    # truncation of the band-limited record to its length)
    phase_certain = not (wrapped and (abs(wrapped[0]) > 1e-2 or np.max(
        np.abs(np.diff(unwrapped)), initial=0) > math.pi / 2))
    if not phase_certain:
        failures.append("the carrier phase turns by more than a quarter turn over a wavelength: "
                        "its branch at the stations is not certain")
    t_origin = (envelope_peak(rec[:, 0], dt, plan.band)[0],
                envelope_centroid(rec[:, 0], dt, plan.band))
    kappa_c = strip.kappa_c  # the carrier is the exact branch's at kappa_c (plan_strip)
    errors = tuple(signal_error(rec[:, s], ref[:, s], dt, plan.band, plan.omega_c,
                                origin=t_origin, distance=float(x[s] - x[0]), kappa=kappa_c,
                                phase_guess=float(np.interp(x[s], phase_x, unwrapped)))
                   for s in range(1, n_user))
    rec, ref = rec[:, :n_user], ref[:, :n_user]
    seconds["reference"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    pred = prediction(plan, dt) if predict else None
    band = (None, "not asked")
    if pred is not None:
        from dispersion.simulation.dispersion_prediction import band_arrival_error

        weights = np.abs(np.fft.rfft(rec[:, 0], nfft)[: np.fft.rfftfreq(nfft).size]) ** 2
        omega_all = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
        inside = (omega_all >= plan.band[0]) & (omega_all <= plan.band[1])
        band = band_arrival_error(pred, bins, weights[inside], group_b)
    seconds["prediction"] = time.perf_counter() - t0
    failures += [f"station {s + 1}: {e.failure}" for s, e in enumerate(errors) if e.failure]
    if pred is not None and pred.failure:
        failures.append(f"prediction: {pred.failure}")
    elif pred is not None and band[1]:
        failures.append(f"band prediction: {band[1]}")
    per_step = run.seconds_per_step
    spread = (float(per_step.min()), float(np.median(per_step)), float(per_step.max()))
    held = mesh.mass if mesh.mass is not None else mesh.mass_inverse
    nbytes = int(run.nbytes + held.data.nbytes + held.indices.nbytes)
    return WaveRun(strip, plan, mesh.n_dofs, int(mesh.massless.size), op.kind, op.why, step,
                   dt, n_steps, rec, ref, errors, pred, seconds, spread, nbytes,
                   tuple(failures), bool(phase_certain), band[0])
