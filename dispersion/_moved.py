"""Old module paths of the split (issue 33), still importing, with a DeprecationWarning.

``dispersion/waves/`` became the wings ``continuum/``, ``discretization/``,
``time_stepping/``, ``answers/`` and ``materials/``; ``dispersion/symbolic/`` gave its basis to
``splines/``, its material to ``materials/`` and its mass rules to ``mass_rules/``
(ARCHITECTURE.md draws the layers). :data:`MOVED` maps every old dotted path to its new one;
ARCHITECTURE.md prints the same table (tests/test_architecture.py checks that they agree).

``import dispersion.waves.velocities`` (or ``from dispersion.waves.velocities import ...``)
warns and hands back the module of the new path itself, so both paths name one object; a module
whose functions went to two wings (``waves.mode_shapes``) is a read-only view of both. The old
packages' faces (``dispersion/waves/__init__.py``, ``dispersion/symbolic/__init__.py``) call
:func:`install` and forward attribute access with :func:`package_getattr`. Nothing here imports
a module of the package until an old path is asked for.

>>> import warnings
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     from dispersion.waves.branch_set import BranchSet
>>> BranchSet.__module__, caught[0].category.__name__
('dispersion.continuum.branch_set', 'DeprecationWarning')
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
import warnings

__all__ = ["MOVED", "install", "package_getattr"]

#: Old dotted module path -> its new path(s) (two where the functions went to two wings).
MOVED: dict[str, tuple[str, ...]] = {
    # dispersion/waves/: the exact plate, the lattice, time stepping, the answers, materials
    "dispersion.waves.rayleigh_lamb": ("dispersion.continuum.rayleigh_lamb",),
    "dispersion.waves.numeric_frequency": ("dispersion.continuum.numeric_frequency",),
    "dispersion.waves.deflated_frequency": ("dispersion.continuum.deflated_frequency",),
    "dispersion.waves.scaled_frequency": ("dispersion.continuum.scaled_frequency",),
    "dispersion.waves.exact_series": ("dispersion.continuum.exact_series",),
    "dispersion.waves.exact_branches": ("dispersion.continuum.exact_branches",),
    "dispersion.waves.branch_set": ("dispersion.continuum.branch_set",),
    "dispersion.waves.illinois": ("dispersion.continuum.illinois",),
    "dispersion.waves.frequency": ("dispersion.continuum.frequency",),
    "dispersion.waves.sh": ("dispersion.continuum.sh",),
    "dispersion.waves.velocities": ("dispersion.continuum.velocities",),
    "dispersion.waves.mode_shapes": ("dispersion.continuum.mode_shapes",
                                     "dispersion.discretization.discrete_mode_shapes"),
    "dispersion.waves.bar_dispersion": ("dispersion.discretization.bar_dispersion",),
    "dispersion.waves.sem_bar": ("dispersion.discretization.sem_bar",),
    "dispersion.waves.discrete_branches": ("dispersion.discretization.discrete_branches",),
    "dispersion.waves.pencil_frequencies": ("dispersion.discretization.pencil_frequencies",),
    "dispersion.waves.pencil_polynomial": ("dispersion.discretization.pencil_polynomial",),
    "dispersion.waves.certified_roots": ("dispersion.discretization.certified_roots",),
    "dispersion.waves.certified_slopes": ("dispersion.discretization.certified_slopes",),
    "dispersion.waves.extended_pencil": ("dispersion.discretization.extended_pencil",),
    "dispersion.waves.discrete_error": ("dispersion.discretization.discrete_error",),
    "dispersion.waves.leading_error": ("dispersion.discretization.leading_error",),
    "dispersion.waves.timestep": ("dispersion.time_stepping.timestep",),
    "dispersion.waves.fully_discrete": ("dispersion.time_stepping.fully_discrete",),
    "dispersion.waves.time_integration": ("dispersion.time_stepping.time_integration",),
    "dispersion.waves.omega_max_bound": ("dispersion.time_stepping.omega_max_bound",),
    "dispersion.waves.branch_table": ("dispersion.answers.branch_table",),
    "dispersion.waves.mode_table": ("dispersion.answers.mode_table",),
    "dispersion.waves.mode_shape_table": ("dispersion.answers.mode_shape_table",),
    "dispersion.waves.series_table": ("dispersion.answers.series_table",),
    "dispersion.waves.critical_steps": ("dispersion.answers.critical_steps",),
    "dispersion.waves.units": ("dispersion.answers.units",),
    "dispersion.waves.branch_views": ("dispersion.branch_views",),
    "dispersion.waves.materials": ("dispersion.materials.materials",),
    "dispersion.waves.unit_mixups": ("dispersion.materials.unit_mixups",),
    # dispersion/symbolic/: the basis, the material and the mass rules left it
    "dispersion.symbolic.bspline": ("dispersion.splines.bspline",),
    "dispersion.symbolic.spline_mass": ("dispersion.splines.spline_mass",),
    "dispersion.symbolic.derivative_gram": ("dispersion.splines.derivative_gram",),
    "dispersion.symbolic.matrix_kind": ("dispersion.splines.matrix_kind",),
    "dispersion.symbolic.lagrange_sem": ("dispersion.splines.lagrange_sem",),
    "dispersion.symbolic.interpolatory_spline": ("dispersion.splines.interpolatory_spline",),
    "dispersion.symbolic.elastic_law": ("dispersion.materials.elastic_law",),
    "dispersion.symbolic.mass": ("dispersion.mass_rules.mass",),
    "dispersion.symbolic.mass_check": ("dispersion.mass_rules.mass_check",),
    "dispersion.symbolic.mass_rule": ("dispersion.mass_rules.mass_rule",),
    "dispersion.symbolic.mass_rule_file": ("dispersion.mass_rules.mass_rule_file",),
    "dispersion.symbolic.lumping_rules": ("dispersion.mass_rules.lumping_rules",),
    "dispersion.symbolic.approximate_dual": ("dispersion.mass_rules.approximate_dual",),
    "dispersion.symbolic.mass_scaling": ("dispersion.mass_rules.mass_scaling",),
    "dispersion.symbolic.explicit_cost": ("dispersion.mass_rules.explicit_cost",),
    "dispersion.symbolic.rule_families": ("dispersion.mass_rules.rule_families",),
}


def _warn(old: str, new: tuple[str, ...]) -> None:
    warnings.warn(f"{old} moved to {' and '.join(new)} (issue 33, ARCHITECTURE.md); "
                  f"import it from there", DeprecationWarning, stacklevel=4)


class _View(types.ModuleType):
    """An old module whose names now live in several modules: each name from its new home."""

    def __init__(self, name: str, homes: list[types.ModuleType]):
        super().__init__(name, f"Moved: the names of {name} now live in "
                               f"{' and '.join(m.__name__ for m in homes)}.")
        self._homes = homes
        self.__all__ = [n for m in homes for n in getattr(m, "__all__", ())]

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        for home in self._homes:
            if hasattr(home, name):
                return getattr(home, name)
        raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | {n for m in self._homes for n in dir(m)})


class _Alias(importlib.abc.Loader):
    """Loads an old path as the module of its new path (or a view of its new paths)."""

    def __init__(self, new: tuple[str, ...]):
        self.new = new
        self._spec = None

    def create_module(self, spec):
        _warn(spec.name, self.new)
        homes = [importlib.import_module(name) for name in self.new]
        if len(homes) > 1:
            return _View(spec.name, homes)
        self._spec = homes[0].__spec__
        return homes[0]

    def exec_module(self, module) -> None:
        # the import system stamps the old path's spec on the module it is handed: give the
        # module its own back (reload, pickling and pkgutil read it)
        if self._spec is not None:
            module.__spec__ = self._spec


class _Finder(importlib.abc.MetaPathFinder):
    """Finds the old paths of :data:`MOVED` (and nothing else)."""

    def find_spec(self, fullname, path=None, target=None):
        new = MOVED.get(fullname)
        if new is None:
            return None
        return importlib.machinery.ModuleSpec(fullname, _Alias(new))


_FINDER = _Finder()


def install() -> None:
    """Put the finder of old paths on ``sys.meta_path`` (once)."""
    if _FINDER not in sys.meta_path:
        sys.meta_path.insert(0, _FINDER)


def package_getattr(package: str, name: str):
    """``package.name`` for an old module path not imported yet (``dispersion.waves.units``)."""
    if f"{package}.{name}" in MOVED:
        return importlib.import_module(f"{package}.{name}")
    raise AttributeError(f"module {package!r} has no attribute {name!r}")
