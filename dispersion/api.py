"""The front door: a plate patch with ``K``, ``M``, ``K_dyn``, its series and branches, and
the ring and bar problems, all with the toolkit's defaults (:mod:`dispersion.defaults`).

Everything here is re-exported by ``import dispersion`` (lazily: nothing heavy is imported
until used).

>>> import dispersion
>>> pt = dispersion.patch(mass="lumped")          # Bloch model, r = 2, p = 2, n = 3
>>> pt.K().shape, pt.M().is_diagonal()
((6, 6), True)
>>> dispersion.series("A0", 4, exact=True)[4]     # exact Rayleigh-Lamb, paper eq (15)
-2/(3*(nu - 1))

The matrices are those of the paper's eq (5) for one Bloch cell (or the x-exact strip),
scaled by the shear modulus and density:

.. math::

    \\mathbf K_{dyn}(\\kappa, \\Omega) = \\mathbf K(\\kappa) - \\Omega^2 \\mathbf M(\\kappa).

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact", eqs (1)-(5), (14)-(20).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from dispersion import defaults
from dispersion.errors import InputError, ParameterError

if TYPE_CHECKING:  # pragma: no cover
    import sympy

    from dispersion.patch_model import PatchModel
    from dispersion.symbolic.patch import Patch

__all__ = ["Patch", "PatchModel", "patch", "series", "exact_branches", "lamb_modes", "material",
           "simulate_ring", "simulate_bar", "branch_table", "mode_shapes", "series_table",
           "critical_steps", "figure", "layered_lamb_modes", "layup", "slowness_curves",
           "evanescent_modes"]


def _fits(name: str, target, args=(), kwargs=None) -> None:
    """Raise :class:`ParameterError` (an InputError and a TypeError) if ``name(*args,
    **kwargs)`` does not fit the signature of ``target``: the unknown keyword named with the
    accepted ones (and the nearest), never a bare TypeError from deep inside."""
    import inspect

    from dispersion.errors import did_you_mean

    kwargs = kwargs or {}
    sig = inspect.signature(target)
    try:
        sig.bind(*args, **kwargs)
    except TypeError as exc:
        accepted = [n for n, p in sig.parameters.items()
                    if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        unknown = [k for k in kwargs if k not in accepted]
        if unknown:
            raise ParameterError(f"{name}() got an unknown keyword {unknown[0]!r}; it accepts "
                                 f"{', '.join(accepted)}{did_you_mean(unknown[0], accepted)}"
                                 ) from None
        raise ParameterError(f"{name}(): {exc}; it accepts {', '.join(accepted)}") from None


def _front_door(func):
    """A function of the front door: a call that does not fit its own signature raises
    :class:`ParameterError` naming the keyword (:func:`_fits`), as a call that does not fit
    what it forwards to does."""
    import functools

    @functools.wraps(func)
    def call(*args, **kwargs):
        _fits(func.__name__, func, args, kwargs)
        return func(*args, **kwargs)
    return call


@_front_door
def patch(*args, **fields) -> PatchModel:
    """The patch to compute with (:class:`~dispersion.patch_model.PatchModel`): its
    :class:`~dispersion.symbolic.patch.Patch` value ``.spec`` of ``fields`` (p, n, model, r,
    mass, contact, gamma_s, weights, nu, law: documented there, with their defaults and limits),
    checked at once (bad parameters raise :class:`InputError` here), with its matrices, series
    and branches. ``r="r"`` keeps the aspect ratio symbolic; ``law`` gives the plate another
    material (:mod:`dispersion.materials.elastic_law`).

    >>> from dispersion.symbolic.patch import Patch
    >>> pt = patch(mass="singular", gamma_s=0)
    >>> pt.plate.massless, pt.spec == Patch(mass="singular", gamma_s=0)
    ((2, 5), True)
    >>> from dispersion.materials.elastic_law import Orthotropic
    >>> patch(law=Orthotropic(3, 2, 1, 1)).series("S0", 2)     # (C11 - C12^2/C22)/C66
    {2: 5/2}
    """
    from dispersion.patch_model import PatchModel
    from dispersion.symbolic.patch import Patch

    _fits("patch", Patch, args, fields)
    return PatchModel(Patch(*args, **fields))


@_front_door
def series(branch: str = "S0", order: int = 8, *, exact: bool = False, nu=None,
           **patch_kwargs) -> dict[int, sympy.Expr]:
    """Series of the S0/A0 branch: exact Rayleigh-Lamb (``exact=True``, eqs 14-15) or of
    the discrete patch ``patch(**patch_kwargs)`` (eqs 17-20).

    >>> series("S0", 4, exact=True)[2]
    -2/(nu - 1)
    """
    if exact:
        if patch_kwargs:
            raise InputError(f"patch parameters {sorted(patch_kwargs)} do not apply with "
                             "exact=True (the exact Rayleigh-Lamb series)")
        from dispersion.continuum.exact_series import exact_series

        return exact_series(branch, order, nu=nu)
    return patch(**patch_kwargs).series(branch, order, nu)


@_front_door
def exact_branches(kappa, nu=defaults.NU_FLOAT, omega_max: float = 8.0, **kwargs):
    """Exact Rayleigh-Lamb branches with :math:`\\Omega \\le` ``omega_max`` on ``kappa``
    (:func:`dispersion.continuum.exact_branches.trace_branches`); ``nu`` may be an isotropic
    :class:`~dispersion.materials.elastic_law.ElasticLaw` (other laws have no closed form:
    refused)."""
    from dispersion.continuum.exact_branches import trace_branches

    _fits("exact_branches", trace_branches, (nu, kappa, omega_max), kwargs)
    if hasattr(nu, "poisson_ratio"):  # an ElasticLaw
        nu = nu.poisson_ratio("exact Rayleigh-Lamb branches")
    return trace_branches(nu, kappa, omega_max, **kwargs)


@_front_door
def material(name: str):
    """A material of the table (:data:`dispersion.materials.materials.MATERIALS`, with sources);
    user materials: :func:`dispersion.materials.materials.user_material`."""
    from dispersion.materials.materials import material as _material

    return _material(name)


@_front_door
def lamb_modes(material, thickness_mm: float, *, frequency_khz=None, fd_mhz_mm=None, **kwargs):
    """Every propagating S, A and SH mode of the plate at the given frequencies (kHz) or
    frequency-thickness products (MHz mm), in physical units
    (:func:`dispersion.answers.mode_table.lamb_modes`; ``material`` may be a table name).

    >>> t = lamb_modes("steel", 3.0, frequency_khz=200)
    >>> [(r["mode"], round(r["c_p [m/s]"]), round(r["c_g [m/s]"])) for r in t.rows()]
    [('S0', 5415, 5374), ('A0', 2023, 3059), ('SH0', 3235, 3235)]
    """
    from dispersion.answers.mode_table import lamb_modes as _lamb_modes

    _fits("lamb_modes", _lamb_modes, (material, thickness_mm), kwargs)
    if isinstance(material, str):
        material = globals()["material"](material)
    return _lamb_modes(material, thickness_mm, frequency_khz=frequency_khz,
                       fd_mhz_mm=fd_mhz_mm, **kwargs)


@_front_door
def branch_table(**request):
    """``dispersion branches`` as a function: exact and discrete branches on a kappa grid, in
    units with a material, bounded as the command bounds them
    (:func:`dispersion.answers.branch_table.branch_table`; a
    :class:`~dispersion.answers.branch_table.BranchTable` that renders itself).

    >>> t = branch_table(exact=True, count=3, kappa_max=1.0, omega_max=2.0)
    >>> t.title()
    'Rayleigh-Lamb branches, nu = 0.3, 3 kappa in [0, 1], Omega <= 2'
    """
    from dispersion.answers.branch_table import branch_table as _branch_table

    _fits("branch_table", _branch_table, (), request)
    return _branch_table(**request)


@_front_door
def mode_shapes(table, mode: str, points: int = 41):
    """Displacements and stresses through the thickness of ``mode`` of a one-frequency
    :func:`lamb_modes` table (:func:`dispersion.answers.mode_shape_table.mode_shapes`)."""
    from dispersion.answers.mode_shape_table import mode_shapes as _mode_shapes

    return _mode_shapes(table, mode, points)


@_front_door
def series_table(branches=("S0", "A0"), order: int = 8, **request):
    """``dispersion series`` as a function (:func:`dispersion.answers.series_table.series_table`:
    a :class:`~dispersion.answers.series_table.SeriesTable` that prints itself)."""
    from dispersion.answers.series_table import series_table as _series_table

    _fits("series_table", _series_table, (branches, order), request)
    return _series_table(branches, order, **request)


@_front_door
def critical_steps(masses=None, p: int = 2, **request):
    """``dispersion timestep`` as a function (:func:`dispersion.answers.critical_steps.critical_steps`)."""
    from dispersion.answers.critical_steps import critical_steps as _critical_steps

    _fits("critical_steps", _critical_steps, (masses, p), request)
    return _critical_steps(masses, p, **request)


@_front_door
def figure(result):
    """The figure of a result (the ``plots`` extra), drawn from the result alone, as the
    command's ``--figure`` draws it: a :class:`~dispersion.answers.branch_table.BranchTable`,
    a :func:`lamb_modes` table, its :func:`mode_shapes`, a ring or a Signorini run.

    >>> fig = figure(lamb_modes("steel", 3.0, frequency_khz=[100, 200, 300]))
    >>> fig.get_suptitle()
    'steel, d = 3 mm, nu = 0.2912'
    """
    from dispersion import plotting

    plotting.require_matplotlib("figure()")
    kind = type(result).__name__
    if kind == "BranchTable":
        from dispersion.plotting.branches import figure_branch_table as draw
    elif kind == "ModeTable":
        from dispersion.plotting.lamb import figure_mode_table as draw
    elif kind == "ModeShapeTable":
        from dispersion.plotting.lamb import figure_mode_shapes as draw
    elif kind == "SignoriniResult":
        from dispersion.plotting.ring import plot_impact as draw
    elif kind == "RingResult":
        from dispersion.plotting.ring import plot_contact_energy

        return plot_contact_energy(result.record())
    else:
        raise InputError(f"figure() draws a BranchTable, ModeTable, ModeShapeTable, RingResult "
                         f"or SignoriniResult, got {kind}")
    return draw(result)


@_front_door
def simulate_ring(mass: str = "singular", scheme: str = "kane", scenario=None, **changes):
    """The ring benchmark (Figure 4): :func:`dispersion.contact.simulate.simulate_ring` on
    ``scenario`` (default: the reconstructed :class:`~dispersion.contact.scenario.Scenario`)
    with fields replaced by ``changes`` (e.g. ``t_end=2.0``)."""
    from dataclasses import fields, replace

    from dispersion.contact.simulate import Scenario
    from dispersion.contact.simulate import simulate_ring as _simulate

    sc = scenario if scenario is not None else Scenario()
    unknown = sorted(set(changes) - {f.name for f in fields(sc)})
    if unknown:
        raise ParameterError(f"simulate_ring() got unknown scenario fields {unknown}; valid: "
                             f"{', '.join(f.name for f in fields(sc))}")
    return _simulate(replace(sc, **changes), mass, scheme)


@_front_door
def simulate_bar(n_elements: int = 40, p: int = defaults.P, mass: str = "lumped", **kwargs):
    """The 1-D bar impact (:func:`dispersion.contact.bar.simulate_bar`)."""
    from dispersion.contact.bar import simulate_bar as _simulate

    _fits("simulate_bar", _simulate, (n_elements, p, mass), kwargs)
    return _simulate(n_elements, p, mass, **kwargs)


def __getattr__(name: str):
    # the patch value and its model load sympy (the exact defaults): only when asked for, so
    # that ``dispersion.lamb_modes`` and the other numeric doors do not pay for it
    if name == "Patch":
        from dispersion.symbolic.patch import Patch

        return Patch
    if name == "PatchModel":
        from dispersion.patch_model import PatchModel

        return PatchModel
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def layup(text, *, ply=None, ply_thickness_mm=None, direction: float = 0.0,
          damping: float = 0.0):
    """A layered plate (:class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`) from a TOML
    layup file (a path ending in ``.toml``, read as untrusted data), from layers
    ``material:thickness_mm[:angle],...`` bottom up, or from a layup such as ``[0/90]s`` with
    a ``ply`` and its thickness (:mod:`dispersion.continuum.layered.layup_file`); ``damping`` a loss
    factor given to every layer.

    >>> [l.angle for l in layup("[0/90]s", ply="T800/913", ply_thickness_mm=0.125).layers]
    [0.0, 90.0, 0.0]
    """
    from dispersion.continuum.layered.layup_file import plate_from_string, read_layup

    if str(text).strip().lower().endswith(".toml"):
        if ply is not None or ply_thickness_mm is not None:
            raise InputError("ply and ply_thickness_mm go with a layup string such as [0/90]s, "
                             "not with a layup file")
        plate = read_layup(text)
        if damping:
            from dispersion.continuum.layered.layered_plate import Layer, LayeredPlate

            plate = LayeredPlate(tuple(Layer(layer.solid.with_loss(damping), layer.thickness_mm,
                                             layer.angle) for layer in plate.layers),
                                 plate.interfaces, plate.direction)
        return plate if not direction else plate.turned(direction)
    return plate_from_string(text, ply=ply, ply_thickness_mm=ply_thickness_mm,
                             direction=direction, damping=damping)


def layered_lamb_modes(plate, *, frequency_khz=None, fd_mhz_mm=None, families=None,
                       zgv: bool = False):
    """Every propagating mode of a layered or anisotropic plate at the given frequencies,
    each root certified, with their skew angles and, with ``zgv``, the zero-group-velocity
    points (:func:`dispersion.answers.layered_mode_table.layered_lamb_modes`; ``plate`` may
    be a layup text as :func:`layup` reads it).

    >>> t = layered_lamb_modes("steel:0.71,aluminium:0.29", frequency_khz=500)
    >>> [r["mode"] for r in t.rows()]
    ['L0', 'SH0', 'L1']
    """
    from dispersion.answers.layered_mode_table import layered_lamb_modes as _modes

    if isinstance(plate, str):
        plate = layup(plate)
    return _modes(plate, frequency_khz=frequency_khz, fd_mhz_mm=fd_mhz_mm, families=families,
                  zgv=zgv)


def evanescent_modes(plate, *, thickness_mm=None, frequency_khz=None, fd_mhz_mm=None,
                     families=None, decay_db: float = 60.0):
    """Every evanescent mode (imaginary and complex wavenumbers, Im k > 0) of an undamped
    plate at the given frequencies with a decay of at most ``decay_db`` dB per plate
    thickness (in (0, 200]), each root certified and their number counted
    (:func:`dispersion.answers.evanescent_mode_table.evanescent_lamb_modes`). ``plate``: a
    :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`, a layup text as
    :func:`layup` reads it (``"steel:3"`` is a 3 mm steel plate), or an isotropic material
    (a table name or a :class:`~dispersion.materials.materials.Material` with a density)
    with ``thickness_mm``.

    >>> t = evanescent_modes("steel:1", frequency_khz=1000, decay_db=20, families=("A",))
    >>> [r["mode"] for r in t.rows()]
    ['A-e1']
    """
    from dispersion.answers.evanescent_mode_table import evanescent_lamb_modes
    from dispersion.continuum.layered.layered_plate import LayeredPlate, layered_plate

    if thickness_mm is not None:
        if isinstance(plate, LayeredPlate):
            raise InputError("thickness_mm goes with a material, not with a layered plate")
        mat = globals()["material"](plate) if isinstance(plate, str) else plate
        if getattr(mat, "rho", 1.0) is None:
            raise InputError("--evanescent with --cl/--ct needs --rho (density in kg/m^3: the "
                             "evanescent solver takes the plate as one layer of a stack)")
        plate = layered_plate([(mat, thickness_mm)])
    elif isinstance(plate, str):
        plate = layup(plate)
    return evanescent_lamb_modes(plate, frequency_khz=frequency_khz, fd_mhz_mm=fd_mhz_mm,
                                 families=families, decay_db=decay_db)


def slowness_curves(plate, frequency_khz: float, angles, *, families=None):
    """Every mode of an undamped layered or anisotropic plate at one frequency for waves
    along each of ``angles`` (degrees): slowness, group velocity, skew angle and energy
    velocity (:func:`dispersion.answers.slowness_table.slowness_curves`; ``plate`` may be a
    layup text as :func:`layup` reads it).

    >>> t = slowness_curves("steel:0.71,aluminium:0.29", 500, [0, 90])
    >>> len(t.rows())
    6
    """
    from dispersion.answers.slowness_table import slowness_curves as _curves

    if isinstance(plate, str):
        plate = layup(plate)
    return _curves(plate, frequency_khz, angles, families=families)
