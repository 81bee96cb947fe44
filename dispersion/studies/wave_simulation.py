"""Measured cost against measured accuracy: a guided-wave burst simulated with every mass rule.

For each mode of the size (:data:`SIZES`), each degree p and each rule of the registry
(:data:`dispersion.symbolic.mass_rule.RULES`, iterated, never listed here), the burst of
:class:`dispersion.simulation.strip.Strip` is simulated over 40 wavelengths
(:func:`dispersion.simulation.wave_run.simulate`) at increasing elements per wavelength N.
What a user pays is the wall time of the explicit loop (median of its five timed segments,
times the steps: every run simulates the same time); what a user gets is the error of the
received burst after 40 wavelengths against the exact reference.

Rules stated before any result was looked at:

* **the arrival-time error** of a run is the larger of the envelope-peak and the
  envelope-centroid (energy) errors at the far station (:mod:`dispersion.simulation.signal_error`);
  a run meets a target (:data:`TARGETS`: 1 % and 0.1 %) when it is at most the target and
  the run lists no failure;
* **the sweep** of a (mode, p, rule) runs N upwards through the size's list and stops after
  the first run that meets the smallest target (a finer mesh costs more and is not needed);
  a run over the size's cost budget (DOF-steps, :mod:`dispersion.simulation.run_cost`) is not
  run and is listed, with the bound;
* **the cheapest** (p, rule, N) for a target is the run of least measured loop time that
  meets it; the same is reported for the modelled cost of today's chart (steps per unit
  time x DOFs x the rule's modelled work per DOF, :mod:`dispersion.studies.cost_accuracy`),
  so the two choices can be compared;
* **the prediction holds** for a run when the measured error lies within
  :data:`PREDICTION_RTOL` of the predicted one (or :data:`PREDICTION_ATOL` absolute);
* **the verification** of the reference: one converged run (``WaveSimulationSize.verification``:
  a high degree, consistent mass, a fine mesh, 0.3 of the critical step) must meet the
  smallest target, and its measured phase-velocity error must agree with the predicted one
  within :data:`VERIFY_ATOL` (the reference's own accuracy over the 40 wavelengths: three
  independent computations, the simulation, the exact modal synthesis and the fully discrete
  Bloch branch, agreeing); else the study lists a failure;
* **the signals shown** are re-simulated after the sweep (same inputs, same numbers: the
  re-run is checked against the sweep's point): the verification run, the cheapest run of
  each target, and the coarsest lumped p = 1 run.

The sweep is a set of independent tasks, one per (mode, p, rule), run through
:func:`dispersion.sweep.parallel_map` (a dask executor when given one); every point records
the worker (host, process) that ran it, and the result how many there were.

>>> size = SIZES["quick"]
>>> size.degrees, size.elements_per_wavelength
((1, 2), (4, 8))
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["SIZES", "SIZE_ENV", "TARGETS", "PREDICTION_RTOL", "PREDICTION_ATOL", "VERIFY_ATOL",
           "WaveSimulationSize", "SweepPoint", "Refusal", "Cheapest", "SignalTrace",
           "PredictionVerdict", "PREDICTED_MEASURES", "STRONG_DISPERSION",
           "WaveSimulationStudy", "wave_simulation", "measure"]

#: Arrival-time error targets after 40 wavelengths.
TARGETS = (1e-2, 1e-3)
#: The prediction holds where |measured - predicted| <= RTOL |predicted| (or ATOL).
PREDICTION_RTOL = 0.2
PREDICTION_ATOL = 2e-4
#: The verification run's phase-velocity error must match its prediction to this (absolute).
VERIFY_ATOL = 1e-5
#: Environment variable naming the size of ``dispersion reproduce``'s run (default "default").
SIZE_ENV = "DISPERSION_WAVE_SIMULATION_SIZE"


@dataclass(frozen=True)
class WaveSimulationSize:
    """What a sweep covers: modes, degrees, N list, the per-run DOF-step budget, the
    verification run and the base strip every run varies."""

    name: str
    modes: tuple[str, ...]
    degrees: tuple[int, ...]
    elements_per_wavelength: tuple[float, ...]
    budget: int
    verification: dict
    base: dict = field(default_factory=dict)


#: The sizes. ``default`` is what ``dispersion reproduce`` runs (about 5 minutes at
#: --jobs 2); ``full`` the whole sweep of the issue (A0 too, N up to 32); ``quick`` a smoke run.
SIZES = {
    "quick": WaveSimulationSize("quick", ("S0",), (1, 2), (4, 8), 10**7,
                                {"p": 2, "mass": "consistent", "elements_per_wavelength": 12,
                                 "courant": 0.3}),
    "default": WaveSimulationSize("default", ("S0",), (1, 2, 3, 4), (4, 6, 8, 12, 16),
                                  25 * 10**6,
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
    stands).
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

    @property
    def ok(self) -> bool:
        return not self.failures


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
    """The cheapest run meeting ``target`` (by ``by``: measured seconds or modelled cost).

    ``cancellation``: the run meets the target by a cancellation of errors near its N, not
    by being converged: the signed (energy) arrival error of its (mode, p, rule) has the other
    sign at the next coarser N (it crossed zero in between), or the next finer N run has a
    larger error (a finer mesh misses what this one met). ``robust``: the cheapest choice
    among the runs that are not such a cancellation.
    """

    mode: str
    target: float
    by: str
    p: int | None
    mass: str | None
    elements_per_wavelength: float | None
    loop_seconds: float | None
    modelled_work: float | None
    arrival_error: float | None
    cancellation: bool = False
    robust: bool = False


@dataclass(frozen=True)
class SignalTrace:
    """A far-station signal and its reference, cut to the burst and decimated, for a figure."""

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


@dataclass(frozen=True)
class PredictionVerdict:
    """Does the prediction hold for ``points[index]`` and ``measure``? And if not, why (the
    first of the stated reasons that applies, from the point's own numbers)."""

    index: int
    measure: str
    measured: float | None
    predicted: float | None
    holds: bool
    reason: str | None


#: The measures the prediction is checked on: (name, measured field, predicted field).
PREDICTED_MEASURES = (
    ("envelope-peak arrival (carrier)", "peak_arrival_error", "predicted_arrival_error"),
    ("energy arrival (carrier)", "energy_arrival_error", "predicted_arrival_error"),
    ("energy arrival (band)", "energy_arrival_error", "predicted_band_arrival_error"),
    ("phase velocity (carrier)", "phase_velocity_error", "predicted_phase_velocity_error"),
)
#: Above this predicted error the burst's band sees very different discrete velocities.
STRONG_DISPERSION = 0.05


def _verdict(i: int, pt: SweepPoint, name: str, mfield: str, pfield: str) -> PredictionVerdict:
    m, p = getattr(pt, mfield), getattr(pt, pfield)
    if m is None:
        return PredictionVerdict(i, name, None, p, False, "not measured: the carrier phase's "
                                 "branch could not be followed along the strip")
    if p is None:
        why = pt.prediction_failure or ("the sampled branch does not reach enough of the "
                                        "burst's band")
        return PredictionVerdict(i, name, m, None, False, f"no prediction: {why}")
    holds = abs(m - p) <= max(PREDICTION_RTOL * abs(p), PREDICTION_ATOL)
    reason = None
    if not holds:
        pk, en = pt.peak_arrival_error, pt.energy_arrival_error
        if abs(p) > STRONG_DISPERSION:
            reason = (f"strong discrete dispersion (predicted {100 * p:+.3g} %): the velocities "
                      "across the burst's band differ, a prediction at the carrier alone does "
                      "not describe the burst")
        elif mfield == "peak_arrival_error" and abs(pk - en) > PREDICTION_RTOL * abs(en):
            reason = ("the envelope is distorted (its peak and its energy centroid disagree): "
                      "the peak is not the group delay of the carrier")
        elif mfield == "energy_arrival_error" and pfield == "predicted_arrival_error":
            band = pt.predicted_band_arrival_error
            averaged = band is not None and abs(m - band) <= max(PREDICTION_RTOL * abs(band),
                                                                  PREDICTION_ATOL)
            reason = ("the energy centroid travels at the group delay averaged over the band "
                      + ("(and the band prediction holds)" if averaged else
                         "(the band prediction misses it too)")
                      + ", the prediction is that of the carrier alone")
        else:
            reason = "not explained by the stated reasons"
    return PredictionVerdict(i, name, m, p, bool(holds), reason)


@dataclass(frozen=True)
class WaveSimulationStudy:
    """The study's result: the sweep, its front, the cheapest choices, the prediction check."""

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
    prediction_rtol: float
    prediction_atol: float
    failures: tuple[str, ...] = ()

    def title(self) -> str:
        return (f"Guided-wave simulation, measured cost against measured accuracy "
                f"({self.size.name} size: {len(self.points)} runs)")


def _base_strip(size: WaveSimulationSize):
    from dispersion.simulation.strip import Strip

    return Strip(**size.base)


def _point(run, worker: str) -> SweepPoint:
    e = run.far
    arrival = max(abs(e.arrival_error), abs(e.energy_arrival_error))
    pred = run.prediction
    setup = sum(v for k, v in run.seconds.items() if k in ("assembly", "factorization"))
    return SweepPoint(
        run.strip.mode, run.strip.p, run.strip.mass, run.strip.elements_per_wavelength,
        run.plan.n, run.dofs, run.mass_kind, run.n_steps, run.dt, run.step.dt_crit,
        run.step.dt_bloch, run.seconds_per_step[1] * run.n_steps, run.seconds_per_step,
        setup, run.seconds_per_time, run.modelled_cost, run.modelled_work, run.nbytes,
        arrival, e.arrival_error,
        e.energy_arrival_error, e.phase_error if run.phase_certain else None,
        e.phase_velocity_error if run.phase_certain else None, e.l2_error,
        e.out_of_band, None if pred is None else pred.arrival_error,
        None if pred is None else pred.phase_error,
        None if pred is None else pred.phase_velocity_error,
        None if pred is None else pred.failure, run.band_prediction,
        (e.failure,) if e.failure else (), worker)


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
        if pt.ok and pt.arrival_error <= min(TARGETS):
            break
    return points, refused


def _cancellation(points, pt) -> bool:
    """True if ``pt`` meets its error by a cancellation (see :class:`Cheapest`)."""
    line = sorted((q for q in points if (q.mode, q.p, q.mass) == (pt.mode, pt.p, pt.mass)
                   and not q.failures), key=lambda q: q.elements_per_wavelength)
    i = line.index(pt)
    signs = [math.copysign(1.0, q.energy_arrival_error) for q in line]
    crossed = i > 0 and signs[i - 1] != signs[i]
    worse = i + 1 < len(line) and line[i + 1].arrival_error > pt.arrival_error
    return bool(crossed or worse)


def _cheapest(points, mode, target, by, robust: bool = False):
    ok = [pt for pt in points if pt.mode == mode and pt.ok and pt.arrival_error <= target
          and not (robust and _cancellation(points, pt))]
    key = ((lambda q: q.loop_seconds) if by == "measured" else
           (lambda q: math.inf if q.modelled_work is None else q.modelled_work))
    if not ok:
        return Cheapest(mode, target, by, None, None, None, None, None, None, False, robust)
    best = min(ok, key=key)
    return Cheapest(mode, target, by, best.p, best.mass, best.elements_per_wavelength,
                    best.loop_seconds, best.modelled_work, best.arrival_error,
                    _cancellation(points, best), robust)


def _trace(why, strip, sweep_point) -> SignalTrace:
    from dispersion.simulation.wave_run import simulate

    run = simulate(strip, predict=False, bloch=False)
    t = run.times
    e = run.far
    D = 2 * math.pi * strip.cycles / run.plan.omega_c
    window = (t >= e.arrival_reference - 1.2 * D) & (t <= e.arrival_reference + 1.2 * D)
    step = max(1, int(np.count_nonzero(window) // 400))
    idx = np.flatnonzero(window)[::step]
    same = sweep_point is None or (
        abs(max(abs(e.arrival_error), abs(e.energy_arrival_error)) - sweep_point.arrival_error)
        <= 1e-12 * max(1.0, abs(sweep_point.arrival_error)))
    return SignalTrace(why, strip.mode, strip.p, strip.mass, strip.elements_per_wavelength,
                       strip.courant, tuple(t[idx].tolist()), tuple(run.records[idx, -1].tolist()),
                       tuple(run.reference[idx, -1].tolist()),
                       max(abs(e.arrival_error), abs(e.energy_arrival_error)), bool(same))


def wave_simulation(size: str | WaveSimulationSize = "default", executor=None,
                    jobs: int | None = None) -> WaveSimulationStudy:
    """Run the study at ``size`` (a name of :data:`SIZES` or a :class:`WaveSimulationSize`)."""
    from dispersion.errors import InputError, check_choice
    from dispersion.studies.cost_accuracy import pareto_front
    from dispersion.simulation.wave_run import simulate
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
    failures = []
    try:
        vrun = simulate(verify)
        verification = _point(vrun, _worker())
        v = verification
        gap = (math.inf if None in (v.predicted_phase_velocity_error, v.phase_velocity_error)
               else abs(v.phase_velocity_error - v.predicted_phase_velocity_error))
        if not (v.ok and v.arrival_error <= min(TARGETS) and gap <= VERIFY_ATOL):
            failures.append(f"verification: the converged run ({verify.label()}, courant "
                            f"{verify.courant:g}) is {v.arrival_error:.3g} off the reference "
                            f"(target {min(TARGETS):g}) and its phase-velocity error "
                            f"{v.phase_velocity_error} is {gap:.3g} from the predicted "
                            f"(bound {VERIFY_ATOL:g})")
    except InputError as exc:
        verification = None
        failures.append(f"verification run refused: {exc}")
    keep = [pt for pt in points]
    front_mask = pareto_front([pt.loop_seconds for pt in keep],
                              [pt.arrival_error if pt.ok else math.inf for pt in keep])
    front = tuple(i for i, f in enumerate(front_mask) if f and keep[i].ok)
    cheapest = tuple(_cheapest(points, mode, target, by, robust) for mode in size.modes
                     for target in TARGETS for by in ("measured", "modelled")
                     for robust in (False, True))
    traces = []
    if verification is not None:
        traces.append(_trace("verification (converged)", verify, verification))
    for c in cheapest:
        if c.by == "measured" and c.p is not None and not (c.robust and any(
                (o.target, o.by, o.p, o.mass, o.elements_per_wavelength) ==
                (c.target, c.by, c.p, c.mass, c.elements_per_wavelength)
                for o in cheapest if not o.robust)):
            s = replace(base, mode=c.mode, p=c.p, mass=c.mass,
                        elements_per_wavelength=c.elements_per_wavelength)
            pt = next(q for q in points if (q.mode, q.p, q.mass, q.elements_per_wavelength)
                      == (c.mode, c.p, c.mass, c.elements_per_wavelength))
            traces.append(_trace(f"cheapest{' converged' if c.robust else ''} at {c.target:g}",
                                 s, pt))
    coarse = [q for q in points if q.p == 1 and q.mass == "lumped" and q.mode == size.modes[0]]
    if coarse:
        q = min(coarse, key=lambda q: q.elements_per_wavelength)
        coarsest = replace(base, mode=q.mode, p=1, mass="lumped",
                           elements_per_wavelength=q.elements_per_wavelength)
        traces.append(_trace("coarsest p = 1 lumped", coarsest, q))
    for tr in traces:
        if not tr.same_as_sweep:
            failures.append(f"the re-run of {tr.why} ({tr.mass}, p = {tr.p}) gave another error "
                            "than the sweep: the simulation is not deterministic")
    workers = len({pt.worker for pt in points})
    if not points:
        raise InputError("the wave-simulation sweep ran no simulation")
    from dispersion.results import jsonable

    verdicts = tuple(_verdict(i, pt, *m) for i, pt in enumerate(points) if pt.ok
                     for m in PREDICTED_MEASURES)
    return WaveSimulationStudy(size, jsonable(base), rules, TARGETS, tuple(points),
                               tuple(refused), front, cheapest, verification, tuple(traces),
                               verdicts, workers, PREDICTION_RTOL, PREDICTION_ATOL,
                               tuple(failures))


def measure(quick: bool = False, executor=None, size: str | None = None) -> WaveSimulationStudy:
    """The report's measurement: ``size`` (default: the environment's :data:`SIZE_ENV`, else
    ``"default"``; ``quick`` runs ``"quick"``)."""
    if size is None:
        size = "quick" if quick else os.environ.get(SIZE_ENV, "default")
    return wave_simulation(size, executor=executor)
