"""Terminal events of :func:`~mechanics.integrators.integrate`: when an event function
crosses zero over a step, and the next point of the bracket that locates the crossing.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).  Plain
scalar functions: :mod:`mechanics._kernels_rhs` compiles these same two for its kernel
(one source of truth), the reference path calls them as they are.
"""

from __future__ import annotations

from .._floats import EPS

#: An event is located to a bracket of EVENT_XTOL · max(|t|, h) (h the step that holds
#: it): 4 ulps of its time, where the time itself is only known to the rounding of t
#: (half an ulp) and the interpolant's rounding blurs the sign of g near the root.
EVENT_XTOL = 4 * EPS


def crosses(g_old: float, g_new: float, direction: float) -> bool:
    """The event function crossed zero over a step: ``g_old`` strictly on one side,
    ``g_new`` on zero or on the other side, in the direction asked (< 0 falling, > 0
    rising, 0 either).  A run that starts on zero does not stop there."""
    down = g_old > 0.0 and g_new <= 0.0
    up = g_old < 0.0 and g_new >= 0.0
    return (down and direction <= 0.0) or (up and direction >= 0.0)


def bracket_step(a: float, ga: float, b: float, gb: float, tol: float, it: int) -> float:
    """The next point in the bracket (a, b) of a sign change of g (values ga, gb; the
    caller halves the value of an end that stays twice, Illinois' rule): the regula
    falsi, a bisection every fourth iteration and whenever the secant leaves the
    bracket, kept tol/2 inside each end, so that each iteration shrinks the bracket by
    tol/2 at least and it ends at most tol wide."""
    m = (a * gb - b * ga) / (gb - ga)
    if it % 4 == 3 or not a < m < b:
        m = a + 0.5 * (b - a)
    half = 0.5 * tol
    return min(max(m, a + half), b - half)
