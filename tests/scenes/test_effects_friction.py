"""Coulomb friction of a round body on a plane (``coulomb_friction``), unit by unit: the
slide's geometry, the friction that keeps it rolling (solved as a linear system), the
exact flow under gravity (against the book's sliding ball: it rolls on at 5/7 of its
speed; m r v + J ω about the contact line is kept), the loads it adds in each mode, its
switches and what it keeps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import SceneError
from mechanics.scenes.effects import Loads
from mechanics.scenes.effects.capabilities import GuidesBody
from mechanics.scenes.engine import Engine
from mechanics.scenes.trajectory import Event

from . import _effects

#: a few products and quotients of O(1) values (accelerations, a switch time): a
#: handful of roundings each
EXACT_RTOL = 32 * EPS
#: positions after a switch: q1 + qd1 τ + ½ a τ² from rounded q1, qd1 and τ
FLOW_ATOL = 64 * EPS

M, RADIUS, G = 2.0, 0.5, 10.0
#: the solid sphere's moment about any axis through G: 2/5 m r²
J = 0.4 * M * RADIUS**2


def ball(**initial):
    return {"name": "ball", "shape": "solid_sphere", "mass": M, "radius": RADIUS,
            "initial": initial}  # fmt: skip


def scene_of(bodies, effects):
    return _effects.scene_of(bodies, effects, duration=2.0)


def refusal(bodies, effects) -> SceneError:
    return _effects.refusal(bodies, effects, duration=2.0)


def sliding(mu=0.2, angle=0.0, extra=(), first=None, **initial):
    """The engine of a ball sliding on the incline under gravity g = 10; the friction
    effect (last) and the engine."""
    bodies = ([first] if first else []) + [ball(**initial)]
    effects = [{"type": "gravity", "g": G}, *extra]
    friction = {"type": "coulomb_friction", "body": "ball", "mu": mu}
    if angle:
        friction["angle"] = angle
    eng = Engine(scene_of(bodies, [*effects, friction]))
    return eng.effects[-1], eng


def other_loads(eng, s, t=0.0) -> Loads:
    """The loads of every effect but the friction, summed (as the engine does first)."""
    out = Loads(eng.n, s)
    for e in eng.forces:
        if e.type != "coulomb_friction":
            e.loads(t, s, out)
    return out


# ------------------------------------------------------------------ the slide


def test_the_slide_is_built_from_the_slope_the_body_and_the_friction() -> None:
    cyl = {"name": "c", "shape": "cylinder", "mass": 2.0, "radius": 0.5, "height": 1.0}
    alpha = 0.3
    for axis, k, moment in (("x", 0, 2.0 * (3 * 0.25 + 1.0) / 12), ("z", 2, 0.5 * 2.0 * 0.25)):
        scene = scene_of(
            [cyl],
            [{"type": "gravity", "g": 1.0},
             {"type": "coulomb_friction", "body": "c", "mu": 0.4, "angle": alpha,
              "body_axis": axis}],
        )  # fmt: skip
        gd = Engine(scene).layout.guides[0]
        np.testing.assert_array_equal(gd.n, [math.sin(alpha), 0.0, math.cos(alpha)])
        np.testing.assert_array_equal(gd.t, [math.cos(alpha), 0.0, -math.sin(alpha)])
        np.testing.assert_array_equal(gd.a, [0.0, 1.0, 0.0])
        assert (gd.r, gd.m, gd.k, gd.mu) == (0.5, 2.0, k, 0.4)
        assert gd.M[0] == 2.0
        assert math.isclose(gd.M[1], moment, rel_tol=4 * EPS)
    # the default axis is z, the default slope 0
    (f, eng) = sliding()
    gd = eng.layout.guides[0]
    assert gd.k == 2
    np.testing.assert_array_equal(gd.n, [0.0, 0.0, 1.0])
    assert f.ctx.guides is eng.layout.guides
    assert f.spec is eng.scene.effects[-1]
    assert f.alpha == 0.0
    assert f.mu == 0.2
    assert f.i == 0
    assert f.guide is gd


def test_the_slide_places_g_at_r_n_plus_s_t_and_turns_the_body_about_a() -> None:
    f, _eng = sliding(angle=0.3)
    gd = f.guide
    q = np.array([[[1.5, 0.25]], [[-2.0, 1.0]]])  # a (2, 1) batch of (s, θ)
    G_, E, R = gd.place(q)
    assert G_.shape == (2, 1, 3)
    assert E.shape == (2, 1, 2, 3)
    assert R.shape == (2, 1, 3, 3)
    for idx, (s_, th) in (((0, 0), (1.5, 0.25)), ((1, 0), (-2.0, 1.0))):
        np.testing.assert_allclose(G_[idx], 0.5 * gd.n + s_ * gd.t, rtol=0, atol=4 * EPS)
        np.testing.assert_array_equal(E[idx][0], gd.t)
        np.testing.assert_array_equal(E[idx][1], [0.0, 0.0, 0.0])
        # the body axis z stays along a; the body x turns from n by θ about a = e_y
        np.testing.assert_array_equal(R[idx][2], gd.a)
        x = math.cos(th) * gd.n + math.sin(th) * np.cross(gd.a, gd.n)
        np.testing.assert_allclose(R[idx][0], x, rtol=0, atol=4 * EPS)
    np.testing.assert_array_equal(gd.W, [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


def test_the_slide_starts_from_distance_speed_and_spin_zero_by_default() -> None:
    _, eng = sliding(distance=1.5, speed=2.0, spin=-3.0)
    q, qd = eng.layout.guides[0].start({"distance": 1.5, "speed": 2.0, "spin": -3.0})
    np.testing.assert_array_equal(q, [1.5, 0.0])
    np.testing.assert_array_equal(qd, [2.0, -3.0])
    q, qd = eng.layout.guides[0].start({})
    np.testing.assert_array_equal(q, [0.0, 0.0])
    np.testing.assert_array_equal(qd, [0.0, 0.0])
    q, qd = eng.layout.guides[0].start({"speed": 2.0})
    np.testing.assert_array_equal(qd, [2.0, 0.0])
    q, qd = eng.layout.guides[0].start({"spin": 2.0, "distance": 1.0})
    np.testing.assert_array_equal(q, [1.0, 0.0])
    np.testing.assert_array_equal(qd, [0.0, 2.0])


def test_the_slides_series_are_s_v_omega_and_the_slip_v_minus_r_omega() -> None:
    _, eng = sliding()
    q = np.array([[1.0, 9.0], [2.0, 8.0]])
    qd = np.array([[3.0, 4.0], [5.0, -2.0]])
    out = eng.layout.guides[0].series(q, qd)
    np.testing.assert_array_equal(out["s"], [1.0, 2.0])
    np.testing.assert_array_equal(out["v"], [3.0, 5.0])
    np.testing.assert_array_equal(out["omega"], [4.0, -2.0])
    np.testing.assert_array_equal(out["slip"], [1.0, 6.0])
    assert set(out) == {"s", "v", "omega", "slip"}


@pytest.mark.parametrize(("Q_s", "Q_th"), [(3.0, 0.0), (0.0, 2.0), (-1.5, 0.75), (4.0, -1.0)])
def test_the_stick_force_is_what_keeps_the_slip_zero(Q_s, Q_th) -> None:
    """m s̈ = Q_s + F, J θ̈ = Q_θ − r F and s̈ = r θ̈, solved as a linear system."""
    _, eng = sliding()
    A = np.array([[M, 0.0, -1.0], [0.0, J, RADIUS], [1.0, -RADIUS, 0.0]])
    s_dd, th_dd, F = np.linalg.solve(A, [Q_s, Q_th, 0.0])
    assert math.isclose(s_dd, RADIUS * th_dd, rel_tol=4 * EPS, abs_tol=4 * EPS)
    got = eng.layout.guides[0].stick_force(Q_s, Q_th)
    assert math.isclose(got, F, rel_tol=EXACT_RTOL, abs_tol=EXACT_RTOL)


# ------------------------------------------------------------------ the exact flow


def exact_of(eng, duration=2.0, effects=None):
    gd = eng.layout.guides[0]
    others = (
        [e for e in eng.effects if not isinstance(e, GuidesBody)] if effects is None else effects
    )
    o = eng.layout.offsets[0]
    q0, qd0 = eng.y0[o : o + 2].copy(), eng.y0[o + 2 : o + 4].copy()
    return gd.exact(others, M, q0, qd0, duration)


def test_a_ball_thrown_without_spin_on_a_level_floor_rolls_on_at_five_sevenths() -> None:
    """Slipping: s̈ = −μ g, θ̈ = μ m g r/J; the slip v − r ω falls at μ g (1 + m r²/J)
    = 7/2 μ g and vanishes at t_s = 2 v0/(7 μ g); from then it rolls at 5 v0/7 (the
    angular momentum about the contact line m r v + J ω is kept)."""
    v0, mu = 3.0, 0.2
    _, eng = sliding(mu=mu, speed=v0, distance=0.5)
    how, f, events = exact_of(eng)
    assert how == "exact: constant accelerations in each phase, the switch solved exactly"
    ts = 2 * v0 / (7 * mu * G)
    assert len(events) == 1
    ev = events[0]
    assert ev.kind == "rolling"
    assert math.isclose(ev.t, ts, rel_tol=EXACT_RTOL)
    assert set(ev.detail) == {"speed"}
    assert math.isclose(ev.detail["speed"], 5 * v0 / 7, rel_tol=EXACT_RTOL)
    # before the switch
    t = np.array([0.0, 0.5 * ts])
    q, qd = f(t)
    a_s, a_th = -mu * G, mu * M * G * RADIUS / J
    np.testing.assert_allclose(q[:, 0], 0.5 + v0 * t + 0.5 * a_s * t * t, rtol=EXACT_RTOL)
    np.testing.assert_allclose(q[:, 1], 0.5 * a_th * t * t, rtol=EXACT_RTOL)
    np.testing.assert_allclose(qd[:, 0], v0 + a_s * t, rtol=EXACT_RTOL)
    np.testing.assert_allclose(qd[:, 1], a_th * t, rtol=EXACT_RTOL)
    # after it: uniform rolling
    t = np.array([ts * 1.5, 2.0])
    q, qd = f(t)
    s1 = 0.5 + v0 * ts + 0.5 * a_s * ts * ts
    th1 = 0.5 * a_th * ts * ts
    vf = 5 * v0 / 7
    np.testing.assert_allclose(q[:, 0], s1 + vf * (t - ts), rtol=EXACT_RTOL)
    np.testing.assert_allclose(q[:, 1], th1 + vf / RADIUS * (t - ts), rtol=EXACT_RTOL)
    np.testing.assert_allclose(qd, [[vf, vf / RADIUS]] * 2, rtol=EXACT_RTOL)
    # a scalar time gives one state
    q, qd = f(0.0)
    np.testing.assert_array_equal(q, [0.5, 0.0])
    np.testing.assert_array_equal(qd, [v0, 0.0])


@pytest.mark.parametrize(("v0", "w0"), [(2.0, -6.0), (-1.0, 5.0), (1.0, 10.0), (-2.0, -1.0)])
def test_a_sliding_ball_rolls_on_with_the_angular_momentum_about_the_contact_line(v0, w0) -> None:
    """On a level floor m r v + J ω is kept (friction and the normal force act on the
    contact line): it rolls on at v_f = (m r v0 + J ω0)/(m r + J/r)."""
    mu = 0.3
    _, eng = sliding(mu=mu, speed=v0, spin=w0)
    _, f, events = exact_of(eng, duration=50.0)
    vf = (M * RADIUS * v0 + J * w0) / (M * RADIUS + J / RADIUS)
    slip0 = v0 - RADIUS * w0
    ts = abs(slip0) / (3.5 * mu * G)
    (ev,) = events
    assert ev.kind == "rolling"
    assert math.isclose(ev.t, ts, rel_tol=EXACT_RTOL)
    assert math.isclose(ev.detail["speed"], vf, rel_tol=EXACT_RTOL, abs_tol=EXACT_RTOL)
    _, qd = f(np.array([ts + 1.0, 40.0]))
    np.testing.assert_allclose(qd[:, 0], [vf, vf], rtol=EXACT_RTOL, atol=FLOW_ATOL)
    np.testing.assert_allclose(qd[:, 1], [vf / RADIUS] * 2, rtol=EXACT_RTOL, atol=FLOW_ATOL)
    # the slipping phase: friction −μ N sign(slip) along t
    sigma = math.copysign(1.0, slip0)
    _q, qd = f(np.array([0.5 * ts]))
    a_s, a_th = -sigma * mu * G, sigma * mu * M * G * RADIUS / J
    np.testing.assert_allclose(qd[0], [v0 + a_s * ts / 2, w0 + a_th * ts / 2], rtol=EXACT_RTOL)


def test_a_switch_after_the_end_of_the_run_is_not_an_event() -> None:
    v0, mu = 3.0, 0.2
    _, eng = sliding(mu=mu, speed=v0)
    ts = 2 * v0 / (7 * mu * G)
    _, f, events = exact_of(eng, duration=ts * 0.99)
    assert events == []
    _q, qd = f(np.array([ts * 1.5]))  # the slipping phase goes on
    np.testing.assert_allclose(qd[0, 0], v0 - mu * G * ts * 1.5, rtol=EXACT_RTOL)


def test_a_ball_at_rest_on_a_gentle_incline_rolls_down_at_five_sevenths_g_sin_alpha() -> None:
    """μ ≥ (2/7) tan α: static friction holds, s̈ = g sin α/(1 + J/(m r²)) = 5/7 g sin α."""
    alpha = 0.3
    _, eng = sliding(mu=0.5, angle=alpha)
    _how, f, events = exact_of(eng)
    assert events == []
    t = np.array([0.0, 1.0, 2.0])
    q, qd = f(t)
    acc = 5 / 7 * G * math.sin(alpha)
    np.testing.assert_allclose(qd[:, 0], acc * t, rtol=EXACT_RTOL, atol=FLOW_ATOL)
    np.testing.assert_allclose(qd[:, 1], acc * t / RADIUS, rtol=EXACT_RTOL, atol=FLOW_ATOL)
    np.testing.assert_allclose(q[:, 0], 0.5 * acc * t * t, rtol=EXACT_RTOL, atol=FLOW_ATOL)


def test_a_ball_at_rest_on_a_steep_slippery_incline_slides_and_never_rolls() -> None:
    """μ < (2/7) tan α: it slips forward at once: s̈ = g (sin α − μ cos α), θ̈ = μ m g r
    cos α/J; the slip grows, no switch."""
    alpha, mu = 1.0, 0.1
    _, eng = sliding(mu=mu, angle=alpha)
    _, f, events = exact_of(eng)
    assert events == []
    t = np.array([0.5, 2.0])
    _, qd = f(t)
    a_s = G * (math.sin(alpha) - mu * math.cos(alpha))
    a_th = mu * M * G * RADIUS * math.cos(alpha) / J
    np.testing.assert_allclose(qd[:, 0], a_s * t, rtol=EXACT_RTOL)
    np.testing.assert_allclose(qd[:, 1], a_th * t, rtol=EXACT_RTOL)


def test_a_ball_spun_forward_on_a_steep_incline_slips_back_the_other_way() -> None:
    """Slip < 0 (spun forward), μ < (2/7) tan α: friction pushes it down the slope,
    s̈ = g (sin α + μ cos α), θ̈ = −μ m g r cos α/J; the slip rises to 0 at t_s and,
    static friction too weak, it slips on forward: a slip_zero event."""
    alpha, mu, w0 = 1.0, 0.1, 8.0
    _, eng = sliding(mu=mu, angle=alpha, spin=w0)
    _, f, events = exact_of(eng, duration=10.0)
    a_s = G * (math.sin(alpha) + mu * math.cos(alpha))
    a_th = -mu * M * G * RADIUS * math.cos(alpha) / J
    ts = RADIUS * w0 / (a_s - RADIUS * a_th)
    (ev,) = events
    assert ev.kind == "slip_zero"
    assert math.isclose(ev.t, ts, rel_tol=EXACT_RTOL)
    assert math.isclose(ev.detail["speed"], a_s * ts, rel_tol=EXACT_RTOL)
    b_s = G * (math.sin(alpha) - mu * math.cos(alpha))
    b_th = mu * M * G * RADIUS * math.cos(alpha) / J
    tau = 1.0
    q, qd = f(np.array([ts + tau]))
    v1 = a_s * ts
    np.testing.assert_allclose(qd[0], [v1 + b_s * tau, v1 / RADIUS + b_th * tau], rtol=EXACT_RTOL)
    s1 = 0.5 * a_s * ts * ts
    np.testing.assert_allclose(q[0, 0], s1 + v1 * tau + 0.5 * b_s * tau**2, rtol=EXACT_RTOL)


def test_the_exact_flow_is_only_for_gravity_alone_pressing_the_body_down() -> None:
    _, eng = sliding(extra=[{"type": "drag", "body": "ball", "linear": 0.1}])
    assert exact_of(eng) is None
    _, eng = sliding(speed=1.0)
    assert exact_of(eng, effects=[]) is None
    up = type("Up", (), {"type": "gravity", "vector": np.array([0.0, 0.0, 1.0])})()
    assert exact_of(eng, effects=[up]) is None
    flat = type("Flat", (), {"type": "gravity", "vector": np.array([1.0, 0.0, 0.0])})()
    assert exact_of(eng, effects=[flat]) is None  # N = 0: no friction to speak of


# ------------------------------------------------------------------ the loads and switches


def test_slipping_friction_is_mu_n_against_the_slip_at_the_contact_point() -> None:
    alpha, mu = 0.4, 0.25
    f, eng = sliding(mu=mu, angle=alpha, speed=2.0)  # slip 2 > 0
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    assert f.mode == 1.0
    assert f.mode0 == 1.0
    weight = out.F[0].copy()
    f.loads(0.0, s, out)
    N = M * G * math.cos(alpha)
    gd = f.guide
    F = -mu * N * gd.t
    np.testing.assert_allclose(out.F[0] - weight, F, rtol=EXACT_RTOL, atol=EXACT_RTOL)
    # at the contact point −r n: moment (−r n) × F = r μ N (n × t) = r μ N a (it spins
    # the ball up in the rolling sense)
    M_O = s.R[0].T @ out.M_A[0]
    np.testing.assert_allclose(M_O, RADIUS * mu * N * gd.a, rtol=EXACT_RTOL, atol=EXACT_RTOL)


def test_rolling_friction_is_the_stick_force_and_slipping_back_reverses_it() -> None:
    alpha, mu = 0.3, 0.5
    f, eng = sliding(mu=mu, angle=alpha)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)  # zero slip, static friction suffices
    assert f.mode == 0.0
    assert f.mode0 == 0.0
    f.loads(0.0, s, out)
    # F = −J D/(J + m r²) with D = m g sin α: −(2/7) m g sin α along t
    F = -2 / 7 * M * G * math.sin(alpha)
    np.testing.assert_allclose(out.F[0] @ f.guide.t, M * G * math.sin(alpha) + F, rtol=EXACT_RTOL)
    f.mode = -1.0
    out = other_loads(eng, s)
    f.loads(0.0, s, out)
    N = M * G * math.cos(alpha)
    np.testing.assert_allclose(out.F[0] @ f.guide.t, M * G * math.sin(alpha) + mu * N,
                               rtol=EXACT_RTOL)  # fmt: skip


def test_friction_refuses_a_body_leaving_the_plane() -> None:
    f, eng = sliding(speed=1.0)
    s = eng.snapshot(0.0, eng.y0)
    out = Loads(1, s)
    out.F[0] = [0.0, 0.0, 5.0]  # a lift larger than any weight: N = −5
    with pytest.raises(SceneError) as info:
        f.loads(0.5, s, out)
    assert info.value.field == "effects[1].body"
    assert info.value.reason == (
        "body 'ball' would leave the plane at t = 0.5 s (the normal force -5 N ≤ 0; no "
        "lift-off is modelled)"
    )
    out.F[0] = [1.0, 0.0, 0.0]  # N = 0 exactly: refused too
    with pytest.raises(SceneError, match=r"the normal force -?0 N ≤ 0"):
        f.loads(0.25, s, out)


def test_the_switch_function_is_the_signed_slip_or_the_friction_reserve() -> None:
    alpha, mu = 0.3, 0.5
    f, eng = sliding(mu=mu, angle=alpha, speed=2.0, spin=1.0)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    assert f.mode == 1.0  # slip 2 − 0.5 = 1.5
    g, size = f.switch_function(0.0, s, out)
    assert (g, size) == (1.5, 2.5)
    f.mode = -1.0
    assert f.switch_function(0.0, s, out) == (-1.5, 2.5)
    f.mode = 0.0  # rolling: μ N − |F_stick|, with the size μ |N| + |Q_s| + |Q_θ|/r
    g, size = f.switch_function(0.0, s, out)
    N, D = M * G * math.cos(alpha), M * G * math.sin(alpha)
    assert math.isclose(g, mu * N - 2 / 7 * D, rel_tol=EXACT_RTOL)
    assert math.isclose(size, mu * N + D, rel_tol=EXACT_RTOL)


def test_a_switch_from_slipping_projects_onto_zero_slip_and_decides_the_mode() -> None:
    f, eng = sliding(mu=0.5, angle=0.3, speed=2.0, spin=1.0)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    ev = f.switch(0.75, s, out)
    assert ev == Event(0.75, "rolling", {"speed": 2.0})
    _q, qd = s.coords[0]
    np.testing.assert_array_equal(qd, [2.0, 4.0])  # θ̇ = ṡ/r
    assert f.mode == 0.0
    # rolling, the stick force outgrows μ N: slips the way the loads drive it
    ev = f.switch(1.0, s, out)
    assert ev == Event(1.0, "slip", {"speed": 2.0})
    assert f.mode == 1.0  # F_stick < 0 (up the slope): slips down


def test_a_switch_from_slipping_where_static_friction_fails_slips_on() -> None:
    f, eng = sliding(mu=0.1, angle=1.0, spin=8.0)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    assert f.mode == -1.0
    ev = f.switch(0.5, s, out)
    assert ev.kind == "slip_zero"
    assert ev.t == 0.5
    assert ev.detail == {"speed": 0.0}
    assert f.mode == 1.0
    np.testing.assert_array_equal(s.coords[0][1], [0.0, 0.0])


def test_at_zero_slip_the_start_decides_and_a_tie_rolls() -> None:
    """|F_stick| = (2/7) m g sin α against μ m g cos α: at μ = (2/7) tan α exactly (a tie
    up to rounding) either is right; below it slips down (mode +1), above it rolls."""
    for mu, mode in ((0.05, 1.0), (0.2, 0.0)):
        f, eng = sliding(mu=mu, angle=0.5)
        s = eng.snapshot(0.0, eng.y0)
        out = other_loads(eng, s)
        f.begin(0.0, s, out)
        assert f.mode == mode
        assert f.mode0 == mode


def test_friction_does_work_until_its_last_switch_to_rolling() -> None:
    f, _ = sliding()
    roll, slip = Event(0.5, "rolling"), Event(0.75, "slip")
    zero, other = Event(0.6, "slip_zero"), Event(0.9, "impact")
    for q in ("p_x", "L_y", None):
        assert f.acts_until([roll], q) == math.inf
    assert f.acts_until([roll], "E") == 0.5
    assert f.acts_until([roll, other], "E") == 0.5
    assert f.acts_until([slip, roll], "E") == 0.5
    assert f.acts_until([roll, slip], "E") == math.inf
    assert f.acts_until([roll, zero], "E") == math.inf
    f.mode0 = 0.0  # rolling from the start, no switch: no work at all
    assert f.acts_until([], "E") == 0.0
    assert f.acts_until([other], "E") == 0.0
    f.mode0 = 1.0
    assert f.acts_until([], "E") == math.inf


def test_on_a_level_plane_under_gravity_alone_it_reports_m_r_v_plus_j_omega() -> None:
    f, eng = sliding(speed=2.0, spin=-1.0)
    assert f.exerts_moment(0)
    assert not any(f.keeps(q) for q in ("p_x", "p_z", "L_y", "E"))
    s = eng.snapshot(np.array([0.0, 0.0]), np.stack([eng.y0, 2 * eng.y0]))
    out = f.conserved(s)
    L, scale = out["L_contact"]
    # m r v + J ω = 2·0.5·2 + 0.2·(−1) = 1.8, doubled; the size: the largest
    # m r |v| + J |ω| = 2 (2 + 0.2)
    np.testing.assert_allclose(L, [1.8, 3.6], rtol=EXACT_RTOL)
    assert math.isclose(scale, 2 * (2.0 + 0.2), rel_tol=EXACT_RTOL)
    assert set(out) == {"L_contact"}
    for kw in ({"angle": 0.2}, {"extra": [{"type": "drag", "body": "ball", "linear": 0.1}]}):
        f, eng = sliding(speed=2.0, **kw)
        assert f.conserved(eng.snapshot(0.0, eng.y0)) == {}


def test_the_ball_is_found_by_name_among_other_bodies() -> None:
    other = {"name": "rock", "shape": "point", "mass": 1.0}
    f, eng = sliding(first=other, speed=2.0)
    assert f.i == 1
    assert f.guide is eng.layout.guides[1]
    assert f.exerts_moment(1)
    assert not f.exerts_moment(0)


@pytest.mark.parametrize(
    ("body", "effects", "field", "reason"),
    [
        (ball(), [], "effects[0].type",
         "coulomb_friction on a plane needs a gravity effect to press the body on it (the "
         "normal force); none is listed"),
        (ball(velocity=[1.0, 0.0, 0.0]), [{"type": "gravity", "g": 1.0}],
         "bodies[0].initial.velocity", "a body on a coulomb_friction takes distance, speed, spin"),
        ({**ball(), "fixed": True}, [{"type": "gravity", "g": 1.0}], "effects[1].body",
         "body 'ball' is fixed: it cannot slide"),
    ],
)  # fmt: skip
def test_friction_refuses_no_gravity_a_free_bodys_keys_or_a_fixed_body(
    body, effects, field, reason
) -> None:
    err = refusal([body], [*effects, {"type": "coulomb_friction", "body": "ball", "mu": 0.2}])
    assert err.field == field
    assert err.reason == reason


def test_friction_refuses_a_body_that_is_not_round_or_a_slope_out_of_range() -> None:
    box = {"name": "ball", "shape": "box", "mass": 1.0, "a": 1.0, "b": 1.0, "c": 1.0}
    gravity = {"type": "gravity", "g": 1.0}
    err = refusal([box], [gravity, {"type": "coulomb_friction", "body": "ball", "mu": 0.2}])
    assert err.field == "effects[1].body"
    assert "only round bodies roll" in err.reason
    err = refusal(
        [ball()], [gravity, {"type": "coulomb_friction", "body": "ball", "mu": 0.2, "angle": 2.0}]
    )
    assert err.field == "effects[1].angle"


# ------------------------------------------------------------------ a ring: exact numbers

#: a ring of mass 2 and radius 1/2 rolling about its axis z: J = m r² = 1/2, so the
#: stick force is −Q_s/2 + Q_θ/(2 r) and every number below is a dyadic rational
RING = {"name": "ring", "shape": "ring", "mass": 2.0, "radius": 0.5}


def ring_on(effects, mu=0.25, **initial):
    friction = {"type": "coulomb_friction", "body": "ring", "mu": mu}
    eng = Engine(scene_of([{**RING, "initial": initial}], [*effects, friction]))
    return eng.effects[-1], eng


def test_at_an_exact_tie_of_the_stick_force_and_mu_n_it_rolls() -> None:
    """Level plane, g = 10, a push P = 10 along t: N = 20, F_stick = −J P/(J + m r²) =
    −5 = −μ N with μ = 1/4: static friction just holds (|F_stick| ≤ μ N)."""
    push = {"type": "force", "body": "ring", "force": [10.0, 0.0, 0.0]}
    f, eng = ring_on([{"type": "gravity", "g": 10.0}, push])
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    assert f.mode == 0.0
    g, _ = f.switch_function(0.0, s, out)
    assert g == 0.0
    f, eng = ring_on([{"type": "gravity", "g": 10.0}, push], mu=0.25 - 2**-20)
    f.begin(0.0, s, other_loads(eng, s))
    assert f.mode == 1.0  # just too weak: it slips forward


def test_in_the_exact_flow_a_tie_at_the_switch_rolls_on() -> None:
    """Gravity (5, 0, −10) on a level plane: N = 20, D = 10, F_stick = −5 = −μ N.  Spun
    forward (slip −1): friction +μ N = 5, s̈ = 15/2, θ̈ = −5, the slip rises at 10 and
    vanishes at t = 1/10, where static friction just holds: it rolls."""
    _, eng = ring_on([{"type": "gravity", "g": 1.0}], spin=2.0)
    slope = type("G", (), {"type": "gravity", "vector": np.array([5.0, 0.0, -10.0])})()
    gd = eng.layout.guides[0]
    _, _, events = gd.exact([slope], 2.0, np.zeros(2), np.array([0.0, 2.0]), 1.0)
    (ev,) = events
    assert ev.kind == "rolling"
    assert math.isclose(ev.t, 0.1, rel_tol=EXACT_RTOL)


def test_a_switch_exactly_at_the_end_of_the_run_is_an_event() -> None:
    """g = 8, μ = 1/4: N = 16, friction −4: s̈ = −2, θ̈ = r 4/J = 4; the slip 2 falls at
    4 and vanishes at t = 1/2 exactly: a run of 1/2 s sees it."""
    _, eng = ring_on([{"type": "gravity", "g": 8.0}], speed=2.0)
    gd = eng.layout.guides[0]
    _, flow, events = gd.exact(eng.effects[:1], 2.0, np.zeros(2), np.array([2.0, 0.0]), 0.5)
    assert events == [Event(0.5, "rolling", {"speed": 1.0})]
    q, qd = flow(0.5)
    np.testing.assert_array_equal(qd, [1.0, 2.0])
    np.testing.assert_array_equal(q, [0.75, 0.5])


def test_a_light_body_still_presses_on_the_plane() -> None:
    """N = m g = 2·0.25 = 0.5 < 1 N: the exact flow and the loads hold all the same."""
    f, eng = ring_on([{"type": "gravity", "g": 0.25}], speed=1.0)
    gd = eng.layout.guides[0]
    found = gd.exact(eng.effects[:1], 2.0, np.zeros(2), np.array([1.0, 0.0]), 1.0)
    assert found is not None
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    f.loads(0.0, s, out)  # friction −μ N = −1/8 on top of the weight
    np.testing.assert_array_equal(out.F, [[-0.125, 0.0, -0.5]])


def test_a_couple_about_the_axis_enters_the_stick_force_and_the_switch_size() -> None:
    """Level plane, g = 10, a couple τ = 1 about a = e_y: Q_s = 0, Q_θ = 1, F_stick =
    m r Q_θ/(J + m r²) = 1; switch function μ N − 1 with the size μ N + |Q_θ|/r."""
    couple = {"type": "torque", "body": "ring", "torque": [0.0, 1.0, 0.0]}
    f, eng = ring_on([{"type": "gravity", "g": 10.0}, couple], speed=1.0, spin=2.0)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    assert f.mode == 0.0
    assert f.switch_function(0.0, s, out) == (5.0 - 1.0, 5.0 + 2.0)
    f.loads(0.0, s, out)
    np.testing.assert_array_equal(out.F, [[1.0, 0.0, -20.0]])


def test_friction_pushes_only_its_own_body() -> None:
    rock = {"name": "rock", "shape": "point", "mass": 1.0}
    f, eng = sliding(first=rock, speed=2.0)
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.begin(0.0, s, out)
    f.loads(0.0, s, out)
    np.testing.assert_array_equal(out.F[0], [0.0, 0.0, -10.0])  # the rock's weight only
    np.testing.assert_array_equal(out.M_A[0], [0.0, 0.0, 0.0])
    np.testing.assert_allclose(out.F[1], [-0.2 * 20.0, 0.0, -20.0], rtol=EXACT_RTOL)


def test_a_new_friction_rolls_until_its_start_decides() -> None:
    f, eng = sliding(speed=2.0)
    assert f.mode == 0.0
    assert f.mode0 == 0.0
    assert f.acts_until([], "E") == 0.0
    s = eng.snapshot(0.0, eng.y0)
    out = other_loads(eng, s)
    f.loads(0.0, s, out)  # the stick force on a level floor: none
    np.testing.assert_array_equal(out.F, [[0.0, 0.0, -20.0]])


def test_a_friction_built_without_a_scene_reads_its_fields() -> None:
    spec = scene_of(
        [ball()],
        [{"type": "gravity", "g": 1.0},
         {"type": "coulomb_friction", "body": "ball", "mu": 0.3, "angle": 0.25}],
    ).effects[1]  # fmt: skip
    f = type(sliding()[0])(spec)
    assert (f.mu, f.alpha, f.i, f.guide, f.ctx) == (0.3, 0.25, 0, None, None)
    assert f._flat is False
    flat = type(f)(scene_of([ball()], [{"type": "gravity", "g": 1.0},
                                       {"type": "coulomb_friction", "body": "ball",
                                        "mu": 0.3}]).effects[1])  # fmt: skip
    assert flat._flat is True


def test_the_flow_at_a_switch_time_is_the_projected_state() -> None:
    """At t = t_s the flow gives the next phase's start: exactly on zero slip."""
    for v0 in (0.3, 1.1, 2.9, 3.7, 5.3, 7.1, 9.7):
        _, eng = sliding(mu=0.3, speed=v0)
        _, f, (ev,) = exact_of(eng, duration=50.0)
        _, qd = f(ev.t)
        assert qd[1] == qd[0] / RADIUS
