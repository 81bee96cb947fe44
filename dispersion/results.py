"""Measured results as data: strict JSON with the inputs, versions, machine and timings.

Every study, benchmark and report section of the toolkit returns a frozen dataclass; this
module turns one into strict JSON (no NaN: a non-finite float becomes ``null``) inside an
*envelope* that records what is needed to trust and repeat it, and reads it back. Renderers
(:mod:`dispersion.report`) take the loaded dictionary and never recompute.

>>> import dataclasses, math
>>> @dataclasses.dataclass(frozen=True)
... class Demo:
...     x: float
...     ys: tuple
>>> jsonable(Demo(x=math.nan, ys=(1, 2.5)))
{'x': None, 'ys': [1, 2.5]}
>>> env = envelope("demo", Demo(1.0, ()), inputs={"quick": True}, seconds=0.5)
>>> sorted(env)
['command', 'created', 'inputs', 'machine', 'result', 'seconds', 'section', 'versions']
"""
from __future__ import annotations

import dataclasses
import datetime as _dt
import enum
import json
import math
import os
import platform
from collections.abc import Mapping, Sequence
from pathlib import Path

from dispersion.errors import DispersionError

__all__ = [
    "PACKAGES", "jsonable", "dumps", "envelope", "save", "load",
    "machine_facts", "package_versions",
]

#: Distributions whose versions every result records.
PACKAGES = ("dispersion-iga", "sympy", "numpy", "scipy", "matplotlib", "mpmath",
            "python-flint")


def jsonable(obj):
    """``obj`` as plain JSON types: dataclasses, mappings, sequences, numpy and sympy values.

    Non-finite floats become ``None`` so the output is strict JSON; sympy expressions become
    their ``str`` (sympy-parsable); paths become strings.
    """
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: jsonable(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if isinstance(obj, enum.Enum):
        return jsonable(obj.value)
    if isinstance(obj, int):
        return obj
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, Path):
        return str(obj)
    if isinstance(obj, Mapping):
        return {str(k): jsonable(v) for k, v in obj.items()}
    type_name = type(obj).__module__.split(".")[0]
    if type_name == "numpy":
        import numpy as np

        if isinstance(obj, np.ndarray):
            return jsonable(obj.tolist())
        if isinstance(obj, np.bool_):
            return bool(obj)
        if isinstance(obj, np.integer):
            return int(obj)
        if isinstance(obj, np.floating):
            return jsonable(float(obj))
        if isinstance(obj, np.complexfloating):
            return {"re": jsonable(float(obj.real)), "im": jsonable(float(obj.imag))}
    if type_name == "sympy" or type_name == "flint":
        return str(obj)
    if isinstance(obj, (Sequence, set, frozenset)):
        return [jsonable(v) for v in obj]
    raise DispersionError(f"cannot store a {type(obj).__name__} as JSON: {obj!r}")


def dumps(obj, indent: int | None = 1) -> str:
    """Strict JSON text of :func:`jsonable` ``(obj)`` (``allow_nan=False``), newline-terminated."""
    return json.dumps(jsonable(obj), indent=indent, allow_nan=False) + "\n"


def machine_facts() -> dict[str, str]:
    """CPU count, platform, processor and Python of the machine that measured."""
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        usable = os.cpu_count() or 1
    return {
        "CPU count (usable / total)": f"{usable} / {os.cpu_count()}",
        "platform": platform.platform(),
        "machine": platform.machine() or "unknown",
        "processor": _cpu_model() or platform.processor() or "unknown",
        "Python": f"{platform.python_implementation()} {platform.python_version()}",
    }


def _cpu_model() -> str | None:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def package_versions(packages: Sequence[str] = PACKAGES) -> dict[str, str]:
    """Installed version of each distribution, or ``"not installed"``."""
    from importlib import metadata  # here, not at import: a small command's start-up

    versions = {}
    for name in packages:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def envelope(section: str, result, *, inputs: Mapping | None = None, seconds: float | None = None,
             command: str | None = None) -> dict:
    """The stored form of one measured ``result``: data plus provenance.

    Keys: ``section``, ``result`` (the data), ``inputs`` (the arguments that produced it),
    ``seconds`` (wall clock of the measurement), ``command`` (the command line that
    regenerates it), ``created`` (UTC, ISO 8601), ``versions``, ``machine``.
    """
    return {
        "section": section,
        "result": jsonable(result),
        "inputs": jsonable(dict(inputs or {})),
        "seconds": jsonable(seconds),
        "command": command,
        "created": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "versions": package_versions(),
        "machine": machine_facts(),
    }


def save(path, section: str, result, **kwargs) -> Path:
    """Write :func:`envelope` ``(section, result, **kwargs)`` to ``path`` atomically."""
    from dispersion.io import write_text

    return write_text(Path(path), dumps(envelope(section, result, **kwargs)))


def load(path) -> dict:
    """Read an envelope written by :func:`save`; raise :class:`DispersionError` if it is not one."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError) as exc:  # RecursionError: nested too deep
        raise DispersionError(f"cannot read result file {path}: {exc}") from None
    if not isinstance(data, dict) or "result" not in data or "section" not in data:
        raise DispersionError(f"{path} is not a dispersion result file (no section/result)")
    return data
