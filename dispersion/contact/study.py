"""The ring as a study: energy change and chatter over (steps per impact, landing angle).

:func:`measure` (the ``ring`` section of ``dispersion reproduce``) runs

- the default scene with the lumped and the singular mass (Figure 4), each repeated with
  round-off perturbations of the initial velocity, :data:`~.roundoff_spread.SPREAD_RUNS`
  runs in all (:data:`~.roundoff_spread.SPREAD_RULE`: the chatter varies from run to run;
  the spread is reported with the count of runs);
- a grid over the scene's size (steps per impact at the paper's dt, via
  :meth:`~.scenario.Scenario.scaled`) and the landing arc angle ``theta0_deg``;
- a dt sweep of the singular mass with a fitted rate (at least 4 points, fit residual,
  monotonicity stated);
- wall time per step against the number of elements;
- the shown scene at a handful of time steps around the paper's (:data:`DT_FACTORS`), both
  masses: the lumped figures move with dt as much as with round-off;
- the scene's history (:data:`SCENE_HISTORY`): every earlier default scene run again;
- the 1D Signorini scene (:mod:`.signorini`) for every mass and every scheme (plain Newmark
  included, flagged by its energy balance), each row over the round-off perturbations of
  :data:`~.signorini.SIGNORINI_SPREAD_RULE`, as many as every spread has (its errors as a
  spread).

Every run is listed once (a scene asked for twice, such as the grid's copy of the shown
scene, runs once); runs of one mesh and mass step together in batches
(:func:`~.simulate.simulate_rings`, :func:`~.signorini.signorini_runs`), the longest jobs
first on the executor.

``quick`` (CI): the scene scaled by 1/8 (about 4 steps per impact), a 2 x 2 grid, the sweep
on the scene scaled by 1/16, one Signorini period, P1 only; the same spread count.

The rule that picks the default scene (:data:`DEFAULT_RULE`) is stated before any figure.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from dispersion.errors import ConvergenceError
from dispersion.contact.roundoff_spread import SPREAD_RULE, SPREAD_RUNS
from dispersion.contact.scenario import Scenario
from dispersion.contact.signorini import SPREAD_FIELDS, gap_ulps, signorini_runs
from dispersion.contact.simulate import simulate_ring, simulate_rings

__all__ = ["DEFAULT_RULE", "DT_FACTORS", "PAPER", "SCENE_HISTORY", "RingStudy", "fit_rate", "measure",
           "step_seconds", "steps_per_impact"]

#: The paper's energy changes (sec. 3): lumped, singular (percent).
PAPER = {"lumped": -9.5, "singular": -0.097}

#: How the default scene is chosen, stated before its figures are shown.
DEFAULT_RULE = (
    "The default scene is the smallest ring in the size grid whose local impact (one wave "
    "round trip through the wall, 2 t / c_p) spans at least 20 steps of the paper's dt = "
    "0.05 s, landing on the lower end of its arc (theta0 = 180 deg, the landing that gives "
    "the paper's large rotation). Size, angle, gap and end time were tuned while the paper's "
    "figures were in view (history below); this grid shows how much the energy figures "
    "depend on those choices.")

#: The scene's history (``git log -p dispersion/contact/scenario.py``), disclosed: each earlier
#: default as the fields that differ from today's :class:`Scenario` (same material, v0, dt and
#: 16 x 2 elements), measured by :func:`measure` (never typed figures).
SCENE_HISTORY = (
    ("r = 1.8-2 m, arc from 215 deg, gap 0.01 m, t_end 12 s", "first reconstruction (cf6ffba)",
     {"r_inner": 1.8, "r_outer": 2.0, "theta0_deg": 215.0, "gap": 0.01, "t_end": 12.0}),
    ("r = 18-20 m, arc from 200 deg, gap 0.01 m, t_end 40 s", "rescaled (32fd48a)",
     {"r_inner": 18.0, "r_outer": 20.0, "theta0_deg": 200.0, "gap": 0.01, "t_end": 40.0}),
    ("r = 144-160 m, arc from 200 deg, gap 0.08 m, t_end 360 s",
     "rescaled for steps per impact (uncommitted step; as the default, arc from 200 deg)",
     {"theta0_deg": 200.0}),
    ("r = 144-160 m, arc from 180 deg, gap 0.08 m, t_end 360 s", "current default (acd178f)", {}),
)

#: Time steps of the dt spread, relative to the scene's dt (the paper's 0.05 s: 0.045, 0.0499,
#: 0.0501, 0.055 s), run for both masses next to the default run (end time rounded to a
#: whole number of steps).
DT_FACTORS = (0.9, 0.998, 1.002, 1.1)


def steps_per_impact(sc: Scenario) -> float:
    """``2 t / (c_p dt)``: steps of one wave round trip through the wall (plane stress)."""
    c_p = np.sqrt(sc.E / (sc.rho * (1 - sc.nu**2)))
    return float(2 * (sc.r_outer - sc.r_inner) / (c_p * sc.dt))


def fit_rate(x, y) -> dict:
    """Least-squares slope of ``log |y|`` against ``log x`` with its residual.

    ``monotone`` says whether ``|y|`` falls strictly as ``x`` falls; a rate is claimed only
    for at least 4 monotone points.

    >>> r = fit_rate([0.1, 0.05, 0.025, 0.0125], [4e-2, 1e-2, 2.5e-3, 6.25e-4])
    >>> round(r["rate"], 6), r["monotone"], r["points"]
    (2.0, True, 4)
    """
    x, y = np.asarray(x, float), np.abs(np.asarray(y, float))
    order = np.argsort(x)
    x, y = x[order], y[order]
    ok = np.isfinite(y) & (y > 0)
    x, y = x[ok], y[ok]
    if len(x) < 2:
        return {"rate": None, "residual": None, "monotone": False, "points": int(len(x))}
    A = np.column_stack([np.log(x), np.ones(len(x))])
    coef, res, *_ = np.linalg.lstsq(A, np.log(y), rcond=None)
    resid = float(np.sqrt(res[0] / len(x))) if len(res) else 0.0
    return {"rate": float(coef[0]), "residual": resid,
            "monotone": bool(np.all(np.diff(y) > 0)), "points": int(len(x))}


@dataclass(frozen=True)
class RingStudy:
    """Everything the ring report shows (plain data; arrays as lists after JSON)."""

    quick: bool
    rule: str
    scene_history: tuple
    paper: dict
    scenario: dict
    steps_per_impact: float
    default_steps_per_impact: float
    default_r_outer: float
    pair: dict
    spread: dict
    grid: list
    dt_sweep: list
    dt_fit: dict
    sweep_scale: float
    timing: list
    signorini: list
    seconds: dict
    dt_spread: dict = None
    #: How many runs each round-off spread has (:data:`~.roundoff_spread.SPREAD_RULE`).
    spread_rule: str = ""


def _at_dt(sc: Scenario, dt: float) -> Scenario:
    """The scene at step ``dt``, its end time rounded to a whole number of steps (the ring
    flies free by then, so the energy figures do not depend on the last fraction of a step)."""
    return replace(sc, dt=dt, t_end=round(sc.t_end / dt) * dt)


def _series(res, every: int = 1) -> dict:
    keep = ("t", "contact_force", "total", "kinetic", "strain", "penetration",
            "gap_min_greville")
    return {k: np.asarray(res.series[k])[::every].tolist() for k in keep}


def _map(executor, fn, items):
    return list(executor.map(fn, items) if executor is not None else map(fn, items))


def step_seconds(sc: Scenario, mass: str = "singular", **kwargs) -> np.ndarray:
    """Wall time (s) of each time step of one ring run, from the integrator's progress
    callback (assembly and set-up excluded)."""
    stamps = []
    simulate_ring(sc, mass, progress=lambda _: stamps.append(time.perf_counter()), **kwargs)
    return np.diff(stamps)


def _timing(level: int, steps: int) -> dict:
    """Mean wall time per step of the singular mass through the first impact."""
    sc = Scenario().with_level(level)
    dts = step_seconds(replace(sc, t_end=steps * sc.dt))
    return {"level": level, "elements": sc.n_xi_elements * sc.n_eta_elements,
            "dofs": sc.n_dofs,
            "steps": steps, "ms_per_step": 1e3 * float(np.mean(dts))}


def _signorini(args):
    """One Signorini row (``(p, mass, scheme, t_end, runs)``): the run at k = 0 and the
    range of each error over the row's runs, the wall moved ``k`` units of 2^-53
    (:data:`~.signorini.SIGNORINI_SPREAD_RULE`), all runs stepped together."""
    p, mass, scheme, t_end, runs = args
    results = signorini_runs(p=p, mass=mass, scheme=scheme, dt=0.002 if p == 1 else 0.001,
                             t_end=t_end, gaps=gap_ulps(runs))
    r = results[0]
    spread = {"runs": runs}
    for name in SPREAD_FIELDS:
        values = [x.errors[name] for x in results]
        undefined = None in values  # no contact before t_end: no relative error
        spread[name] = {"min": None if undefined else min(values),
                        "max": None if undefined else max(values)}
    return {"p": p, "n_elements": r.n_elements, "mass": mass, "scheme": scheme, "dt": r.dt,
            "t_end": t_end, "seconds": r.seconds, **r.errors, "spread": spread}


def _ring_batch(args) -> list:
    """Ring runs ``(scene, mass, perturbation, seed, keep_series)`` stepped together
    (:func:`~.simulate.simulate_rings`): ``(summary row, series or None)`` each, ``seconds``
    the batch's wall time divided by its runs."""
    runs, every = args
    t0 = time.perf_counter()
    results = simulate_rings([r[:4] for r in runs])
    seconds = (time.perf_counter() - t0) / len(runs)
    out = []
    for (sc, mass, *_, keep), res in zip(runs, results):
        if isinstance(res, ConvergenceError):
            out.append(({"mass": mass, "dt": sc.dt, "converged": False, "error": str(res),
                         "seconds": seconds}, None))
        else:
            out.append((dict(res.summary, converged=True, seconds=seconds),
                        _series(res, every) if keep else None))
    return out


#: Most runs stepped together in one job: large enough that a step's fixed costs are shared
#: (a batch of 8 ring runs costs about a third per run of one run alone), small enough that
#: two workers get balanced shares of the section.
BATCH_RUNS = 8


def _batches(runs: list, cost) -> list:
    """``runs`` in jobs of at most :data:`BATCH_RUNS` runs of one mesh and mass rule, runs
    of similar length together; longest jobs first (no long job starts last)."""
    groups: dict = {}
    for run in runs:
        groups.setdefault((run[0].n_xi_elements, run[0].n_eta_elements, run[1]), []).append(run)
    jobs = []
    for members in groups.values():
        members.sort(key=cost, reverse=True)
        jobs += [members[i:i + BATCH_RUNS] for i in range(0, len(members), BATCH_RUNS)]
    return sorted(jobs, key=lambda job: -sum(map(cost, job)))


def measure(quick: bool = False, executor=None) -> RingStudy:
    """Run the ring study (``quick``: a short ring, coarse grids; see module docstring).

    Every ring run of the study is one item of a list, the same scene asked for twice run
    once; the runs go to the executor in batches (:func:`_batches`) stepped together, and
    the Signorini rows with them, the longest jobs first.
    """
    t_all = time.perf_counter()
    base = Scenario()
    seconds = {}
    scene = base.scaled(0.125) if quick else base
    masses = ("lumped", "singular")
    runs: dict = {}  # (scene, mass, perturbation, seed) -> keep the series

    def ring(sc: Scenario, mass: str, k: int = 0, series: bool = False) -> tuple:
        key = (sc, mass, 1e-12 if k else 0.0, k)
        runs[key] = runs.get(key, False) or series
        return key

    # the shown scene, its round-off spread (SPREAD_RUNS runs, k = 0 keeps its series)
    spread_keys = {m: [ring(scene, m, k, series=k == 0) for k in range(SPREAD_RUNS)]
                   for m in masses}
    # the same scene at a handful of dt around the paper's: the lumped figures move with dt
    # as much as with round-off (issue 18); every run is stated
    dt_keys = {(m, f): ring(_at_dt(scene, scene.dt * f), m) for m in masses for f in DT_FACTORS}
    factors = (0.0625, 0.125) if quick else (0.125, 0.25, 0.5, 1.0)
    angles = (180.0, 200.0) if quick else (180.0, 190.0, 200.0)
    grid_jobs = [(replace(base, theta0_deg=a).scaled(f), m)
                 for f in factors for a in angles for m in masses]
    grid_keys = [ring(sc, m) for sc, m in grid_jobs]
    # the scene's history, measured: each earlier default run now (quick: the small ones)
    hist_scenes = [replace(base, **fields) for _, _, fields in SCENE_HISTORY]
    hist_keys = [{m: None if quick and sc.n_steps > 2000 and sc != scene else ring(sc, m)
                  for m in masses} for sc in hist_scenes]
    sweep_scale = 0.0625 if quick else 0.125
    sweep_scene = base.scaled(sweep_scale)
    dts = [sweep_scene.dt * k for k in (2.0, 1.0, 0.5, 0.25)]
    sweep_keys = [ring(replace(sweep_scene, dt=dt), "singular") for dt in dts]
    # every Signorini scheme, the unstable one included: the report shows it flagged
    t_sig = 3.0 if quick else 12.0
    sig_rows = [(1, m, s, t_sig, SPREAD_RUNS) for m in ("lumped", "consistent", "singular")
                for s in ("kane", "central", "standard")]
    if not quick:
        sig_rows += [(2, m, "kane", t_sig, SPREAD_RUNS)
                     for m in ("lumped", "consistent", "singular")]

    def cost(run) -> float:
        return float(run[0].n_steps * run[0].n_dofs)

    batches = _batches([(*key, keep) for key, keep in runs.items()], cost)
    jobs = [(_ring_batch, (batch, 1 if quick else 2), sum(map(cost, batch)))
            for batch in batches]
    jobs += [(_signorini, row, SPREAD_RUNS * row[3] / (0.002 if row[0] == 1 else 0.001)
              * 21 * row[0]) for row in sig_rows]
    jobs.sort(key=lambda job: -job[2])
    t0 = time.perf_counter()
    done = _map(executor, _call, [(fn, arg) for fn, arg, _ in jobs])
    seconds["runs"] = time.perf_counter() - t0
    rows: dict = {}
    signorini_done = {}
    for (fn, arg, _), result in zip(jobs, done):
        if fn is _ring_batch:
            for run, row in zip(arg[0], result):
                rows[run[:4]] = row
        else:
            signorini_done[arg] = result

    pair, spread = {}, {}
    for m in masses:
        first, series = rows[spread_keys[m][0]]
        pair[m] = {"summary": first, "series": series}
        ok = [r for r, _ in (rows[k] for k in spread_keys[m]) if r["converged"]]
        e = [r["energy_change_percent"] for r in ok]
        ev = [r["contact_events"] for r in ok]
        spread[m] = {"runs": len(ok), "energy_min": min(e), "energy_max": max(e),
                     "events_min": min(ev), "events_max": max(ev), "perturbation": 1e-12}

    def got(key):
        return dict(rows[key][0])

    dt_spread = {}
    for m in masses:
        dt_rows = [pair[m]["summary"]] + [got(dt_keys[(m, f)]) for f in DT_FACTORS]
        dt_runs = [{"dt": r["dt"], "energy_change_percent": r.get("energy_change_percent"),
                    "contact_events": r.get("contact_events"), "converged": r["converged"],
                    "energy_flag": r.get("energy_flag")} for r in dt_rows]
        both = [r for r in dt_runs if r["converged"]] + [
            {"energy_change_percent": r["energy_change_percent"],
             "contact_events": r["contact_events"]}
            for r, _ in (rows[k] for k in spread_keys[m][1:]) if r["converged"]]
        e = [r["energy_change_percent"] for r in both]
        ev = [r["contact_events"] for r in both]
        dt_spread[m] = {"runs": sorted(dt_runs, key=lambda r: r["dt"]),
                        "all_runs": len(both), "energy_min": min(e), "energy_max": max(e),
                        "events_min": min(ev), "events_max": max(ev)}

    grid = [got(key) for key in grid_keys]
    for (sc, _), row in zip(grid_jobs, grid):
        row["steps_per_impact"] = steps_per_impact(sc)
        row["theta0_deg"] = sc.theta0_deg
        row["r_outer"] = sc.r_outer

    history = []
    for (label, note, fields), sc, keys in zip(SCENE_HISTORY, hist_scenes, hist_keys):
        row = {"scene": label, "note": note, "fields": dict(fields)}
        for m in masses:
            r = None if keys[m] is None else got(keys[m])
            row[m] = ({"status": "not run in quick mode"} if r is None else
                      {"status": "Newton failed", "error": r.get("error")}
                      if not r.get("converged") else
                      {"status": "ok", "energy_change_percent": r["energy_change_percent"],
                       "contact_events": r["contact_events"]})
        row["steps_per_impact"] = steps_per_impact(sc)
        history.append(row)

    sweep = [got(key) for key in sweep_keys]
    ok = [r for r in sweep if r["converged"]]
    dt_fit = fit_rate([r["dt"] for r in ok], [r["energy_change_percent"] for r in ok])

    signorini = [signorini_done[row] for row in sig_rows]

    # timed in this process after every other run, the pool idle
    t0 = time.perf_counter()
    timing = [_timing(lev, 20 if quick else 40) for lev in ((0, 1) if quick else (0, 1, 2))]
    seconds["timing"] = time.perf_counter() - t0
    seconds["total"] = time.perf_counter() - t_all
    sc_dict = dict(vars(scene), E=scene.E)
    return RingStudy(quick, DEFAULT_RULE, tuple(history), PAPER, sc_dict,
                     steps_per_impact(scene), steps_per_impact(base), base.r_outer,
                     pair, spread, grid, sweep, dt_fit, sweep_scale, timing,
                     signorini, seconds, dt_spread, SPREAD_RULE)


def _call(job):
    fn, arg = job
    return fn(arg)
