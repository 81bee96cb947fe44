"""Measured cost against measured accuracy: a guided-wave burst simulated with every mass rule.

For each mode of the size (:data:`SIZES`), each degree p and each rule of the registry
(:data:`dispersion.mass_rules.mass_rule.RULES`, iterated, never listed here), the burst of
:class:`dispersion.simulation.strip.Strip` is simulated over 40 wavelengths
(:func:`dispersion.simulation.wave_run.simulate`) at increasing elements per wavelength N.
What a user pays is the wall time of the run: the assembly, the mass's factorization, the
step estimate (Lanczos) and the explicit loop (:data:`dispersion.simulation.wave_run.USER_PAYS`;
the loop's seconds are the median of its five timed segments times the steps, every run
simulating the same time); what a user gets is the received burst after 40 wavelengths,
judged against the exact reference.

Rules stated before any result was looked at:

* **the error of a run** is the largest of three measures at the far station
  (:data:`HEADLINE`, :mod:`dispersion.simulation.signal_error`): the *arrival time* (the larger
  of the envelope-peak and envelope-centroid errors, relative to the travel time), the
  *carrier phase* (:math:`|\\Delta\\varphi|` in radians: the relative L2 error a pure phase
  shift of the carrier makes, so it reads on the waveform's scale) and the *waveform* (the
  relative L2 error of the received signal). A run meets a target (:data:`TARGETS`: 1 % and
  0.1 %) when all three are measured (no failure at the far station, the carrier phase
  followed along the strip) and the largest is at most the target; a run where one cannot be
  measured is *not measurable* and meets none;
* **space and time apart**: beside each run, the same three errors of its semi-discrete
  (space only) records, formed exactly from the run's own records by the frequency map of
  central differences (:mod:`dispersion.simulation.semi_discrete`): what the mesh alone does;
  the rest is the time integration's;
* **the sweep** of a (mode, p, rule) runs N upwards through the size's list and stops after
  the first run that meets the smallest target (a finer mesh costs more and is not needed);
  a run over the size's cost budget (DOF-steps, :mod:`dispersion.simulation.run_cost`) is not
  run and is listed, with the bound;
* **the cheapest** (p, rule, N) for a target is the run of least total seconds (what a user
  pays) that meets it; the same is reported for the modelled cost of today's chart (steps per
  unit time x DOFs x the rule's modelled work per DOF, :mod:`dispersion.studies.cost_accuracy`),
  so the two choices can be compared; and, whatever the targets, the run of least error;
* **the prediction holds** for a run and a measure when the measured error lies within the
  run's own tolerance of the predicted one: the sum of (a) the *floor*, the disagreement the
  verification run (below) shows for that measure: the accuracy of the comparison itself at a
  converged setting; (b) the *measured spread*: the same relative error after half the travel
  and after all of it (a mode travelling uniformly has the same relative error at both; a
  part falling off like one over the distance, the load's near field or the record's ends,
  is as large at the far station as their difference), and for the envelope peak the
  difference of the two arrival estimates (peak and energy centroid); (c) for a prediction
  at the carrier alone, its own estimate of what that leaves out: the difference of the
  carrier's and the band-averaged predictions (:data:`PREDICTED_MEASURES`);
* **the verification** of the reference: one converged run (``WaveSimulationSize.verification``:
  a high degree, consistent mass, a fine mesh, 0.3 of the critical step) must arrive within
  the smallest target, and its measured phase-velocity error must agree with the predicted
  one within :data:`VERIFY_ATOL` (the reference's own accuracy over the 40 wavelengths: three
  independent computations, the simulation, the exact modal synthesis and the fully discrete
  Bloch branch, agreeing); else the study lists a failure;
* **the thickness** of the strip is the scene's plate, meshed by the plan's rule (elements
  within a wavelength over N in either direction): one to three elements through it at these
  N, which is what the scene needs, for every rule alike. What a thicker mesh would cost each
  step is measured instead (:mod:`dispersion.simulation.thickness_cost`: the consistent and
  the lumped step at the base N, every degree, the plan's thickness elements times
  ``WaveSimulationSize.thickness_multiples``), so the page states how a factorized mass's
  share grows with the thickness elements;
* **the signals shown** are re-simulated after the sweep (same inputs, same numbers: the
  re-run is checked against the sweep's point): the verification run, the cheapest run of
  each target, the run of least error, and the coarsest lumped p = 1 run.

The sweep is a set of independent tasks, one per (mode, p, rule), run through
:func:`dispersion.sweep.parallel_map` (a dask executor when given one); every point records
the worker (host, process) that ran it, and the result how many there were.

>>> size = SIZES["quick"]
>>> size.degrees, size.elements_per_wavelength
((1, 2), (4, 8))
>>> headline_error(0.002, -0.03, 0.05)
(0.05, 'waveform')
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["SIZES", "SIZE_ENV", "TARGETS", "HEADLINE", "VERIFY_ATOL", "WaveSimulationSize",
           "SweepPoint", "Refusal", "Cheapest", "SignalTrace", "PredictionVerdict",
           "PREDICTED_MEASURES", "STRONG_DISPERSION", "WaveSimulationStudy", "wave_simulation",
           "measure", "headline_error"]

#: Error targets after 40 wavelengths (the largest of the three measures of :data:`HEADLINE`).
TARGETS = (1e-2, 1e-3)
#: The three measures of a run's error, as shown: (name, field of :class:`SweepPoint`).
HEADLINE = (("arrival", "arrival_error"), ("phase", "phase_error"), ("waveform", "l2_error"))
#: The verification run's phase-velocity error must match its prediction to this (absolute).
VERIFY_ATOL = 1e-5
#: Environment variable naming the size of ``dispersion reproduce``'s run (default "default").
SIZE_ENV = "DISPERSION_WAVE_SIMULATION_SIZE"


def headline_error(arrival, phase, l2) -> tuple[float | None, str | None]:
    """``(error, which)``: the largest of the three measures (magnitudes) and its name from
    :data:`HEADLINE`; ``(None, None)`` if one is not measured (None or not finite)."""
    values = {"arrival": arrival, "phase": phase, "waveform": l2}
    if any(v is None or not math.isfinite(v) for v in values.values()):
        return None, None
    which = max(values, key=lambda k: abs(values[k]))
    return float(abs(values[which])), which


@dataclass(frozen=True)
class WaveSimulationSize:
    """What a sweep covers: modes, degrees, N list, the per-run DOF-step budget, the
    verification run, the base strip every run varies, and the thickness meshes (multiples
    of the plan's) at which each step's cost is measured."""

    name: str
    modes: tuple[str, ...]
    degrees: tuple[int, ...]
    elements_per_wavelength: tuple[float, ...]
    budget: int
    verification: dict
    base: dict = field(default_factory=dict)
    thickness_multiples: tuple[int, ...] = (1, 2, 4, 8)


#: The sizes. ``default`` is what ``dispersion reproduce`` runs (minutes at --jobs 2);
#: ``full`` the whole sweep of the issue (A0 too, N up to 32); ``quick`` a smoke run. The
#: default's budget is 1.2 times its first one (25e6 DOF-steps), as its strip is: the 20 %
#: room for a faster discrete wave (:data:`dispersion.simulation.strip.FAST_ROOM`) keeps the
#: settings it runs.
SIZES = {
    "quick": WaveSimulationSize("quick", ("S0",), (1, 2), (4, 8), 10**7,
                                {"p": 2, "mass": "consistent", "elements_per_wavelength": 12,
                                 "courant": 0.3}, {}, (1, 2)),
    "default": WaveSimulationSize("default", ("S0",), (1, 2, 3, 4), (4, 6, 8, 12, 16),
                                  30 * 10**6,
                                  {"p": 3, "mass": "consistent", "elements_per_wavelength": 8,
                                   "courant": 0.3}),
    "full": WaveSimulationSize("full", ("S0", "A0"), (1, 2, 3, 4),
                               (4, 5, 6, 8, 10, 12, 16, 20, 24, 32), 10**9,
                               {"p": 4, "mass": "consistent", "elements_per_wavelength": 12,
                                "courant": 0.3}),
}


@dataclass(frozen=True)
class SweepPoint:
    """One measured run (errors relative, phase in rad; times in H/c_T; seconds wall).

    ``failures``: what could not be measured at the far station (the run then meets no
    target); ``prediction_failure``: why the analysis has no prediction (the measurement
    stands). ``error`` is the largest of the three measures (:func:`headline_error`,
    ``error_kind`` which one), None where the run is not measurable; the ``semi_`` fields are
    the same for the semi-discrete records (space only). ``spread_*``: the change of a
    relative error between half the travel and the far station (None without a station
    there). Seconds: ``total_seconds`` is what a user pays, the sum of ``assembly_seconds``,
    ``factorization_seconds``, ``step_seconds`` (Lanczos) and ``loop_seconds``;
    ``setup_seconds`` the first three; ``bloch_seconds`` the toolkit's step (not counted).
    """

    mode: str
    p: int
    mass: str
    elements_per_wavelength: float
    n: int
    dofs: int
    mass_kind: str
    n_steps: int
    dt: float
    dt_crit: float
    dt_bloch: float | None
    loop_seconds: float
    seconds_per_step: tuple[float, float, float]
    setup_seconds: float
    seconds_per_time: float
    modelled_cost: float
    modelled_work: float | None
    nbytes: int
    arrival_error: float
    peak_arrival_error: float
    energy_arrival_error: float
    phase_error: float | None
    phase_velocity_error: float | None
    l2_error: float
    out_of_band: float
    predicted_arrival_error: float | None
    predicted_phase_error: float | None
    predicted_phase_velocity_error: float | None
    prediction_failure: str | None
    predicted_band_arrival_error: float | None
    failures: tuple[str, ...]
    worker: str
    error: float | None = None
    error_kind: str | None = None
    semi_arrival_error: float | None = None
    semi_peak_arrival_error: float | None = None
    semi_energy_arrival_error: float | None = None
    semi_phase_error: float | None = None
    semi_phase_velocity_error: float | None = None
    semi_l2_error: float | None = None
    semi_error: float | None = None
    semi_error_kind: str | None = None
    semi_failures: tuple[str, ...] = ()
    spread_peak_arrival: float | None = None
    spread_energy_arrival: float | None = None
    spread_phase_velocity: float | None = None
    assembly_seconds: float = 0.0
    factorization_seconds: float = 0.0
    step_seconds: float = 0.0
    bloch_seconds: float = 0.0
    total_seconds: float = 0.0
    courant: float = 0.0
    thickness_elements: int = 0

    @property
    def ok(self) -> bool:
        """Measurable: no failure at the far station and all three measures there."""
        return not self.failures and self.error is not None


@dataclass(frozen=True)
class Refusal:
    """A (mode, p, rule[, N]) not run, and why (a rule the strip cannot use, or the budget)."""

    mode: str
    p: int
    mass: str
    elements_per_wavelength: float | None
    reason: str


@dataclass(frozen=True)
class Cheapest:
    """The cheapest run meeting ``target`` (by ``by``: measured total seconds or modelled
    cost): ``points[index]`` (None: no run of the sweep meets it).

    ``cancellation``: the run meets the target by a cancellation of errors near its N, not
    by being converged: the signed energy-arrival or phase error of its (mode, p, rule) has
    the other sign at the next coarser N (it crossed zero in between), or the next finer N
    run has a larger error (a finer mesh misses what this one met). ``robust``: the cheapest
    choice among the runs that are not such a cancellation.
    """

    mode: str
    target: float
    by: str
    index: int | None
    p: int | None
    mass: str | None
    elements_per_wavelength: float | None
    cancellation: bool = False
    robust: bool = False


@dataclass(frozen=True)
class SignalTrace:
    """A far-station signal, its semi-discrete twin and its reference, cut to the burst and
    decimated, for a figure; ``failure`` says why the run is not measurable (None: it is),
    ``error`` / ``error_kind`` its headline error."""

    why: str
    mode: str
    p: int
    mass: str
    elements_per_wavelength: float
    courant: float
    t: tuple[float, ...]
    simulated: tuple[float, ...]
    reference: tuple[float, ...]
    arrival_error: float
    same_as_sweep: bool
    semi: tuple[float, ...] | None = None
    phase_error: float | None = None
    l2_error: float | None = None
    error: float | None = None
    error_kind: str | None = None
    failure: str | None = None


@dataclass(frozen=True)
class PredictionVerdict:
    """Does the prediction hold for ``points[index]`` and ``measure``? Within ``tolerance``,
    the sum of its ``parts`` (the rule of the module docstring); and if not, why (the first
    of the stated reasons that applies, from the point's own numbers)."""

    index: int
    measure: str
    measured: float | None
    predicted: float | None
    holds: bool
    reason: str | None
    tolerance: float | None = None
    parts: dict = field(default_factory=dict)


#: The measures the prediction is checked on: (name, measured field, predicted field, the
#: parts of its tolerance beside the floor). A part is a field of :class:`SweepPoint` (a
#: measured spread), ``"peak-energy"`` (the two arrival estimates' difference) or
#: ``"carrier-band"`` (the carrier prediction's difference from the band-averaged one).
PREDICTED_MEASURES = (
    ("envelope-peak arrival (carrier)", "peak_arrival_error", "predicted_arrival_error",
     ("spread_peak_arrival", "peak-energy", "carrier-band")),
    ("energy arrival (carrier)", "energy_arrival_error", "predicted_arrival_error",
     ("spread_energy_arrival", "carrier-band")),
    ("energy arrival (band)", "energy_arrival_error", "predicted_band_arrival_error",
     ("spread_energy_arrival",)),
    ("phase velocity (carrier)", "phase_velocity_error", "predicted_phase_velocity_error",
     ("spread_phase_velocity",)),
)
#: Above this predicted error the burst's band sees very different discrete velocities.
STRONG_DISPERSION = 0.05


def _part(pt: SweepPoint, name: str) -> float | None:
    if name == "peak-energy":
        return abs(pt.peak_arrival_error - pt.energy_arrival_error)
    if name == "carrier-band":
        a, b = pt.predicted_arrival_error, pt.predicted_band_arrival_error
        return None if a is None or b is None else abs(a - b)
    value = getattr(pt, name)
    return None if value is None else float(value)


def _floors(verification: SweepPoint | None) -> dict:
    """The floor of each measure: the verification run's |measured - predicted| (None where
    it has no such pair)."""
    out = {}
    for name, mfield, pfield, _ in PREDICTED_MEASURES:
        m = None if verification is None else getattr(verification, mfield)
        p = None if verification is None else getattr(verification, pfield)
        out[name] = None if m is None or p is None else abs(m - p)
    return out


def _verdict(i: int, pt: SweepPoint, name: str, mfield: str, pfield: str, parts_of=(),
             floor: float | None = None) -> PredictionVerdict:
    m, p = getattr(pt, mfield), getattr(pt, pfield)
    if m is None:
        return PredictionVerdict(i, name, None, p, False, "not measured: the carrier phase's "
                                 "branch could not be followed along the strip")
    if p is None:
        why = pt.prediction_failure or ("the sampled branch does not reach enough of the "
                                        "burst's band")
        return PredictionVerdict(i, name, m, None, False, f"no prediction: {why}")
    parts = {"floor": floor or 0.0}
    for part in parts_of:
        value = _part(pt, part)
        parts[part] = 0.0 if value is None else value
    tolerance = float(sum(parts.values()))
    holds = abs(m - p) <= tolerance
    reason = None
    if not holds:
        if abs(p) > STRONG_DISPERSION:
            carrier_arrival = (pfield == "predicted_arrival_error")
            reason = (f"strong discrete dispersion (predicted {100 * p:+.3g} %): the velocities "
                      "across the burst's band differ"
                      + (", a prediction at the carrier alone does not describe the burst"
                         if carrier_arrival else ""))
        elif mfield == "energy_arrival_error" and pfield == "predicted_arrival_error":
            band = pt.predicted_band_arrival_error
            band_tol = (floor or 0.0) + (pt.spread_energy_arrival or 0.0)
            averaged = band is not None and abs(m - band) <= band_tol
            reason = ("the energy centroid travels at the group delay averaged over the band "
                      + ("(and the band prediction holds)" if averaged else
                         "(the band prediction misses it too)")
                      + ", the prediction is that of the carrier alone")
        else:
            reason = "not explained by the stated reasons"
    return PredictionVerdict(i, name, m, p, bool(holds), reason, tolerance, parts)


@dataclass(frozen=True)
class WaveSimulationStudy:
    """The study's result: the sweep, its front, the cheapest choices, the least errors, the
    prediction check (with the floors of its tolerances) and the step's cost against the
    thickness mesh."""

    size: WaveSimulationSize
    strip: dict
    rules: tuple[str, ...]
    targets: tuple[float, ...]
    points: tuple[SweepPoint, ...]
    refused: tuple[Refusal, ...]
    front: tuple[int, ...]
    cheapest: tuple[Cheapest, ...]
    verification: SweepPoint | None
    traces: tuple[SignalTrace, ...]
    prediction: tuple[PredictionVerdict, ...]
    workers: int
    failures: tuple[str, ...] = ()
    #: Per mode: the index of the measurable run of least error, and of least semi-discrete
    #: error (None: no measurable run).
    least: dict = field(default_factory=dict)
    least_semi: dict = field(default_factory=dict)
    #: The floor of each predicted measure's tolerance (the verification run's disagreement).
    floors: dict = field(default_factory=dict)
    #: The step's cost against the thickness mesh, one per degree
    #: (:class:`dispersion.simulation.thickness_cost.ThicknessCost`).
    thickness: tuple = ()
    headline: tuple = HEADLINE
    user_pays: tuple[str, ...] = ()

    def title(self) -> str:
        return (f"Guided-wave simulation, measured cost against measured accuracy "
                f"({self.size.name} size: {len(self.points)} runs)")


def _base_strip(size: WaveSimulationSize):
    from dispersion.simulation.strip import Strip

    return Strip(**size.base)


def _half_station(run) -> int | None:
    """The index (into ``run.errors``) of the station nearest half the travel, if not the far."""
    x = np.asarray(run.plan.stations)
    if x.size < 3:
        return None
    s = 1 + int(np.argmin(np.abs(x[1:-1] - (x[0] + x[-1]) / 2)))
    return s - 1


def _point(run, worker: str) -> SweepPoint:
    e, sd = run.far, run.semi_far
    arrival = max(abs(e.arrival_error), abs(e.energy_arrival_error))
    phase = e.phase_error if run.phase_certain else None
    failures = tuple(f for f in (e.failure, None if run.phase_certain else
                                 "the carrier phase could not be followed along the strip")
                     if f)
    error, kind = headline_error(arrival, phase, e.l2_error) if not failures else (None, None)
    semi = dict.fromkeys(("arrival", "peak", "energy", "phase", "pv", "l2"))
    semi_error = semi_kind = None
    semi_failures = tuple(f for f in run.failures if f.startswith("semi-discrete"))
    if sd is not None:
        semi.update(arrival=max(abs(sd.arrival_error), abs(sd.energy_arrival_error)),
                    peak=sd.arrival_error, energy=sd.energy_arrival_error, l2=sd.l2_error)
        if run.semi_phase_certain:
            semi.update(phase=sd.phase_error, pv=sd.phase_velocity_error)
        if not sd.failure:
            semi_error, semi_kind = headline_error(semi["arrival"], semi["phase"], semi["l2"])
    h = _half_station(run)
    spreads = [None, None, None]
    if h is not None and not failures and not run.errors[h].failure:
        m = run.errors[h]
        spreads = [abs(e.arrival_error - m.arrival_error),
                   abs(e.energy_arrival_error - m.energy_arrival_error),
                   abs(e.phase_velocity_error - m.phase_velocity_error)]
    pred = run.prediction
    sec = run.seconds
    return SweepPoint(
        run.strip.mode, run.strip.p, run.strip.mass, run.strip.elements_per_wavelength,
        run.plan.n, run.dofs, run.mass_kind, run.n_steps, run.dt, run.step.dt_crit,
        run.step.dt_bloch, run.loop_seconds, run.seconds_per_step,
        run.setup_seconds, run.seconds_per_time, run.modelled_cost, run.modelled_work,
        run.nbytes, arrival, e.arrival_error,
        e.energy_arrival_error, phase, e.phase_velocity_error if run.phase_certain else None,
        e.l2_error, e.out_of_band, None if pred is None else pred.arrival_error,
        None if pred is None else pred.phase_error,
        None if pred is None else pred.phase_velocity_error,
        None if pred is None else pred.failure, run.band_prediction, failures, worker,
        error, kind, semi["arrival"], semi["peak"], semi["energy"], semi["phase"], semi["pv"],
        semi["l2"], semi_error, semi_kind, semi_failures, *spreads,
        sec["assembly"], sec["factorization"], sec["critical_step"], sec.get("bloch_step", 0.0),
        run.total_seconds, run.strip.courant, run.plan.n_elements_y)


def _worker() -> str:
    import socket

    return f"{socket.gethostname()}:{os.getpid()}"


def _sweep_task(task) -> tuple[list[SweepPoint], list[Refusal]]:
    """One (mode, p, rule): N upwards until the smallest target is met (module docstring)."""
    from dispersion.errors import InputError
    from dispersion.simulation.run_cost import RequestTooLarge, check_cost, estimate_cost
    from dispersion.simulation.strip import plan_strip
    from dispersion.simulation.wave_run import simulate

    base, mode, p, mass, epws, budget = task
    points, refused = [], []
    for N in epws:
        strip = replace(base, mode=mode, p=p, mass=mass, elements_per_wavelength=N)
        try:
            check_cost(estimate_cost(plan_strip(strip)), "run", budget)
            run = simulate(strip, cost_limit=budget)
        except RequestTooLarge as exc:
            refused.append(Refusal(mode, p, mass, N, f"over the budget: {exc}"))
            break
        except InputError as exc:
            refused.append(Refusal(mode, p, mass, None, str(exc)))
            break
        pt = _point(run, _worker())
        points.append(pt)
        if pt.ok and pt.error <= min(TARGETS):
            break
    return points, refused


def _line(points, pt):
    return sorted((q for q in points if (q.mode, q.p, q.mass) == (pt.mode, pt.p, pt.mass)
                   and q.ok), key=lambda q: q.elements_per_wavelength)


def _cancellation(points, pt) -> bool:
    """True if ``pt`` meets its error by a cancellation (see :class:`Cheapest`)."""
    line = _line(points, pt)
    i = line.index(pt)
    crossed = i > 0 and any(
        math.copysign(1.0, getattr(line[i - 1], f)) != math.copysign(1.0, getattr(pt, f))
        for f in ("energy_arrival_error", "phase_error"))
    worse = i + 1 < len(line) and line[i + 1].error > pt.error
    return bool(crossed or worse)


def _cheapest(points, mode, target, by, robust: bool = False) -> Cheapest:
    ok = [i for i, pt in enumerate(points) if pt.mode == mode and pt.ok
          and pt.error <= target and not (robust and _cancellation(points, pt))]
    key = ((lambda i: points[i].total_seconds) if by == "measured" else
           (lambda i: math.inf if points[i].modelled_work is None else points[i].modelled_work))
    if not ok:
        return Cheapest(mode, target, by, None, None, None, None, False, robust)
    i = min(ok, key=key)
    best = points[i]
    return Cheapest(mode, target, by, i, best.p, best.mass, best.elements_per_wavelength,
                    _cancellation(points, best), robust)


def _least(points, mode, field_name: str) -> int | None:
    ok = [i for i, pt in enumerate(points) if pt.mode == mode
          and getattr(pt, field_name) is not None
          and (field_name != "error" or pt.ok)]
    return min(ok, key=lambda i: getattr(points[i], field_name)) if ok else None


def _trace(why, strip, sweep_point) -> SignalTrace:
    from dispersion.simulation.wave_run import simulate

    run = simulate(strip, predict=False, bloch=False)
    t = run.times
    e = run.far
    pt = _point(run, "")
    D = 2 * math.pi * strip.cycles / run.plan.omega_c
    window = (t >= e.arrival_reference - 1.2 * D) & (t <= e.arrival_reference + 1.2 * D)
    step = max(1, int(np.count_nonzero(window) // 400))
    idx = np.flatnonzero(window)[::step]
    same = sweep_point is None or (
        abs(pt.arrival_error - sweep_point.arrival_error)
        <= 1e-12 * max(1.0, abs(sweep_point.arrival_error))
        and abs(pt.l2_error - sweep_point.l2_error) <= 1e-12 * max(1.0, sweep_point.l2_error))
    semi = (None if run.semi_records is None else tuple(run.semi_records[idx, -1].tolist()))
    return SignalTrace(why, strip.mode, strip.p, strip.mass, strip.elements_per_wavelength,
                       strip.courant, tuple(t[idx].tolist()), tuple(run.records[idx, -1].tolist()),
                       tuple(run.reference[idx, -1].tolist()), pt.arrival_error, bool(same),
                       semi, pt.phase_error, pt.l2_error, pt.error, pt.error_kind,
                       "; ".join(pt.failures) or None)


def _thickness(size, base) -> tuple:
    """The step's cost against the thickness mesh at the base N, every degree (docstring)."""
    from dispersion.simulation.strip import plan_strip
    from dispersion.simulation.thickness_cost import thickness_cost

    out = []
    for p in size.degrees:
        strip = replace(base, mode=size.modes[0], p=p)
        own = plan_strip(replace(strip, mass="lumped")).n_elements_y
        out.append(thickness_cost(strip, tuple(own * k for k in size.thickness_multiples),
                                  ("lumped", "consistent")))
    return tuple(out)


def wave_simulation(size: str | WaveSimulationSize = "default", executor=None,
                    jobs: int | None = None) -> WaveSimulationStudy:
    """Run the study at ``size`` (a name of :data:`SIZES` or a :class:`WaveSimulationSize`)."""
    from dispersion.errors import InputError, check_choice
    from dispersion.simulation.wave_run import USER_PAYS, simulate
    from dispersion.studies.cost_accuracy import pareto_front
    from dispersion.sweep import parallel_map
    from dispersion.mass_rules.mass_rule import RULES

    if isinstance(size, str):
        size = SIZES[check_choice("size", size, tuple(SIZES))]
    base = _base_strip(size)
    rules = tuple(RULES)
    tasks = [(base, mode, p, mass, size.elements_per_wavelength, size.budget)
             for mode in size.modes for p in sorted(size.degrees, reverse=True)
             for mass in rules]
    verify = replace(base, mode=size.modes[0], **size.verification)
    results = parallel_map(_sweep_task, tasks, executor=executor, jobs=jobs,
                           desc="wave simulation")
    points, refused = [], []
    for pts, ref in results:
        points += pts
        refused += ref
    if not points:
        raise InputError("the wave-simulation sweep ran no simulation")
    failures = []
    try:
        vrun = simulate(verify)
        verification = _point(vrun, _worker())
        v = verification
        gap = (math.inf if None in (v.predicted_phase_velocity_error, v.phase_velocity_error)
               else abs(v.phase_velocity_error - v.predicted_phase_velocity_error))
        if not (not v.failures and v.arrival_error <= min(TARGETS) and gap <= VERIFY_ATOL):
            failures.append(f"verification: the converged run ({verify.label()}, courant "
                            f"{verify.courant:g}) is {v.arrival_error:.3g} off the reference "
                            f"in arrival (target {min(TARGETS):g}) and its phase-velocity error "
                            f"{v.phase_velocity_error} is {gap:.3g} from the predicted "
                            f"(bound {VERIFY_ATOL:g})")
    except InputError as exc:
        verification = None
        failures.append(f"verification run refused: {exc}")
    floors = _floors(verification)
    if any(f is None for f in floors.values()):
        failures.append("the verification run gives no floor for "
                        + ", ".join(k for k, f in floors.items() if f is None)
                        + ": those tolerances have none")
    ok = [i for i, pt in enumerate(points) if pt.ok]
    mask = pareto_front([points[i].total_seconds for i in ok], [points[i].error for i in ok])
    front = tuple(i for i, f in zip(ok, mask) if f)
    cheapest = tuple(_cheapest(points, mode, target, by, robust) for mode in size.modes
                     for target in TARGETS for by in ("measured", "modelled")
                     for robust in (False, True))
    least = {mode: _least(points, mode, "error") for mode in size.modes}
    least_semi = {mode: _least(points, mode, "semi_error") for mode in size.modes}
    traces, shown = [], set()

    def show(why, i):
        pt = points[i]
        if i in shown:
            return
        shown.add(i)
        s = replace(base, mode=pt.mode, p=pt.p, mass=pt.mass,
                    elements_per_wavelength=pt.elements_per_wavelength)
        traces.append(_trace(why, s, pt))

    if verification is not None:
        traces.append(_trace("verification (converged)", verify, verification))
    for c in cheapest:
        if c.by == "measured" and c.index is not None:
            show(f"cheapest{' converged' if c.robust else ''} at {c.target:g}", c.index)
    for mode, i in least.items():
        if i is not None:
            show(f"least error of the sweep ({mode})", i)
    coarse = [i for i, q in enumerate(points)
              if q.p == 1 and q.mass == "lumped" and q.mode == size.modes[0]]
    if coarse:
        show("coarsest p = 1 lumped", min(coarse, key=lambda i: points[i].elements_per_wavelength))
    for tr in traces:
        if not tr.same_as_sweep:
            failures.append(f"the re-run of {tr.why} ({tr.mass}, p = {tr.p}) gave another error "
                            "than the sweep: the simulation is not deterministic")
    thickness = _thickness(size, base)
    workers = len({pt.worker for pt in points})
    from dispersion.results import jsonable

    verdicts = tuple(_verdict(i, pt, name, mfield, pfield, parts, floors[name])
                     for i, pt in enumerate(points) if pt.ok
                     for name, mfield, pfield, parts in PREDICTED_MEASURES)
    return WaveSimulationStudy(size, jsonable(base), rules, TARGETS, tuple(points),
                               tuple(refused), front, cheapest, verification, tuple(traces),
                               verdicts, workers, tuple(failures), least, least_semi, floors,
                               thickness, HEADLINE, USER_PAYS)


def measure(quick: bool = False, executor=None, size: str | None = None) -> WaveSimulationStudy:
    """The report's measurement: ``size`` (default: the environment's :data:`SIZE_ENV`, else
    ``"default"``; ``quick`` runs ``"quick"``)."""
    if size is None:
        size = "quick" if quick else os.environ.get(SIZE_ENV, "default")
    return wave_simulation(size, executor=executor)
