"""Report sections of ``dispersion reproduce``: renderers from measured JSON to pages.

Measuring is apart from presenting. Each section is a module ``dispersion.report.<name>``
with two names:

``measure``
    The measurement: a function that lives in the module of its object (imported here, not
    defined here), called as ``measure(quick=quick, executor=executor)`` and returning a
    frozen dataclass (or a mapping) that :func:`dispersion.results.jsonable` stores.
    ``quick`` selects the subset CI runs; ``executor`` is a ``concurrent.futures`` executor
    for independent runs (or ``None``: run in-process).
``render(data, out) -> str``
    The presentation: ``data`` is the ``"result"`` of ``<name>.json`` as loaded from disk
    (plain JSON types; ``None`` where a float was not finite). It writes its figures and
    tables into ``out`` (atomically, :mod:`dispersion.io`) and returns the Markdown of the
    section for ``index.md``, linking files by relative path. It computes nothing that
    takes time, so ``dispersion reproduce --render`` rebuilds every page from the JSON alone.

A section may also define ``headline(data) -> str``, one line for the console summary that
follows the verdict (rendered from the stored result like the rest), ``TOLERANCES`` (how
its fields are compared with the reference, :mod:`dispersion.report.compare`) and
``missing_peers(data)`` (the optional programs the result shows were not run).

``dispersion reproduce`` runs ``measure`` of each section, saves ``<name>.json``
(:func:`dispersion.results.save`: result, inputs, versions, machine, seconds, command),
then renders every section from the saved files and writes ``index.md``.
"""
from __future__ import annotations

import importlib
from types import ModuleType

from dispersion.errors import DispersionError, InputError

__all__ = ["SECTIONS", "DEFAULT_SECTIONS", "OPT_IN_SECTIONS", "section_module"]

#: Report sections in the order they run (module names in :mod:`dispersion.report`).
SECTIONS = ("coefficients", "branches", "ring", "series_speed", "studies", "peers",
            "cost_accuracy", "lumping", "finite_patches", "wave_simulation")
#: Sections measured only when named (``--sections``): a sweep beyond the paper that takes
#: minutes (wave_simulation: a few hundred simulations; the seconds each section took are in
#: the timing table of its index page), which the main job does not ask of every user. Their
#: committed results stay in the reference and are rendered with it.
OPT_IN_SECTIONS = ("wave_simulation",)
#: What ``dispersion reproduce`` measures by default.
DEFAULT_SECTIONS = tuple(s for s in SECTIONS if s not in OPT_IN_SECTIONS)


def section_module(name: str) -> ModuleType:
    """Import ``dispersion.report.<name>``; it must define ``measure`` and ``render``."""
    if name not in SECTIONS:
        raise InputError(f"sections must be among {', '.join(SECTIONS)}, got {name!r}")
    module_name = f"{__name__}.{name}"
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        if exc.name != module_name:
            raise
        raise DispersionError(f"report section {name!r} is missing ({module_name})") from exc
    for attr in ("measure", "render"):
        if not callable(getattr(module, attr, None)):
            raise DispersionError(f"report section {name!r} defines no {attr}()")
    return module

