"""dispersion: grid dispersion of B-spline plate patches and singular mass matrices.

Follows Tkachuk, Matzen, Kolman, Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact".

The public API (see :mod:`dispersion.api`), with the defaults of :mod:`dispersion.defaults`:

- :func:`patch` -> :class:`Patch` with ``K()``, ``M()``, ``K_dyn()``, ``series()``,
  ``branches()``;
- :func:`series` (discrete or ``exact=True`` Rayleigh-Lamb), :func:`exact_branches`;
- the commands as functions: :func:`branch_table` (``dispersion branches``),
  :func:`lamb_modes` and :func:`mode_shapes` (its calculator), :func:`series_table`,
  :func:`critical_steps` (``dispersion timestep``); every result renders itself
  (:mod:`dispersion.rendering`: ``to_text``, ``to_csv``, ``to_json``, ``to_dataframe``);
- :func:`simulate_ring` (Figure 4) and :func:`simulate_bar`;
- the errors :class:`InputError`, :class:`DispersionError`, ...

``import dispersion`` is cheap: the names above load their modules (sympy, numpy) on first
use.

>>> import dispersion
>>> dispersion.patch().K_dyn().shape
(6, 6)
"""
from __future__ import annotations

import importlib

from dispersion.errors import ConvergenceError, DispersionError, IndefiniteMassWarning, InputError

#: Distribution name on the package index (the import name is ``dispersion``).
DISTRIBUTION = "dispersion-iga"

_API = ("Patch", "PatchModel", "patch", "series", "exact_branches", "lamb_modes", "material",
        "simulate_ring", "simulate_bar", "branch_table", "mode_shapes", "series_table",
        "critical_steps", "figure", "layered_lamb_modes", "layup")
#: Public modules by their short names (``dispersion.plate``), wherever they live in the wings.
_MODULES = {
    "api": "api", "patch_model": "patch_model", "defaults": "defaults", "errors": "errors", "io": "io", "results": "results",
    "sweep": "sweep", "testing": "testing", "contact": "contact", "claims": "claims",
    "symbolic": "symbolic", "waves": "waves", "studies": "studies",
    "bspline": "symbolic.bspline", "mass": "symbolic.mass", "plate": "symbolic.plate",
    "series_kernel": "symbolic.series_kernel", "power_balance": "symbolic.power_balance",
    "rayleigh_lamb": "waves.rayleigh_lamb", "exact_branches": "waves.exact_branches",
    "numeric_frequency": "waves.numeric_frequency",
    "deflated_frequency": "waves.deflated_frequency", "scaled_frequency": "waves.scaled_frequency",
    "discrete_branches": "waves.discrete_branches", "velocities": "waves.velocities",
    "units": "waves.units", "mode_shapes": "waves.mode_shapes",
    "bar_dispersion": "waves.bar_dispersion", "errata": "claims.errata",
    "exact_series": "waves.exact_series", "branch_study": "studies.branch_study",
    "paper_studies": "studies.paper_studies", "series_race": "studies.series_race",
    "coefficient_value": "studies.coefficient_value",
    "plotting": "plotting", "report": "report", "branch_views": "waves.branch_views",
    "table": "table", "branch_set": "waves.branch_set",
    "explicit": "claims.explicit", "limits": "claims.limits", "reader": "claims.reader",
    "schema": "claims.schema", "verify": "claims.verify", "cli": "cli", "staging": "staging",
    "claim": "claims.claim", "claim_model": "claims.claim_model",
    "claim_fields": "claims.claim_fields", "claims_file": "claims.claims_file",
    "exact_model": "claims.exact_model", "bar_model": "claims.bar_model",
    "peers": "studies.peers", "layered_peers": "studies.layered_peers", "spline_mass": "symbolic.spline_mass",
    "extended_pencil": "waves.extended_pencil", "pencil_polynomial": "waves.pencil_polynomial",
    "asymptotic_fit": "studies.asymptotic_fit",
    "materials": "waves.materials", "frequency": "waves.frequency", "sh": "waves.sh",
    "mode_table": "waves.mode_table",
    "mass_rule": "symbolic.mass_rule", "timestep": "waves.timestep",
    "fully_discrete": "waves.fully_discrete", "cost_accuracy": "studies.cost_accuracy",
    "time_integration": "waves.time_integration", "branch_table": "waves.branch_table",
    "mode_shape_table": "waves.mode_shape_table", "unit_mixups": "waves.unit_mixups",
    "rendering": "rendering", "critical_steps": "waves.critical_steps",
    "series_table": "waves.series_table", "errata_sheet": "claims.errata_sheet",
    "discrete_error": "waves.discrete_error", "pencil_frequencies": "waves.pencil_frequencies",
    "illinois": "waves.illinois", "mass_check": "symbolic.mass_check",
    "matrix_kind": "symbolic.matrix_kind", "certified_roots": "waves.certified_roots",
    "certified_slopes": "waves.certified_slopes", "omega_max_bound": "waves.omega_max_bound",
    # the mass rules of the lumping literature (issue 29)
    "approximate_dual": "symbolic.approximate_dual", "explicit_cost": "symbolic.explicit_cost",
    "interpolatory_spline": "symbolic.interpolatory_spline",
    "lagrange_sem": "symbolic.lagrange_sem", "lumping_rules": "symbolic.lumping_rules",
    "mass_scaling": "symbolic.mass_scaling", "leading_error": "waves.leading_error",
    "sem_bar": "waves.sem_bar", "lumping_orders": "studies.lumping_orders",
    "orders": "claims.orders", "derivative_gram": "symbolic.derivative_gram",
    "rule_families": "symbolic.rule_families",
    "mass_rule_file": "symbolic.mass_rule_file", "ownership": "ownership", "budget": "budget",
    "untrusted": "untrusted",
    "wave_simulation": "studies.wave_simulation",
    # the plate's material (issue 28 item 6)
    "elastic_law": "symbolic.elastic_law",
}
_SUBMODULES = tuple(_MODULES)

__all__ = ["DispersionError", "InputError", "ConvergenceError", "IndefiniteMassWarning",
           "__version__", *_API]


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(DISTRIBUTION)
    except PackageNotFoundError:  # a source tree that was never installed
        return "0+unknown"


def __getattr__(name: str):
    if name == "__version__":
        value = _version()
    elif name in _API:
        value = getattr(importlib.import_module(".api", __name__), name)
    elif name in _SUBMODULES:
        return importlib.import_module(f".{_MODULES[name]}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | set(_SUBMODULES))
