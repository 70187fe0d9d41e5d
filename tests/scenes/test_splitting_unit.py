"""Unit tests of :mod:`mechanics.scenes.splitting`, each against a hand computation: the
schedule of one step (Strang's kick–drift–kick, Yoshida's triple jump with its γ by
hand), a few steps of a harmonic oscillator by the kick and drift formulas, the dense
function's partial steps, the exact torque-free drift of a body spinning about a
principal axis (R3(ω t)), the step rounded to divide the sample interval, and the
refusals naming scene.method with their reason word for word."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.errors import OutOfDomainError
from mechanics.scenes import SceneError, splitting
from mechanics.scenes.engine import Engine

from .builders import box, point, scene

#: a few kick–drift steps of O(1) numbers: each update one or two roundings, and the
#: spring's force −k L (d/L) rounds differently from −k d (a few eps of the force)
STEP_RTOL = 32 * EPS
#: the Yoshida coefficients by hand: a cube root and a division, compared to 2 roundings
GAMMA_RTOL = 4 * EPS
#: the torque-free flow of mechanics.tops about a principal axis (a phase ω t evaluated
#: through Jacobi functions of modulus 0): a few eps of the unit attitude
TOP_ATOL = 32 * EPS


_scene = functools.partial(scene, name="split", duration=0.2, samples=3, method="splitting")
_point = functools.partial(point, mass=2.0, position=(1.0, 0.0, 0.0), velocity=(0.0, 0.5, 0.0))
#: J = m (b² + c², a² + c², a² + b²)/12 = (0.05, 0.1, 0.13)
_box = functools.partial(box, "b", mass=12.0, a=0.3, b=0.2, c=0.1, omega=(0.0, 0.0, 2.0))


#: a spring to the origin of stiffness 8 on a point of mass 2: ω² = 4
SPRING = {"type": "spring", "body": "p", "anchor": [0.0, 0.0, 0.0], "stiffness": 8.0}


def _yoshida(p: int) -> tuple[float, float]:
    """γ1 = 1/(2 − 2^(1/(p+1))), γ0 = 1 − 2 γ1 (Yoshida 1990): order p → p + 2."""
    g1 = 1.0 / (2.0 - 2.0 ** (1.0 / (p + 1)))
    return g1, 1.0 - 2.0 * g1


# ----------------------------------------------------------------------- the schedule


def test_the_order_two_step_is_strang_kick_drift_kick() -> None:
    assert splitting._schedule(2) == [("kick", 0.5), ("drift", 1.0), ("kick", 0.5)]


def test_the_order_four_step_is_the_triple_jump_of_strang_with_kicks_merged() -> None:
    g1, g0 = _yoshida(2)
    want = [
        ("kick", g1 / 2),
        ("drift", g1),
        ("kick", (g1 + g0) / 2),
        ("drift", g0),
        ("kick", (g0 + g1) / 2),
        ("drift", g1),
        ("kick", g1 / 2),
    ]
    got = splitting._schedule(4)
    assert [p for p, _ in got] == [p for p, _ in want]
    np.testing.assert_allclose([c for _, c in got], [c for _, c in want], rtol=GAMMA_RTOL)
    assert g0 < 0  # the backward middle jump of a fourth-order composition


def test_the_order_six_step_jumps_the_order_four_step_again() -> None:
    g1, g0 = _yoshida(2)
    h1, h0 = _yoshida(4)  # 1/(2 − 2^(1/5))
    got = splitting._schedule(6)
    drifts = [c for p, c in got if p == "drift"]
    kicks = [c for p, c in got if p == "kick"]
    # 3 × 3 Strang steps: 9 drifts, 10 kicks after merging, alternating
    assert [p for p, _ in got] == ["kick", "drift"] * 9 + ["kick"]
    want = [x * y for x in (h1, h0, h1) for y in (g1, g0, g1)]
    np.testing.assert_allclose(drifts, want, rtol=GAMMA_RTOL)
    np.testing.assert_allclose(kicks[0], h1 * g1 / 2, rtol=GAMMA_RTOL)
    assert math.fsum(drifts) == pytest.approx(1.0, rel=16 * EPS)
    assert math.fsum(kicks) == pytest.approx(1.0, rel=16 * EPS)
    assert splitting.ORDERS == (2, 4, 6)


# ------------------------------------------------------------------- steps by hand


def _kdk(x, v, h, sched, k=8.0, m=2.0):
    """The kick (v += c h (−k x)/m) and drift (x += c h v) of a point on a spring to
    the origin, written out for a list of (part, fraction)."""
    x, v = np.array(x, dtype=float), np.array(v, dtype=float)
    for part, c in sched:
        if part == "kick":
            v = v + c * h * (-k * x) / m
        else:
            x = x + c * h * v
    return x, v


def _strang():
    return [("kick", 0.5), ("drift", 1.0), ("kick", 0.5)]


def _state(eng, y):
    r, v, _, _ = eng.layout.gather(y)
    return r[0], v[0]


def test_two_strang_steps_of_a_harmonic_oscillator_by_hand() -> None:
    """Duration 0.2 in 3 samples (interval 0.1), step 0.05: two Strang steps per interval."""
    eng = Engine(_scene([_point()], [SPRING], step=0.05, order=2))
    segs, h = splitting.run(eng, 2, 0.05)
    assert h == 0.1 / 2
    assert [(a, b) for a, b, _ in segs] == [(0.0, 0.1), (0.1, 0.2)]
    x, v = [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]
    for _ in range(2):
        x, v = _kdk(x, v, h, _strang())
    r1, v1 = _state(eng, segs[0][2](0.1))
    np.testing.assert_allclose(r1, x, rtol=0, atol=STEP_RTOL)
    np.testing.assert_allclose(v1, v, rtol=0, atol=STEP_RTOL)
    # the second interval starts where the first ended
    r1b, v1b = _state(eng, segs[1][2](0.1))
    np.testing.assert_allclose([r1b, v1b], [r1, v1], rtol=0, atol=0)
    for _ in range(2):
        x, v = _kdk(x, v, h, _strang())
    r2, v2 = _state(eng, segs[1][2](0.2))
    np.testing.assert_allclose(r2, x, rtol=0, atol=STEP_RTOL)
    np.testing.assert_allclose(v2, v, rtol=0, atol=STEP_RTOL)


def test_one_fourth_order_step_by_the_yoshida_schedule_by_hand() -> None:
    g1, g0 = _yoshida(2)
    sched = [
        ("kick", g1 / 2),
        ("drift", g1),
        ("kick", (g1 + g0) / 2),
        ("drift", g0),
        ("kick", (g0 + g1) / 2),
        ("drift", g1),
        ("kick", g1 / 2),
    ]
    eng = Engine(_scene([_point()], [SPRING]))
    segs, h = splitting.run(eng, 4, None)  # no step: one step per sample interval
    assert h == 0.1
    x, v = _kdk([1.0, 0.0, 0.0], [0.0, 0.5, 0.0], h, sched)
    r1, v1 = _state(eng, segs[0][2](0.1))
    np.testing.assert_allclose(r1, x, rtol=0, atol=STEP_RTOL)
    np.testing.assert_allclose(v1, v, rtol=0, atol=STEP_RTOL)
    # the energy ½ m v² + ½ k x² is kept to O(h⁴) = 1e-4 of E, not exactly
    E = lambda x, v: 0.5 * 2.0 * (v @ v) + 0.5 * 8.0 * (x @ x)  # noqa: E731
    E0 = E(np.array([1.0, 0, 0]), np.array([0, 0.5, 0]))
    assert abs(E(r1, v1) - E0) <= 1e-4 * E0


def test_the_dense_function_takes_whole_steps_then_a_part_of_one() -> None:
    eng = Engine(_scene([_point()], [SPRING], step=0.05, order=2))
    segs, h = splitting.run(eng, 2, 0.05)
    at = segs[0][2]
    # t = 0.075: one whole step (0.075/0.05 = 1.5 → 1), then one of 0.075 − 0.05
    x, v = _kdk([1.0, 0.0, 0.0], [0.0, 0.5, 0.0], h, _strang())
    x, v = _kdk(x, v, 0.075 - h, _strang())
    r, vel = _state(eng, at(0.075))
    np.testing.assert_allclose(r, x, rtol=0, atol=STEP_RTOL)
    np.testing.assert_allclose(vel, v, rtol=0, atol=STEP_RTOL)
    # at the segment's start: the start itself; a batch of times: one row per time
    np.testing.assert_array_equal(at(0.0), eng.y0)
    both = at(np.array([0.0, 0.075]))
    assert both.shape == (2, eng.y0.size)
    np.testing.assert_array_equal(both[0], eng.y0)
    np.testing.assert_array_equal(both[1], at(0.075))


def test_the_step_is_rounded_down_to_divide_the_sample_interval() -> None:
    eng = Engine(_scene([_point()], [SPRING]))
    gap = 0.1  # duration 0.2 in 3 samples
    assert splitting.run(eng, 2, 0.03)[1] == gap / 4  # ⌈0.1/0.03⌉ = 4 steps
    assert splitting.run(eng, 2, 1.0)[1] == gap  # a step longer than the interval: 1
    assert splitting.run(eng, 2, None)[1] == gap


def test_the_drift_turns_a_spinning_box_by_its_exact_torque_free_flow() -> None:
    """ω = 2 about the principal axis e3 (J3 = 0.13 ≠ 1): ^A R^O(t) = R3(2t), L_A = J ω
    constant; the centre drifts on a straight line."""
    box = _box()
    box["initial"]["velocity"] = [1.0, 0.0, 0.0]
    eng = Engine(_scene([box], [], duration=0.5))
    segs, _ = splitting.run(eng, 4, None)
    r, v, L, R = eng.layout.gather(segs[0][2](0.25))
    c, s = math.cos(0.5), math.sin(0.5)
    np.testing.assert_allclose(R[0], [[c, s, 0], [-s, c, 0], [0, 0, 1]], rtol=0, atol=TOP_ATOL)
    np.testing.assert_allclose(L[0], [0.0, 0.0, 0.13 * 2.0], rtol=0, atol=TOP_ATOL)
    np.testing.assert_allclose(r[0], [0.25, 0.0, 0.0], rtol=0, atol=STEP_RTOL)
    np.testing.assert_array_equal(v[0], [1.0, 0.0, 0.0])


def test_a_box_at_rest_is_not_turned() -> None:
    eng = Engine(_scene([_box(omega=(0.0, 0.0, 0.0))], [], duration=0.5))
    segs, _ = splitting.run(eng, 2, None)
    _, _, L, R = eng.layout.gather(segs[1][2](0.5))
    np.testing.assert_array_equal(R[0], np.eye(3))
    np.testing.assert_array_equal(L[0], np.zeros(3))


def test_turn_of_a_body_near_the_separatrix_names_scene_method(monkeypatch) -> None:
    import mechanics.tops

    def refuse(*a, **kw):
        raise OutOfDomainError("too close to the separatrix")

    eng = Engine(_scene([_box()], [], duration=0.5))
    monkeypatch.setattr(mechanics.tops, "FreeAsymmetricTop", refuse)
    with pytest.raises(SceneError) as info:
        splitting._turn(eng, eng.layout.J[0], np.array([0.0, 0.0, 0.26]), np.eye(3), 0.1)
    assert info.value.field == "scene.method"
    assert info.value.reason == (
        "'splitting': a body turns within float64's reach of the separatrix, where the "
        "torque-free flow is not resolved: use 'integrate'"
    )
    assert info.value.__cause__ is None
    assert info.value.__suppress_context__


# ------------------------------------------------------------------------- refusals


def _refusal(bodies, effects) -> str:
    eng = Engine(_scene(bodies, effects, duration=0.5))
    with pytest.raises(SceneError) as info:
        splitting.check(eng)
    assert info.value.field == "scene.method"
    assert str(info.value).startswith("split.toml: scene.method: 'splitting': ")
    return info.value.reason


def test_a_pinned_or_fixed_body_is_refused() -> None:
    why = "'splitting': it takes points and free rigid bodies only (no joint, tank or fixed body)"
    pinned = [{"type": "fixed_point", "body": "b", "distance": 0.1}]
    assert _refusal([_box()], pinned) == why
    fixed = {"name": "wall", "shape": "point", "mass": 1.0, "fixed": True}
    assert _refusal([_point(), fixed], []) == why


def test_impacts_are_refused() -> None:
    ball = {
        "name": "ball",
        "shape": "solid_sphere",
        "mass": 1.0,
        "radius": 0.1,
        "initial": {"position": [0.0, 0.0, 1.0]},
    }
    floor = [{"type": "impact", "body": "ball", "restitution": 0.5}]
    assert _refusal([ball], floor) == (
        "'splitting': a fixed step cannot locate impacts or switches: use 'auto' or 'integrate'"
    )


def test_an_effect_without_a_potential_is_refused_naming_the_first() -> None:
    drag = {"type": "drag", "body": "p", "linear": 0.1}
    damper = {"type": "damper", "body": "p", "anchor": [0.0, 0.0, 0.0], "damping": 0.1}
    assert _refusal([_point()], [SPRING, drag, damper]) == (
        "'splitting': the 'drag' effect is not conservative (no potential energy)"
    )
    # a zero force keeps the energy but has no potential energy: refused too
    zero = {"type": "force", "body": "p", "force": [0.0, 0.0, 0.0]}
    assert _refusal([_point()], [zero]) == (
        "'splitting': the 'force' effect is not conservative (no potential energy)"
    )


def test_a_body_with_a_zero_principal_moment_is_refused_naming_it() -> None:
    rod = {"name": "stick", "shape": "rod", "mass": 1.0, "length": 1.0}
    assert _refusal([_point(), rod], []) == (
        "'splitting': body 'stick' has a zero principal moment (no torque-free flow)"
    )


def test_a_conservative_scene_of_points_and_boxes_is_accepted() -> None:
    gravity = {"type": "gravity", "g": 9.81}
    eng = Engine(_scene([_point(), _box()], [SPRING, gravity], duration=0.5))
    assert splitting.check(eng) is None


def test_one_strang_step_kicks_the_spin_by_the_moment_of_an_off_centre_spring() -> None:
    """A box at rest (mass 12, J3 = 0.13), a spring of stiffness 8 from its body point
    a = (0.15, 0, 0) to the anchor (0.15, 0.1, 0): the force, and its moment about G,
    are along y and z, so the box turns about its principal axis e3 and the drift is
    R3(φ), φ = h L3/J3.  One Strang step written out: kick ½h (v += ½h F/m, L_A +=
    ½h M_A), drift h (r += h v, R = R3(φ)), kick ½h at the new place."""
    k, m, J3, h = 8.0, 12.0, 0.13, 0.1
    a, anchor = np.array([0.15, 0.0, 0.0]), np.array([0.15, 0.1, 0.0])
    spring = {
        "type": "spring",
        "body": "b",
        "at": a.tolist(),
        "anchor": anchor.tolist(),
        "stiffness": k,
    }
    eng = Engine(_scene([_box(omega=(0.0, 0.0, 0.0))], [spring]))

    def load(r, R):
        rho = R.T @ a  # the body point from G, space components
        F = -k * (r + rho - anchor)
        return F, R @ np.cross(rho, F)  # the moment about G in body components

    r, v, L, R = np.zeros(3), np.zeros(3), np.zeros(3), np.eye(3)
    F, M = load(r, R)
    v, L = v + 0.5 * h * F / m, L + 0.5 * h * M
    assert F[1] == 8.0 * 0.1  # the spring stretched by 0.1 along −y
    assert M[2] == 0.15 * F[1]
    r = r + h * v
    phi = h * L[2] / J3
    c, s = math.cos(phi), math.sin(phi)
    R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    F, M = load(r, R)
    v, L = v + 0.5 * h * F / m, L + 0.5 * h * M

    segs, _ = splitting.run(eng, 2, None)
    got = eng.layout.gather(segs[0][2](0.1))
    for name, g, want in zip("rvLR", got, (r, v, L, R), strict=True):
        np.testing.assert_allclose(g[0], want, rtol=0, atol=TOP_ATOL, err_msg=name)


def test_a_run_near_the_separatrix_stops_naming_scene_method(monkeypatch) -> None:
    import mechanics.tops

    def refuse(*a, **kw):
        raise OutOfDomainError("too close to the separatrix")

    eng = Engine(_scene([_box()], [], duration=0.5))
    monkeypatch.setattr(mechanics.tops, "FreeAsymmetricTop", refuse)
    with pytest.raises(SceneError, match="within float64's reach of the separatrix") as info:
        splitting.run(eng, 2, None)
    assert str(info.value).startswith("split.toml: scene.method: 'splitting': ")
