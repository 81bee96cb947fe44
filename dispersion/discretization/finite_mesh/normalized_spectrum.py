"""The normalized spectrum of a finite patch: :math:`\\omega_h^n / \\omega^n` against n/N.

The signature figure of the field (Cottrell, Reali, Bazilevs, Hughes 2006): the n-th discrete
frequency over the n-th frequency of the continuum, against n over the number of discrete
frequencies N. The continuum's frequencies, sorted:

* **the bar** (c = 1, length L): :math:`\\omega^n = n \\pi / L` with n = 1, 2, ... (both ends
  fixed, or both free: the rigid mode n = 0 is left out of the ratio),
  :math:`(n - 1/2) \\pi / L` (one of each), :math:`2 \\pi \\lceil n/2 \\rceil / L` (periodic);
* **the strip with sliding ends** (:math:`u_x = 0`, no shear traction): the Rayleigh-Lamb
  modes at :math:`\\kappa_m = m \\pi H / L`, m = 1, 2, ..., every branch of both symmetry
  classes (:func:`dispersion.continuum.exact_branches.trace_branches`, the certified tracer),
  and at m = 0 the motions with :math:`u_x = 0`: the thickness-stretch cut-offs
  :math:`j \\pi c_L / (2 c_T)` (and the rigid translation in y, left out);
* **any other strip**: a refined discretization, the same patch with twice and three times
  the elements in both directions and the consistent mass; only the modes on which the two
  refined ones agree to :data:`REFINED_AGREEMENT` are compared (the rule is stated here,
  before any result), and their largest disagreement is reported (``converged``).

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> s = normalized_spectrum(finite_bar(1, 40, ends="fixed", mass="consistent"))
>>> s.reference, bool(s.ratio[0] > 1), round(float(s.ratio[-1]), 4)   # 39 of 40 modes
('closed form', True, 1.1283)

References
----------
J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, "Isogeometric analysis of structural
vibrations", CMAME 195 (2006) 5257-5296, figs 5-7 (normalized discrete spectra). J. L. Rose,
*Ultrasonic Guided Waves in Solid Media*, 2014, ch. 6 (Lamb waves; a strip with symmetry
planes at its ends carries them at kappa = m pi H / L).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from dispersion.errors import InputError

__all__ = ["NormalizedSpectrum", "normalized_spectrum", "continuum_frequencies",
           "REFINED_AGREEMENT", "RIGID"]

#: Relative agreement of the two refined references under which a mode is compared.
REFINED_AGREEMENT = 1e-3
#: Frequencies below this (in the patch's unit, relative to its largest) are rigid modes.
RIGID = 1e-7


@dataclass(frozen=True, repr=False)
class NormalizedSpectrum:
    """``fraction`` n/N, ``ratio`` omega_h^n / omega^n, the discrete ``omega`` and the
    continuum's ``exact`` (rigid modes left out), ``reference`` in words; ``converged``: the
    refined references' largest disagreement over the compared modes (None: exact)."""

    patch: object
    fraction: np.ndarray
    ratio: np.ndarray
    omega: np.ndarray
    exact: np.ndarray
    reference: str
    converged: float | None = None

    def __repr__(self) -> str:
        return f"NormalizedSpectrum({self.patch.label()}: {self.ratio.size} modes, {self.reference})"


def _bar_exact(patch, count: int) -> np.ndarray:
    L = patch.length
    n = np.arange(1, count + 1)
    if patch.periodic:
        return 2 * math.pi * np.ceil(n / 2) / L
    if patch.ends[0] == patch.ends[1]:
        return n * math.pi / L
    return (n - 0.5) * math.pi / L


def _sliding_exact(patch, count: int) -> np.ndarray:
    """The strip with sliding ends: sorted, at least ``count`` non-zero frequencies."""
    from dispersion.continuum.exact_branches import trace_branches
    from dispersion.continuum.rayleigh_lamb import OMEGA_MAX, cutoff_frequencies

    L, nu = patch.length, patch.nu
    cap = 4.0
    while True:
        cap = min(cap, OMEGA_MAX)
        m = np.arange(1, int(cap * L / math.pi) + 2)
        br = trace_branches(nu, m * math.pi / L, cap)
        if br.failures:
            raise InputError(f"the exact tracer did not certify every root: {br.failures[0]}")
        vals = [v[np.isfinite(v)] for v in br.omega.values()]
        stretch = [w for kind in ("S", "A") for w, fam in cutoff_frequencies(kind, nu, cap)
                   if fam == "L"]
        out = np.sort(np.concatenate(vals + [np.asarray(stretch, float)]))
        out = out[(out > 0) & (out <= cap)]
        if out.size >= count or cap >= OMEGA_MAX:
            return out[:count]
        cap *= 1.6


def continuum_frequencies(patch, count: int) -> tuple[np.ndarray, str]:
    """The first ``count`` non-zero continuum frequencies of ``patch`` and their source, where
    a closed form or the exact tracer gives them (else InputError)."""
    if patch.model == "bar":
        return _bar_exact(patch, count), "closed form"
    if patch.ends == ("sliding", "sliding") and not patch.mapped:
        return _sliding_exact(patch, count), "Rayleigh-Lamb tracer"
    raise InputError("the continuum of this strip has no closed form: use a refined mesh")


def _refined(patch, factor: int):
    n = patch.p + factor * (patch.n - patch.p)
    return replace(patch, n_elements=patch.n_elements * factor, n=n, mass="consistent",
                   removal=None, removal_parameter=None, h=None)


def normalized_spectrum(patch, spectrum=None) -> NormalizedSpectrum:
    """omega_h^n / omega^n of ``patch`` against n/N (module docstring); ``spectrum``: its
    :class:`~dispersion.discretization.finite_mesh.mesh_spectrum.MeshSpectrum` if already computed."""
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies

    omega = (all_frequencies(mesh_pencil(patch)) if spectrum is None else spectrum).omega
    moving = omega[omega > RIGID * omega[-1]]
    N = omega.size
    fraction = (np.arange(N - moving.size, N) + 1) / N
    try:
        exact, source = continuum_frequencies(patch, moving.size)
        return NormalizedSpectrum(patch, fraction, moving / exact, moving, exact, source)
    except InputError:
        if patch.model == "bar" or patch.mapped:
            raise
    refs = []
    for factor in (2, 3):
        r = all_frequencies(mesh_pencil(_refined(patch, factor))).omega
        refs.append(r[r > RIGID * r[-1]][:moving.size])
    k = min(len(refs[0]), len(refs[1]))
    agree = np.abs(refs[0][:k] / refs[1][:k] - 1)
    bad = np.flatnonzero(agree > REFINED_AGREEMENT)
    keep = int(bad[0]) if bad.size else k
    return NormalizedSpectrum(patch, fraction[:keep], moving[:keep] / refs[1][:keep],
                              moving[:keep], refs[1][:keep],
                              "refined discretization (2x and 3x the elements, consistent "
                              "mass)", float(agree[:keep].max(initial=0.0)))
