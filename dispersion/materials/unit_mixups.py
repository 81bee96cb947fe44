"""Inputs off by a unit: which given value is implausible by orders of magnitude, and why.

A request that fails a range check is often a unit mix-up (a thickness in metres where mm are
asked, a speed in km/s for m/s, Young's modulus in Pa for GPa, a density in g/cm^3, a
frequency in Hz for kHz). :func:`unit_mixups` names each input that lies outside the range
where that quantity is found in solids and plates (by orders of magnitude: the ranges are
wide) but inside it once read in the other unit. The ranges (stated once, :data:`PLAUSIBLE`) are generous: a value
inside them is never questioned, and nothing here refuses a request; the hints only complete a
message that a range check already raised.

>>> unit_mixups(thickness_mm=0.003)
['thickness_mm = 0.003 mm is implausibly small: metres given for mm? (0.003 m = 3 mm)']
>>> unit_mixups(c_T=3.235, E_gpa=200.0)
['c_T = 3.235 m/s is implausibly small: km/s given for m/s? (3.235 km/s = 3235 m/s)']
"""
from __future__ import annotations

__all__ = ["PLAUSIBLE", "unit_mixups", "frequency_mixup"]

#: Where each quantity lies for engineering solids and plates, with the unit it is given in:
#: thickness 10 um to 10 m, bulk speeds 100 m/s (soft polymers) to 20 km/s (beryllium,
#: diamond), density 100 kg/m^3 (foams) to 25000 (osmium), Young's modulus 1 MPa (rubber) to
#: 2000 GPa (diamond: 1220), frequency 1 Hz to 10 GHz.
PLAUSIBLE = {
    "thickness_mm": (1e-2, 1e4, "mm"),
    "c_L": (100.0, 2e4, "m/s"), "c_T": (50.0, 2e4, "m/s"),
    "rho": (100.0, 2.5e4, "kg/m^3"),
    "E_gpa": (1e-3, 2e3, "GPa"),
    "frequency_khz": (1e-3, 1e7, "kHz"),
}

#: Unit mix-ups tried for each quantity: (what the value may have been given in, factor that
#: turns it into the asked unit).
_OTHER = {
    "thickness_mm": (("metres", "m", 1e3), ("micrometres", "um", 1e-3)),
    "c_L": (("km/s", "km/s", 1e3),), "c_T": (("km/s", "km/s", 1e3),),
    "rho": (("g/cm^3", "g/cm^3", 1e3),),
    "E_gpa": (("Pa", "Pa", 1e-9), ("MPa", "MPa", 1e-3)),
    "frequency_khz": (("Hz", "Hz", 1e-3), ("MHz", "MHz", 1e3)),
}


def unit_mixups(**given) -> list[str]:
    """A line for each given quantity (keys of :data:`PLAUSIBLE`) that lies outside its range
    yet inside it read in another unit; None values are skipped.

    >>> unit_mixups(E_gpa=200e9, rho=7.85)
    ['rho = 7.85 kg/m^3 is implausibly small: g/cm^3 given for kg/m^3? (7.85 g/cm^3 = 7850 kg/m^3)', 'E_gpa = 2e+11 GPa is implausibly large: Pa given for GPa? (2e+11 Pa = 200 GPa)']
    >>> unit_mixups(thickness_mm=3.0, c_L=5960.0, frequency_khz=200.0)
    []
    """
    out = []
    for name in PLAUSIBLE:
        value = given.get(name)
        if value is None:
            continue
        lo, hi, unit = PLAUSIBLE[name]
        value = float(value)
        if lo <= value <= hi or not value > 0:
            continue
        for words, short, factor in _OTHER[name]:
            if lo <= value * factor <= hi:
                size = "small" if value < lo else "large"
                out.append(f"{name} = {value:g} {unit} is implausibly {size}: {words} given for "
                           f"{unit}? ({value:g} {short} = {value * factor:g} {unit})")
                break
    return out


def frequency_mixup(value_khz: float, lo_khz: float, hi_khz: float) -> list[str]:
    """A line if a frequency outside the plate's range ``[lo_khz, hi_khz]`` falls inside it
    read in Hz or in MHz (the range depends on the plate, so it is passed in).

    >>> frequency_mixup(200000.0, 0.69, 1.03e4)
    ['frequency_khz = 200000 kHz is out of range: Hz given for kHz? (200000 Hz = 200 kHz; write 200000Hz)']
    """
    for words, factor in (("Hz", 1e-3), ("MHz", 1e3)):
        if not lo_khz <= value_khz <= hi_khz and lo_khz <= value_khz * factor <= hi_khz:
            return [f"frequency_khz = {value_khz:g} kHz is out of range: {words} given for kHz? "
                    f"({value_khz:g} {words} = {value_khz * factor:g} kHz; write "
                    f"{value_khz:g}{words})"]
    return []
