"""The patch to compute with: a :class:`~dispersion.symbolic.patch.Patch` value and what the
toolkit derives from it (matrices, series, branches), as ``dispersion.patch()`` returns it.

The ``Patch`` is a value at the bottom of the package: it states its fields and their rules and
computes nothing, so the modules that compute take it without importing back up. This front-door
object sits above them and hands each request to the function that owns it:

* :meth:`PatchModel.K_dyn`, :meth:`~PatchModel.K`, :meth:`~PatchModel.M`: the matrices of
  :mod:`dispersion.symbolic.plate` (paper eq (5));
* :meth:`PatchModel.series`: :func:`dispersion.symbolic.power_balance.discrete_series`
  (eqs 17-20);
* :meth:`PatchModel.branches`: :func:`dispersion.discretization.discrete_branches.discrete_branches`.

The patch's own fields and labels read through (``pt.mass``, ``pt.label()``).

>>> pt = PatchModel(Patch(mass="singular", gamma_s=0))
>>> pt.K_dyn().shape, pt.mass, pt.plate.massless
((6, 6), 'singular', (2, 5))
>>> pt.spec == Patch(mass="singular", gamma_s=0)
True
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

from dispersion.errors import InputError
from dispersion.symbolic.patch import Patch

if TYPE_CHECKING:  # pragma: no cover
    import sympy

    from dispersion.symbolic.plate import PlatePatch

__all__ = ["PatchModel"]


@dataclass(frozen=True)
class PatchModel:
    """``spec`` (the :class:`Patch` value) with its matrices, series and branches."""

    spec: Patch

    def __getattr__(self, name: str):
        # only called for names the model itself lacks: the patch's fields and labels
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.spec, name)

    @cached_property
    def plate(self) -> PlatePatch:
        """The exact :class:`dispersion.symbolic.plate.PlatePatch` (built on first use)."""
        from dispersion.symbolic.plate import plate_patch

        return plate_patch(self.spec)

    def K_dyn(self, kappa=None, Omega=None, nu=None) -> sympy.Matrix:
        """:math:`K - \\Omega^2 M` (sympy); symbols ``kappa``, ``Omega``, ``nu`` by default.

        The moduli are those of the patch's elastic law; ``nu`` (an isotropic plate) replaces
        its Poisson's ratio here. Each value is a finite real number or a sympy expression with
        symbols; anything else (NaN, infinity, a string, a complex number) is an
        :class:`~dispersion.errors.InputError`.

        >>> PatchModel(Patch()).K_dyn(kappa=float("nan"))
        Traceback (most recent call last):
        ...
        dispersion.errors.InputError: kappa must be a finite real number or a sympy symbol, got nan
        """
        from dispersion.symbolic.plate import dynamic_stiffness

        return dynamic_stiffness(self.plate, _matrix_value("kappa", kappa),
                                 _matrix_value("Omega", Omega), _matrix_value("nu", nu))

    def _check_isotropic(self, name: str) -> None:
        if not self.spec.isotropic:
            raise InputError(f"{name} applies to an isotropic plate; this one is "
                             f"{self.spec.law.describe()}")

    def K(self, kappa=None, nu=None) -> sympy.Matrix:
        """Stiffness :math:`K(\\kappa)` over the shear modulus (sympy)."""
        return self.K_dyn(kappa, 0, nu)

    def M(self, kappa=None) -> sympy.Matrix:
        """Mass :math:`M(\\kappa)` over the density (sympy): the variant of ``mass``.

        Every variant keeps the translational mass (the sum of all entries):

        >>> x = Patch(model="x-exact")
        >>> sum(PatchModel(x.replace(mass="singular")).M()) == sum(PatchModel(x).M())
        True
        """
        import sympy

        from dispersion.errors import check_finite
        from dispersion.symbolic.plate import mass_block, x_functions

        if kappa is None:
            kappa = sympy.Symbol("kappa")
        else:
            check_finite("kappa", kappa)
            from dispersion.reader import as_sympy

            kappa = as_sympy("kappa", kappa)  # a number: never text
        return x_functions(self.plate, kappa)["mx"] * mass_block(self.plate)

    def series(self, branch: str = "S0", order: int = 8, nu=None) -> dict[int, sympy.Expr]:
        """Taylor coefficients of :math:`\\Omega^2` in :math:`\\kappa` (eqs 17-20), in the
        symbols of the patch's law (nu symbolic unless the patch or ``nu`` gives a number)."""
        from dispersion.symbolic.power_balance import discrete_series

        return discrete_series(branch, order, self._with_nu(nu))

    def _with_nu(self, nu) -> Patch:
        """The spec, its Poisson's ratio replaced by ``nu`` if given (isotropic plates)."""
        if nu is None:
            return self.spec
        self._check_isotropic("nu")
        return self.spec.replace(nu=nu)

    def branches(self, kappa, nu=None, group: bool = False):
        """All discrete branches on the grid ``kappa``
        (:func:`dispersion.discretization.discrete_branches.discrete_branches`) of the patch and its
        law (``nu`` replaces an isotropic plate's Poisson's ratio; a symbolic one takes the
        default :data:`dispersion.defaults.NU`; other laws are taken as they are);
        ``group=True`` adds the
        group velocities (``DiscreteBranches.group``). The request is bounded as ``dispersion
        branches`` bounds it (:data:`dispersion.answers.branch_table.MAX_COUNT`,
        :func:`~dispersion.budget.check_discrete_branches`), before any work.

        >>> PatchModel(Patch(n=30)).branches(range(20000))
        Traceback (most recent call last):
        ...
        dispersion.errors.InputError: count * (mass rules) * n^3 must be <= 11059200 (about a minute), got 540000000: at most count = 409 at n = 30 with 1 mass rule(s)
        """
        import numpy as np

        from dispersion.answers.branch_table import MAX_COUNT
        from dispersion.budget import check_discrete_branches
        from dispersion.discretization.discrete_branches import discrete_branches

        if self.spec.symbolic_r:
            raise InputError(f"r must be a number > 0 for numeric branches, got the symbol "
                             f"{self.spec.r}")
        size = np.size(kappa)
        if size > MAX_COUNT:
            raise InputError(f"kappa must have at most {MAX_COUNT} points, got {size}")
        check_discrete_branches(size, [self.spec.mass], self.spec.p, self.spec.n)
        if nu is not None or self.spec.isotropic:  # Poisson's ratio, as a float route takes it
            nu = float(self.spec.nu_value if nu is None else nu)
        return discrete_branches(self.plate, nu, kappa, group=group)


def _matrix_value(name: str, value):
    """``value`` of a patch matrix: None (the symbol), an expression with symbols, or a
    finite real number; anything else raises :class:`InputError` naming ``name``."""
    from dispersion.errors import as_real

    if value is None or getattr(value, "free_symbols", None):
        return value
    try:
        return as_real(name, value, "a finite real number or a sympy symbol")
    except InputError:
        raise
    except Exception:  # an object whose comparison or conversion fails
        raise InputError(f"{name} must be a finite real number or a sympy symbol, "
                         f"got {type(value).__name__}") from None
