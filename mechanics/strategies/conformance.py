"""Strategies for engines: rigid-body states a stepper can take, and random variants of
the conformance battery's scenarios, each with its exact reference (issue 29, item 3).

A user holds their engine to the book on inputs nobody chose::

    from hypothesis import given
    from mechanics import strategies as ms
    from mechanics.conformance import run_battery

    @given(ms.scenarios())
    def test_my_engine(scenario):
        report = run_battery(MyAdapter(), scenarios=[scenario], profile="first-order")
        assert report.passed, report.to_markdown()

Every drawn scenario is a variant of one of the battery's (:data:`SCENARIO_KINDS`) and
carries the **name of the built-in scenario it varies**, so that thresholds keyed by
that name and the profiles' exceptions (the impacts' jumping velocities, the
separatrix's phase) apply to it as to the original; its description says it is drawn.
Each lies inside its valid range (:func:`mechanics.conformance.scenarios.check_scenario`
passes): durations long enough to read its figures, impacts away from the samples,
bounces that do not come to rest.  The ranges are those an engine steps at the battery's
steps (2⁻⁶ … 2⁻⁹ s) without trouble: moments 0.1 … 10 kg m² with J₁/J₂ ≥ 0.2, spins up
to 4 rad/s, speeds up to 10 m/s; the hard regimes of the mathematical strategies
(moments 1e-100 apart, 1e±100 scales) are not drawn here.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from typing import Any

import numpy as np
from hypothesis import assume, event
from hypothesis import strategies as st

from .._floats import EPS
from ..conformance.protocol import Body, Ground, Pivot, Scenario, Shape, Thrust
from ..conformance.scenarios import (
    ScenarioRangeError,
    _bounce_impacts,
    _heavy_top,
    _rows,
    _times,
    check_scenario,
    get_scenario,
)
from ..conformance.scenarios import _vec3 as _vec
from ..rotation import matrix_from_euler
from ._common import check_positive, check_regimes, memoised

__all__ = ["SCENARIO_KINDS", "body_states", "scenarios"]

#: the kinds :func:`scenarios` draws, each named after the built-in scenario it varies
SCENARIO_KINDS = (
    "free_top",
    "free_top_near_separatrix",
    "heavy_top",
    "parabola",
    "two_body_impact",
    "bouncing_ball",
    "rocket",
)

_G = 9.81
#: the battery's steps, and its samples' spacings per kind (as in its built-in scenarios)
_STEPS = (2.0**-6, 2.0**-7, 2.0**-8)
#: the drawn free tops' sample spacing: half the built-in ones' 2⁻⁴ s, for spins up to
#: 4 rad/s (at 2⁻⁴ s the period read off the exact samples was off by up to 1.5e-8, at
#: 2⁻⁵ s by ≤ 2.5e-10, below the exact profile's 2⁻²⁸), halved while a top's figures
#: cannot be read off its samples to that profile (:data:`_FREE_DTS`: hypothesis found a
#: top whose period was 4.75e-9 off at 2⁻⁵ s, above the profile's 3.73e-9)
_FREE_DT = 2.0**-5
#: the spacings tried in turn, each a multiple of the finest step 2⁻⁸ s
_FREE_DTS = (_FREE_DT, 2.0**-6, 2.0**-7, 2.0**-8)
#: the words of check_scenario's refusal of samples too sparse to read a figure off
_TOO_SPARSE = "its samples are too sparse to read it"
#: t/dt rounds by an ulp or two: a t on the sample grid is not pushed to the next point
_GRID_RTOL = 2**4 * EPS
#: a unit vector's components below this are drawn as 0
_TINY = 2.0**-30
#: a drawn free top away from the separatrix has |L² − 2EJ₂| ≥ this × L² (near it the
#: phase error grows as the period does: the first-order toy's attitude error reached
#: 0.08 at |L² − 2EJ₂| = 0.03 L², 14 % at most on 250 draws once kept away from it)
_SEPARATRIX_GAP = 0.1
#: the longest period of a drawn top near the separatrix (s): the built-in one's 16.5 s
_SEPARATRIX_PERIOD = 16.5
#: the drawn heavy tops' largest θ (rad): see _heavy
_THETA_MAX = 2.0


def _grid(t: float, dt: float) -> float:
    """t rounded up to the sample grid (a t on it, within the division's rounding, stays)."""
    return math.ceil(t / dt * (1.0 - _GRID_RTOL)) * dt


_angles = st.tuples(
    st.floats(-math.pi, math.pi), st.floats(0.05, math.pi - 0.05), st.floats(-math.pi, math.pi)
)


def _unit(z: float, azimuth: float) -> tuple[float, float, float]:
    """The unit vector at height z and azimuth (uniform z and azimuth: uniform on the
    sphere), its components below :data:`_TINY` set to 0 (a subnormal component of ω is
    refused by the exact top: a stepper's range does not reach there)."""
    rho = math.sqrt(1.0 - z * z)
    u = np.array([rho * math.cos(azimuth), rho * math.sin(azimuth), z])
    u[np.abs(u) < _TINY] = 0.0
    return _vec(u / np.linalg.norm(u))


_units = st.builds(_unit, st.floats(-1.0, 1.0), st.floats(-math.pi, math.pi))


def _draw_moments(
    draw: st.DrawFn, symmetric: bool = False, wide: bool = False
) -> tuple[float, float, float]:
    """(J₁, J₂, J₃) ascending, 0.1 … 10 kg m², J₁/J₂ ≥ 0.2, J₃ ≤ J₁ + J₂; ``wide``:
    gaps of at least 30 % of J₂ (J₁/J₂ ≤ 0.7, J₃ − J₂ ≥ 0.3 J₁), so that the motion near
    the separatrix unfolds at λ₀ ≳ 0.2 |ω| and flips within the duration."""
    J2 = draw(st.floats(0.5, 5.0))
    if symmetric:
        return (J2, J2, J2 * draw(st.floats(0.3, 1.9)))
    J1 = J2 * draw(st.floats(0.2, 0.7 if wide else 0.9))
    J3 = J2 + draw(st.floats(0.3 if wide else 0.1, 0.9)) * J1
    return (J1, J2, J3)


# applied after the definition, so that mutmut mutates the function (it skips decorated ones)
_moments = st.composite(_draw_moments)


def body_states(*, max_spin: float = 4.0, max_speed: float = 10.0) -> st.SearchStrategy[Body]:
    """A rigid body's state an engine can step (a :class:`~mechanics.conformance.Body`).

    Principal moments 0.1 … 10 kg m² (J₁/J₂ ≥ 0.2, the triangle inequality kept), mass
    0.1 … 10 kg, any attitude (Euler angles with θ away from 0 and π by 0.05), ω in body
    components up to ``max_spin`` rad/s, G within 1 m of the origin moving at up to
    ``max_speed`` m/s.  Shrinks toward slow bodies at the origin.

    Parameters
    ----------
    max_spin : float
        The bound on |ω| (rad/s), finite and > 0.
    max_speed : float
        The bound on |v_G| (m/s), finite and > 0.

    Returns
    -------
    SearchStrategy of Body
        :class:`~mechanics.conformance.Body` records named ``"body"``.

    Raises
    ------
    hypothesis.errors.InvalidArgument
        ``max_spin`` or ``max_speed`` not a finite real number > 0.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(body_states(max_spin=1.0))
    ... def test_body(b):
    ...     J1, J2, J3 = b.inertia
    ...     assert J1 <= J2 <= J3 <= J1 + J2 and math.hypot(*b.omega) <= 1.0 + 1e-15
    >>> test_body()
    """
    spin = check_positive(max_spin, "max_spin")
    speed = check_positive(max_speed, "max_speed")

    @st.composite
    def draw_body(draw: st.DrawFn) -> Body:
        J = draw(_moments())
        R = matrix_from_euler(*draw(_angles))
        w = np.array(draw(_units)) * draw(st.floats(0.0, spin))
        x = np.array(draw(_units)) * draw(st.floats(0.0, 1.0))
        v = np.array(draw(_units)) * draw(st.floats(0.0, speed))
        return Body(
            "body", draw(st.floats(0.1, 10.0)), J, None, _vec(x), _vec(v), _rows(R), _vec(w)
        )

    return draw_body()


body_states = memoised(body_states)  # one strategy per arguments (_common.memoised)


def _free_top(draw: st.DrawFn, near_separatrix: bool) -> Scenario:
    from ..tops import FreeAsymmetricTop

    J = draw(_moments(wide=near_separatrix))
    R = matrix_from_euler(*draw(_angles))
    if near_separatrix:  # spun about axis 2, 1 % off it in a drawn direction
        phi = draw(st.floats(-math.pi, math.pi))
        size = draw(st.floats(3.0, 4.0))  # fast enough to flip within the duration
        w = size * np.array([0.01 * math.cos(phi), 1.0, 0.01 * math.sin(phi)])
    else:
        w = np.array(draw(_units)) * draw(st.floats(0.5, 4.0))
    period = FreeAsymmetricTop(J, w, R).flip_period()
    L2 = float(np.sum((np.array(J) * w) ** 2))
    twoEJ2 = float(np.sum(np.array(J) * w**2)) * J[1]
    if not near_separatrix:  # away from it: the near kind is drawn on purpose
        assume(abs(L2 - twoEJ2) >= _SEPARATRIX_GAP * L2)
    name = (
        "free_top_near_separatrix"
        if near_separatrix
        else ("free_top_axis1" if twoEJ2 > L2 else "free_top_axis3")
    )
    # two crossings of ω's intermediate component need a period; a long one is skipped
    # (near the separatrix: none longer than the built-in one's 16.5 s, whose phase a
    # first-order engine just keeps at 2⁻⁸ s)
    assume(math.isfinite(period) and period <= (_SEPARATRIX_PERIOD if near_separatrix else 24.0))
    duration = _grid(1.25 * period + 0.5, _FREE_DT)  # on every spacing's grid
    base = get_scenario(name)
    box = Body("box", 1.0, J, None, R_A_O=_rows(R), omega=_vec(w))
    for dt in _FREE_DTS:
        s = Scenario(
            name,
            f"drawn: {base.description} (J = {J[0]:.3g}, {J[1]:.3g}, {J[2]:.3g} kg m²)",
            base.book,
            (box,),
            duration=duration,
            sample_times=_times(duration, dt),
            steps=_STEPS,
            extra={"kind": "free_top"},
        )
        try:
            check_scenario(s)
        except ScenarioRangeError as exc:
            if _TOO_SPARSE not in str(exc):
                raise  # any other refusal is a bug of this module
            continue
        return s
    assume(False)  # not readable at the finest step's spacing: an invalid draw (not seen)
    raise AssertionError("unreachable")  # pragma: no cover - assume(False) raises


def _heavy(draw: st.DrawFn) -> Scenario:
    J1, _, J3 = draw(_moments(symmetric=True))
    m = draw(st.floats(0.5, 5.0))
    ell = draw(st.floats(0.05, 0.5))
    theta0 = draw(st.floats(0.2, 1.2))
    spin = draw(st.floats(2.0, 12.0))
    R0 = matrix_from_euler(0.0, theta0, 0.0)
    base = get_scenario("heavy_top")
    body = Body(
        "top",
        m,
        (J1, J1, J3),
        None,
        position=_vec(R0.T @ np.array([0.0, 0.0, ell])),
        R_A_O=_rows(R0),
        omega=(0.0, 0.0, spin),
    )
    s = _replace(
        base,
        description=f"drawn: a heavy symmetric top, θ0 = {theta0:.3g} rad, spin {spin:.3g} "
        f"rad/s, ℓ = {ell:.3g} m",
        bodies=(body,),
        pivot=Pivot(0, (0.0, 0.0, -ell)),
    )
    top = _heavy_top(s)  # the reference's own top
    period = top.nutation_period()
    assume(math.isfinite(period) and period <= 2.0)
    # θ kept above the horizon by 0.43 rad: a top that swings down near θ = π precesses
    # fast through the ψ of its low point, and the mean precession rate read off 2⁻⁷ s
    # samples was off by up to 7e-3 on the exact motion (θ ranging 2.8 rad)
    theta = top.theta(np.linspace(0.0, 0.5 * period, 65))
    assume(float(np.max(theta)) <= _THETA_MAX)
    # three turning points of θ (one at the start) need 1.5 periods
    duration = _grid(1.6 * period + 0.05, 2.0**-7)
    return _replace(s, duration=duration, sample_times=_times(duration, 2.0**-7))


def _parabola(draw: st.DrawFn) -> Scenario:
    r = draw(st.floats(0.05, 0.2))
    m = draw(st.floats(0.1, 2.0))
    vz = draw(st.floats(2.0, 10.0))
    vx, vy = draw(st.floats(-5.0, 5.0)), draw(st.floats(-5.0, 5.0))
    w = np.array(draw(_units)) * draw(st.floats(0.0, 4.0))
    duration = _grid(1.5 * vz / _G, 2.0**-5)
    ball = Body(
        "ball",
        m,
        (0.4 * m * r * r,) * 3,
        Shape("sphere", (r,)),
        position=(0.0, 0.0, 1.0),
        velocity=(vx, vy, vz),
        R_A_O=_rows(matrix_from_euler(*draw(_angles))),
        omega=_vec(w),
    )
    base = get_scenario("parabola")
    return _replace(
        base, description=f"drawn: {base.description}", bodies=(ball,), duration=duration,
        sample_times=_times(duration, 2.0**-5),
    )  # fmt: skip


def _impact(draw: st.DrawFn) -> Scenario:
    n = np.array(draw(_units))
    m1, m2 = draw(st.floats(0.5, 5.0)), draw(st.floats(0.5, 5.0))
    r1, r2 = draw(st.floats(0.05, 0.2)), draw(st.floats(0.05, 0.2))
    u1 = draw(st.floats(0.5, 3.0))
    u2 = draw(st.floats(-3.0, u1 - 0.5))  # closing at 0.5 m/s at least
    e = draw(st.floats(0.1, 1.0))
    dt = 2.0**-5
    # the impact between two samples, at least 0.3 of a spacing from each (9.4 ms)
    tc = (draw(st.integers(8, 20)) + draw(st.floats(0.3, 0.7))) * dt
    d = r1 + r2 + (u1 - u2) * tc
    spheres = tuple(
        Body(name, mass, (0.4 * mass * r * r,) * 3, Shape("sphere", (r,)), _vec(x), _vec(u * n))
        for name, mass, r, x, u in (("a", m1, r1, -0.5 * d * n, u1), ("b", m2, r2, 0.5 * d * n, u2))
    )
    base = get_scenario("two_body_impact")
    return _replace(
        base, description=f"drawn: two spheres head-on, e = {e:.3g}", bodies=spheres,
        pair_restitution=((0, 1, e),),
    )  # fmt: skip


def _bounce(draw: st.DrawFn) -> Scenario:
    r = draw(st.floats(0.05, 0.2))
    e = draw(st.floats(0.7, 0.95))
    h_lo = draw(st.floats(0.8, 2.0))
    vx = draw(st.floats(-1.0, 1.0))
    base = get_scenario("bouncing_ball")
    dt, fine = 2.0**-5, min(_STEPS)

    def at(h0: float) -> Scenario:
        ball = Body(
            "ball", 0.5, (0.002,) * 3, Shape("sphere", (r,)),
            position=(0.0, 0.0, h0 + r), velocity=(vx, 0.0, 0.0),
        )  # fmt: skip
        tf = math.sqrt(2 * h0 / _G)
        third_apex = tf * (1 + 2 * e + 2 * e * e + e**3)
        duration = _grid(third_apex + 0.1, dt)
        return _replace(
            base, description=f"drawn: a ball dropped from {h0:.4g} m, e = {e:.3g}",
            bodies=(ball,), duration=duration, sample_times=_times(duration, dt),
            ground=Ground(e),
        )  # fmt: skip

    # the impacts scale with √h0: the first h0 from h_lo up whose impacts all keep 2 of
    # the finest steps from the samples (about one in eight does; 400 candidates)
    for h0 in np.geomspace(h_lo, 1.3 * h_lo, 400):
        s = at(float(h0))
        impacts, _ = _bounce_impacts(s)
        t = np.asarray(s.sample_times)
        inside = [ti for ti in impacts if ti <= s.duration]
        if all(np.min(np.abs(t - ti)) >= 2 * fine for ti in inside):
            return s
    assume(False)  # none: an invalid draw (not seen in 10⁴ draws)
    raise AssertionError("unreachable")


def _rocket(draw: st.DrawFn) -> Scenario:
    m0 = draw(st.floats(5.0, 20.0))
    burn = draw(st.integers(16, 64)) * 2.0**-3  # 2 … 8 s
    q = m0 * draw(st.floats(0.1, 0.7)) / burn  # 30 … 90 % of the mass left at burn-out
    u = draw(st.floats(10.0, 50.0))
    duration = burn + 2.0
    body = Body(
        "rocket",
        m0,
        (0.1, 0.1, 0.05),
        R_A_O=_rows(matrix_from_euler(*draw(_angles))),
        velocity=_vec(np.array(draw(_units)) * draw(st.floats(0.0, 5.0))),
    )
    base = get_scenario("rocket")
    return _replace(
        base, description=f"drawn: a {m0:.3g} kg rocket burning {q:.3g} kg/s for {burn:g} s",
        bodies=(body,), duration=duration, sample_times=_times(duration, 2.0**-3),
        thrust=Thrust(0, q, u, burn),
    )  # fmt: skip


def _replace(s: Scenario, **changes: Any) -> Scenario:
    return dataclasses.replace(s, **changes)


_DRAW = {
    "free_top": lambda draw: _free_top(draw, False),
    "free_top_near_separatrix": lambda draw: _free_top(draw, True),
    "heavy_top": _heavy,
    "parabola": _parabola,
    "two_body_impact": _impact,
    "bouncing_ball": _bounce,
    "rocket": _rocket,
}


def scenarios(kinds: Iterable[str] | None = None) -> st.SearchStrategy[Scenario]:
    """Random variants of the battery's scenarios, each inside its valid range.

    See the module's docstring; ``kinds`` restricts them to some of :data:`SCENARIO_KINDS`.
    The exact reference of a drawn scenario is
    :func:`mechanics.conformance.reference` of it, as for the built-in ones.

    Parameters
    ----------
    kinds : iterable of str, optional
        Some of :data:`SCENARIO_KINDS` (default all).

    Returns
    -------
    SearchStrategy of Scenario
        :class:`~mechanics.conformance.Scenario` records, each named after the built-in
        scenario it varies, that pass :func:`~mechanics.conformance.scenarios.check_scenario`.

    Raises
    ------
    hypothesis.errors.InvalidArgument
        ``kinds`` a string, empty or with an unknown name.

    Examples
    --------
    A drawn parabola keeps the built-in one's name, and its description says it is drawn:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=5, derandomize=True)
    ... @given(scenarios(kinds=["parabola"]))
    ... def test_parabola(s):
    ...     assert s.name == "parabola" and s.description.startswith("drawn: ")
    >>> test_parabola()
    """
    names = check_regimes(kinds, SCENARIO_KINDS, "scenarios")

    @st.composite
    def draw_scenario(draw: st.DrawFn) -> Scenario:
        kind = draw(st.sampled_from(names))
        event(f"scenarios: {kind}")
        s = _DRAW[kind](draw)
        check_scenario(s)  # by construction; a failure here is a bug of this module
        return s

    return draw_scenario()


scenarios = memoised(scenarios)  # one strategy per arguments (_common.memoised)
