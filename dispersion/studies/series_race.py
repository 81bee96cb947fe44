"""Speed of the series engine: a race against Maxima and the growth of its cost with the patch.

Two measurements, one result (:class:`SeriesSpeed`, stored as JSON by
:func:`dispersion.results.save`):

* **race**: the exact Rayleigh-Lamb S0 + A0 series to :math:`\\kappa^K`, nu symbolic,
  (a) whole process, cold: ``python -m dispersion series --exact --branch both --order K
  --format json`` against ``maxima --very-quiet -b <program>`` (the program
  ``dispersion/data/rayleigh_lamb_series.mac``: CRE arithmetic truncated by
  ``ratweight``/``ratwtlvl``, Horner evaluation, leading balance once, one linear equation
  per order), wall clock and peak resident memory of each child (GNU ``time``);
  the same command through its lean entry ``python -m dispersion.cli.series`` (this
  subcommand alone, without the other subcommands' imports, sympy-free) is timed too;
  (b) compute only: our in-process time for the same work (flint kernel and the printed
  strings) against the compute time Maxima reports itself (``elapsed_run_time()``).
  Every coefficient of both is compared exactly at two rational values of nu.
* **scaling**: seconds for the discrete S0 + A0 series to :math:`\\kappa^8` against the number
  n of control points (degree p = 2, 3, 4) for the consistent, lumped and singular masses,
  with the growth exponent fitted by least squares on log t = a + b log n (at least 4 points;
  the residual is the rms of the log misfit).

Maxima runs only if it is installed (``shutil.which("maxima")``); otherwise the result says so.
A peer run counts only if it succeeded (:func:`peer_failure`): a run that exits non-zero,
prints an error, returns no coefficients or coefficients that differ from ours is stored as
failed with its message, and no time, memory or ratio is kept for it.

>>> fit_growth([3, 4, 6, 8], [1.0, 8 / 3.375, 8.0, 8 / 0.421875])["exponent"]
3.0
"""
from __future__ import annotations

import functools
import math
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from fractions import Fraction
from importlib import resources
from pathlib import Path

from dispersion.errors import InputError

__all__ = [
    "MAXIMA_INSTALL", "TIMEOUT", "TIMEOUT_MAX", "RacePoint", "ScalingPoint", "GrowthFit", "SeriesSpeed",
    "fit_growth", "maxima_program", "measure", "parse_maxima_output", "peer_failure", "race",
    "run_child", "scaling",
]

#: How to install the peer (Debian; the program loads ``stringproc`` from maxima-share).
MAXIMA_INSTALL = "apt-get install maxima maxima-share"
#: Default and largest ceiling (seconds) for one child process of the race.
TIMEOUT = 120.0
TIMEOUT_MAX = 600.0
_NU_PROBES = (Fraction(3, 10), Fraction(-2, 7))


@dataclass(frozen=True)
class RacePoint:
    """One order of the race: seconds and peak MiB of each side (None: not run / failed)."""

    order: int
    ours_process_s: float | None
    ours_compute_s: float | None
    ours_peak_mib: float | None
    ours_lean_process_s: float | None = None  # ``python -m dispersion.cli.series``: no sympy
    maxima_process_s: float | None = None
    maxima_compute_s: float | None = None
    maxima_peak_mib: float | None = None
    agree: bool | None = None  # every coefficient equal (None: Maxima not run)
    maxima_status: str | None = None  # "ok", "failed" or None (not run)
    maxima_error: str | None = None  # why a failed peer run does not count


@dataclass(frozen=True)
class ScalingPoint:
    mass: str
    p: int
    n: int
    order: int
    seconds: float
    patch: dict | None = None  # the Patch it was computed on (Patch.as_dict())


@dataclass(frozen=True)
class GrowthFit:
    """t ~ C n^exponent fitted on ``points`` (n, seconds); ``monotone``: t increases with n."""

    mass: str
    p: int
    exponent: float
    residual: float
    monotone: bool
    points: int


@dataclass(frozen=True)
class SeriesSpeed:
    race: tuple[RacePoint, ...]
    scaling: tuple[ScalingPoint, ...]
    fits: tuple[GrowthFit, ...]
    maxima: str | None  # Maxima's version, None if not installed
    notes: tuple[str, ...] = ()
    settings: dict = field(default_factory=dict)


def maxima_program() -> Path:
    """Path of the Maxima program shipped with the package (``dispersion/data/*.mac``)."""
    return Path(str(resources.files("dispersion") / "data" / "rayleigh_lamb_series.mac"))


_COEF = re.compile(r"^COEF\s+(S0|A0)\s+(\d+)\s+(.+?)\s*$")
_TIME = re.compile(r"^TIME\s+([0-9.eE+-]+)\s*$")


def parse_maxima_output(text: str) -> tuple[dict[str, dict[int, str]], float | None]:
    """The ``COEF <branch> <power> <expr>`` and ``TIME <s>`` lines of the Maxima program.

    >>> parse_maxima_output("junk\\nCOEF S0 2 -2/(nu-1)\\nTIME 0.25\\n")
    ({'S0': {2: '-2/(nu-1)'}}, 0.25)
    """
    coeffs: dict[str, dict[int, str]] = {}
    seconds = None
    for line in text.splitlines():
        if m := _COEF.match(line.strip()):
            coeffs.setdefault(m[1], {})[int(m[2])] = m[3]
        elif m := _TIME.match(line.strip()):
            seconds = float(m[1])
    return coeffs, seconds


def run_child(cmd: list[str], timeout: float, cwd: str | None = None):
    """Run ``cmd``; return ``(wall seconds, peak RSS MiB, stdout, exit status, stderr)``, None
    on timeout.

    The peak memory is the child's own, read by GNU ``time -f %M`` (a forked child's own
    ``ru_maxrss`` starts at the parent's size, so the parent cannot measure it directly);
    None if ``/usr/bin/time`` is absent.
    """
    import tempfile

    gnu_time = _gnu_time()
    with tempfile.TemporaryDirectory(prefix="dispersion-rss-") as tmp:
        rss_file = Path(tmp) / "rss"
        full = [gnu_time, "-f", "%M", "-o", str(rss_file), *cmd] if gnu_time else cmd
        start = time.perf_counter()
        try:
            proc = subprocess.run(full, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True, cwd=cwd, timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            return None
        wall = time.perf_counter() - start
        peak = None
        if gnu_time and rss_file.exists():
            text = rss_file.read_text().strip().splitlines()
            if text and text[-1].isdigit():
                peak = int(text[-1]) / 1024.0
    return wall, peak, proc.stdout, proc.returncode, proc.stderr


@functools.lru_cache(maxsize=1)
def _gnu_time() -> str | None:
    """Path of GNU ``time`` if it accepts ``-f %M -o FILE`` (Debian package ``time``)."""
    import tempfile

    exe = shutil.which("time") or ("/usr/bin/time" if Path("/usr/bin/time").exists() else None)
    if exe is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        probe = subprocess.run([exe, "-f", "%M", "-o", str(Path(tmp) / "m"), sys.executable,
                                "-c", "pass"], capture_output=True, check=False)
        ok = probe.returncode == 0 and (Path(tmp) / "m").is_file()
    return exe if ok else None


def _ours_compute(order: int) -> tuple[float, dict[str, dict[int, str]]]:
    """In-process: the same work as the CLI's JSON path (flint kernel + printed strings)."""
    from dispersion.symbolic.power_balance import format_coefficient
    from dispersion.continuum.exact_series import exact_series_raw

    start = time.perf_counter()
    out = {b: {k: format_coefficient(a, d) for k, a, d in exact_series_raw(b, order)}
           for b in ("S0", "A0")}
    return time.perf_counter() - start, out


def _value(text: str, nu: Fraction) -> Fraction:
    """Exact value of a coefficient string (ours or Maxima's) at a rational nu: read by the
    whitelist parser :func:`dispersion.studies.coefficient_value.coefficient_value`, never
    ``eval``-ed."""
    from dispersion.studies.coefficient_value import coefficient_value

    return coefficient_value(text, nu)


def _agree(ours: dict, theirs: dict) -> bool:
    for branch, coeffs in ours.items():
        if set(coeffs) != set(theirs.get(branch, {})):
            return False
        for power, text in coeffs.items():
            for nu in _NU_PROBES:
                if _value(text, nu) != _value(theirs[branch][power], nu):
                    return False
    return True


#: Lines by which Maxima (or its Lisp) reports an error; its batch mode may still exit 0.
_PEER_ERROR = re.compile(
    r"(-- an error|error|failed to load|could not find|not found|undefined|unbound"
    r"|Maxima encountered a Lisp)", re.IGNORECASE)


def peer_failure(returncode: int, stdout: str, stderr: str, coeffs: dict,
                 ours: dict) -> str | None:
    """Why a peer run does not count (None: it succeeded).

    It fails if it exited non-zero, printed an error line (on either stream), returned no
    coefficient, or returned coefficients that differ from ``ours`` (compared exactly at two
    rational values of nu).

    >>> peer_failure(0, "COEF S0 2 -2/(nu-1)", "", {"S0": {2: "-2/(nu-1)"}},
    ...              {"S0": {2: "-2/(nu - 1)"}}) is None
    True
    >>> peer_failure(0, "loadfile: failed to load stringproc", "", {}, {"S0": {2: "2"}})
    'printed an error: loadfile: failed to load stringproc'
    """
    lines = [ln.strip() for ln in (stdout + "\n" + stderr).splitlines()
             if ln.strip() and not _COEF.match(ln.strip())]
    errors = [ln for ln in lines if _PEER_ERROR.search(ln)]
    if returncode != 0:
        return f"exit status {returncode}" + (f": {errors[0][:200]}" if errors else "")
    if errors:
        return f"printed an error: {errors[0][:200]}"
    if not any(coeffs.values()):
        return "returned no coefficients" + (f" (last line: {lines[-1][:200]})" if lines else "")
    try:
        same = _agree(ours, coeffs)
    except InputError as exc:
        return f"returned an unreadable coefficient ({exc})"
    return None if same else "its coefficients differ from ours"


def _maxima_version(exe: str) -> str:
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=30)
        return out.stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def race(orders, timeout: float = TIMEOUT, maxima: str | None = "maxima",
         notes: list | None = None, maxima_max_order: int = 64,
         repeats: int = 1, python: str | None = None) -> tuple[RacePoint, ...]:
    """Race ours against Maxima at each order of ``orders`` (Maxima skipped if ``None`` and
    above ``maxima_max_order``). With ``repeats`` > 1 the two run in turn (ours, Maxima, ours,
    ...) and each figure is the median over the runs, so that a shared machine's drift moves
    both sides alike; a peer that fails once is failed. ``python``: the interpreter that runs
    ours (default this one), e.g. that of a non-editable install as a user has it."""
    from statistics import median

    notes = [] if notes is None else notes
    exe = shutil.which(maxima) if maxima else None
    program = maxima_program()
    points = []
    python = python or sys.executable
    _warm_bytecode(notes, python)
    for order in orders:
        cmd = [python, "-m", "dispersion", "series", "--exact", "--branch", "both",
               "--order", str(order), "--format", "json"]
        mine, lean, theirs = [], [], []
        why = None
        for _ in range(max(1, repeats)):
            run = run_child(cmd, timeout)
            if run is None or run[3] != 0:
                why = "timeout" if run is None else f"exit {run[3]}"
                break
            mine.append(run)
            lrun = run_child([python, "-m", "dispersion.cli.series", *cmd[4:]], timeout)
            if lrun is not None and lrun[3] == 0:
                lean.append(lrun[0])
            if exe is not None and order <= maxima_max_order:
                with _batch_file(order, program) as (folder, name):
                    theirs.append(run_child([exe, "--very-quiet", "-b", name], timeout,
                                            cwd=folder))
        if why is not None:
            notes.append(f"ours at kappa^{order}: {why}")
            points.append(RacePoint(order, None, None, None))
            continue
        compute, ours = _ours_compute(order)
        peaks = [r[1] for r in mine if r[1] is not None]
        point = dict(order=order, ours_process_s=median(r[0] for r in mine),
                     ours_compute_s=compute, ours_peak_mib=max(peaks) if peaks else None,
                     ours_lean_process_s=median(lean) if lean else None)
        if theirs:
            fail = None
            for mrun in theirs:
                if mrun is None:
                    fail = f"stopped after {timeout:g} s"
                else:
                    coeffs, _ = parse_maxima_output(mrun[2])
                    fail = peer_failure(mrun[3], mrun[2], mrun[4], coeffs, ours)
                if fail is not None:
                    break
            if fail is None:
                m_peaks = [r[1] for r in theirs if r[1] is not None]
                m_compute = [parse_maxima_output(r[2])[1] for r in theirs]
                point.update(maxima_process_s=median(r[0] for r in theirs),
                             maxima_compute_s=median(c for c in m_compute if c is not None)
                             if any(c is not None for c in m_compute) else None,
                             maxima_peak_mib=max(m_peaks) if m_peaks else None,
                             agree=True, maxima_status="ok")
            else:  # a failed peer run is not timed: no time, memory or ratio is kept
                notes.append(f"Maxima at kappa^{order} failed, not timed: {fail}")
                point.update(agree=False, maxima_status="failed", maxima_error=fail)
        points.append(RacePoint(**point))
    return tuple(points)


def _warm_bytecode(notes: list, python: str) -> None:
    """One untimed run of ours that may write Python's bytecode cache, as a user's installed
    copy has it (``pip install`` compiles; ``PYTHONDONTWRITEBYTECODE`` in the benchmark's
    environment would otherwise make every timed run compile the package from source).
    Maxima's side needs no such step (its Lisp image is compiled)."""
    import os

    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    cmd = [python, "-m", "dispersion", "series", "--exact", "--order", "4",
           "--format", "json"]
    try:
        subprocess.run(cmd, capture_output=True, env=env, timeout=TIMEOUT, check=False)
        subprocess.run([cmd[0], "-m", "dispersion.cli.series", *cmd[4:]], capture_output=True,
                       env=env, timeout=TIMEOUT, check=False)
    except (OSError, subprocess.SubprocessError) as exc:
        notes.append(f"bytecode warm-up run failed ({exc}); timed runs may compile")
        return
    notes.append("ours: one untimed warm-up run first (Python's bytecode cache written, as "
                 "after pip install)")
    probe = subprocess.run([python, "-c", "import sys; print(any('__editable__' in "
                            "str(getattr(f, '__module__', '')) for f in sys.meta_path))"],
                           capture_output=True, text=True, timeout=TIMEOUT, check=False)
    if probe.stdout.strip() == "True":
        notes.append("ours runs from an editable install (pip install -e): its import finder "
                     "adds start-up that an installed copy does not have")


class _batch_file:
    """A temporary folder with ``run.mac``: ``N : order/2$`` then the shipped program."""

    def __init__(self, order: int, program: Path):
        self.order, self.program = order, program

    def __enter__(self):
        import tempfile

        self._tmp = tempfile.TemporaryDirectory(prefix="dispersion-maxima-")
        folder = Path(self._tmp.name)
        path = str(self.program).replace("\\", "/").replace('"', '\\"')
        (folder / "run.mac").write_text(f'N : {self.order // 2}$\nbatchload("{path}")$\n',
                                        encoding="utf-8")
        return str(folder), "run.mac"

    def __exit__(self, *exc):
        self._tmp.cleanup()


def fit_growth(ns, seconds) -> dict:
    """Least-squares fit of log t = a + b log n: ``{"exponent": b, "residual": rms}``.

    Needs at least 4 points with t > 0; the residual is the rms of the log misfit.
    """
    pts = [(math.log(n), math.log(t)) for n, t in zip(ns, seconds) if t and t > 0]
    if len(pts) < 4:
        raise InputError(f"a growth fit needs at least 4 points, got {len(pts)}")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    b = sum((x - mx) * (y - my) for x, y in pts) / sxx
    a = my - b * mx
    rms = math.sqrt(sum((y - a - b * x) ** 2 for x, y in pts) / len(pts))
    return {"exponent": round(b, 6), "residual": rms}


def scaling(grid: dict[int, tuple[int, ...]], masses=("consistent", "lumped", "singular"),
            order: int = 8) -> tuple[tuple[ScalingPoint, ...], tuple[GrowthFit, ...]]:
    """Seconds of the discrete S0 + A0 series to kappa^order on ``grid`` = {p: (n, ...)}."""
    from dispersion.symbolic.patch import Patch
    from dispersion.symbolic.power_balance import discrete_series_raw

    discrete_series_raw(("S0",), 2, n=3, model="x-exact")  # warm-up: imports and flint
    points, fits = [], []
    for mass in masses:
        for p, ns in grid.items():
            times = []
            for n in ns:
                spec = Patch(p=p, n=n, mass=mass)  # the toolkit's default patch otherwise
                start = time.perf_counter()
                discrete_series_raw(("S0", "A0"), order, spec)
                times.append(time.perf_counter() - start)
                points.append(ScalingPoint(mass, p, n, order, times[-1], spec.as_dict()))
            if len(ns) >= 4:
                f = fit_growth(ns, times)
                fits.append(GrowthFit(mass, p, f["exponent"], f["residual"],
                                      all(b > a for a, b in zip(times, times[1:])), len(ns)))
    return tuple(points), tuple(fits)


def measure(quick: bool = False, executor=None, *, timeout: float = TIMEOUT,
            maxima: str | None = "maxima", extended: bool = False,
            repeats: int | None = None, python: str | None = None) -> SeriesSpeed:
    """The race and the scaling table (``quick``: fewer orders and sizes, for CI).

    Full: ours and Maxima at kappa^8, 16, 32, 64, three runs of each side in turn (medians:
    a single run at kappa^16 varies by about 20 %); scaling at kappa^8 for p = 2 (n = 3..10),
    3 and 4 (four sizes each), about a minute on a quiet 2-core machine. Quick: kappa^8 and
    16, one run. ``extended`` (``dispersion bench``) adds n = 12. ``executor`` is not used:
    the timings run one after the other so that they do not compete for the cores.
    ``repeats``: runs of each side of the race (default 3, quick 1). ``python``: interpreter
    that runs ours in the race (default this one).
    """
    if not (isinstance(timeout, (int, float)) and 0 < timeout <= TIMEOUT_MAX):
        raise InputError(f"timeout (seconds per child process) must lie in (0, {TIMEOUT_MAX:g}], "
                         f"got {timeout!r}")
    notes: list[str] = []
    orders = (8, 16) if quick else (8, 16, 32, 64)
    grid = {2: (3, 4, 5, 6)} if quick else {2: (3, 4, 6, 8, 10) + ((12,) if extended else ()),
                                             3: (4, 5, 6, 7), 4: (5, 6, 7, 8)}
    maxima_max_order = 64
    repeats = (1 if quick else 3) if repeats is None else repeats
    exe = shutil.which(maxima) if maxima else None
    if exe is None:
        notes.append(f"Maxima not found ({maxima!r} on PATH): the race shows ours only "
                     f"({MAXIMA_INSTALL})")
    if _gnu_time() is None:
        notes.append("GNU time not found: no peak memory (apt-get install -y time)")
    if python is not None:
        notes.append(f"ours run by {python}")
    race_points = race(orders, timeout, maxima, notes, maxima_max_order, repeats, python)
    points, fits = scaling(grid)
    return SeriesSpeed(race_points, points, fits, _maxima_version(exe) if exe else None,
                       tuple(notes), {"quick": quick, "orders": list(orders),
                                      "grid": {str(k): list(v) for k, v in grid.items()},
                                      "scaling_order": 8, "timeout_s": timeout,
                                      "maxima_max_order": maxima_max_order,
                                      "extended": extended, "repeats": repeats})
