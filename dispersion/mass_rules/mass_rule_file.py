"""A user's mass rule from TOML: untrusted text read as plain data, within stated limits.

A rule file (``dispersion timestep --mass-rule FILE.toml``, ``dispersion branches
--mass-rule``) states redistribution weights::

    name = "far-half"
    lumped = false            # row-sum lump R^T M R (eq 1 right) if true
    description = "half to each of the two far neighbours"
    [weights]                 # contact index -> {target index: weight}; negative
    "-1" = { "-2" = 0.5, "-3" = 0.5 }   # indices count from the far end (any n)

It may come from anyone, so it is read as the claims files are
(:mod:`dispersion.untrusted`): a regular file only (no ``/dev/zero``, no pipe), of at most
:data:`MAX_FILE_BYTES` bytes (checked before reading), UTF-8, a name ending in ``.toml``
(a path is never parsed as TOML text), tables nested at most :data:`MAX_NESTING` deep and
at most :data:`MAX_KEYS` keys, both counted on the raw text before it is parsed
(:func:`dispersion.untrusted.check_toml`), and then by a whitelist:

- keys ``name``, ``lumped``, ``description``, ``weights`` only;
- ``name``: 1 to 48 characters among letters, digits, space and ``. _ + - ( )``, not the
  name of a registered rule; ``description``: at most 200 printable characters (so no
  text of the file can move a cursor or forge a line on a terminal);
- indices: integers written with at most four digits (``"-1"``, ``"3"``); two keys that
  name the same index (``"-1"`` and ``"-1 "``, ``"01"`` and ``"1"``) are refused, never
  one silently lost; at most :data:`MAX_ENTRIES` contact indices and as many targets each;
- weights: numbers in [0, 1] (not booleans), summing to 1 for each contact index, never
  sending an index's mass to itself; what depends on the size n of the space (an index
  out of range, a target in the contact set) is refused when the rule is applied, still
  naming the file.

Every refusal is one :class:`~dispersion.errors.InputError` naming the file.

>>> rule = rule_from_toml('name = "far-half"\\n[weights]\\n"-1" = {"-2" = 0.5, "-3" = 0.5}')
>>> from dispersion.splines.bspline import open_knot_vector
>>> from dispersion.mass_rules.mass_rule import gram_space, mass_matrix
>>> mass_matrix(rule, gram_space(open_knot_vector(1, 2))).tolist()  # M00 + M02 + M22/4 = 5/24
[[5/24, 1/6, 0], [1/6, 11/24, 0], [0, 0, 0]]
>>> rule_from_toml('name = "x"\\n[weights]\\n"-1" = {"-2" = 1}\\n"-1 " = {"-3" = 1}')
Traceback (most recent call last):
...
dispersion.errors.InputError: mass rule <string>: weights: keys '-1' and '-1 ' both name index -1
"""
from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping

from dispersion.errors import InputError
from dispersion.mass_rules.mass_check import MassProperties
from dispersion.mass_rules.mass_rule import RULES, MassRule, MassSpace, _build_singular
from dispersion.untrusted import load_toml, printable, read_text

__all__ = ["MAX_FILE_BYTES", "MAX_NESTING", "MAX_ENTRIES", "MAX_KEYS", "rule_from_toml",
           "read_rule_file"]

#: Largest rule file read: a rule of 64 contact indices with 64 targets each is under 40 KiB.
MAX_FILE_BYTES = 64 * 1024
#: Deepest nesting: the file -> ``[weights]`` -> a contact index's table.
MAX_NESTING = 2
#: Most contact indices, and most targets of one index.
MAX_ENTRIES = 64
#: Most keys and table headers of a rule file, counted on the raw text before it is parsed:
#: the four top keys, ``[weights]`` and its indices with their targets.
MAX_KEYS = 8 + MAX_ENTRIES * (MAX_ENTRIES + 1)
_KEYS = ("name", "lumped", "description", "weights")
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9 ._+()-]{0,47}")
_INDEX = re.compile(r"\s*([+-]?)([0-9]{1,4})\s*")
_WHAT = "mass rule file"


def _resolve(index: int, n: int) -> int:
    return index + n if index < 0 else index


def _index(key, file: str, where: str) -> int:
    found = _INDEX.fullmatch(key) if isinstance(key, str) else None
    if found is None:
        raise InputError(f"mass rule {file}: {where}: index {printable(repr(key), 60)} is not an "
                         "integer of at most four digits")
    return int(found.group(1) + found.group(2))


def _indexed(table: Mapping, file: str, where: str) -> dict[int, object]:
    """``table`` with integer keys; two keys naming one index are refused."""
    if len(table) > MAX_ENTRIES:
        raise InputError(f"mass rule {file}: {where} has {len(table)} entries, more than the "
                         f"limit of {MAX_ENTRIES}")
    out, seen = {}, {}
    for key, value in table.items():
        i = _index(key, file, where)
        if i in seen:
            raise InputError(f"mass rule {file}: {where}: keys {printable(repr(seen[i]), 40)} and "
                             f"{printable(repr(key), 40)} both name index {i}")
        seen[i] = key
        out[i] = value
    return out


def _rule(data: dict, file: str) -> MassRule:
    unknown = sorted(set(data) - set(_KEYS))
    if unknown:
        raise InputError(f"mass rule {file}: unknown keys {printable(unknown, 120)} (allowed: "
                         f"{', '.join(_KEYS)})")
    name = data.get("name")
    if not isinstance(name, str) or not _NAME.fullmatch(name):
        raise InputError(f"mass rule {file}: name must be 1 to 48 letters, digits, spaces or "
                         f"'. _ + - ( )', got {printable(repr(name), 80)}")
    if name in RULES:
        raise InputError(f"mass rule {file}: name {name!r} is taken by a registered rule; "
                         "choose a new non-empty name")
    lumped = data.get("lumped", False)
    if not isinstance(lumped, bool):
        raise InputError(f"mass rule {file}: lumped must be true or false, got "
                         f"{printable(repr(lumped), 60)}")
    description = data.get("description", "redistribution weights from TOML")
    if not isinstance(description, str) or len(description) > 200 or \
            printable(description, 400) != description:
        raise InputError(f"mass rule {file}: description must be at most 200 printable "
                         f"characters, got {printable(repr(description), 80)}")
    raw = data.get("weights")
    if not isinstance(raw, Mapping) or not raw:
        raise InputError(f"mass rule {file}: [weights] must be a non-empty table")
    table = {}
    for c, ws in _indexed(raw, file, "weights").items():
        if not isinstance(ws, Mapping):
            raise InputError(f"mass rule {file}: weights of index {c} must be a table "
                             "{index = weight}")
        targets = _indexed(ws, file, f"weights of index {c}")
        if not targets:
            raise InputError(f"mass rule {file}: index {c} has no weights")
        for j, w in targets.items():
            if isinstance(w, bool) or not isinstance(w, (int, float)) or not math.isfinite(w):
                raise InputError(f"mass rule {file}: weight [{c}][{j}] must be a finite number, "
                                 f"got {printable(repr(w), 60)}")
            if not 0 <= w <= 1:
                raise InputError(f"mass rule {file}: weight [{c}][{j}] must lie in [0, 1], "
                                 f"got {w!r}")
            if j == c:
                raise InputError(f"mass rule {file}: index {c} sends mass to itself")
        if abs(math.fsum(targets.values()) - 1) > 1e-12:
            raise InputError(f"mass rule {file}: the weights of index {c} must sum to 1 "
                             f"(translational mass), got {math.fsum(targets.values())!r}")
        table[c] = targets

    def build(space: MassSpace):
        import numpy as np

        from dispersion.mass_rules.mass import redistribution_matrix

        n = space.n
        weights = {}
        for c, ws in table.items():
            cr = _resolve(c, n)
            if cr in weights:
                raise InputError(f"mass rule {file}: contact index {c} repeats another on "
                                 f"n = {n}")
            weights[cr] = {_resolve(j, n): w for j, w in ws.items()}
        try:  # what depends on n (indices in range, targets outside the contact set)
            R = redistribution_matrix(n, weights)
        except InputError as exc:
            raise InputError(f"mass rule {file}: on n = {n}: {exc}") from None
        if not space.exact:
            R = np.array(R.tolist(), dtype=float)
        return _build_singular(MassSpace(space.M, space.kv, space.elements, R), lump=lumped)

    return MassRule(name, build, MassProperties(diagonal=lumped, zero_rows=True),
                    "lumped" if lumped else "consistent", False, description)


def read_rule_file(path) -> MassRule:
    """The rule of the TOML file ``path`` (see the module doc for what is refused).

    >>> read_rule_file("rule.txt")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule file rule.txt: the name must end in .toml
    """
    text = read_text(path, _WHAT, MAX_FILE_BYTES, suffix=".toml")
    shown = printable(os.fspath(path))
    return _rule(load_toml(text, os.fspath(path), _WHAT, MAX_NESTING, MAX_FILE_BYTES,
                           max_keys=MAX_KEYS), f"file {shown}")


def rule_from_toml(source) -> MassRule:
    """A redistribution rule from TOML text, or from a file: a :class:`os.PathLike`, or a
    string of one line without ``=`` (a path: :func:`read_rule_file`). The weights go
    through :func:`dispersion.mass_rules.mass.redistribution_matrix` (sum one, in [0, 1]) on
    every space the rule is applied to."""
    if isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source
                                           and "=" not in source):
        return read_rule_file(source)
    if not isinstance(source, str):
        raise InputError(f"a mass rule is TOML text or a path, got {type(source).__name__}")
    if len(source) > MAX_FILE_BYTES:
        raise InputError(f"mass rule <string>: {len(source)} characters, more than the limit "
                         f"of {MAX_FILE_BYTES}")
    return _rule(load_toml(source, "<string>", "mass rule", MAX_NESTING, MAX_FILE_BYTES,
                           max_keys=MAX_KEYS), "<string>")
