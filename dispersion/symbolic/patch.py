"""The plate patch as one value: model, r, p, n, mass, contact, gamma_s, weights and its
material (the elastic law, :mod:`dispersion.materials.elastic_law`; ``nu`` names the isotropic one).

Every entry point (the API, the command line, a claims file, a report section) builds one
:class:`Patch` at its boundary and passes it down whole; the defaults are those of
:mod:`dispersion.defaults`, stated once, and the rules of each field (the size limits of
:func:`check_size`, the range of the aspect ratio) are stated here, once. Results carry the ``Patch`` they were computed
on, and every caption, title and CSV header is rendered from it (:meth:`Patch.label`,
:meth:`Patch.title`, :meth:`Patch.header_lines`).

>>> Patch()
Patch(p=2, n=3, model='bloch', r=2, mass='consistent', contact='top', gamma_s=1/2, weights=None, nu=None)
>>> Patch(mass="singular", gamma_s=0).label()
'bloch p=2 n=3 r=2, singular mass (top, gamma_s=0)'
>>> Patch(model="x-exact").r is None
True
>>> Patch(nu=0.3).law
Isotropic(nu=3/10)

A ``Patch`` is a value: it computes nothing. Its matrices, series and branches come from the
functions that take it (:func:`dispersion.symbolic.plate.plate_patch`,
:func:`dispersion.symbolic.power_balance.discrete_series`,
:func:`dispersion.discretization.discrete_branches.discrete_branches`), or, at the front door, from
:class:`dispersion.patch_model.PatchModel` (what ``dispersion.patch()`` returns).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING, Any

from dispersion import defaults
from dispersion.errors import InputError, check_positive_int
from dispersion.reader import rational

if TYPE_CHECKING:  # pragma: no cover
    import sympy

__all__ = ["Patch", "as_patch", "check_size", "rational", "aspect_ratio", "PATCH_FIELDS"]


def check_size(p, n) -> tuple[int, int]:
    """Return ``(p, n)`` as ints if ``1 <= p <= P_MAX`` and ``p + 1 <= n <= N_MAX``
    (:data:`dispersion.defaults.P_MAX`, :data:`dispersion.defaults.N_MAX`).

    The degree is checked first, so ``p = 100, n = 101`` names the degree.

    >>> check_size(2, 3)
    (2, 3)
    >>> check_size(60, 61)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: degree p must be an integer in [1, 24], got 60
    """
    p = check_positive_int("degree p", p, maximum=defaults.P_MAX)
    n = check_positive_int("control points n", n, maximum=defaults.N_MAX)
    if n < p + 1:
        raise InputError(f"control points n must be >= p + 1 = {p + 1}, got {n}")
    return p, n


def aspect_ratio(r) -> sympy.Rational:
    """The Bloch aspect ratio r = b/h, exact, within :data:`dispersion.defaults.R_RANGE`."""
    import sympy

    r = rational("aspect ratio r", r)
    lo, hi = (sympy.Rational(x.numerator, x.denominator) for x in defaults.R_RANGE)
    if not lo <= r <= hi:
        shown = str(r) if len(str(r)) <= 20 else str(sympy.Float(r, 3))
        raise InputError(f"aspect ratio r must lie in [{lo}, {hi}], got {shown}")
    return r


def _weight(w):
    """A redistribution weight: a finite number as given, text by the whitelist (never
    evaluated)."""
    from dispersion.errors import as_real

    return rational("weight", w) if isinstance(w, str) else as_real("weight", w)


def _index(i) -> int:
    """A contact or neighbour index: an int, or an integer written in decimal (JSON keys)."""
    if isinstance(i, bool) or not isinstance(i, (int, str)) or (
            isinstance(i, str) and not i.strip().lstrip("+-").isdigit()) or len(str(i)) > 6:
        raise TypeError
    return int(i)


def _freeze_weights(weights):
    """``{contact: {neighbour: weight}}`` -> a hashable, sorted tuple form (or None)."""
    if weights is None:
        return None
    if isinstance(weights, tuple):
        return weights
    try:
        return tuple(sorted((_index(c), tuple(sorted((_index(j), _weight(w))
                                                     for j, w in dict(ws).items())))
                            for c, ws in dict(weights).items()))
    except (TypeError, ValueError, AttributeError):
        shown = repr(weights)
        raise InputError("weights must map contact indices to {neighbour index: weight}, "
                         f"got {shown if len(shown) <= 80 else shown[:77] + '...'}") from None


@dataclass(frozen=True)
class Patch:
    """A plate patch of B-splines through the thickness with one mass variant.

    Parameters
    ----------
    p, n : int
        Degree and number of control points through the thickness (limits:
        :func:`check_size`).
    model : str
        ``"bloch"`` (one Bloch-periodic column, aspect ratio ``r = b/h``) or ``"x-exact"``.
    r : number, ``"r"`` or None
        Aspect ratio b/h of the Bloch model (``"r"``: kept as a symbol); None for x-exact.
    mass : str or MassRule
        A rule of :mod:`dispersion.mass_rules.mass_rule` (name or a user rule object).
        ``"consistent"``, ``"lumped"``, ``"singular"`` or ``"singular-lumped"``.
    contact, gamma_s :
        Contact set and redistribution weight of the singular masses (ignored otherwise).
    weights : mapping, optional
        General redistribution weights ``{c: {j: w}}``; override ``contact``/``gamma_s``.
    nu : number or None
        Poisson's ratio of an isotropic plate (exact; floats by their shortest decimal): None
        keeps it symbolic in the series, and numbers use :data:`dispersion.defaults.NU` (see
        :attr:`nu_value`). Shorthand for ``law=Isotropic(nu)``; None for other laws.
    law : ElasticLaw, optional
        The plate's material (:mod:`dispersion.materials.elastic_law`), carried to every
        computation on the patch. Default: :class:`~dispersion.materials.elastic_law.Isotropic`
        of ``nu``. Give ``nu`` or ``law``, not both.
    """

    p: int = defaults.P
    n: int = defaults.N
    model: str = defaults.MODEL
    r: Any = defaults.R
    mass: str = defaults.MASS
    contact: str = defaults.CONTACT
    gamma_s: Any = defaults.GAMMA_S
    weights: Any = field(default=None, hash=False)
    nu: Any = None
    law: Any = field(default=None, repr=False)

    def __post_init__(self):
        import sympy

        from dispersion.mass_rules.mass_rule import get_rule

        p, n = check_size(self.p, self.n)
        if self.model not in defaults.PATCH_MODELS:
            raise InputError(f"model must be one of {', '.join(defaults.PATCH_MODELS)}; "
                             f"got {self.model!r}")
        rule = get_rule(self.mass)  # a registered name or a MassRule, else InputError
        if rule.basis == "lagrange":  # C0 elements: p DOFs a cell along x, n = p e + 1
            from dispersion.splines.lagrange_sem import c0_elements

            if self.model == "bloch":
                raise InputError(f"mass {rule.name!r} uses C0 Lagrange elements, which carry "
                                 "p DOFs a cell along x; the Bloch patch has one B-spline "
                                 "symbol there", ways=[("model", "x-exact")])
            c0_elements(p, n)
        r = self.r
        if self.model == "x-exact":
            if r is not None and r != defaults.R:
                raise InputError(f"r applies to the Bloch model only; model x-exact got r={r!r}")
            r = None
        elif r is None or r == "r" or isinstance(r, sympy.Symbol):
            r = sympy.Symbol("r", positive=True)
        else:
            r = aspect_ratio(r)
        gamma_s = None if self.gamma_s is None else rational("gamma_s", self.gamma_s)
        weights = _freeze_weights(self.weights)
        if gamma_s is not None:
            from dispersion.errors import check_real_in_range

            check_real_in_range("gamma_s", gamma_s, 0, 1)
        if self.contact not in defaults.CONTACT_SETS:
            raise InputError(f"contact must be one of {', '.join(defaults.CONTACT_SETS)}; "
                             f"got {self.contact!r}")
        if (self.contact == "both" and n < 4 and weights is None and gamma_s != 0
                and get_rule(self.mass).redistributes):
            # each surface sends gamma_s to its second neighbour inward (paper eqs 2-3): with
            # three points that is the other surface, itself in contact
            raise InputError(f"contact 'both' needs n >= 4 control points or gamma_s = 0 (with "
                             f"n = {n} each surface's second neighbour is the other surface); "
                             f"got n = {n}, gamma_s = {gamma_s}")
        nu, law = _material(self.nu, self.law)
        for name, value in (("p", p), ("n", n), ("r", r), ("gamma_s", gamma_s), ("nu", nu),
                            ("weights", weights), ("law", law)):
            object.__setattr__(self, name, value)

    def __repr__(self) -> str:
        shown = [f"{f.name}={getattr(self, f.name)!r}" for f in fields(self) if f.repr]
        if not self.isotropic:  # nu says all of an isotropic law
            shown.append(f"law={self.law!r}")
        return f"Patch({', '.join(shown)})"

    # ------------------------------------------------------------------ derived values

    @property
    def singular(self) -> bool:
        """True for the singular masses (contact set and weights apply)."""
        from dispersion.mass_rules.mass_rule import get_rule

        return get_rule(self.mass).redistributes

    @property
    def basis(self) -> str:
        """The discrete space through the thickness: ``"bspline"`` or ``"lagrange"`` (C0
        elements, set by the rule, :attr:`dispersion.mass_rules.mass_rule.MassRule.basis`)."""
        from dispersion.mass_rules.mass_rule import get_rule

        return get_rule(self.mass).basis

    @property
    def mass_name(self) -> str:
        """The mass rule's name (``mass`` may be a rule object)."""
        return getattr(self.mass, "name", self.mass)

    @property
    def symbolic_r(self) -> bool:
        """True if the aspect ratio is kept as the symbol r."""
        return self.r is not None and not getattr(self.r, "is_number", True)

    @property
    def isotropic(self) -> bool:
        """True if the plate is isotropic (its law is Poisson's ratio ``nu`` alone)."""
        from dispersion.materials.elastic_law import Isotropic

        return isinstance(self.law, Isotropic)

    @property
    def nu_value(self):
        """Poisson's ratio for numbers: ``nu``, or the default :data:`dispersion.defaults.NU`
        (isotropic plates; :class:`InputError` for other laws)."""
        if not self.isotropic:
            raise InputError(f"nu applies to an isotropic plate; this one is "
                             f"{self.law.describe()}")
        return defaults.NU if self.nu is None else self.nu

    @property
    def weights_dict(self) -> dict | None:
        """``weights`` as ``{contact: {neighbour: weight}}`` (None if not given)."""
        return None if self.weights is None else {c: dict(ws) for c, ws in self.weights}

    def replace(self, **changes) -> Patch:
        """A copy with ``changes`` (checked like a new patch); a new ``nu`` or ``law``
        replaces the material (the two name one law).

        >>> Patch(nu=0.3).replace(nu=None).law
        Isotropic(nu=None)
        """
        if "nu" in changes and "law" not in changes:
            if not self.isotropic:
                raise InputError(f"nu applies to an isotropic plate; this one is "
                                 f"{self.law.describe()} (give law= to change the material)")
            changes["law"] = None
        elif "law" in changes and "nu" not in changes:
            changes["nu"] = None
        return replace(self, **changes)

    def as_dict(self) -> dict:
        """JSON-ready fields (numbers as strings where exact); ``law`` only where the plate
        is not isotropic (``nu`` says all of an isotropic law)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "law"}
        out["mass"] = self.mass_name
        for key in ("r", "gamma_s", "nu"):
            out[key] = None if out[key] is None else str(out[key])
        out["weights"] = self.weights_dict and {str(c): {str(j): str(w) for j, w in ws.items()}
                                                for c, ws in self.weights_dict.items()}
        if not self.isotropic:
            out["law"] = self.law.as_dict()
        return out

    @classmethod
    def from_dict(cls, data: dict) -> Patch:
        """Inverse of :meth:`as_dict`.

        Stored data (a report folder's JSON) is read as data: its numbers by the whitelist
        (:func:`dispersion.reader.rational`), anything else refused with an
        :class:`InputError`.

        >>> p = Patch(mass="singular", r="1/2"); Patch.from_dict(p.as_dict()) == p
        True
        >>> Patch.from_dict({"r": "__import__('os').system('touch pwned') or 2"})
        Traceback (most recent call last):
        ...
        dispersion.errors.InputError: aspect ratio r must be a finite rational number, got "__import__('os').system('touch pwned') or 2" (unexpected character "'" at position 12)
        """
        if not isinstance(data, dict):
            raise InputError(f"a stored patch must be a mapping, got {type(data).__name__}")
        names = {f.name for f in fields(cls)}
        unknown = sorted(str(k)[:40] for k in data if k not in names)
        if unknown:
            raise InputError(f"a stored patch has unknown fields {', '.join(map(repr, unknown))}"
                             f" (fields: {', '.join(sorted(names))})")
        data = dict(data)
        if isinstance(data.get("law"), dict):
            from dispersion.materials.elastic_law import ElasticLaw

            data["law"] = ElasticLaw.from_dict(data["law"])
        return cls(**data)

    # ------------------------------------------------------------------ labels

    def label(self) -> str:
        """Short description, e.g. ``bloch p=2 n=3 r=2, singular mass (top, gamma_s=0)``."""
        geom = f"{self.model} p={self.p} n={self.n}" + (f" r={self.r}" if self.r is not None
                                                         else "")
        mass = f"{self.mass_name} mass"
        if self.singular:
            mass += (f" (weights {self.weights_dict})" if self.weights is not None
                     else f" ({self.contact}, gamma_s={self.gamma_s})")
        if self.law.label() is not None:
            mass += f", {self.law.label()}"
        return f"{geom}, {mass}"

    def title(self) -> str:
        """Figure title: every field that applies, in words.

        >>> Patch(mass="singular", r="1/2").title()
        'Bloch r = b/h = 1/2, p = 2, n = 3, singular mass (contact top, gamma_s = 1/2)'
        """
        text = f"{self.geometry_title()}, {self.mass_title()}"
        if self.law.title() is not None:
            text += f", {self.law.title()}"
        return text

    def geometry_title(self) -> str:
        """The patch without its mass: ``Bloch r = b/h = 2, p = 2, n = 3``."""
        geom = ("Bloch r = b/h = " + str(self.r) if self.model == "bloch" else "x-exact")
        return f"{geom}, p = {self.p}, n = {self.n}"

    def mass_title(self) -> str:
        """The mass with what applies to it: ``singular mass (contact top, gamma_s = 1/2)``."""
        text = f"{self.mass_name} mass"
        if self.singular:
            text += (f" (weights {self.weights_dict})" if self.weights is not None
                     else f" (contact {self.contact}, gamma_s = {self.gamma_s})")
        return text

    def header_lines(self) -> list[str]:
        """``key = value`` lines of the fields that apply (for CSV ``#`` headers)."""
        out = [f"model = {self.model}"] + ([f"r = {self.r}"] if self.r is not None else [])
        out += [f"p = {self.p}", f"n = {self.n}", f"mass = {self.mass_name}"]
        if self.singular:
            out += ([f"weights = {self.weights_dict}"] if self.weights is not None
                    else [f"contact = {self.contact}", f"gamma_s = {self.gamma_s}"])
        return out + self.law.header_lines()


def _material(nu, law):
    """``(nu, law)`` of a patch: one law, and nu its Poisson's ratio where it is isotropic."""
    from dispersion.materials.elastic_law import ElasticLaw, Isotropic

    if law is not None and not isinstance(law, ElasticLaw):
        raise InputError(f"law must be an ElasticLaw (dispersion.materials.elastic_law), got "
                         f"{type(law).__name__}")
    if nu is not None:
        from dispersion.errors import check_nu

        nu = check_nu(rational("nu", nu))
        if law is not None and law != Isotropic(nu):
            raise InputError(f"give nu or law, not both (nu = {nu}, law {law.describe()})")
        return nu, Isotropic(nu)
    if law is None:
        return None, Isotropic()
    if isinstance(law, Isotropic):  # exact, as nu given alone (a symbol: None, the patch's)
        return _material(law.nu, None)
    return None, law


def as_patch(patch: Patch | None = None, **fields) -> Patch:
    """``patch`` with ``fields`` replaced, or a new :class:`Patch` of ``fields``.

    The one way functions that take a patch accept it: a ``Patch`` value, keywords, or both.

    >>> as_patch(mass="lumped") == Patch(mass="lumped")
    True
    """
    if patch is None:
        return Patch(**fields)
    if not isinstance(patch, Patch):
        raise InputError(f"patch must be a dispersion.symbolic.patch.Patch, got {type(patch).__name__}")
    return patch.replace(**fields) if fields else patch


#: The fields of :class:`Patch` in their positional order (``Patch(2, 3, "bloch", ...)``).
PATCH_FIELDS = tuple(f.name for f in fields(Patch))
