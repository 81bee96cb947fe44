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

from dispersion.errors import (ConvergenceError, DispersionError, IndefiniteMassWarning, InputError,
                               ParameterError)

#: Distribution name on the package index (the import name is ``dispersion``).
DISTRIBUTION = "dispersion-iga"

_API = ("Patch", "PatchModel", "patch", "series", "exact_branches", "lamb_modes", "material",
        "simulate_ring", "simulate_bar", "branch_table", "mode_shapes", "series_table",
        "critical_steps", "figure", "layered_lamb_modes", "layup", "slowness_curves",
        "evanescent_modes")
#: Public modules by their short names (``dispersion.plate``), wherever they live in the wings.
_MODULES = {
    "api": "api", "patch_model": "patch_model", "defaults": "defaults", "errors": "errors", "io": "io", "results": "results",
    "sweep": "sweep", "testing": "testing", "contact": "contact", "claims": "claims",
    "symbolic": "symbolic", "waves": "waves", "studies": "studies",
    # the wings of issue 33 (ARCHITECTURE.md); "materials" is the wing, whose face hands on
    # the names of the material table module (materials.materials)
    "splines": "splines", "mass_rules": "mass_rules", "continuum": "continuum",
    "discretization": "discretization", "time_stepping": "time_stepping", "answers": "answers",
    "discrete_mode_shapes": "discretization.discrete_mode_shapes",
    "bspline": "splines.bspline", "mass": "mass_rules.mass", "plate": "symbolic.plate",
    "series_kernel": "symbolic.series_kernel", "power_balance": "symbolic.power_balance",
    "rayleigh_lamb": "continuum.rayleigh_lamb", "exact_branches": "continuum.exact_branches",
    "numeric_frequency": "continuum.numeric_frequency",
    "deflated_frequency": "continuum.deflated_frequency",
    "scaled_frequency": "continuum.scaled_frequency",
    "discrete_branches": "discretization.discrete_branches", "velocities": "continuum.velocities",
    "units": "answers.units", "mode_shapes": "continuum.mode_shapes",
    "bar_dispersion": "discretization.bar_dispersion", "errata": "claims.errata",
    "exact_series": "continuum.exact_series", "branch_study": "studies.branch_study",
    "paper_studies": "studies.paper_studies", "series_race": "studies.series_race",
    "coefficient_value": "studies.coefficient_value",
    "plotting": "plotting", "report": "report", "branch_views": "branch_views",
    "table": "table", "branch_set": "continuum.branch_set",
    "explicit": "claims.explicit", "limits": "claims.limits", "reader": "reader",
    "reader_limits": "reader_limits",
    "schema": "claims.schema", "verify": "claims.verify", "cli": "cli", "staging": "staging",
    "claim": "claims.claim", "claim_model": "claims.claim_model",
    "claim_fields": "claims.claim_fields", "claims_file": "claims.claims_file",
    "exact_model": "claims.exact_model", "bar_model": "claims.bar_model",
    "peers": "studies.peers", "layered_peers": "studies.layered_peers",
    "spline_mass": "splines.spline_mass",
    "extended_pencil": "discretization.extended_pencil",
    "pencil_polynomial": "discretization.pencil_polynomial",
    "asymptotic_fit": "studies.asymptotic_fit",
    "materials": "materials", "frequency": "continuum.frequency", "sh": "continuum.sh",
    "mode_table": "answers.mode_table",
    "mass_rule": "mass_rules.mass_rule", "timestep": "time_stepping.timestep",
    "fully_discrete": "time_stepping.fully_discrete", "cost_accuracy": "studies.cost_accuracy",
    "time_integration": "time_stepping.time_integration", "branch_table": "answers.branch_table",
    "mode_shape_table": "answers.mode_shape_table", "unit_mixups": "materials.unit_mixups",
    "rendering": "rendering", "critical_steps": "answers.critical_steps",
    "series_table": "answers.series_table", "errata_sheet": "claims.errata_sheet",
    "discrete_error": "discretization.discrete_error",
    "pencil_frequencies": "discretization.pencil_frequencies",
    "illinois": "continuum.illinois", "root_certificate": "continuum.root_certificate",
    "mass_check": "mass_rules.mass_check",
    "matrix_kind": "splines.matrix_kind", "certified_roots": "discretization.certified_roots",
    "certified_slopes": "discretization.certified_slopes",
    "omega_max_bound": "time_stepping.omega_max_bound",
    # the mass rules of the lumping literature (issue 29)
    "approximate_dual": "mass_rules.approximate_dual", "explicit_cost": "mass_rules.explicit_cost",
    "interpolatory_spline": "splines.interpolatory_spline",
    "lagrange_sem": "splines.lagrange_sem", "lumping_rules": "mass_rules.lumping_rules",
    "mass_scaling": "mass_rules.mass_scaling", "leading_error": "discretization.leading_error",
    "sem_bar": "discretization.sem_bar", "lumping_orders": "studies.lumping_orders",
    "orders": "claims.orders", "derivative_gram": "splines.derivative_gram",
    "rule_families": "mass_rules.rule_families",
    "mass_rule_file": "mass_rules.mass_rule_file", "ownership": "ownership", "budget": "budget",
    "untrusted": "untrusted",
    "wave_simulation": "studies.wave_simulation",
    # the plate's material (issue 28 item 6)
    "elastic_law": "materials.elastic_law",
    # the finite mesh (issue 35)
    "finite_mesh": "discretization.finite_mesh",
    "finite_patch": "discretization.finite_mesh.finite_patch",
    "finite_matrices": "discretization.finite_mesh.finite_matrices",
    "finite_assembly": "discretization.finite_mesh.finite_assembly",
    "mapped_assembly": "discretization.finite_mesh.mapped_assembly",
    "direction_mass": "discretization.finite_mesh.direction_mass",
    "mesh_pencil": "discretization.finite_mesh.mesh_pencil",
    "mesh_spectrum": "discretization.finite_mesh.mesh_spectrum",
    "banded_pencil": "discretization.finite_mesh.banded_pencil",
    "normalized_spectrum": "discretization.finite_mesh.normalized_spectrum",
    "lattice_reference": "discretization.finite_mesh.lattice_reference",
    "outlier_numbers": "discretization.finite_mesh.outlier_numbers",
    "outlier_removal": "discretization.finite_mesh.outlier_removal",
    "mesh_step": "time_stepping.mesh_step", "positive_definite": "time_stepping.positive_definite",
    "lagrange_space": "splines.lagrange_space", "mesh_claims": "claims.mesh_claims",
    "nurbs": "splines.nurbs",
    "finite_patches": "studies.finite_patches",
    # layered and anisotropic plates (issue 36)
    "stiffness": "materials.stiffness", "solid": "materials.solid",
    "layered": "continuum.layered", "layered_plate": "continuum.layered.layered_plate",
    "layup_file": "continuum.layered.layup_file", "stroh": "continuum.layered.stroh",
    "dynamic_stiffness": "continuum.layered.dynamic_stiffness", "safe": "continuum.layered.safe",
    "layered_modes": "continuum.layered.layered_modes",
    "layered_branches": "continuum.layered.layered_branches",
    "damped_modes": "continuum.layered.damped_modes",
    "layered_zgv": "continuum.layered.layered_zgv",
    "argument_principle": "continuum.layered.argument_principle",
    "evanescent_mode_table": "answers.evanescent_mode_table",
    "layered_mode_table": "answers.layered_mode_table",
    "layered_mode_shapes": "continuum.layered.layered_mode_shapes",
    "slowness_table": "answers.slowness_table",
    "plate_table": "answers.plate_table",
    "layered_model": "continuum.layered.layered_model",
    # the continuum as a family of plate models (issue 33 item 2)
    "plate_model": "continuum.plate_model", "isotropic_plate": "continuum.isotropic_plate",
}
_SUBMODULES = tuple(_MODULES)

__all__ = ["DispersionError", "InputError", "ParameterError", "ConvergenceError",
           "IndefiniteMassWarning",
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
