"""Finite patches: the spectrum and the stable step a real mesh has, its outliers and their removal.

The measurement of the report section ``finite_patches`` (issue 35), every number from the
discretization wing (:mod:`dispersion.discretization`):

* ``table``: the issue's table: :math:`\\omega_{max} h / c` of the bar of p = 2..4,
  consistent and row-sum lumped, on the periodic lattice and on the open mesh of
  :data:`TABLE_ELEMENTS` elements with free and with fixed ends (the proven bound), and the
  N -> infinity limit of each mesh's outliers (the boundary block,
  :func:`~dispersion.discretization.finite_mesh.outlier_numbers.boundary_limit`);
* ``bar``: for p = 1..4, every rule of the registry the bar builds (the singular rules at the
  free ends, their contact boundary) and free and fixed ends, on :data:`SPECTRUM_ELEMENTS`
  elements: the normalized spectrum :math:`\\omega_h^n / \\omega^n` against n/N (the closed
  form) and the outlier numbers (count above the lattice, ratio to it, the top mode's share
  on the boundary functions and its peak);
* ``removal``: the three published removal methods and the singular mass, p = 2..4,
  consistent and lumped, free and fixed ends: the proven largest frequency, the step gained
  over the plain mesh, the outlier count, and the cost in the low spectrum: the largest
  relative error of the first :data:`LOW_MODES` non-rigid frequencies against the closed
  form, beside the plain mesh's; normalized spectra before and after at p = 4;
* ``strip``: the plane-strain strip: the normalized spectrum with sliding ends against the
  Rayleigh-Lamb modes (p = 1..4, consistent and lumped) and the ratio of its largest
  frequency to the Bloch patch's with free, fixed and sliding ends on two mesh sizes;
* ``ring``: the ring of the contact scene (:class:`dispersion.contact.scenario.Scenario`) as a
  mapped patch (plane stress): its own proven stable step for each mass, beside the scene's
  step and the contact wing's estimate (massless DOFs held fixed);
* ``shapes``: the outlier modes of the bar of p = 3 (consistent and lumped, free ends);
* ``claims``: the papers' claims about finite meshes (``examples/literature``, kind
  ``mesh_step``), verified.

>>> bar_rules()[:3]                        # the registry's names, never copied
('consistent', 'lumped', 'hrz')
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

__all__ = ["FinitePatchesStudy", "finite_patches", "measure", "TABLE_ELEMENTS",
           "SPECTRUM_ELEMENTS", "LOW_MODES", "bar_rules", "MESH_CLAIMS"]

#: Elements of the issue's table (its 60; 120 gives the same figures).
TABLE_ELEMENTS = 60
#: Elements of the bar's spectra, outlier numbers and removal methods.
SPECTRUM_ELEMENTS = 40
#: Non-rigid modes whose frequency error measures a removal's cost in the low spectrum.
LOW_MODES = 5
#: The literature's claims files about finite meshes (relative to the checkout root).
MESH_CLAIMS = ("deng2021", "deng2022", "manni2022", "nguyen2022")


@dataclass(frozen=True)
class FinitePatchesStudy:
    """The section's result (module docstring); lists of plain rows, arrays as lists."""

    table: tuple
    bar: tuple
    removal: tuple
    removal_spectra: tuple
    strip: tuple
    strip_spectra: tuple
    ring: tuple
    shapes: tuple
    claims: tuple
    failures: tuple
    seconds: float
    settings: dict


def bar_rules() -> tuple[str, ...]:
    """Every registered rule, read from the registry (the bar builds them, or says why not)."""
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _patch(p, ends, mass, n, **kw):
    from dispersion.discretization.finite_mesh.finite_patch import finite_bar

    return finite_bar(p, n, ends=ends, mass=mass, length=float(n), **kw)


def _table(degrees, failures) -> list[dict]:
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.time_stepping.mesh_step import mesh_omega_max
    from dispersion.discretization.finite_mesh.outlier_numbers import boundary_limit

    rows = []
    for p in degrees:
        for mass in ("consistent", "lumped"):
            row = {"p": p, "mass": mass}
            for ends in ("free", "fixed"):
                patch = _patch(p, ends, mass, TABLE_ELEMENTS)
                w = mesh_omega_max(patch)
                lat = lattice_omega_max(patch)
                row["lattice"] = lat
                row[ends] = w.omega_proven
                row[f"{ends}_estimate"] = w.omega
                pen = mesh_pencil(patch)
                from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies

                s = all_frequencies(pen).omega
                above = s[s > lat * (1 + 1e-9)]
                row[f"{ends}_count"] = int(above.size)
                try:
                    lim = boundary_limit(pen, above, lat) if above.size else ()
                    row[f"{ends}_limit"] = float(lim[0]) if lim else lat
                except Exception as exc:  # noqa: BLE001 - listed, never dropped
                    failures.append(f"table p = {p} {mass} {ends}: limit: {exc}")
                    row[f"{ends}_limit"] = None
            rows.append(row)
    return rows


def _bar(degrees, failures) -> list[dict]:
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies
    from dispersion.discretization.finite_mesh.normalized_spectrum import normalized_spectrum
    from dispersion.discretization.finite_mesh.outlier_numbers import outliers
    from dispersion.errors import DispersionError

    rows = []
    for ends in ("free", "fixed"):
        for p in degrees:
            for mass in bar_rules():
                try:
                    patch = _patch(p, ends, mass, SPECTRUM_ELEMENTS)
                    s = all_frequencies(mesh_pencil(patch), vectors=True)
                    ns = normalized_spectrum(patch, s)
                    o = outliers(patch, limit=False, spectrum=s)
                except DispersionError as exc:
                    failures.append(f"bar p = {p} {mass} {ends}: {exc}")
                    continue
                rows.append({"p": p, "mass": mass, "ends": ends, "fraction": ns.fraction,
                             "ratio": ns.ratio, "count": o.count, "omega_max": o.omega_max,
                             "lattice": o.lattice, "outlier_ratio": o.ratio,
                             "boundary_share": o.boundary_share, "peak": o.peak,
                             "method": s.method})
    return rows


def _low_error(omega: np.ndarray, patch) -> float:
    from dispersion.discretization.finite_mesh.normalized_spectrum import RIGID, continuum_frequencies

    moving = omega[omega > RIGID * omega[-1]][:LOW_MODES]
    exact, _ = continuum_frequencies(patch, moving.size)
    return float(np.max(np.abs(moving / exact - 1)))


def _removal(degrees, failures):
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies
    from dispersion.time_stepping.mesh_step import mesh_omega_max
    from dispersion.discretization.finite_mesh.normalized_spectrum import normalized_spectrum
    from dispersion.discretization.finite_mesh.outlier_removal import REMOVALS
    from dispersion.errors import DispersionError

    rows, spectra = [], []
    methods = [(None, None, None)] + [(r, None, None) for r in REMOVALS]
    singular = {"lumped": [(None, "singular-lumped", 0.0), (None, "singular-lumped", 0.5)],
                "consistent": [(None, "singular", 0.0), (None, "singular", 0.5)]}
    for p in degrees:
        for mass in ("consistent", "lumped"):
            for ends in ("free", "fixed"):
                plain = None
                cases = methods + (singular[mass] if ends == "free" else [])
                for removal, rule, gamma in cases:
                    kw = {} if gamma is None else {"gamma_s": gamma}
                    label = removal or (f"{rule} (gamma_s = {gamma:g})" if rule else "none")
                    try:
                        patch = _patch(p, ends, rule or mass, SPECTRUM_ELEMENTS, removal=removal,
                                       **kw)
                        pen = mesh_pencil(patch)
                        s = all_frequencies(pen)
                        w = mesh_omega_max(pen)
                    except DispersionError as exc:
                        failures.append(f"removal p = {p} {mass} {ends} {label}: {exc}")
                        continue
                    low = _low_error(s.omega, patch)
                    row = {"p": p, "mass": mass, "ends": ends, "method": label,
                           "omega_max": w.omega_proven, "low_error": low,
                           "note": pen.removal_note or ""}
                    if removal is None and rule is None:
                        plain = row
                    if plain is not None:
                        row["gain"] = plain["omega_max"] / w.omega_proven
                        row["plain_low_error"] = plain["low_error"]
                    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max

                    lat = lattice_omega_max(patch)
                    row["count"] = int(np.sum(s.omega > lat * (1 + 1e-9)))
                    row["lattice"] = lat
                    rows.append(row)
                    if p == max(degrees) and ends == "free":
                        ns = normalized_spectrum(patch, s)
                        spectra.append({"p": p, "mass": mass, "ends": ends, "method": label,
                                        "fraction": ns.fraction, "ratio": ns.ratio})
    return rows, spectra


def _strip(degrees, quick, failures):
    from dispersion.discretization.finite_mesh.finite_patch import finite_strip
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max
    from dispersion.time_stepping.mesh_step import mesh_omega_max
    from dispersion.discretization.finite_mesh.normalized_spectrum import normalized_spectrum
    from dispersion.errors import DispersionError

    rows, spectra = [], []
    sizes = (8, 16) if quick else (12, 24)
    for p in degrees:
        n = p + 2
        for mass in ("consistent", "lumped"):
            try:
                ns = normalized_spectrum(finite_strip(p, sizes[0], n=n, ends="sliding",
                                                      mass=mass))
                spectra.append({"p": p, "n": n, "mass": mass, "elements": sizes[0],
                                "fraction": ns.fraction, "ratio": ns.ratio,
                                "reference": ns.reference})
            except DispersionError as exc:
                failures.append(f"strip spectrum p = {p} {mass}: {exc}")
            for ends in ("free", "fixed", "sliding"):
                row = {"p": p, "n": n, "mass": mass, "ends": ends}
                for N in sizes:
                    try:
                        patch = finite_strip(p, N, n=n, ends=ends, mass=mass)
                        w = mesh_omega_max(patch)
                        lat = lattice_omega_max(patch)
                    except DispersionError as exc:
                        failures.append(f"strip p = {p} {mass} {ends} N = {N}: {exc}")
                        continue
                    row[f"ratio_{N}"] = w.omega_proven / lat
                    row["lattice"] = lat
                    row[f"omega_{N}"] = w.omega_proven
                rows.append(row)
    return rows, spectra, sizes


def _ring(quick, failures):
    from dispersion.contact.newmark import critical_step
    from dispersion.contact.scenario import Scenario
    from dispersion.contact.simulate import ring_problem
    from dispersion.discretization.finite_mesh.finite_patch import mapped_strip
    from dispersion.time_stepping.mesh_step import mesh_omega_max
    from dispersion.errors import DispersionError

    sc = Scenario()
    rows = []
    for mass in ("lumped", "singular-lumped", "singular", "consistent"):
        try:
            prob, patch = ring_problem(sc, mass)
            w = mesh_omega_max(mapped_strip(patch, mass=mass, nu=sc.nu, plane="stress",
                                            gamma_s=sc.gamma_s))
            held = critical_step(prob)
        except DispersionError as exc:
            failures.append(f"ring {mass}: {exc}")
            continue
        cT = sc.shear_wave_speed
        rows.append({"mass": mass, "dt_mesh": w.dt / cT, "omega_mesh": w.omega_proven * cT,
                     "dt_held_fixed": held, "dt_scene": sc.dt,
                     "elements": [sc.n_xi_elements, sc.n_eta_elements],
                     "dofs": 2 * patch.n_points})
    return rows


def _shapes():
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies

    out = []
    for mass in ("consistent", "lumped"):
        patch = _patch(3, "free", mass, SPECTRUM_ELEMENTS)
        pen = mesh_pencil(patch)
        s = all_frequencies(pen, vectors=True)
        x = np.asarray(pen.matrices.basis_x.kv.greville(), float)
        for k in (1, 2, 3):
            v = pen.mode_on_mesh(s.vectors[:, -k])
            out.append({"mass": mass, "p": 3, "rank": k, "omega": float(s.omega[-k]),
                        "x": x, "mode": v / np.abs(v).max()})
    return out


def _claims(failures):
    from pathlib import Path

    from dispersion.claims.schema import load_claims
    from dispersion.claims.verify import verify_claims

    root = Path(__file__).resolve().parents[2] / "examples" / "literature"
    rows = []
    for name in MESH_CLAIMS:
        path = root / f"{name}.toml"
        if not path.is_file():
            failures.append(f"claims file examples/literature/{name}.toml is missing")
            continue
        res = verify_claims(load_claims(path), jobs=1)
        for r in res.results:
            rows.append({"file": f"{name}.toml", "claim": r.name, "source": r.source or "",
                         "status": r.status, "derived": r.derived,
                         "difference": r.difference})
    return rows


def finite_patches(quick: bool = False) -> FinitePatchesStudy:
    """Measure the section (module docstring); ``quick``: p = 1..2 for the spectra, fewer
    removal degrees, smaller strips."""
    t0 = time.perf_counter()
    failures: list[str] = []
    degrees = (1, 2) if quick else (1, 2, 3, 4)
    table = _table((2,) if quick else (2, 3, 4), failures)
    bar = _bar(degrees, failures)
    removal, removal_spectra = _removal((2,) if quick else (2, 3, 4), failures)
    strip, strip_spectra, sizes = _strip((1, 2) if quick else degrees, quick, failures)
    ring = _ring(quick, failures)
    shapes = _shapes()
    claims = () if quick else _claims(failures)
    settings = {"table_elements": TABLE_ELEMENTS, "spectrum_elements": SPECTRUM_ELEMENTS,
                "low_modes": LOW_MODES, "degrees": list(degrees), "strip_elements": list(sizes),
                "quick": quick}
    return FinitePatchesStudy(tuple(table), tuple(bar), tuple(removal), tuple(removal_spectra),
                              tuple(strip), tuple(strip_spectra), tuple(ring), tuple(shapes),
                              tuple(claims), tuple(failures), time.perf_counter() - t0,
                              settings)


def measure(quick: bool = False, executor=None) -> FinitePatchesStudy:
    """The report's measurement (``executor`` unused: in-process, about a minute)."""
    del executor
    return finite_patches(quick)
