"""The argument principle along a polygon, with every sampled argument certain (ball
arithmetic): how many zeros an entire function has inside.

For a function F analytic inside and on a closed polygon with no zero on it, the number of
its zeros inside (with multiplicity) is the winding number of F around 0 along the polygon,

.. math::

    N = \\frac{1}{2\\pi} \\oint \\mathrm d \\arg F.

F is enclosed in a ball (python-flint ``acb``) at each sample; a sample whose ball meets 0,
or whose argument is not known to within 30 degrees (:data:`CONE`), or where F cannot be
enclosed (a pivot not proven invertible), leaves the count unknown. Each edge is cut into
first segments, and a segment whose two end arguments differ by more than :data:`MAX_STEP`
is halved, down to :data:`MAX_DEPTH` halvings (then the count is unknown: a zero on or very
near the contour), so the argument is followed in steps of less than an eighth of a turn.
The damped solver's certificate (:mod:`~dispersion.continuum.layered.damped_modes`) is this
function on its 16-gon (it read 16 fixed samples with steps below 3/4 of a half turn). It
reads the winding from samples: a pair of zeros closer to the contour than the final sample spacing, whose
arguments cancel between two samples, is not excluded (a proof would need a bound on F'
along each segment; an enclosure of F on a whole segment at once was tried and is far too
wide through the stiffness' inversions).

References
----------
P. Henrici, *Applied and Computational Complex Analysis*, vol. 1, Wiley (1974), section 4.6
(the argument principle); L. M. Delves, J. N. Lyness, "A numerical method for locating the
zeros of an analytic function", Math. Comp. 21 (1967) 543 (the adaptive argument).
"""
from __future__ import annotations

import cmath
import math

import numpy as np

__all__ = ["winding", "regular_polygon", "graded_polygon", "CONE", "MAX_STEP", "MAX_DEPTH",
           "MAX_EVALUATIONS"]

#: Largest radius of a sample's ball relative to its centre's modulus (sin 30 deg).
CONE = 0.5
#: Largest change of the argument between neighbouring samples (an eighth of a turn).
MAX_STEP = math.pi / 4
#: Halvings of a first segment before its count is given up.
MAX_DEPTH = 30
#: Evaluations of F along one contour before its count is given up.
MAX_EVALUATIONS = 4000


def regular_polygon(centre: complex, radius: float, sides: int = 16) -> list[complex]:
    """The vertices of the regular polygon inscribed in the circle (one vertex at angle 0,
    so a polygon centred on the imaginary axis is its own mirror image)."""
    return [centre + radius * cmath.exp(2j * math.pi * j / sides) for j in range(sides)]


def graded_polygon(vertices, near, longest: float) -> list[complex]:
    """The closed polygon ``vertices`` with points added along each edge, spaced at most
    ``longest`` and at most half the distance to the nearest of the points ``near`` (the
    zeros known beforehand). Rule: a zero at distance d from a segment of length s <= d / 2
    turns the argument by at most 2 atan(1/4) = 0.49 rad along it, so fewer than a dozen
    known zeros together cannot turn it by a whole turn between two samples (the aliasing
    that a fixed first segment allows: four roots within 0.06 of the origin, the top edge
    0.055 above them, counted 2 with first segments of 0.25)."""
    near = np.asarray(list(near), dtype=complex)
    out = []
    for a, b in zip(vertices, list(vertices[1:]) + [vertices[0]]):
        length, t = abs(b - a), 0.0
        while t < length:
            z = a + (b - a) * (t / length)
            out.append(z)
            d = float(np.min(np.abs(near - z))) if near.size else math.inf
            t += min(longest, max(d / 2, 1e-12 * length))
    return out


def winding(F, vertices, segment: float | None = None):
    """The number of zeros of ``F`` inside the closed polygon ``vertices`` (counter-
    clockwise), or None where it is not known. ``F(z)`` returns an ``acb`` ball holding
    F(z); ``segment``: the longest first segment (default: each edge whole). Returns
    ``(count, evaluations)``."""
    evals = [0]

    def point(z):
        evals[0] += 1
        if evals[0] > MAX_EVALUATIONS:
            raise _GiveUp
        try:
            ball = F(z)
        except ZeroDivisionError:   # a matrix not proven invertible in ball arithmetic
            raise _GiveUp from None
        m = complex(ball.mid())
        rho = math.hypot(float(ball.real.rad()), float(ball.imag.rad()))
        if not rho < CONE * abs(m):
            raise _GiveUp
        return cmath.phase(m)

    def step(a, b, pa, pb, depth):
        d = (pb - pa + math.pi) % (2 * math.pi) - math.pi
        if abs(d) <= MAX_STEP:
            return d
        if depth >= MAX_DEPTH:
            raise _GiveUp
        c = 0.5 * (a + b)
        pc = point(c)
        return step(a, c, pa, pc, depth + 1) + step(c, b, pc, pb, depth + 1)

    pts = []
    for a, b in zip(vertices, list(vertices[1:]) + [vertices[0]]):
        pieces = 1 if segment is None else max(1, math.ceil(abs(b - a) / segment))
        pts += [a + (b - a) * j / pieces for j in range(pieces)]
    try:
        phases = [point(z) for z in pts]
        total = sum(step(a, b, pa, pb, 0) for a, b, pa, pb in
                    zip(pts, pts[1:] + pts[:1], phases, phases[1:] + phases[:1]))
    except _GiveUp:
        return None, evals[0]
    return round(total / (2 * math.pi)), evals[0]


class _GiveUp(Exception):
    """A sample not known or a segment not resolved within the budget."""
