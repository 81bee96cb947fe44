"""The model keys of a claims entry read into the one value a claim is about.

``model = "rayleigh-lamb"`` is the exact plate (:class:`~dispersion.claims.exact_model.ExactModel`);
``"bloch"`` or ``"x-exact"`` with the patch keys ``p``, ``n``, ``r``, ``mass``, ``contact``,
``gamma_s`` and ``weights`` is a :class:`dispersion.symbolic.patch.Patch`, the toolkit's one
patch value, its unset fields the defaults of :mod:`dispersion.defaults`; ``"bar"`` (explicit
dynamics claims only) is a :class:`~dispersion.claims.bar_model.BarModel`. The value is built
here, once, and passed down whole; a bad setting is refused naming its key and range.

>>> def fail(key, message):
...     raise ValueError(f"{key}: {message}")
>>> claim_model({"model": "bloch", "mass": "singular", "r": "1/2"}, {}, fail).label()
'bloch p=2 n=3 r=1/2, singular mass (top, gamma_s=1/2)'
>>> claim_model({}, {}, fail) == Patch()
True
>>> claim_model({"model": "bloch", "gamma_s": 2}, {}, fail)
Traceback (most recent call last):
...
ValueError: gamma_s: the toolkit cannot build this patch: gamma_s must lie in [0, 1], got 2
"""
from __future__ import annotations

import re
from dataclasses import fields
from typing import Union

from dispersion import defaults
from dispersion.claims.bar_model import BarModel
from dispersion.claims.exact_model import EXACT, ExactModel
from dispersion.claims.claim_fields import rational, shown
from dispersion.errors import InputError
from dispersion.symbolic.patch import Patch

__all__ = ["PATCH_KEYS", "ClaimModel", "claim_model", "check_patch"]

#: The keys of a claims entry that set the patch: the fields of :class:`Patch` but ``model``
#: (the entry's ``model`` key names the patch model or another model), ``nu`` (a claim's
#: ``nu`` is the number it substitutes into the series, not a setting of the patch) and
#: ``law`` (a claim is about an isotropic plate: its ``nu`` makes the patch's law).
PATCH_KEYS = tuple(f.name for f in fields(Patch) if f.name not in ("model", "nu", "law"))
#: What a claim is about.
ClaimModel = Union[Patch, BarModel, ExactModel]


def claim_model(entry: dict, own: dict, fail, bar: bool = False) -> ClaimModel:
    """The model of claims entry ``entry`` (``own``: the keys the entry itself gives, not
    inherited from ``[defaults]``); ``bar`` admits the periodic bar. ``fail(key, message)``
    raises the error naming the key."""
    name = entry.get("model", defaults.MODEL)
    if name == EXACT:  # patch keys inherited from [defaults] do not apply to it
        given = [k for k in PATCH_KEYS if k in own]
        if given:
            fail(given[0], f"not a setting of the exact model ({EXACT})")
        return ExactModel()
    if bar and name == BarModel.name:
        return _bar(entry, own, fail)
    if name not in defaults.PATCH_MODELS:
        fail("model", f"must be {EXACT!r} or a patch model ({', '.join(defaults.PATCH_MODELS)})"
                      + (f" or {BarModel.name!r}" if bar else "") + f", got {shown(name)}")
    kw = _integers(entry, fail)
    for key in ("mass", "contact"):
        if key in entry:
            kw[key] = entry[key]
    if "r" in entry:
        from dispersion.symbolic.power_balance import R_SYM

        kw["r"] = rational(entry["r"], "r", fail, symbol=R_SYM)
    if "gamma_s" in entry:
        kw["gamma_s"] = rational(entry["gamma_s"], "gamma_s", fail)
    if "weights" in entry:
        kw["weights"] = _weights(entry["weights"], fail)
    if name != "bloch" and "r" in entry:
        fail("r", f"the aspect ratio belongs to the bloch model, not {name!r}")
    try:
        patch = Patch(model=name, **kw)
        from dispersion.symbolic.power_balance import MAX_WORK

        if (2 * patch.n) ** 2 * 2 > MAX_WORK:  # the least work of any series claim
            raise InputError(f"control points n must satisfy (2n)^2 * order <= {MAX_WORK} "
                             f"(bounded time and memory), got n = {patch.n}")
    except InputError as exc:
        _failure(exc, entry, fail, PATCH_KEYS, "patch")
    return patch


def check_patch(model: ClaimModel, entry: dict, fail) -> None:
    """Build the patch's matrices once (after the work is known to be bounded): every setting
    checked, the weights against the control points included."""
    if not isinstance(model, Patch):
        return
    if model.weights is not None and model.singular:  # the weights' own rules, named as such
        from dispersion.mass_rules.mass import redistribution_matrix

        try:
            redistribution_matrix(model.n, model.weights_dict)
        except InputError as exc:
            fail("weights", f"the toolkit cannot build this patch: {exc}")
    from dispersion.symbolic.plate import plate_patch

    try:
        plate_patch(model)
    except InputError as exc:
        _failure(exc, entry, fail, PATCH_KEYS, "patch")


def _integers(entry: dict, fail) -> dict:
    """``p`` and ``n`` as given: TOML integers only (``2.0`` is refused)."""
    kw = {}
    for key in ("p", "n"):
        if key in entry:
            if type(entry[key]) is not int:
                fail(key, f"must be an integer, got {shown(entry[key])}")
            kw[key] = entry[key]
    return kw


def _bar(entry: dict, own: dict, fail) -> BarModel:
    keys = tuple(f.name for f in fields(BarModel))  # p and mass
    for key in PATCH_KEYS:
        if key in own and key not in keys:
            fail(key, f"not a setting of the periodic bar ({' and '.join(keys)} only)")
    kw = _integers({k: v for k, v in entry.items() if k != "n"}, fail)
    if "mass" in entry:
        kw["mass"] = entry["mass"]
    try:
        return BarModel(**kw)
    except InputError as exc:
        _failure(exc, entry, fail, keys, "bar")


def _failure(exc: InputError, entry: dict, fail, keys, what: str) -> None:
    """``fail`` on the key the toolkit's message names first: the subject (the words before
    "must"), else any key the message names (``n must be >= p + 1`` with only ``p`` given)."""
    text = str(exc).replace("(", " ")
    words = text.split(" must")[0].split() + text.split()
    key = next((w for w in words if w in keys and w in entry), "model")
    fail(key, f"the toolkit cannot build this {what}: {exc}")


def _weights(w, fail) -> tuple:
    """``{contact index: {neighbour index: weight}}`` as a sorted tuple of tuples."""
    if not isinstance(w, dict) or not w or len(w) > 64:
        fail("weights", "must be a table {contact index: {neighbour index: weight}} "
                        "(at most 64 contact indices)")
    out = []
    for c, ws in w.items():
        if not re.fullmatch(r"0|[1-9]\d{0,2}", c) or not isinstance(ws, dict) or not ws \
                or len(ws) > 64:
            fail("weights", f"must be a table {{contact index: {{neighbour index: weight}}}}, "
                            f"got key {shown(c)}")
        row = []
        for j, v in ws.items():
            if not re.fullmatch(r"0|[1-9]\d{0,2}", j):
                fail("weights", f"neighbour index must be a whole number < 1000, got {shown(j)}")
            row.append((int(j), rational(v, "weights", fail)))
        out.append((int(c), tuple(sorted(row))))
    return tuple(sorted(out))

