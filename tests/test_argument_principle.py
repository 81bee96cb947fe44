"""The argument principle's count (dispersion/continuum/layered/argument_principle.py) on
polynomials, whose zeros are known in closed form: the graded first samples keep known zeros
near the contour from aliasing a whole turn, which a fixed first segment does not."""
from __future__ import annotations

import math

import flint
from hypothesis import example, given
from hypothesis import strategies as st
from promise_search import FAST

from dispersion.continuum.layered.argument_principle import graded_polygon, winding

RECT = [complex(-1.06, -0.115), complex(1.06, -0.115), complex(1.06, 0.115),
        complex(-1.06, 0.115)]


def _polynomial(zeros):
    def F(z):
        out = flint.acb(1)
        for r in zeros:
            out *= flint.acb(z) - flint.acb(r)
        return out
    return F


def _inside(z, rect):
    return rect[0].real < z.real < rect[2].real and rect[0].imag < z.imag < rect[2].imag


def test_four_zeros_near_the_top_edge_alias_on_a_fixed_segment_not_on_graded_samples():
    """z^4 - a^4, a = 0.06 (A0's four roots of 1 mm at Omega 0.002, in kappa): the top edge
    runs 0.055 above i a; a fixed first segment of 0.25 sees the argument turn 376 deg
    between two samples and reads 16 deg."""
    zeros = [0.06, -0.06, 0.06j, -0.06j]
    F = _polynomial(zeros)
    assert winding(F, RECT, segment=0.25)[0] == 2           # the aliasing, as it was
    assert winding(F, graded_polygon(RECT, zeros, 0.25))[0] == 4


@FAST
@given(st.lists(st.tuples(st.floats(-2.0, 2.0), st.floats(-0.5, 0.5)), min_size=1,
                max_size=12),
       st.floats(0.05, 0.5))     # about the count's SEGMENT (0.25); at 1e-3 the rectangle's
                                 # 4,700 first samples exceed MAX_EVALUATIONS (None)
@example([(0.0, 0.1149)], 0.25)         # a zero 1e-4 below the top edge
@example([(x / 100, 0.0) for x in range(-6, 6)], 0.5)   # twelve zeros within 0.06
def test_graded_samples_count_every_known_zero(points, longest):
    zeros = [complex(x, y) for x, y in points]
    # zeros on the contour have no count: keep those at least 1e-6 from it
    zeros = [z for z in zeros
             if min(abs(abs(z.real) - 1.06), abs(abs(z.imag) - 0.115)) > 1e-6]
    pts = graded_polygon(RECT, zeros, longest)
    for a, b in zip(pts, pts[1:] + pts[:1]):
        gap = min(abs(z - a) for z in zeros) if zeros else math.inf
        # (+ 1e-15: the points' own rounding, coordinates below 1.1)
        assert abs(b - a) <= min(longest, max(gap / 2, 1e-12 * 2.12)) + 1e-15
    counted, _ = winding(_polynomial(zeros), pts)
    expected = sum(_inside(z, RECT) for z in zeros)
    assert counted == expected
