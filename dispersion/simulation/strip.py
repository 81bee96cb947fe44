"""The guided-wave scene: a plane-strain plate strip, its burst, mesh size and stations.

A :class:`Strip` is the one value a simulation is built from (inputs only; it computes
nothing). :func:`plan_strip` derives, once, the numbers every later step reads
(:class:`StripPlan`), from the exact Rayleigh-Lamb branch of the chosen mode:

* **carrier**: wavenumber :math:`\\kappa_c = k_c H` on the exact S0 or A0 branch, frequency
  :math:`\\Omega_c = \\Omega(\\kappa_c)`
  (:func:`dispersion.continuum.exact_branches.exact_fundamental`),
  wavelength :math:`\\lambda = 2\\pi H / \\kappa_c` (units: H the half-thickness, :math:`c_T`);
* **mesh**: elements of length :math:`b = \\lambda / N` along the strip (N elements per
  wavelength; b/H as a fraction with a denominator of at most 1000, within 1e-6 relative)
  and :math:`n_y = \\lceil 2H/b \\rceil` through the thickness, so no element is longer
  than :math:`\\lambda/N` in either direction (or ``thickness_elements``, when given: a
  thicker mesh than the scene needs, for measuring what a solve costs with it);
  :math:`n = \\max(p + n_y, 3)` control points
  through the thickness (three: the singular rules' least), or
  :math:`n = p\\, n_y + 1` nodes for a rule on C0 Lagrange elements (its basis);
* **stations**: the reference station :math:`x_0` (``reference_station`` wavelengths from the
  loaded end, in the far field) and ``stations - 1`` more, equally spaced up to
  :math:`x_1 = x_0 +` ``travel`` wavelengths; and the *phase stations*, one per wavelength
  from :math:`x_0` to :math:`x_1`, along which the carrier phase error is followed from zero
  (it grows by less than a quarter turn per wavelength unless the phase velocity is 25 % off);
* **time**: the record runs to :math:`t_{end} = D + 1.2\\, x_1 / c_{g,slow}` (the burst's
  duration plus its travel at the slowest exact group velocity of the main lobe
  :math:`\\Omega_c(1 \\pm 2/N_c)`, with 20 % room for a discrete wave that is slower);
* **length**: the far end reflects; the strip is long enough that no reflection reaches
  :math:`x_1` before :math:`t_{end}`, with the same 20 % room for a discrete wave faster than
  the fastest exact group velocity of the band:
  :math:`L \\ge (1.2\\, c_{g,fast} t_{end} + x_1)/2`, rounded up to whole elements (the
  semi-discrete records, :mod:`dispersion.simulation.semi_discrete`, need every station's
  record free of reflections to its end: with the exact speed alone the reflection's onset
  at :math:`x_1` sat at the end of the record and moved the semi-discrete errors of a
  40-wavelength run at 0.9 of the critical step by up to 2.5 %, and with the room they agree
  with a run at 0.1 of it to 1e-5).

>>> plan = plan_strip(Strip(p=1, elements_per_wavelength=4, travel=2, stations=2))
>>> plan.n, plan.n_elements_y, round(plan.element_length * 4 / plan.wavelength, 5)
(3, 2, 1.0)
>>> bool(plan.length >= plan.stations[-1] + plan.wavelength)
True

References
----------
J. L. Rose, *Ultrasonic Guided Waves in Solid Media*, 2014, ch. 6 and 8 (group velocity,
tone bursts, far field). A. Tkachuk et al. (paper), section 2 (the plate patch).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache

import numpy as np

from dispersion.errors import (InputError, check_choice, check_int_in_range,
                               check_real_in_range)

__all__ = ["MODES", "Strip", "StripPlan", "plan_strip", "BAND_LEVEL", "SLOW_ROOM", "FAST_ROOM"]

#: The excitations: symmetric end load (S0) or antisymmetric end load (A0).
MODES = ("S0", "A0")
#: Level of the burst's spectrum that bounds the band of the modal synthesis and of every
#: signal compared (:meth:`dispersion.simulation.tone_burst.ToneBurst.band`): 1e-3 of the
#: peak; what lies outside carries under 1e-6 of the burst's energy.
BAND_LEVEL = 1e-3
#: Room in the record for a discrete wave slower than the exact one (20 %).
SLOW_ROOM = 1.2
#: Room in the strip's length for a discrete wave faster than the exact one (20 %): its
#: reflection still reaches the far station after the record ends.
FAST_ROOM = 1.2


@dataclass(frozen=True)
class Strip:
    """A plate strip excited at one end by a tone burst, and how it is discretized.

    Parameters
    ----------
    p : int
        B-spline degree along and through the strip, 1 to 4.
    mass : str
        A rule of :data:`dispersion.mass_rules.mass_rule.RULES` (its x-direction rule along the
        strip, the rule itself through the thickness, as in the plate patch).
    mode : str
        ``"S0"`` (symmetric end traction along x) or ``"A0"`` (antisymmetric: uniform shear
        traction along y).
    elements_per_wavelength : float
        N, in [2, 64].
    kappa_c : float
        Carrier wavenumber :math:`k_c H` on the exact branch, in [0.05, 2].
    cycles : int
        Cycles of the Hann-windowed burst, 1 to 20.
    courant : float
        The step as a fraction of the mesh's own critical step, in (0, 0.99] (at 1 central
        differences are only marginally stable, and the critical step is a Lanczos
        estimate good to about 1e-7).
    travel : float
        Wavelengths from the reference station to the far station, in [1, 200] (the study
        uses 40).
    reference_station : float
        Wavelengths from the loaded end to the reference station, in [1, 20].
    stations : int
        Recording stations from the reference to the far station, 2 to 20.
    material : str
        A material of :data:`dispersion.materials.materials.MATERIALS` (it fixes nu, and the
        physical units of the outputs).
    thickness_mm : float
        Plate thickness d = 2H in mm (physical units only), in (0, 1000].
    contact, gamma_s :
        Contact set and weight of the singular rules (their massless control points).
    thickness_elements : int or None
        Elements through the thickness, 1 to 64; None (the default): the fewest that keep
        every element within a wavelength over N (the plan's rule).
    """

    p: int = 2
    mass: str = "lumped"
    mode: str = "S0"
    elements_per_wavelength: float = 8
    kappa_c: float = 0.5
    cycles: int = 5
    courant: float = 0.9
    travel: float = 40
    reference_station: float = 2
    stations: int = 5
    material: str = "steel"
    thickness_mm: float = 1.0
    contact: str = "top"
    gamma_s: float = 0.5
    thickness_elements: int | None = None

    def __post_init__(self):
        from dispersion.defaults import CONTACT_SETS
        from dispersion.materials.materials import MATERIALS

        set_ = object.__setattr__
        set_(self, "p", check_int_in_range("p", self.p, 1, 4))
        check_choice("mode", self.mode, MODES)
        check_choice("material", self.material, tuple(MATERIALS))
        check_choice("contact", self.contact, CONTACT_SETS)
        if not isinstance(self.mass, str):
            raise InputError(f"mass must be the name of a registered rule, got {self.mass!r}")
        for name, lo, hi, lo_open in (("elements_per_wavelength", 2, 64, False),
                                      ("kappa_c", 0.05, 2, False), ("courant", 0, 0.99, True),
                                      ("travel", 1, 200, False),
                                      ("reference_station", 1, 20, False),
                                      ("thickness_mm", 0, 1000, True), ("gamma_s", 0, 1, False)):
            set_(self, name, float(check_real_in_range(name, getattr(self, name), lo, hi,
                                                       lo_open=lo_open)))
        set_(self, "cycles", check_int_in_range("cycles", self.cycles, 1, 20))
        set_(self, "stations", check_int_in_range("stations", self.stations, 2, 20))
        if self.thickness_elements is not None:
            set_(self, "thickness_elements",
                 check_int_in_range("thickness_elements", self.thickness_elements, 1, 64))

    @property
    def kind(self) -> str:
        """``"S"`` or ``"A"``: the symmetry class of the mode."""
        return self.mode[0]

    def label(self) -> str:
        """One line naming the run, rendered from the fields."""
        return (f"{self.mode}, p = {self.p}, {self.mass} mass, "
                f"{self.elements_per_wavelength:g} elements per wavelength")


@dataclass(frozen=True)
class StripPlan:
    """What :func:`plan_strip` derives from a :class:`Strip` (lengths in H, times in H/c_T):
    ``n`` functions through the thickness, ``n_x`` along the strip."""

    strip: Strip
    nu: float
    omega_c: float
    wavelength: float
    element_length: float
    n_elements_x: int
    n_elements_y: int
    n: int
    n_x: int
    length: float
    stations: tuple[float, ...]
    phase_stations: tuple[float, ...]
    t_end: float
    band: tuple[float, float]
    group_slow: float
    group_fast: float
    group_c: float
    phase_c: float
    time_unit_us: float = field(default=0.0)
    aspect: Fraction = Fraction(1)

    @property
    def r(self) -> Fraction:
        """Aspect ratio b/H of the Bloch patch: the strip's element length, exactly."""
        return self.aspect

    @property
    def distance(self) -> float:
        """:math:`x_1 - x_0`: the travel from the reference to the far station (H)."""
        return self.stations[-1] - self.stations[0]


def _exact_velocities(kind: str, nu: float, omega: np.ndarray):
    """Exact wavenumber and group velocity of the fundamental mode at each Omega."""
    kappa, group = _cached_velocities(kind, float(nu), tuple(np.asarray(omega, float).tolist()))
    return np.array(kappa), np.array(group)


@lru_cache(maxsize=64)
def _cached_velocities(kind: str, nu: float, omega: tuple):
    # every run of a sweep shares its burst: the band's roots are solved once per process
    from dispersion.errors import ConvergenceError
    from dispersion.continuum.frequency import modes_at_frequency

    omega = np.array(omega)
    roots = modes_at_frequency(nu, omega, kinds=(kind,), zgv=False)
    if roots.failures:
        raise ConvergenceError(f"exact {kind}0 roots not certified: {roots.failures[0]}")
    label = f"{kind}0"
    pick = [i for i, lab in enumerate(roots.label) if lab == label]
    if [roots.index[i] for i in pick] != list(range(len(omega))):
        raise ConvergenceError(f"exact {label} missing at some frequency of the band")
    return tuple(roots.kappa[pick].tolist()), tuple(roots.group[pick].tolist())


def plan_strip(strip: Strip) -> StripPlan:
    """Derive the carrier, mesh, stations, record length and strip length (module docstring)."""
    from dispersion.simulation.tone_burst import ToneBurst
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.continuum.exact_branches import exact_fundamental
    from dispersion.continuum.frequency import FREQUENCY_OMEGA_MIN
    from dispersion.materials.materials import MATERIALS

    mat = MATERIALS[strip.material]
    nu = float(mat.nu)
    omega_c = float(exact_fundamental(strip.kind, [strip.kappa_c], nu)[0])
    burst = ToneBurst(strip.cycles, omega_c)
    lo, hi = burst.band(BAND_LEVEL)
    lo = max(lo, FREQUENCY_OMEGA_MIN)
    wavelength = 2 * math.pi / strip.kappa_c
    # the element length as a fraction of H with a denominator of at most 1000 (within 1e-6
    # of a wavelength over N): the Bloch patch of the prediction takes the same exact r, and
    # its exact pencil polynomial stays small
    aspect = Fraction(wavelength / strip.elements_per_wavelength).limit_denominator(1000)
    b = float(aspect)
    n_y = (max(math.ceil(2.0 / b - 1e-12), 1) if strip.thickness_elements is None
           else strip.thickness_elements)
    lagrange = getattr(get_rule(strip.mass), "basis", "bspline") == "lagrange"
    n = strip.p * n_y + 1 if lagrange else max(strip.p + n_y, 3)
    x0 = strip.reference_station * wavelength
    x1 = x0 + strip.travel * wavelength
    stations = tuple(np.linspace(x0, x1, strip.stations).tolist())
    every = x0 + wavelength * np.arange(math.floor(strip.travel + 1e-9) + 1)
    phase_stations = tuple(sorted(set(every.tolist()) | {x1}))
    lobe = omega_c * np.linspace(1 - 2 / strip.cycles, 1 + 2 / strip.cycles, 41)
    lobe = lobe[lobe >= lo]
    band_grid = np.linspace(lo, hi, 161)
    _, cg_lobe = _exact_velocities(strip.kind, nu, lobe)
    kap, cg_band = _exact_velocities(strip.kind, nu, np.concatenate([band_grid, [omega_c]]))
    slow, fast = float(cg_lobe.min()), float(cg_band.max())
    t_end = burst.duration + SLOW_ROOM * x1 / slow
    length = max((FAST_ROOM * fast * t_end + x1) / 2, x1 + wavelength)
    n_x = math.ceil(length / b - 1e-9)
    n_x_functions = n_x * strip.p + 1 if lagrange else n_x + strip.p
    half_thickness_m = strip.thickness_mm / 2 * 1e-3
    return StripPlan(strip, nu, omega_c, wavelength, b, n_x, n_y if lagrange else n - strip.p,
                     n, n_x_functions, n_x * b, stations, phase_stations, t_end,
                     (float(lo), float(hi)), slow, fast, float(cg_band[-1]),
                     omega_c / float(kap[-1]), half_thickness_m / mat.c_T * 1e6, aspect)
