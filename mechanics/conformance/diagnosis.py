"""What a failing scenario's figures imply (issue 29, item 2): rules that read the
figures together and name the law that is wrong.

Each rule is derived from what a law's error does to the figures, and each is tested
against the bug it names and against a correct engine and the other bugs, which it
must not name (tests/conformance/test_diagnosis.py):

``order``
    The order of convergence reads below :data:`NO_CONVERGENCE` (½): the error does not
    shrink with the step.  Step error shrinks as hᵖ (p ≥ 1 for any consistent
    method); a wrong law leaves an O(1) error at every step (the four bugs of issue
    29's trial read |order| ≤ 0.02, a correct first-order engine ≥ 0.89).  At or above
    it the failure is step error, and the profile that fits the order read is named;
    the two rules below that name a law then stay silent (a correct engine at a
    stricter profile drifts in L more than in E too: the explicit midpoint 40 times).
``attitude``
    The attitude is wrong while ω is right (its figure fails, or it is within its bound
    but the error does not converge).  ω in body components follows from Euler's
    equations alone; the attitude also needs the convention.  Where the transposed
    matrix matches the exact one (within the attitude's bound and :data:`TRANSPOSE_GAIN`
    times better than the matrix returned), the engine returns its active body-to-world
    matrix, the protocol's passive ^A R^O transposed.
``rotational``
    Angular momentum drifts while energy holds (the L drift above rounding and
    :data:`DRIFT_RATIO` times the E drift or more, in a failing scenario whose error does
    not converge).  A wrong gyroscopic term (dropped, or J taken in world axes)
    still conserves T = ½ Σ Jᵢωᵢ² (J ω̇ = X × ω gives Ṫ = ω · (X × ω) = 0
    whatever X is), but turns L in space: the rotational dynamics, Euler's equations
    (4.47), are wrong.  Not said
    when the attitude rule found a transpose (L in space is then computed with the wrong
    matrix).
``restitution``
    The bouncing ball's apex heights fall by e_m² per bounce: e_m is the measured
    restitution, the median of √(h_{k+1}/h_k).  Where e_m is nearer e² than e, the law
    is applied twice or squared; nearer 1, e is ignored.  The head-on impact's measured
    e likewise (its ``restitution`` figure).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from .._floats import EPS
from .protocol import Scenario, Trajectory
from .scenarios import bounce_apexes
from .thresholds import PROFILES

__all__ = ["DRIFT_RATIO", "NO_CONVERGENCE", "TRANSPOSE_GAIN", "diagnose"]

#: the stepping profiles' order bounds, highest first: (bound, profile)
_CLASSES = sorted(
    ((float(o), p.name) for p in PROFILES.values() if (o := p.thresholds["order"]) is not None),
    reverse=True,
)
#: an order below this reads as "the error does not shrink with the step": the lowest
#: order bound of a stepping profile (first-order's ½, half the lowest order of a
#: consistent method)
NO_CONVERGENCE = _CLASSES[-1][0]
#: L drifting this many times more than E (2⁴): the rotational dynamics, not the step
DRIFT_RATIO = 2.0**4
#: the transposed matrix must be this many times nearer the exact one than the matrix
#: returned (2) to name the transpose.  The transposed matrix of an engine with the
#: transposition bug keeps the engine's step error, which may be any fraction of the
#: bound (a correct first-order engine's reached 0.15 of 0.25 where the untransposed
#: matrix was off by 1.99: a gain of 2⁴ missed it); the gain only guards against an
#: attitude that is nearly symmetric (a rotation by an angle near 0 or π), whose
#: transpose is as near as the matrix itself whatever the convention.
TRANSPOSE_GAIN = 2.0
#: a drift at or below this (2¹⁰ eps, relative) is rounding, not a drift
_ROUNDING = 2**10 * EPS


def _failed(figures: Mapping, name: str) -> bool:
    f = figures.get(name)
    return f is not None and f.passed is False


def _converging(figures: Mapping) -> bool | None:
    """Does the error shrink with the step?  None: no order was read."""
    f = figures.get("order")
    if f is None or f.value is None:
        return None
    return bool(f.value >= NO_CONVERGENCE)


def _order(figures: Mapping) -> list[str]:
    converging = _converging(figures)
    if converging is None:
        return []
    p = figures["order"].value
    if not converging:
        return [
            f"The error does not shrink with the step (order {p:.2g}): a law is wrong, "
            "not the step size."
        ]
    fits = next(name for bound, name in _CLASSES if p >= bound)  # p >= NO_CONVERGENCE
    return [
        f"The error shrinks with the step at order {p:.2g}: step error, not a wrong "
        f"law (a finer step, or a looser profile; the profile for an engine of this order "
        f"is {fits})."
    ]


def _attitude(figures: Mapping, ref: Trajectory, tr: Trajectory) -> tuple[list[str], bool]:
    """(sentences, whether the transpose matched)."""
    a = figures.get("attitude")
    if a is None or a.value is None or a.threshold is None or _failed(figures, "omega"):
        return [], False
    failed = a.passed is False
    # within its bound but not shrinking with the step: a small rotation's transpose is
    # off by 2 sin(angle), under the bound for an angle below ~1/8 at first-order
    stuck = _converging(figures) is False and a.value > _ROUNDING
    if not (failed or stuck):
        return [], False
    swapped = float(np.max(np.abs(np.swapaxes(tr.R_A_O, -1, -2) - ref.R_A_O)))
    if swapped <= a.threshold and swapped * TRANSPOSE_GAIN <= a.value:
        return [
            f"The attitude is off by {a.value:.3g} while ω is right, and its transpose "
            f"matches the exact one to {swapped:.3g}: the engine returns its active "
            "(body-to-world) matrix; the protocol's is the passive ^A R^O, its transpose "
            "(rows are the body axes)."
        ], True
    if not failed or _converging(figures):  # within bound, or step error (the order rule)
        return [], False
    return [
        f"The attitude is off by {a.value:.3g} while ω is right: the attitude's update or "
        "its convention is wrong (passive ^A R^O, Ṙ = −[ω]× R with ω in body components)."
    ], False


def _rotational(figures: Mapping) -> list[str]:
    if _converging(figures):  # step error: the order rule says so
        return []
    e = figures.get("E_drift")
    for name in ("L_drift", "L_z_drift", "L_3_drift"):
        f = figures.get(name)
        if e is None or f is None or f.value is None or f.value <= _ROUNDING:
            continue
        if f.value >= DRIFT_RATIO * e.value:
            return [
                f"Angular momentum drifts ({name} {f.value:.3g}) while energy holds "
                f"(E_drift {e.value:.3g}): the rotational dynamics are wrong; check the "
                "gyroscopic term ω × (J ω) of Euler's equations (4.47), J the principal "
                "moments in body axes."
            ]
    return []


def _nearest_law(measured: float, e: float) -> str:
    laws = {"e": e, "e²": e * e, "1 (e ignored)": 1.0}
    name = min(laws, key=lambda k: abs(measured - laws[k]))
    if name == "e":
        return ""
    if name == "e²":
        return f" ≈ e² = {e * e:.3g}: restitution applied twice or squared"
    return ": e is ignored (the impact is elastic)"


def _restitution(s: Scenario, figures: Mapping, tr: Trajectory, measured: Mapping) -> list[str]:
    kind = s.extra.get("kind")
    apexes = _failed(figures, "apex_heights") or _failed(figures, "apex_times")
    if kind in ("bounce", "rest") and apexes:
        e = s.ground.restitution if s.ground is not None else math.nan
        _, h = bounce_apexes(s, tr)
        h = h[h > 0]
        if h.size < 2:
            return []
        e_m = float(np.median(np.sqrt(h[1:] / h[:-1])))
        law = _nearest_law(e_m, e)
        return [
            f"The apex heights fall as e_m² per bounce with e_m = {e_m:.3g} (median of "
            f"√(h_k+1/h_k)) against the scenario's e = {e:.3g}{law}."
        ]
    if kind == "impact" and _failed(figures, "restitution"):
        e = s.pair_restitution[0][2]
        got = measured.get("restitution")
        if not isinstance(got, float):
            return []
        return [f"The measured restitution is {got:.3g} against e = {e:.3g}{_nearest_law(got, e)}."]
    return []


def diagnose(
    s: Scenario, ref: Trajectory, tr: Trajectory, figures: Mapping, measured: Mapping
) -> list[str]:
    """The sentences the rules of this module say about a run's figures.

    Parameters
    ----------
    s : Scenario
        The scenario run.
    ref : Trajectory
        Its exact trajectory.
    tr : Trajectory
        The finest run, validated (:func:`~.protocol.check_trajectory`).
    figures : Mapping
        The run's figures by name (name → :class:`~.battery.Figure`).
    measured : Mapping
        The derived figures read off ``tr`` (:func:`~.scenarios.measure`).

    Returns
    -------
    list of str
        One sentence per rule that fires (the order, the attitude, the rotational
        dynamics, the restitution), in that order; empty when none does.

    Raises
    ------
    ValueError
        Where ``tr`` and ``ref`` do not broadcast (nothing is validated here).
    MechanicsValueError
        Where a bounce's apexes must be read and the scenario has no ground or the ball
        no shape (:func:`~.scenarios.bounce_apexes`).

    Examples
    --------
    An engine that returns its active matrix, the passive ^A R^O transposed:

    >>> import dataclasses
    >>> from mechanics.conformance import Figure, get_scenario, reference
    >>> s = get_scenario("free_top_axis3")
    >>> ref = reference(s).trajectory
    >>> tr = dataclasses.replace(ref, R_A_O=np.swapaxes(ref.R_A_O, -1, -2))
    >>> off = float(np.max(np.abs(tr.R_A_O - ref.R_A_O)))
    >>> figures = {"attitude": Figure("attitude", "error", off, 2**-10, False)}
    >>> out = diagnose(s, ref, tr, figures, {})
    >>> len(out), "its active (body-to-world) matrix" in out[0]
    (1, True)
    """
    attitude, transposed = _attitude(figures, ref, tr)
    out = _order(figures) + attitude
    if not transposed:
        out += _rotational(figures)
    return out + _restitution(s, figures, tr, measured)
