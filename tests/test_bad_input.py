"""The bad-input corpus: every command and every public function refuses bad input up front.

Each CLI case runs ``dispersion.cli.main(argv)`` in this process (fast) inside a scratch
folder and must: exit with status 2; print exactly one line on stderr, without a traceback,
that names the parameter (``param``, a regular expression) and states its valid range
(``RANGE``); create, change or remove no file. Each API case must raise
:class:`~dispersion.errors.InputError` with a one-line message naming the parameter.

"Up front" is enforced: a case gets ``CPU_SECONDS`` of CPU time (not wall time, so a loaded
machine does not fail it; ``WALL_SECONDS`` only backs it up for a case that waits), no
worker process and ``HEADROOM`` bytes of new address space; a command that starts the work instead of refusing fails the case (it does
not hang the suite or eat the machine's memory). The bounds the commands must refuse are the
measurements of issue 11 (e.g. ``series --exact --order 100000``: 3.2 GiB in 60 s).

To add a case, append ``Cli(command, argv, param)`` or ``Api(name, call, param)`` below.
Argument placeholders: ``{dir}`` an existing folder, ``{file}`` an existing file holding
user data, ``{missing}`` a path under a missing folder, ``{under_file}`` a path "inside"
the existing file.
"""
from __future__ import annotations

import math
import re
import resource
import signal
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
import sympy

import dispersion.cli
from dispersion.errors import InputError

# Import everything the commands load lazily, so a refusal is timed without import cost.
from dispersion.discretization import discrete_branches as _branches  # noqa: E402
from dispersion import sweep
from dispersion.claims import errata
from dispersion.splines import bspline
from dispersion.mass_rules import mass, mass_rule
from dispersion.symbolic import plate, power_balance
from dispersion.continuum import rayleigh_lamb
from dispersion.continuum import exact_series as exact_series_mod
from dispersion.continuum import exact_branches as exact_branches_mod
from dispersion import io as dio
from dispersion.contact import bar, scenario, simulate

CPU_SECONDS = 2.0
WALL_SECONDS = 20.0
HEADROOM = 3 * 2**30
#: A stated range: an interval, a comparison, a list of choices or an explicit rule.
RANGE = re.compile(r"[\[(]\s*-?[\w.+-]+\s*,|>=|<=|>|<|one of|choose from|must be|must lie|"
                   r"must name|must not|only|not allowed|not apply|at most|at least|"
                   r"exceeds|bound|does not exist|not a folder|not writable|existing|no such file|"
                   r"expected|malformed|new or empty",
                   re.IGNORECASE)


@dataclass(frozen=True)
class Cli:
    command: str
    argv: tuple[str, ...]
    param: str

    def __init__(self, command: str, argv: str | list[str], param: str):
        object.__setattr__(self, "command", command)
        object.__setattr__(self, "argv", tuple(argv.split() if isinstance(argv, str) else argv))
        object.__setattr__(self, "param", param)

    def __str__(self) -> str:
        short = [a if len(a) <= 24 else f"{a[:6]}...({len(a)} chars)" for a in self.argv]
        return " ".join((self.command, *short)) or "''"


@dataclass(frozen=True)
class Api:
    name: str
    call: Callable[[], object]
    param: str

    def __str__(self) -> str:
        return self.name


# ------------------------------------------------------------------------------ series
ORDER, GAMMA, NU, R = r"order", r"gamma[-_ ]?s", r"\bnu\b", r"(--r\b|\br\b|aspect ratio)"
SERIES = [
    Cli("series", "--order 100000", ORDER),
    Cli("series", "--exact --order 100000", ORDER),
    Cli("series", "--exact --nu 3/10 --order 100000", ORDER),
    Cli("series", "--order " + "1" + "0" * 400, ORDER),
    Cli("series", "--order -2", ORDER),
    Cli("series", "--order 0", ORDER),
    Cli("series", "--order 7", ORDER),
    Cli("series", "--order abc", ORDER),
    Cli("series", "--order 1e400", ORDER),
    Cli("series", "--mass singular --gamma-s 2", GAMMA),
    Cli("series", "--mass singular --gamma-s -0.1", GAMMA),
    Cli("series", "--mass singular --gamma-s nan", GAMMA),
    Cli("series", "--mass singular --gamma-s inf", GAMMA),
    Cli("series", "--mass singular --gamma-s abc", GAMMA),
    Cli("series", "--mass singular --gamma-s 1e400", GAMMA),
    Cli("series", "--nu 0.5", NU),
    Cli("series", "--nu -1", NU),
    Cli("series", "--nu nan", NU),
    Cli("series", "--nu 1e400", NU),
    Cli("series", "--nu zoo", NU),
    Cli("series", "--nu abc", NU),
    Cli("series", "--exact --nu 0.7", NU),
    Cli("series", "--r 0", R),
    Cli("series", "--r -3", R),
    Cli("series", "--r 1e-200", R),
    Cli("series", "--r 1e-8", R),
    Cli("series", "--r nan", R),
    Cli("series", "--r inf", R),
    Cli("series", "--r 1e400", R),
    Cli("series", "--r abc", R),
    Cli("series", "--p 0", r"\bp\b|degree"),
    Cli("series", "--p -1", r"\bp\b|degree"),
    Cli("series", "--p 100 --n 101", r"\bp\b|degree"),
    Cli("series", "--p 1.5", r"\bp\b|degree"),
    Cli("series", "--n 2", r"\bn\b|control points"),
    Cli("series", "--n 0", r"\bn\b|control points"),
    Cli("series", "--n 100000", r"\bn\b|control points"),
    Cli("series", "--mass heavy", r"mass"),
    Cli("series", "--contact middle", r"contact"),
    Cli("series", "--model y-exact", r"model"),
    Cli("series", "--branch S1", r"branch"),
    Cli("series", "--format xml", r"format"),
    Cli("series", "--exact --mass lumped", r"mass"),
    Cli("series", "--exact --model x-exact", r"model"),
    Cli("series", "--exact --mass singular --gamma-s 0.3", GAMMA + "|mass"),
    Cli("series", "--exact --r 3", R),
    Cli("series", "--model x-exact --r -3", R),
    Cli("series", "--model x-exact --r 3", R),
    Cli("series", "--mass consistent --gamma-s 0.3", GAMMA),
    Cli("series", "--mass lumped --contact bottom", r"contact"),
    Cli("series", "--paper --order 12", ORDER),
    Cli("series", "--paper --mass lumped", r"mass"),
    Cli("series", "--paper --exact", r"exact"),
    Cli("series", ["--json", ""], r"--json"),
    Cli("series", "--json {dir}", r"--json"),
    Cli("series", "--json {missing}", r"--json"),
    Cli("series", "--json {under_file}", r"--json"),
]

# ---------------------------------------------------------------------------- branches
CSV = "--csv o.csv"
KAPPA, OMEGA, COUNT = r"kappa", r"omega", r"count"
BRANCHES = [
    Cli("branches", f"{CSV} --count 100000000", COUNT),
    Cli("branches", f"{CSV} --count " + "1" + "0" * 400, COUNT),
    Cli("branches", f"{CSV} --count 1", COUNT),
    Cli("branches", f"{CSV} --count 0", COUNT),
    Cli("branches", f"{CSV} --count -5", COUNT),
    Cli("branches", f"{CSV} --count abc", COUNT),
    Cli("branches", f"{CSV} --count 1.5", COUNT),
    Cli("branches", f"{CSV} --omega-max 1e6", OMEGA),
    Cli("branches", f"{CSV} --omega-max 0", OMEGA),
    Cli("branches", f"{CSV} --omega-max -1", OMEGA),
    Cli("branches", f"{CSV} --omega-max nan", OMEGA),
    Cli("branches", f"{CSV} --omega-max inf", OMEGA),
    Cli("branches", f"{CSV} --omega-max abc", OMEGA),
    Cli("branches", f"{CSV} --kappa-max 1e300", KAPPA),
    Cli("branches", f"{CSV} --kappa-min -1", KAPPA),
    Cli("branches", f"{CSV} --kappa-min 5 --kappa-max 1", KAPPA),
    Cli("branches", f"{CSV} --kappa-max nan", KAPPA),
    Cli("branches", f"{CSV} --kappa-max inf", KAPPA),
    Cli("branches", f"{CSV} --kappa-min abc", KAPPA),
    Cli("branches", f"{CSV} --nu 0.5", NU),
    Cli("branches", f"{CSV} --nu nan", NU),
    Cli("branches", f"{CSV} --nu -2", NU),
    Cli("branches", f"{CSV} --nu abc", NU),
    Cli("branches", f"{CSV} --r 0", R),
    Cli("branches", f"{CSV} --r -1", R),
    Cli("branches", f"{CSV} --r nan", R),
    Cli("branches", f"{CSV} --r 1e-200", R),
    Cli("branches", f"{CSV} --r 1e300", R),
    Cli("branches", f"{CSV} --p 0", r"\bp\b|degree"),
    Cli("branches", f"{CSV} --p 50 --n 51", r"\bp\b|degree"),
    Cli("branches", f"{CSV} --n 2", r"\bn\b|control points"),
    Cli("branches", f"{CSV} --n 10000", r"\bn\b|control points"),
    Cli("branches", f"{CSV} --mass heavy", r"mass"),
    Cli("branches", f"{CSV} --contact middle", r"contact"),
    Cli("branches", f"{CSV} --mass singular --gamma-s 1.5", GAMMA),
    Cli("branches", f"{CSV} --mass singular --gamma-s nan", GAMMA),
    Cli("branches", f"{CSV} --mass consistent --gamma-s 0.3", GAMMA),
    Cli("branches", f"{CSV} --model y", r"model"),
    Cli("branches", f"{CSV} --exact --mass singular", r"mass"),
    Cli("branches", f"{CSV} --exact --r 3", R),
    Cli("branches", f"{CSV} --exact --model x-exact", r"model"),
    Cli("branches", f"{CSV} --model x-exact --r 3", R),
    Cli("branches", f"{CSV} --format xml", r"format"),
    Cli("branches", "--csv {dir}", r"--csv"),
    Cli("branches", ["--csv", ""], r"--csv"),
    Cli("branches", "--csv {missing}", r"--csv"),
    Cli("branches", "--csv {under_file}", r"--csv"),
    Cli("branches", f"{CSV} --figure fig.txt", r"--figure"),
    Cli("branches", f"{CSV} --figure {{dir}}", r"--figure"),
    Cli("branches", f"{CSV} --figure {{missing}}.png", r"--figure"),
    Cli("branches", [*CSV.split(), "--figure", ""], r"--figure"),
]
# issue 20: the frequency axis, materials and mode shapes of ``branches``
_F = f"{CSV} --exact --material steel --thickness 3"
BRANCHES += [
    Cli("branches", f"{_F} --frequency abc", r"--frequency"),
    Cli("branches", f"{_F} --frequency 200GHz", r"--frequency"),
    Cli("branches", f"{_F} --frequency -5", r"--frequency"),
    Cli("branches", f"{_F} --frequency 0", r"--frequency"),
    Cli("branches", f"{_F} --frequency nan", r"--frequency"),
    Cli("branches", f"{_F} --frequency inf", r"--frequency"),
    Cli("branches", f"{_F} --frequency 1e9", r"frequency"),
    Cli("branches", f"{_F} --frequency 1e-9", r"frequency"),
    Cli("branches", f"{_F} --frequency 5:1:3", r"--frequency"),
    Cli("branches", f"{_F} --frequency 1:5:0", r"--frequency"),
    Cli("branches", f"{_F} --frequency 1:5:1000000", r"--frequency"),
    Cli("branches", f"{_F} --frequency 1:5:x", r"--frequency"),
    Cli("branches", f"{_F} --frequency 1:2", r"--frequency"),
    Cli("branches", [*_F.split(), "--frequency", ""], r"--frequency"),
    Cli("branches", f"{_F} --frequency 10:100MHz:100000", r"kappa samples|frequenc"),
    Cli("branches", f"{_F} --fd 1e6", r"fd"),
    Cli("branches", f"{_F} --fd -1", r"--fd"),
    Cli("branches", f"{_F} --fd 1MHz", r"--fd"),
    Cli("branches", f"{_F} --fd 1 --frequency 200", r"--fd|--frequency"),
    Cli("branches", f"{_F} --frequency 200,300 --mode-shape S0", r"--mode-shape"),
    Cli("branches", f"{_F} --frequency 200 --mode-shape S9", r"--mode-shape"),
    Cli("branches", f"{_F} --frequency 200 --kappa-max 3", r"--kappa-max"),
    Cli("branches", f"{_F} --frequency 200 --json {{dir}}", r"--json"),
    Cli("branches", f"{CSV} --frequency 200", r"--exact"),
    Cli("branches", f"{CSV} --exact --frequency 200", r"material"),
    Cli("branches", f"{CSV} --exact --material steel --frequency 200", r"thickness"),
    Cli("branches", f"{CSV} --exact --material unobtainium", r"material"),
    Cli("branches", f"{CSV} --exact --mode-shape S0", r"--mode-shape"),
    Cli("branches", "--csv - --exact --json -", r"--json"),
    Cli("branches", f"{CSV} --exact --cl 6000 --ct 3000 --rho -1 --thickness 1", r"rho"),
    Cli("branches", f"{CSV} --exact --cl 3000 --ct 3000 --thickness 1", r"--cl"),
    Cli("branches", f"{CSV} --exact --cl 6000 --thickness 1", r"--cl"),
    Cli("branches", f"{CSV} --exact --youngs-modulus nan --nu 0.3 --rho 7800 --thickness 1",
        r"--youngs-modulus"),
    Cli("branches", f"{CSV} --exact --youngs-modulus 200 --nu 0.6 --rho 7800 --thickness 1",
        r"\bnu\b"),
    Cli("branches", f"{CSV} --exact --youngs-modulus 200 --rho 7800 --thickness 1",
        r"--youngs-modulus"),
    Cli("branches", f"{CSV} --exact --material steel --cl 6000 --thickness 1", r"--material"),
]

# -------------------------------------------------------------------------------- ring
DT, T_END = r"\bdt\b", r"t[-_]end"
RING = [
    Cli("ring", "--dt 1e-7", DT),
    Cli("ring", "--dt 1e-300 --t-end 1e-299", DT),
    Cli("ring", "--dt 0", DT),
    Cli("ring", "--dt -0.05", DT),
    Cli("ring", "--dt nan", DT),
    Cli("ring", "--dt inf", DT),
    Cli("ring", "--dt abc", DT),
    Cli("ring", "--t-end 0.01", T_END),
    Cli("ring", "--t-end 0.07", T_END),
    Cli("ring", "--t-end 0", T_END),
    Cli("ring", "--t-end -1", T_END),
    Cli("ring", "--t-end nan", T_END),
    Cli("ring", "--t-end 1e300", T_END),
    Cli("ring", "--t-end 1e9", T_END),
    Cli("ring", "--level 5", r"level"),
    Cli("ring", "--level -1", r"level"),
    Cli("ring", "--level abc", r"level"),
    Cli("ring", "--mass heavy", r"mass"),
    Cli("ring", "--scheme euler", r"scheme"),
    Cli("ring", "--gamma-s 2", GAMMA),
    Cli("ring", "--gamma-s nan", GAMMA),
    Cli("ring", "--mass lumped --gamma-s 0.3", GAMMA),
    Cli("ring", "--format xml", r"format"),
    Cli("ring", "--out {file}", r"--out"),
    Cli("ring", ["--out", ""], r"--out"),
    Cli("ring", "--out {under_file}", r"--out"),
    Cli("ring", "--out -", r"--out"),
]

# --------------------------------------------------------------------------- reproduce
REPRODUCE = [
    Cli("reproduce", "--jobs 0", r"jobs"),
    Cli("reproduce", "--jobs -1", r"jobs"),
    Cli("reproduce", "--jobs abc", r"jobs"),
    Cli("reproduce", "--jobs 100000", r"jobs"),
    Cli("reproduce", "--sections bogus", r"sections"),
    Cli("reproduce", ["--sections", ""], r"sections"),
    Cli("reproduce", "--sections coefficients,bogus", r"sections"),
    Cli("reproduce", ["--out", ""], r"--out"),
    Cli("reproduce", "--out {file}", r"--out"),
    Cli("reproduce", "--out {under_file}", r"--out"),
    Cli("reproduce", "--out -", r"--out"),
]

# ------------------------------------------------------------------------------- bench
BUDGET = r"budget"
BENCH = [
    Cli("bench", "--budget 1e308", BUDGET),
    Cli("bench", "--budget 1e400", BUDGET),
    Cli("bench", "--budget 1e6", BUDGET),
    Cli("bench", "--budget 0", BUDGET),
    Cli("bench", "--budget -1", BUDGET),
    Cli("bench", "--budget nan", BUDGET),
    Cli("bench", "--budget inf", BUDGET),
    Cli("bench", "--budget abc", BUDGET),
    Cli("bench", "--format xml", r"format"),
    Cli("bench", "--out {file}", r"--out"),
    Cli("bench", ["--out", ""], r"--out"),
    Cli("bench", "--out {under_file}", r"--out"),
]

# ------------------------------------------------------------------------------ verify
VERIFY = [
    Cli("verify", "--paper --junit {dir}", r"--junit"),
    Cli("verify", ["--paper", "--junit", ""], r"--junit"),
    Cli("verify", "--paper --junit {missing}", r"--junit"),
    Cli("verify", "--paper --junit {under_file}", r"--junit"),
    Cli("verify", "--paper --format xml", r"format"),
    Cli("verify", "--paper --jobs 0", r"jobs"),
    Cli("verify", "--paper --jobs abc", r"jobs"),
    Cli("verify", "--paper --jobs 100000", r"jobs"),
    Cli("verify", "nosuch.toml", r"nosuch\.toml"),
    Cli("verify", "{dir}", r"existing|FILE|claims"),
    Cli("verify", "{file}", r"user\.txt"),
]

# ------------------------------------------------------------------------------ impact
SCENE = "signorini-1d"
IMPACT = [
    Cli("impact", "bogus-scene", r"scene"),
    Cli("impact", f"{SCENE} --format xml", r"format"),
    Cli("impact", f"{SCENE} --out {{file}}", r"--out"),
    Cli("impact", [SCENE, "--out", ""], r"--out"),
    Cli("impact", f"{SCENE} --out -", r"--out"),
    Cli("impact", f"{SCENE} --out {{under_file}}", r"--out"),
    Cli("impact", f"{SCENE} --dt 0", DT),
    Cli("impact", f"{SCENE} --dt nan", DT),
    Cli("impact", f"{SCENE} --dt -1", DT),
    Cli("impact", f"{SCENE} --dt 1e-12", DT),
    Cli("impact", f"{SCENE} --t-end 0", T_END),
    Cli("impact", f"{SCENE} --t-end inf", T_END),
    Cli("impact", f"{SCENE} --t-end 1e12", T_END),
    Cli("impact", f"{SCENE} --elements 0", r"elements"),
    Cli("impact", f"{SCENE} --elements 1000000000", r"elements"),
    Cli("impact", f"{SCENE} --p 0", r"\bp\b|degree"),
    Cli("impact", f"{SCENE} --mass heavy", r"mass"),
    Cli("impact", f"{SCENE} --scheme euler", r"scheme"),
]

# ---------------------------------------------------------------------------- timestep
TIMESTEP = [
    Cli("timestep", "--p 0", r"\bp\b|degree"),
    Cli("timestep", "--p 100", r"\bp\b|degree"),
    Cli("timestep", "--p 1.5", r"\bp\b|degree"),
    Cli("timestep", "--h 0", r"\bh\b"),
    Cli("timestep", "--h nan", r"\bh\b"),
    Cli("timestep", "--h -1", r"\bh\b"),
    Cli("timestep", "--mass heavy", r"mass"),
    Cli("timestep", "--material unobtainium", r"material"),
    Cli("timestep", "--cl 6000", r"--cl"),
    Cli("timestep", "--cl 100 --ct 5000", r"--cl must exceed --ct"),
    Cli("timestep", "--model bar --mass singular", r"singular|contact"),
    Cli("timestep", "--n 2", r"\bn\b|control points"),
    Cli("timestep", "--p 24 --n 200", r"\bn\b|control points"),
    Cli("timestep", "--c 5", r"--c\b"),
    Cli("timestep", "--model bar --c -3 --mass lumped", r"wave_speed|--c"),
    Cli("timestep", "--mass-rule nosuch.toml", r"nosuch\.toml"),
    Cli("timestep", "--mass singular --gamma-s 2", r"gamma.s"),
    Cli("timestep", "--format xml", r"format"),
]

# ---------------------------------------------------------------------------- simulate
SIMULATE = [
    Cli("simulate", "--p 0", r"\bp\b"),
    Cli("simulate", "--p 5", r"\bp\b"),
    Cli("simulate", "--elements-per-wavelength 1", r"elements-per-wavelength"),
    Cli("simulate", "--elements-per-wavelength nan", r"elements-per-wavelength"),
    Cli("simulate", "--courant 0", r"courant"),
    Cli("simulate", "--courant 1", r"courant"),
    Cli("simulate", "--kappa 3", r"kappa"),
    Cli("simulate", "--cycles 0", r"cycles"),
    Cli("simulate", "--travel 0.5", r"travel"),
    Cli("simulate", "--stations 1", r"stations"),
    Cli("simulate", "--thickness 0", r"thickness"),
    Cli("simulate", "--gamma-s 2", r"gamma-s"),
    Cli("simulate", "--mass heavy", r"mass"),
    Cli("simulate", "--mode S1", r"mode"),
    Cli("simulate", "--material unobtainium", r"material"),
    Cli("simulate", "--csv {dir}", r"--csv"),
    Cli("simulate", "--figure out.txt", r"--figure"),
    Cli("simulate", "--p 4 --mass consistent --elements-per-wavelength 64 --travel 200",
        r"DOF"),
]

CLI_CASES = (SERIES + BRANCHES + RING + REPRODUCE + BENCH + VERIFY + IMPACT + TIMESTEP
             + SIMULATE)


# ----------------------------------------------------------------------------- the API
def _patch(**kw):
    return plate.plate_patch(**kw)


def _kappa(*values):
    return np.array(values, dtype=float)


def _lamb(**kw):
    from dispersion.materials.materials import material
    from dispersion.answers.mode_table import lamb_modes

    return lamb_modes(material("aluminium"), kw.pop("d", 1.0), **kw)


def _mixed_nu():
    from dispersion.answers.units import ALUMINIUM, physical_branches

    ex = exact_branches_mod.trace_branches(0.3, [0.5], 2.0)
    return physical_branches(ex.kappa, ex.omega, None, ALUMINIUM, 3.0)


API_CASES = [
    Api("lamb_modes(frequency_khz=nan)", lambda: _lamb(frequency_khz=math.nan), r"frequency"),
    Api("lamb_modes(frequency_khz=1e12)", lambda: _lamb(frequency_khz=1e12), r"frequency"),
    Api("lamb_modes(fd_mhz_mm=0)", lambda: _lamb(fd_mhz_mm=0.0), r"fd"),
    Api("lamb_modes(both)", lambda: _lamb(frequency_khz=1.0, fd_mhz_mm=1.0), r"frequency"),
    Api("lamb_modes(d=0)", lambda: _lamb(frequency_khz=100.0, d=0.0), r"thickness"),
    Api("lamb_modes(many)", lambda: _lamb(frequency_khz=np.full(10**6, 6e3)), r"kappa samples"),
    Api("modes_at_frequency(nu=0.5)", lambda: __import__(
        "dispersion.continuum.frequency", fromlist=["x"]).modes_at_frequency(0.5, [1.0]), NU),
    Api("user_material(c_L, c_T, nu)", lambda: __import__(
        "dispersion.materials.materials", fromlist=["x"]).user_material(
        c_L=6000.0, c_T=3000.0, nu=0.3), r"material inputs"),
    Api("physical_branches(nu 0.3, aluminium)", _mixed_nu, r"nu = 0\.3"),
    Api("plate_patch(r=10**400)", lambda: _patch(model="bloch", r=10**400), R),
    Api("plate_patch(r=1e-200)", lambda: _patch(model="bloch", r=1e-200), R),
    Api("plate_patch(r=nan)", lambda: _patch(model="bloch", r=math.nan), R),
    Api("plate_patch(r=-1)", lambda: _patch(model="bloch", r=-1), R),
    Api("plate_patch(r=zoo)", lambda: _patch(model="bloch", r=sympy.zoo), R),
    Api("plate_patch(r='abc')", lambda: _patch(model="bloch", r="abc"), R),
    Api("plate_patch(model='x-exact', r=-3)", lambda: _patch(model="x-exact", r=-3), R),
    Api("plate_patch(p=0)", lambda: _patch(p=0), r"\bp\b|degree"),
    Api("plate_patch(p=1.5)", lambda: _patch(p=1.5), r"\bp\b|degree"),
    Api("plate_patch(p=True)", lambda: _patch(p=True), r"\bp\b|degree"),
    Api("plate_patch(n=2)", lambda: _patch(n=2), r"\bn\b|control points"),
    Api("plate_patch(n=10**6)", lambda: _patch(n=10**6), r"\bn\b|control points"),
    Api("plate_patch(p=60, n=61)", lambda: _patch(p=60, n=61), r"\bp\b|degree"),
    Api("plate_patch(mass='x')", lambda: _patch(mass="x"), r"mass"),
    Api("plate_patch(model='y')", lambda: _patch(model="y"), r"model"),
    Api("plate_patch(contact='middle')", lambda: _patch(mass="singular", contact="middle"),
        r"contact"),
    Api("plate_patch(gamma_s=sympy.nan)", lambda: _patch(mass="singular", gamma_s=sympy.nan),
        GAMMA),
    Api("plate_patch(gamma_s=2)", lambda: _patch(mass="singular", gamma_s=2), GAMMA),
    Api("plate_patch(gamma_s=10**400)", lambda: _patch(mass="singular", gamma_s=10**400), GAMMA),
    Api("dynamic_stiffness(nu=0.5)", lambda: plate.dynamic_stiffness(_patch(), nu=0.5), NU),
    Api("dynamic_stiffness(nu=sympy.nan)",
        lambda: plate.dynamic_stiffness(_patch(), nu=sympy.nan), NU),
    Api("exact_series(order=100000)", lambda: exact_series_mod.exact_series("S0", 100000), ORDER),
    Api("exact_series(order=5)", lambda: exact_series_mod.exact_series("S0", 5), ORDER),
    Api("exact_series(order=-2)", lambda: exact_series_mod.exact_series("S0", -2), ORDER),
    Api("exact_series(order=4.5)", lambda: exact_series_mod.exact_series("S0", 4.5), ORDER),
    Api("exact_series(branch='S1')", lambda: exact_series_mod.exact_series("S1", 4), r"branch"),
    Api("exact_series(nu=0.7)", lambda: exact_series_mod.exact_series("S0", 4, nu=0.7), NU),
    Api("exact_series(nu=nan)", lambda: exact_series_mod.exact_series("S0", 4, nu=math.nan), NU),
    Api("discrete_series(order=100000)",
        lambda: power_balance.discrete_series("S0", 100000), ORDER),
    Api("discrete_series(branch='X')", lambda: power_balance.discrete_series("X", 4), r"branch"),
    Api("discrete_series(gamma_s=nan)",
        lambda: power_balance.discrete_series("S0", 4, mass="singular", gamma_s=math.nan), GAMMA),
    Api("discrete_branches(symbolic r)",
        lambda: _branches.discrete_branches(_patch(model="bloch", r=None), 0.3, _kappa(0.1)), R),
    Api("discrete_branches(nu=0.5)",
        lambda: _branches.discrete_branches(_patch(), 0.5, _kappa(0.1)), NU),
    Api("discrete_branches(kappa=[nan])",
        lambda: _branches.discrete_branches(_patch(), 0.3, _kappa(math.nan)), KAPPA),
    Api("discrete_branches(kappa=[])",
        lambda: _branches.discrete_branches(_patch(), 0.3, _kappa()), KAPPA),
    Api("discrete_branches(kappa=[-1])",
        lambda: _branches.discrete_branches(_patch(), 0.3, _kappa(-1)), KAPPA),
    Api("trace_branches(omega_max=1e6)",
        lambda: exact_branches_mod.trace_branches(0.3, _kappa(0.1, 1.0), 1e6), OMEGA),
    Api("trace_branches(omega_max=nan)",
        lambda: exact_branches_mod.trace_branches(0.3, _kappa(0.1), math.nan), OMEGA),
    Api("trace_branches(nu=0.5)", lambda: exact_branches_mod.trace_branches(0.5, _kappa(0.1), 8), NU),
    Api("trace_branches(kappa=[inf])",
        lambda: exact_branches_mod.trace_branches(0.3, _kappa(math.inf), 8), KAPPA),
    Api("cutoff_frequencies(omega_max=1e12)",
        lambda: rayleigh_lamb.cutoff_frequencies("S", 0.3, 1e12), OMEGA),
    Api("redistribution_matrix(NaN weights)",
        lambda: mass.redistribution_matrix(3, {2: {1: math.nan, 0: math.nan}},
                                           allow_negative=True), r"weight"),
    Api("contact_weights(gamma_s=sympy.nan)",
        lambda: mass.contact_weights(3, "top", sympy.nan), GAMMA),
    Api("mass_variant(variant='x')", lambda: mass_rule.mass_variant(sympy.eye(3), "x"), r"mass"),
    Api("open_knot_vector(p=-1)", lambda: bspline.open_knot_vector(-1, 3), r"\bp\b|degree"),
    Api("open_knot_vector(n_elements=0)", lambda: bspline.open_knot_vector(2, 0), r"element"),
    Api("open_knot_vector(n_elements=10**9)",
        lambda: bspline.open_knot_vector(2, 10**9), r"element"),
    Api("simulate_bar(n_elements=0)", lambda: bar.simulate_bar(n_elements=0), r"n_elements"),
    Api("simulate_bar(E=-1)", lambda: bar.simulate_bar(E=-1.0), r"\bE\b"),
    Api("simulate_bar(rho=0)", lambda: bar.simulate_bar(rho=0.0), r"rho"),
    Api("simulate_bar(v0=nan)", lambda: bar.simulate_bar(v0=math.nan), r"v0"),
    Api("simulate_bar(courant=0)", lambda: bar.simulate_bar(courant=0.0), r"courant"),
    Api("simulate_bar(dt=-1)", lambda: bar.simulate_bar(dt=-1.0), r"\bdt\b"),
    Api("simulate_bar(dt=1e-12)", lambda: bar.simulate_bar(dt=1e-12), r"\bdt\b"),
    Api("simulate_bar(mass='x')", lambda: bar.simulate_bar(mass="x"), r"mass"),
    Api("simulate_bar(L=inf)", lambda: bar.simulate_bar(L=math.inf), r"\bL\b"),
    Api("simulate_bar(gamma_s=nan)", lambda: bar.simulate_bar(mass="singular", gamma_s=math.nan),
        GAMMA),
    Api("Scenario(gap=inf)", lambda: scenario.Scenario(gap=math.inf), r"gap"),
    Api("Scenario(gap=-0.1)", lambda: scenario.Scenario(gap=-0.1), r"gap"),
    Api("Scenario(theta0_deg=nan)", lambda: scenario.Scenario(theta0_deg=math.nan), r"theta0"),
    Api("Scenario(rho=-1)", lambda: scenario.Scenario(rho=-1.0), r"rho"),
    Api("Scenario(v0_over_cT=0)", lambda: scenario.Scenario(v0_over_cT=0.0), r"v0_over_cT"),
    Api("Scenario(dt=0)", lambda: scenario.Scenario(dt=0.0), r"\bdt\b"),
    Api("Scenario(dt=1e-7)", lambda: scenario.Scenario(dt=1e-7), r"\bdt\b"),
    Api("Scenario(t_end=0.01)", lambda: scenario.Scenario(t_end=0.01), T_END),
    Api("Scenario(nu=0.5)", lambda: scenario.Scenario(nu=0.5), NU),
    Api("Scenario(r_outer<r_inner)", lambda: scenario.Scenario(r_outer=100.0), r"r_outer"),
    Api("Scenario(gamma_s=nan)", lambda: scenario.Scenario(gamma_s=math.nan), GAMMA),
    Api("Scenario(n_xi_elements=10**6)",
        lambda: scenario.Scenario(n_xi_elements=10**6), r"n_xi_elements"),
    Api("simulate_ring(mass='x')",
        lambda: simulate.simulate_ring(scenario.Scenario(t_end=1.0), "x"), r"mass"),
    Api("simulate_ring(scheme='x')",
        lambda: simulate.simulate_ring(scenario.Scenario(t_end=1.0), "singular", "x"), r"scheme"),
    Api("parallel_map(jobs=0)", lambda: sweep.parallel_map(abs, [1, 2], jobs=0), r"jobs"),
    Api("process_pool(0)", lambda: sweep.process_pool(0), r"max_workers"),
    Api("check_output_file('')", lambda: dio.check_output_file("", option="--csv"), r"--csv"),
    Api("errata_table(equations=('99',))", lambda: errata.errata_table(equations=("99",)),
        r"equation"),
    Api("dispersion.patch(model='x-exact', r=3)",
        lambda: __import__("dispersion").patch(model="x-exact", r=3), R),
    Api("dispersion.series(exact=True, mass=...)",
        lambda: __import__("dispersion").series("S0", 4, exact=True, mass="lumped"), r"exact"),
]


# ----------------------------------------------------------------------------- running
class NotUpFront(BaseException):
    """The call started the work instead of refusing (it ran past ``CPU_SECONDS``)."""


def _vm_size() -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmSize:"):
            return int(line.split()[1]) * 1024
    return 0  # pragma: no cover


class _UpFront:
    """Bound a call's CPU time (SIGPROF), wall time (SIGALRM) and address space (RLIMIT_AS)."""

    def __enter__(self):
        def late(signum, frame):
            raise NotUpFront(f"not refused up front: still running after {CPU_SECONDS} s of CPU")

        self._handlers = [signal.signal(signal.SIGPROF, late), signal.signal(signal.SIGALRM, late)]
        self._limits = resource.getrlimit(resource.RLIMIT_AS)
        hard = self._limits[1]
        soft = _vm_size() + HEADROOM
        if hard == resource.RLIM_INFINITY or soft < hard:
            resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
        signal.setitimer(signal.ITIMER_PROF, CPU_SECONDS)
        signal.setitimer(signal.ITIMER_REAL, WALL_SECONDS)
        return self

    def __exit__(self, *exc):
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGPROF, self._handlers[0])
        signal.signal(signal.SIGALRM, self._handlers[1])
        resource.setrlimit(resource.RLIMIT_AS, self._limits)
        return False


@pytest.fixture(autouse=True)
def no_workers(monkeypatch):
    """A refusal starts no worker process: spawning one means the work began."""
    import concurrent.futures.process as cfp

    def spawn(self):
        raise NotUpFront("not refused up front: started a worker process")

    monkeypatch.setattr(cfp.ProcessPoolExecutor, "_spawn_process", spawn)


def _snapshot(root: Path) -> dict[str, bytes | None]:
    return {str(p.relative_to(root)): (p.read_bytes() if p.is_file() else None)
            for p in sorted(root.rglob("*"))}


@pytest.fixture
def scratch(tmp_path, monkeypatch):
    (tmp_path / "existing").mkdir()
    (tmp_path / "user.txt").write_text("a user's chapter, not ours\n")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _fill(arg: str, root: Path) -> str:
    return arg.format(dir=root / "existing", file=root / "user.txt",
                      missing=root / "missing" / "x.out", under_file=root / "user.txt" / "x.out")


@pytest.mark.parametrize("case", CLI_CASES, ids=str)
def test_cli_refuses_bad_input(case, scratch, capsys):
    argv = [case.command, *(_fill(a, scratch) for a in case.argv)]
    before = _snapshot(scratch)
    try:
        with _UpFront():
            status = dispersion.cli.main(argv)
    except SystemExit as exc:  # argparse
        status = exc.code
    except NotUpFront as exc:  # short report: the frames of the interrupted work are noise
        pytest.fail(str(exc), pytrace=False)
    err = capsys.readouterr().err.strip()
    assert status == 2, f"exit status {status}, stderr: {err!r}"
    assert "\n" not in err and "Traceback" not in err, err
    assert re.search(case.param, err, re.IGNORECASE), f"parameter {case.param!r} not named: {err}"
    assert RANGE.search(err), f"no valid range stated: {err}"
    assert _snapshot(scratch) == before, "files were created, changed or removed"


@pytest.mark.parametrize("case", API_CASES, ids=str)
def test_api_refuses_bad_input(case):
    try:
        with _UpFront(), pytest.raises(InputError) as info:
            case.call()
    except NotUpFront as exc:
        pytest.fail(str(exc), pytrace=False)
    msg = str(info.value)
    assert "\n" not in msg
    assert re.search(case.param, msg, re.IGNORECASE), f"parameter {case.param!r} not named: {msg}"
    assert RANGE.search(msg), f"no valid range stated: {msg}"


def test_corpus_size():
    # issue 11: at least 150 cases over every subcommand and the public API
    assert len(CLI_CASES) + len(API_CASES) >= 150
    commands = {c.command for c in CLI_CASES}
    assert set(dispersion.cli._SUBCOMMANDS) <= commands
    assert {"verify", "impact"} <= commands
