"""The free-body engine: each effect against a closed form, the invariants it declares,
rigid-body contacts and simultaneous impacts, and the combinations it refuses."""

from __future__ import annotations

import dataclasses
import functools
import math
import re

import numpy as np
import pytest
from hypothesis import assume, event, example, given, reject, settings
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.impact import RigidBody, rigid_impact
from mechanics.scenes import SceneError, parse_scene, run_scene
from mechanics.scenes import effects as fx
from mechanics.scenes.budget import BudgetError

from .builders import ball as _ball
from .builders import box as _box
from .builders import cylinder, scene
from .builders import point as _point

#: DOP853 at rtol = atol = 1e-12 over a few periods of an O(1) motion: the global error
#: is ~1e-11 relative; 2^20 eps = 2.3e-10 leaves a factor of 20
INTEGRATED_RTOL = 2**20 * EPS
#: one impulse in closed form: a handful of roundings of O(1) terms
IMPULSE_RTOL = 256 * EPS
#: a random scene is a whole run (~50 ms): 3/10 of the profile's examples (30 under
#: ci and dev, 300 under explore, which hunts)
SCENE_EXAMPLES = max(10, settings.default.max_examples * 3 // 10)
#: the random corner drops' step cap.  Two runs of 306 draws each (dev profile, the steps
#: counted at budget.Clock.step): every draw took at most 44 steps (median 12) but 5 and 7
#: (~2 %) that passed 400, each a corner's stiff slip onset; 100 is 2.3× the largest
#: ordinary run and ~1.5 s of a stiff one
CORNER_MAX_STEPS = 100

_scene = functools.partial(scene, name="engine", duration=1.0, samples=101, method="auto")
_cylinder = functools.partial(cylinder, mass=2.0)


def _conserved(r) -> set[str]:
    return {c.name for c in r.conserved}


# ------------------------------------------------------------------ each effect


def test_newton_gravity_closes_a_circular_orbit_in_its_period() -> None:
    # two unit masses 1 apart, G = 1: μ = G (m1 + m2) = 2, relative speed √(μ/a)
    w = math.sqrt(2.0) / 2
    T = 2 * math.pi / math.sqrt(2.0)  # 2π √(a³/μ)
    r = run_scene(
        _scene(
            [
                _point("a", position=[0.5, 0, 0], velocity=[0, w, 0]),
                _point("b", position=[-0.5, 0, 0], velocity=[0, -w, 0]),
            ],
            [{"type": "newton_gravity", "G": 1.0}],
            duration=T,
        )
    )
    assert r.passed, r.summary()
    s = r.trajectory.series
    end = np.array([s["a.x"][-1], s["a.y"][-1], s["b.x"][-1], s["b.y"][-1]])
    np.testing.assert_allclose(end, [0.5, 0, -0.5, 0], rtol=0, atol=64 * INTEGRATED_RTOL)
    half = len(r.trajectory.t) // 2  # half a period: the pair has turned by π
    assert s["a.x"][half] == pytest.approx(-0.5, abs=64 * INTEGRATED_RTOL)
    assert _conserved(r) == {"p_x", "p_y", "p_z", "L_x", "L_y", "L_z", "E"}


def test_a_spring_attached_off_the_centre_turns_the_body() -> None:
    spring = {"type": "spring", "body": "box", "at": [0.1, 0.2, 0.0], "stiffness": 5.0}
    r = run_scene(_scene([_box(position=[1.0, 0.5, 0.2])], [spring], duration=3.0))
    assert r.passed, r.summary()
    assert r.method.startswith("integrated")
    s = r.trajectory.series
    assert max(np.abs(s["omega1"]).max(), np.abs(s["omega3"]).max()) > 0.1, "it turns"
    # the anchor is the origin: central force, so L about the origin is kept; energy too
    assert _conserved(r) == {"L_x", "L_y", "L_z", "E"}
    # the same spring at G exerts no moment: no rotation at all
    at_G = {k: v for k, v in spring.items() if k != "at"}
    r0 = run_scene(_scene([_box(position=[1.0, 0.5, 0.2])], [at_G], duration=3.0))
    assert r0.passed
    assert not any(np.abs(r0.trajectory.series[f"omega{k}"]).max() for k in (1, 2, 3))


def test_a_damped_spring_between_two_bodies_keeps_the_momentum_and_dissipates() -> None:
    spring = {
        "type": "spring",
        "body": "a",
        "other": "b",
        "stiffness": 4.0,
        "rest_length": 1.0,
        "damping": 0.5,
    }
    r = run_scene(
        _scene(
            [
                _point("a", position=[0, 0, 0], velocity=[1.0, 0.3, 0]),
                _point("b", mass=2.0, position=[1.5, 0, 0], velocity=[0, -0.2, 0.1]),
            ],
            [spring],
            duration=10.0,
        )
    )
    assert r.passed, r.summary()
    assert _conserved(r) == {"p_x", "p_y", "p_z", "L_x", "L_y", "L_z"}
    E = r.trajectory.series["E"]
    assert np.all(np.diff(E) <= INTEGRATED_RTOL * E[0]), "a damper never adds energy"
    assert E[-1] < 0.9 * E[0]


def test_drag_follows_the_closed_forms() -> None:
    m, v0, b, c = 2.0, 3.0, 0.4, 0.3
    r = run_scene(
        _scene(
            [
                _point("lin", mass=m, velocity=[v0, 0, 0]),
                _point("quad", mass=m, velocity=[v0, 0, 0]),
                {
                    "name": "ball",
                    "shape": "solid_sphere",
                    "mass": m,
                    "radius": 0.5,
                    "initial": {"omega": [0.0, 0.0, v0]},
                },
            ],
            [
                {"type": "drag", "body": "lin", "linear": b},
                {"type": "drag", "body": "quad", "quadratic": c},
                {"type": "drag", "body": "ball", "angular_linear": b},
            ],
            duration=4.0,
        )
    )
    assert r.passed, r.summary()
    t, s = r.trajectory.t, r.trajectory.series
    J = 0.4 * m * 0.25
    tol = 16 * INTEGRATED_RTOL
    np.testing.assert_allclose(s["lin.vx"], v0 * np.exp(-b * t / m), rtol=tol)
    np.testing.assert_allclose(s["lin.x"], v0 * m / b * -np.expm1(-b * t / m), rtol=tol, atol=tol)
    np.testing.assert_allclose(s["quad.vx"], v0 / (1 + c * v0 * t / m), rtol=tol)
    np.testing.assert_allclose(s["quad.x"], m / c * np.log1p(c * v0 * t / m), rtol=tol, atol=tol)
    np.testing.assert_allclose(s["ball.omega3"], v0 * np.exp(-b * t / J), rtol=tol)
    assert "E" not in _conserved(r)


def test_a_push_and_a_couple_give_their_impulses() -> None:
    m, a = 2.0, 0.5
    J = 0.4 * m * a * a
    ball = {"name": "ball", "shape": "solid_sphere", "mass": m, "radius": a}
    effects = [
        {"type": "force", "body": "ball", "force": [0.0, 4.0, 0.0], "start": 0.1, "end": 0.35},
        # body-fixed, at a point off G, perpendicular to its arm: a constant moment about e3
        {
            "type": "force",
            "body": "ball",
            "force": [0.0, 2.0, 0.0],
            "at": [a, 0.0, 0.0],
            "frame": "body",
            "start": 0.5,
            "end": 0.75,
        },
        {"type": "torque", "body": "ball", "torque": [0.5, 0.0, 0.0], "start": 1.0, "end": 1.5},
    ]
    r = run_scene(_scene([ball], effects[:1], duration=1.0))
    assert r.passed, r.summary()
    assert r.trajectory.state_at(1.0)["vy"] == pytest.approx(4.0 * 0.25 / m, rel=IMPULSE_RTOL)
    r = run_scene(_scene([{**ball, "initial": {}}], effects[1:2], duration=1.0))
    assert r.passed, r.summary()
    # the arm and the force turn together: ω3 grows by (a · 2 N) Δt / J
    assert r.trajectory.state_at(1.0)["omega3"] == pytest.approx(
        a * 2.0 * 0.25 / J, rel=INTEGRATED_RTOL
    )
    r = run_scene(_scene([ball], effects[2:], duration=2.0))
    assert r.passed, r.summary()
    assert r.trajectory.state_at(2.0)["omega1"] == pytest.approx(0.25 / J, rel=INTEGRATED_RTOL)
    assert r.trajectory.state_at(2.0)["vy"] == 0.0


def test_body_frame_thrust_on_a_body_that_does_not_turn_equals_space_thrust() -> None:
    def rocket(frame):
        return _scene(
            [{"name": "r", "shape": "cylinder", "mass": 10.0, "radius": 0.2, "height": 2.0}],
            [
                {
                    "type": "thrust",
                    "body": "r",
                    "mass_flow": 1.0,
                    "exhaust_speed": 50.0,
                    "fuel_mass": 4.0,
                    "direction": [0.0, 0.0, 1.0],
                    "frame": frame,
                }
            ],
            duration=6.0,
            method="integrate",
        )

    a, b = run_scene(rocket("space")), run_scene(rocket("body"))
    assert a.passed
    assert b.passed
    np.testing.assert_allclose(a.trajectory.series["vz"], b.trajectory.series["vz"], rtol=0, atol=0)
    # (7.30) without gravity: v = u ln(m0 / m)
    assert a.trajectory.state_at(6.0)["vz"] == pytest.approx(
        50.0 * math.log(10.0 / 6.0), rel=INTEGRATED_RTOL
    )


# ------------------------------------------------------------------ contacts


def _dropped_box(e=0.6, duration=0.5, method="auto"):
    return _scene(
        [_box(position=[0.0, 0.0, 1.0], psi=0.3, theta=0.7, phi=0.2, omega=[0.5, -1.0, 2.0])],
        [
            {"type": "gravity", "g": 9.81},
            {"type": "impact", "body": "box", "restitution": e},
        ],
        duration=duration,
        samples=501,
        method=method,
    )


def test_a_box_dropped_on_a_corner_restitutes_at_that_corner() -> None:
    r = run_scene(_dropped_box())
    assert r.method.startswith("integrated")
    assert r.passed, r.summary()
    ev = r.trajectory.events[0]
    assert "corner" in ev.detail["feature"]
    assert ev.detail["normal_speed_after"] == pytest.approx(
        0.6 * ev.detail["normal_speed_before"], rel=IMPULSE_RTOL
    )
    assert min(r.trajectory.gaps.values(), key=np.min).min() >= -64 * EPS


def _spy_on_impulses(monkeypatch) -> list:
    """Record, at each impulse of a body against a plane, (the arm S − r_G, v_G and ω
    after, :func:`mechanics.impact.rigid_impact`'s result on the state before, the
    attitude's departure from orthogonality)."""
    seen = []
    real = fx.Impact._apply

    def spy(self, s, S, n, v_n):
        i = self.i
        R = s.R[i]
        before = RigidBody(
            s.m[i],
            R.T @ np.diag(s.J[i]) @ R,
            s.r[i].copy(),
            s.v[i].copy(),
            s.to_space(i, s.omega[i]),
        )
        ref = rigid_impact(before, None, r_S=S, n=n, e=self.e).body_1
        orth = float(np.abs(R @ R.T - np.eye(3)).max())
        real(self, s, S, n, v_n)
        seen.append((S - s.r[i], s.v[i].copy(), s.to_space(i, s.omega[i]), ref, orth))

    monkeypatch.setattr(fx.Impact, "_apply", spy)
    return seen


def test_the_corner_impulse_agrees_with_mechanics_impact(monkeypatch) -> None:
    """Independent route: the engine's impulse against :func:`mechanics.impact.rigid_impact`
    (a 3 × 3 solve in space components) on the state just before each impact.  The two
    routes agree up to the rounding and to the integrated attitude's departure from
    orthogonality (the engine works in body components, the reference with Rᵀ J R)."""
    seen = _spy_on_impulses(monkeypatch)
    r = run_scene(_dropped_box(duration=0.45))
    assert len(r.trajectory.events) == len(seen) >= 2
    for _, v, w, ref, orth in seen:
        # the velocities are O(1)-O(10): a unit of absolute error per unit of speed
        tol = (IMPULSE_RTOL + 64 * orth) * (1.0 + np.abs(ref.omega).max())
        np.testing.assert_allclose(v, ref.v_G, rtol=0, atol=tol)
        np.testing.assert_allclose(w, ref.omega, rtol=0, atol=tol)


def _ball_on_rough_floor(vx, mu, e=0.5, wy=0.0):
    a, m = 0.1, 2.0
    return _scene(
        [
            {
                "name": "ball",
                "shape": "solid_sphere",
                "mass": m,
                "radius": a,
                "initial": {
                    "position": [0, 0, 0.3],
                    "velocity": [vx, 0, -2.0],
                    "omega": [0, wy, 0],
                },
            }
        ],
        [{"type": "impact", "body": "ball", "restitution": e, "friction": mu}],
        duration=0.2,
    )


def test_a_ball_that_sticks_on_a_rough_floor_leaves_rolling_at_five_sevenths() -> None:
    """Stick: the angular momentum about the contact point is kept (the impulse acts
    there), m v a = m v' a + (2/5) m a² ω', and rolling v' = ω' a gives v' = 5 v / 7."""
    r = run_scene(_ball_on_rough_floor(vx=1.0, mu=2.0))
    assert r.passed, r.summary()
    (ev,) = r.trajectory.events
    assert ev.detail["friction"] == "stick"
    after = r.trajectory.state_at(0.2)
    assert after["vx"] == pytest.approx(5 / 7, rel=IMPULSE_RTOL)
    assert after["wy"] * 0.1 == pytest.approx(5 / 7, rel=IMPULSE_RTOL)  # rolls: ω a = v
    assert after["vz"] == pytest.approx(0.5 * 2.0, rel=IMPULSE_RTOL)


def _sticking_corner(duration: float) -> dict:
    """A box whose corner 1 strikes a rough floor (μ = 0.75, e = 0) at t = 0.371 s and
    sticks, until its friction reaches the cone at t = 0.4011 s (found by make test, as
    an example of the random rough-corner test)."""
    a = 2.2460138109030545
    box = _box(position=[0.0, 0.0, 1.0], psi=0.05, theta=a, phi=0.05, omega=[0.05, a, 0.05])
    effects = [
        {"type": "gravity", "g": 9.81},
        {"type": "impact", "body": "box", "restitution": 0.0, "friction": 0.75},
    ]
    return _scene([box], effects, duration=duration, samples=46)


def _stick_then_slip(r) -> None:
    assert r.passed, r.summary()
    kinds = [(e.kind, e.detail.get("friction")) for e in r.trajectory.events]
    assert kinds == [("impact", "stick"), ("rest", "stick"), ("slip", "slip")], kinds


def test_a_sticking_corner_whose_friction_reaches_the_cone_switches_to_slip_once() -> None:
    """It used to slip in directions the rounding chose, switching ~10^10 times (the
    stick's slip drift read as a slip; ran past an hour): it slips the way its friction
    pointed, one switch.  The run ends 3 µs into the slip (the next test runs on)."""
    _stick_then_slip(run_scene(_sticking_corner(0.401111)))


@pytest.mark.slow
def test_a_corner_that_begins_to_slip_slips_on_to_the_end_with_one_switch() -> None:
    """The same corner, on to 0.45 s (about 40 s: slow tier, ``make test-slow``).  Why it
    costs: just after the onset the slip u is tiny, and Coulomb's friction −μ λ u/|u|
    relaxes any slip across ŝ at the rate μ λ K/|u| (K the contact's inverse mass): a
    stiff mode, which an explicit method follows with steps ~|u|/(μ λ K) (4,000 steps
    of ~5 ns over the first 0.1 ms).  No further switch, and every self-check passes."""
    _stick_then_slip(run_scene(_sticking_corner(0.45)))


def test_a_ball_that_slips_on_a_rough_floor_gets_mu_times_the_normal_impulse() -> None:
    """Slip: S_n = (1 + e) m |v_n|, S_t = μ S_n against the slip, so Δv_x = −μ (1 + e) |v_n|
    and the spin gains a μ S_n / J = (5/2) μ (1 + e) |v_n| / a."""
    mu, e, vn, a = 0.05, 0.5, 2.0, 0.1  # sticking needs S_t = (2/7) m v = 0.57 > μ S_n = 0.3
    r = run_scene(_ball_on_rough_floor(vx=1.0, mu=mu, e=e))
    assert r.passed, r.summary()
    (ev,) = r.trajectory.events
    assert ev.detail["friction"] == "slip"
    after = r.trajectory.state_at(0.2)
    assert after["vx"] == pytest.approx(1.0 - mu * (1 + e) * vn, rel=IMPULSE_RTOL)
    assert after["wy"] == pytest.approx(2.5 * mu * (1 + e) * vn / a, rel=IMPULSE_RTOL)


@settings(max_examples=SCENE_EXAMPLES)
@example(w=(1.0, 1.0, 0.0), angles=(1.0, 1.0, 1.0), mu=1.0, e=0.0625)  # a missed contact
@example(w=(0.0, 1.0, 0.0), angles=(1.0, 1.0, 1.0), mu=1.0, e=0.0625)  # after a touch
# rebounds whose hop stays below the gap's rounding (found by CI's derandomised run)
@example(w=(1.375, -1.625, 0.0), angles=(1.0, 1.5, 2.96875), mu=1.0, e=0.044921875)
@example(w=(1.0, 1.5, 2.96875), angles=(1.375, 0.0625, 0.0625), mu=1.0, e=0.044921875)
# a slip direction of subnormal size (|u_t| underflowed; found by the explore profile)
@example(w=(0.0, 0.0, 8.195866755129457e-293), angles=(1.0, 1.0, 1.0), mu=0.25, e=0.0)
# an impulse at one corner makes a merely touching one close (found by make test)
@example(w=(0.0, 0.0, 1.0), angles=(1.0, 1.5, 0.5), mu=0.0, e=0.0)
# (a corner sticking until its friction reaches the cone: its own tests below)
@given(
    w=st.tuples(*[st.floats(-5, 5)] * 3),
    angles=st.tuples(*[st.floats(0.05, 3.0)] * 3),
    mu=st.floats(0.0, 2.0),
    e=st.floats(0.0, 1.0),
)
def test_random_rough_corner_impacts_restitute_and_dissipate(w, angles, mu, e) -> None:
    """Any tilt, spin, friction and restitution: every run passes its self-checks (the
    loss read off the velocities equals the impulse's work, and no impact adds energy).

    A run is capped at :data:`CORNER_MAX_STEPS` steps, and a draw that reaches the cap is
    rejected (``reject``, counted by hypothesis, never a pass): those are the ~2 % of
    draws in which a corner comes to rest and then begins to slip, whose stiff onset
    takes thousands of explicit steps (125–210 s for one draw; the stiffness is explained
    and run to its end in ``test_a_corner_that_begins_to_slip_slips_on_to_the_end_with_one_switch``,
    slow tier)."""
    psi, theta, phi = angles
    box = _box(position=[0.0, 0.0, 1.0], psi=psi, theta=theta, phi=phi, omega=list(w))
    sc = _scene(
        [box],
        [
            {"type": "gravity", "g": 9.81},
            {"type": "impact", "body": "box", "restitution": e, "friction": mu},
        ],
        duration=0.45,
        samples=46,
        max_steps=CORNER_MAX_STEPS,
    )
    capped = refusal = None
    try:
        r = run_scene(sc)
    except BudgetError as exc:
        capped = str(exc)
    except SceneError as exc:
        refusal = str(exc)
    if capped is not None:
        assert "max_steps" in capped, capped  # the step cap, never the wall clock
        event("rejected: a stiff slip onset reached the step cap")
        reject()
    if refusal is not None:
        # refused, never run half-way: a box coming to rest on the floor, an impulse
        # that Newton's e with friction would make gain energy (Kane's paradox), or
        # several corners meeting the floor at once while sliding (not modelled)
        refusals = (
            "come to rest in contact",
            "come to rest at t",  # a rest the resting contact cannot treat
            "would add",
            "a resting contact",
            "friction that slides are not modelled",
        )
        assert any(r in refusal for r in refusals), refusal
        return
    assert r.passed, r.summary()
    for ev in r.trajectory.events:
        if ev.kind != "impact":  # it comes to rest: the support's own self-checks
            continue
        d = ev.detail
        if d["impact_model"] == "simultaneous":  # Newton's law at each, or none needed
            speeds = zip(d["normal_speeds_before"], d["normal_speeds_after"], strict=True)
            for P, (before, after) in zip(d["impulses"], speeds, strict=True):
                want = e * max(before, 0.0)
                if P > 0:
                    assert after == pytest.approx(want, rel=IMPULSE_RTOL, abs=IMPULSE_RTOL)
                else:
                    assert after >= want - IMPULSE_RTOL * (1.0 + want)
            continue
        assert d["normal_speed_after"] == pytest.approx(
            e * d["normal_speed_before"], rel=IMPULSE_RTOL, abs=IMPULSE_RTOL
        )


def test_a_box_released_from_a_resting_corner_by_an_impact_at_another_is_not_refused(
    monkeypatch,
) -> None:
    """Found by hypothesis's random profile: a box (e = 0, smooth) comes to rest on corner
    7, pivots on it, and corner 6 strikes the floor; the impulse lets corner 7 go with
    the gap its support's drift left (−2.5e-14, beyond a fresh contact's start rounding
    of ~2.4e-14), which the old search refused as a missed contact."""
    box = _box(
        position=[0.0, 0.0, 1.0], psi=1.0, theta=0.0546875, phi=0.125, omega=[-3.546875, 0, 0]
    )
    sc = _scene(
        [box],
        [
            {"type": "gravity", "g": 9.81},
            {"type": "impact", "body": "box", "restitution": 0.0, "friction": 0.0},
        ],
        duration=0.45,
        samples=46,
    )
    r = run_scene(sc)
    assert r.passed, r.summary()
    kinds = [(e.kind, e.detail.get("feature")) for e in r.trajectory.events]
    assert any(k == "impact" for k, _ in kinds), kinds  # the strike that lets go
    # negative control: with no drift allowed at a release, the old refusal comes back
    from mechanics.scenes import collision

    monkeypatch.setattr(collision, "CONSERVED_RTOL_INTEGRATED", 0.0)
    with pytest.raises(SceneError, match=r"corner 7 .* a contact was missed"):
        run_scene(sc)


def test_an_impulse_that_would_add_energy_is_refused_with_one_line() -> None:
    """Kane's paradox, found by the random test: a tilted box on a very rough floor,
    where Newton's e with Coulomb friction would add 18 % of the kinetic energy."""
    box = _box(position=[0.0, 0.0, 1.0], psi=1.0, theta=1.5, phi=2.0)
    effects = [
        {"type": "gravity", "g": 9.81},
        {"type": "impact", "body": "box", "restitution": 1.0, "friction": 1.0},
    ]
    with pytest.raises(SceneError, match=r"would add .* J of kinetic energy") as info:
        run_scene(_scene([box], effects, duration=0.45))
    assert info.value.field == "effects[1].friction"
    # the whole line a user reads: which impulse, the friction and e, the gain, the name
    # of the paradox and what to change (the numbers' digits are the run's own)
    assert re.fullmatch(
        r"engine\.toml: effects\[1\]\.friction: body 'box' and the plane \(corner \d of 'box'\) "
        r"at t = \S+ s: the slip impulse with friction 1 and e = 1 would add \S+ J of kinetic "
        r"energy \(Newton's restitution with friction, Kane's paradox\); lower the friction or e",
        str(info.value),
    )
    effects[1]["friction"] = 0.0  # smooth: the same drop is fine
    assert run_scene(_scene([box], effects, duration=0.45)).passed


def test_an_impact_that_adds_energy_fails_the_dissipation_check(monkeypatch) -> None:
    """Negative control of the self-check behind the refusal: an impulse whose loss is
    reported negative (but within the refusal's rounding) is caught by the run."""
    from mechanics.scenes.result import conserved_tolerance, self_checks

    r = run_scene(_ball_on_rough_floor(vx=1.0, mu=0.1))
    d = r.trajectory.events[0].detail
    d["energy_loss"] = -1e-6 * d["kinetic_energy_before"]
    d["kinetic_energy_after"] = d["kinetic_energy_before"] - d["energy_loss"]
    tol = conserved_tolerance(r.scene, r.trajectory)
    bad = {c.name.split(" (")[0] for c in self_checks(r.trajectory, tol) if not c.ok}
    assert bad == {"impacts dissipate"}


def test_newtons_cradle_passes_the_momentum_down_the_row() -> None:
    r_ = 0.1
    balls = [
        {
            "name": f"b{k}",
            "shape": "solid_sphere",
            "mass": 1.0,
            "radius": r_,
            "initial": {"position": [2 * r_ * k + (0.0 if k else -0.3), 0.0, 0.0]}
            | ({"velocity": [1.0, 0.0, 0.0]} if k == 0 else {}),
        }
        for k in range(5)
    ]
    impacts = [
        {"type": "impact", "body": f"b{k + 1}", "other": f"b{k}", "restitution": 1.0}
        for k in range(4)
    ]
    for method in ("auto", "integrate"):
        r = run_scene(_scene(balls, impacts, duration=1.0, method=method))
        assert r.passed, r.summary()
        ev = r.trajectory.events
        assert len(ev) == 4
        assert len({e.t for e in ev}) == 1, "four impacts at one instant"
        assert ev[0].t == pytest.approx(0.3, rel=IMPULSE_RTOL)
        end = [r.trajectory.state_at(1.0)[f"b{k}.vx"] for k in range(5)]
        np.testing.assert_allclose(end, [0, 0, 0, 0, 1.0], rtol=0, atol=IMPULSE_RTOL)


def test_exact_and_integrated_flights_of_a_spinning_box_agree() -> None:
    box = _box(position=[0, 0, 5.0], velocity=[1.0, 0.5, 3.0], omega=[0.3, 2.0, 0.1], theta=0.4)
    sc = _scene([box], [{"type": "gravity", "g": 9.81}], duration=1.0)
    ex, it = run_scene(sc), run_scene(dataclasses.replace(sc, method="integrate"))
    assert ex.method.startswith("exact")
    assert it.method.startswith("integrated")
    assert ex.passed, ex.summary()
    assert it.passed, it.summary()
    for key in ("x", "z", "vz", "omega1", "omega2", "omega3"):
        a, b = ex.trajectory.series[key], it.trajectory.series[key]
        assert np.max(np.abs(a - b)) <= 64 * INTEGRATED_RTOL * max(1.0, np.max(np.abs(a))), key
    assert {"L_x (spin about G)", "L_z"} <= _conserved(ex)


# ------------------------------------------------------------------ invariants

#: effect templates for two bodies a (a sphere) and b (a box), and what each keeps of
#: p_x p_y p_z L_x L_y L_z E, written from the physics (not read from the code)
EFFECTS = {
    "gravity": ({"type": "gravity", "g": 9.81}, {"p_x", "p_y", "L_z", "E"}),
    "newton": (
        {"type": "newton_gravity", "G": 0.05},
        {"p_x", "p_y", "p_z", "L_x", "L_y", "L_z", "E"},
    ),
    "spring": (
        {
            "type": "spring",
            "body": "a",
            "other": "b",
            "other_at": [0.1, 0.0, 0.3],
            "stiffness": 3.0,
        },
        {"p_x", "p_y", "p_z", "L_x", "L_y", "L_z", "E"},
    ),
    "damper": (
        {"type": "damper", "body": "a", "other": "b", "at": [0.0, 0.2, 0.0], "damping": 0.3},
        {"p_x", "p_y", "p_z", "L_x", "L_y", "L_z"},
    ),
    "anchored": (
        {"type": "spring", "body": "b", "at": [0.1, 0.1, 0.0], "stiffness": 2.0},
        {"L_x", "L_y", "L_z", "E"},
    ),
    "drag": ({"type": "drag", "body": "a", "quadratic": 0.2, "angular_linear": 0.1}, set()),
    "couple": ({"type": "torque", "body": "b", "torque": [0.0, 0.3, 0.1]}, {"p_x", "p_y", "p_z"}),
}


@settings(max_examples=SCENE_EXAMPLES)
# a subnormal spin: the top's pole vector from J ω, which underflowed (explore profile)
@example(chosen=["anchored"], va=(0.0, 0.0, 0.0), wb=(0.0, 5e-324, 5e-324))
@given(
    chosen=st.lists(st.sampled_from(sorted(EFFECTS)), min_size=1, max_size=4, unique=True),
    va=st.tuples(*[st.floats(-1, 1)] * 3),
    wb=st.tuples(*[st.floats(-2, 2)] * 3),
)
def test_random_effect_sets_conserve_what_their_physics_keeps(chosen, va, wb) -> None:
    bodies = [
        {
            "name": "a",
            "shape": "solid_sphere",
            "mass": 1.5,
            "radius": 0.2,
            "initial": {
                "position": [0.0, 0.0, 0.0],
                "velocity": list(va),
                "omega": [0.0, 0.0, 1.0],
            },
        },
        _box("b", mass=2.0, position=[1.0, 0.3, -0.2], omega=list(wb)),
    ]
    r = run_scene(_scene(bodies, [EFFECTS[k][0] for k in chosen], duration=1.0, samples=41))
    expected = set.intersection(*(EFFECTS[k][1] for k in chosen))
    assert {c for c in _conserved(r) if "spin" not in c} == expected
    assert r.passed, r.summary()


def test_an_effect_that_claims_too_much_fails_the_run(monkeypatch) -> None:
    """Negative control: drag declared energy-keeping is caught by the drift check."""
    monkeypatch.setattr(fx.Drag, "keeps", lambda self, q: True)
    r = run_scene(
        _scene([_point("a", velocity=[1.0, 0, 0])], [{"type": "drag", "body": "a", "linear": 0.5}])
    )
    assert "E" in _conserved(r)
    assert not r.passed
    assert [c.name for c in r.conserved if not c.ok] == ["p_x", "E"]


# ------------------------------------------------------------------ refused


@pytest.mark.parametrize(
    ("bodies", "effects", "where", "match"),
    [
        (
            [_point("a")],
            [{"type": "torsion", "body": "a", "stiffness": 1.0}],
            "effects[0].type",
            "fixed_axis",
        ),
        (
            [_point("a")],
            [{"type": "spring", "body": "a", "at": [0.1, 0, 0], "stiffness": 1.0}],
            "effects[0].at",
            "is a point",
        ),
        (
            [_box("a"), _box("b", position=[2.0, 0, 0])],
            [{"type": "impact", "body": "a", "other": "b", "restitution": 0.5}],
            "effects[0].other",
            "two polyhedral",
        ),
        (
            [{"name": "d", "shape": "disc", "mass": 1.0, "radius": 0.1}, _point("p")],
            [{"type": "impact", "body": "d", "other": "p", "restitution": 0.5}],
            "effects[0].body",
            "the rim of a disc",
        ),
        (
            [_point("a", omega=[0, 0, 1.0])],
            [],
            "bodies[0].initial.omega",
            "no attitude",
        ),
        (
            [
                {
                    "name": "rod",
                    "shape": "rod",
                    "mass": 1.0,
                    "length": 1.0,
                    "initial": {"omega": [0, 0, 1.0]},
                }
            ],
            [],
            "bodies[0].initial.omega",
            "zero principal moment",
        ),
        (
            [_point("a", position=[0, 0, 0.05])],
            [
                {"type": "impact", "body": "a", "restitution": 0.5},
                {
                    "type": "thrust",
                    "body": "a",
                    "mass_flow": 1.0,
                    "exhaust_speed": 1.0,
                    "fuel_mass": 1.0,
                },
            ],
            "effects[1].fuel_mass",
            "less than the body's mass",
        ),
        (
            [_box("b", position=[0, 0, 0.1])],
            [{"type": "impact", "body": "b", "restitution": 0.5}],
            "effects[0]",
            "overlap at t = 0",
        ),
        (
            [_point("a", velocity=[1.0, 0, 0]) | {"fixed": True}],
            [],
            "bodies[0].initial.velocity",
            "stays at rest",
        ),
        (
            [_point("a")],
            [{"type": "force", "body": "a", "force": [1, 0, 0], "start": 2.0, "end": 1.0}],
            "effects[0].end",
            "after start",
        ),
    ],
)
def test_combinations_that_make_no_physical_sense_are_refused(
    bodies, effects, where, match
) -> None:
    with pytest.raises(SceneError, match=match) as info:
        _scene(bodies, effects)
    assert info.value.field == where
    assert str(info.value).startswith(f"engine.toml: {where}: ")


# ------------------------------------------------------------------ pinned bodies


def test_a_pinned_top_on_the_engine_moves_as_the_exact_heavy_top() -> None:
    """The engine's pinned body (L_C and R_A_O integrated) against its exact flow for
    the built-in heavy top (:class:`mechanics.tops.HeavySymmetricTop`, elliptic
    functions): G's height is ℓ cos θ."""
    from identities.book.scenes.compare import run_book_scene
    from mechanics.scenes import builtin_path, load_scene
    from mechanics.scenes.engine import Engine

    scene = load_scene(builtin_path("heavy_top"))
    exact = run_book_scene(scene).trajectory
    assert exact.method.startswith("exact")
    tr = Engine(dataclasses.replace(scene, method="integrate")).run()
    ell = scene.effects_of("fixed_point")[0].fields["distance"]
    np.testing.assert_allclose(
        tr.series["z"], ell * exact.series["cos_theta"], rtol=0, atol=64 * INTEGRATED_RTOL * ell
    )


def test_the_pivot_reaction_is_m_a_G_minus_the_weight() -> None:
    """(4.4) for the top: F_C = m a_G − m g, with a_G here from central differences of
    the sampled v_G (an independent route); their truncation, h²/6 max|v‴|, bounds the
    difference (max|v‴| estimated from the third differences)."""
    from mechanics.scenes import builtin_path, load_scene
    from mechanics.scenes.engine import Engine

    scene = dataclasses.replace(
        load_scene(builtin_path("heavy_top")), method="integrate", samples=3001
    )
    tr = Engine(scene).run()
    t, s = tr.t, tr.series
    h = t[1] - t[0]
    v = np.stack([s["vx"], s["vy"], s["vz"]], -1)
    F = np.stack([s["reaction_x"], s["reaction_y"], s["reaction_z"]], -1)
    a_fd = (v[2:] - v[:-2]) / (2 * h)
    jerk = np.abs(np.diff(v, 3, axis=0)).max() / h**3
    m, g = 1.0, np.array([0.0, 0.0, -9.81])
    err = np.abs(F[1:-1] + m * g - m * a_fd).max()
    assert err <= 2 * m * h * h / 6 * jerk + 64 * INTEGRATED_RTOL * np.abs(F).max()
    assert err > 0, "the routes differ (truncation): not a value compared with itself"


def test_a_ball_bounces_on_a_raised_floor_where_the_floor_is() -> None:
    """A plane through (0.5, −0.3, 1): the integrated run once subtracted the plane's
    point from every Chebyshev coefficient of a feature's height and struck in mid-air
    (found with a top 4 cm above its floor); exact and integrated runs must agree."""
    ball = {
        "name": "ball",
        "shape": "solid_sphere",
        "mass": 0.5,
        "radius": 0.1,
        "initial": {"position": [0.0, 0.0, 3.0]},
    }
    effects = [
        {"type": "gravity", "g": 9.81},
        {"type": "impact", "body": "ball", "plane_point": [0.5, -0.3, 1.0], "restitution": 0.7},
    ]
    ex = run_scene(_scene([ball], effects, duration=2.0))
    it = run_scene(_scene([ball], effects, duration=2.0, method="integrate"))
    assert ex.method.startswith("exact")
    for r in (ex, it):
        assert r.passed, r.summary()
        assert r.trajectory.events
    t_first = math.sqrt(2 * 1.9 / 9.81)  # the centre falls from 3 to 1.1
    assert it.trajectory.events[0].t == pytest.approx(t_first, rel=2**14 * EPS)
    assert [e.t for e in it.trajectory.events] == pytest.approx(
        [e.t for e in ex.trajectory.events], rel=2**14 * EPS
    )


def test_an_impulse_away_from_the_contact_fails_the_run() -> None:
    """Negative control of the 'impacts at contact' self-check."""
    from mechanics.scenes.result import conserved_tolerance, self_checks

    r = run_scene(_dropped_box())
    r.trajectory.events[0].detail["gap"] = 1e-3
    tol = conserved_tolerance(r.scene, r.trajectory)
    bad = {c.name.split(" (")[0] for c in self_checks(r.trajectory, tol) if not c.ok}
    assert bad == {"impacts at contact"}


@pytest.mark.parametrize(
    ("extra", "where", "match"),
    [
        ({"position": [0.0, 0.0, 1.0]}, "bodies[0].initial.position", "follows from its attitude"),
        ({"omega": [0.0, 0.0, 1.0], "phi_dot": 1.0}, "bodies[0].initial.omega", "either omega"),
    ],
)
def test_a_pinned_body_refuses_what_its_pivot_decides(extra, where, match) -> None:
    top = _box("top") | {"initial": {"theta": 0.5, **extra}}
    effects = [
        {"type": "fixed_point", "body": "top", "distance": 0.1},
        {"type": "drag", "body": "top", "angular_linear": 0.1},
    ]
    with pytest.raises(SceneError, match=match) as info:
        _scene([top], effects)
    assert info.value.field == where


# ------------------------------------------------------------------ hinged bodies


def _rod_on_a_hinge(extra_effects, **initial):
    rod = {"name": "rod", "shape": "rod", "mass": 1.0, "length": 1.0, "initial": initial}
    hinge = {
        "type": "fixed_axis",
        "body": "rod",
        "axis": [0.0, 1.0, 0.0],
        "body_axis": "y",
        "distance": 0.5,
    }
    return [rod], [{"type": "gravity", "g": 9.81}, hinge, *extra_effects]


def test_a_pendulum_striking_a_wall_rebounds_with_e_times_its_angular_velocity() -> None:
    """A rod hinged at its end (body y along the axis, its length toward G), released
    from the horizontal, strikes a wall 0.1 m past the vertical with its end: one degree
    of freedom, so the impulse only scales φ̇: φ̇' = −e φ̇, with φ̇² = 3 g cos φ_c from the
    energy (4.57) at the contact angle sin φ_c = −0.1."""
    wall = {
        "type": "impact",
        "body": "rod",
        "plane_point": [0.1, 0.0, 0.0],
        "plane_normal": [-1.0, 0.0, 0.0],
        "restitution": 0.6,
    }
    bodies, effects = _rod_on_a_hinge([wall], angle=math.pi / 2)
    r = run_scene(_scene(bodies, effects, duration=1.0, samples=401))
    assert r.passed, r.summary()
    ev = r.trajectory.events[0]
    w_before = math.sqrt(3 * 9.81 * math.sqrt(0.99))
    # the end's normal speed is |φ̇| ℓ cos φ_c toward the wall (ℓ = 1)
    assert ev.detail["normal_speed_before"] == pytest.approx(
        w_before * math.sqrt(0.99), rel=2**14 * EPS
    )
    after = r.trajectory.state_at(ev.t)["phidot"]  # the piece after the impact
    assert after == pytest.approx(0.6 * w_before, rel=2**14 * EPS)  # reversed: now > 0
    assert r.trajectory.state_at(ev.t)["phi"] == pytest.approx(math.asin(-0.1), rel=2**14 * EPS)


def test_the_bearing_moment_of_a_hinge_is_perpendicular_to_its_axis() -> None:
    """(4.4) with an off-centre push along the axis: the bearings hold a moment, never
    about the axis itself (the hinge turns freely)."""
    push = {"type": "force", "body": "rod", "force": [0.0, 2.0, 0.0], "at": [0.3, 0.0, 0.2]}
    bodies, effects = _rod_on_a_hinge([push], angle=0.3)
    r = run_scene(_scene(bodies, effects, duration=1.0, samples=101))
    assert r.passed, r.summary()
    s = r.trajectory.series
    M = np.stack([s["bearing_moment_x"], s["bearing_moment_y"], s["bearing_moment_z"]], -1)
    assert np.abs(M[:, 1]).max() <= 64 * EPS * np.abs(M).max()
    assert np.abs(M).max() > 0.1, "the push along the axis at an arm needs a bearing moment"


JOINT_EFFECTS = {
    "gravity": {"type": "gravity", "g": 9.81},
    "drag": {"type": "drag", "body": "b", "angular_linear": 0.05, "quadratic": 0.1},
    "push": {
        "type": "force",
        "body": "b",
        "force": [0.5, -0.2, 0.3],
        "at": [0.05, 0.1, 0.0],
        "end": 0.3,
    },
    "couple": {"type": "torque", "body": "b", "torque": [0.0, 0.02, 0.05], "frame": "body"},
}


@settings(max_examples=SCENE_EXAMPLES)
# a spin of 1e-167: the integrator's error norm was 0/0 (found by the explore profile)
@example(joint="fixed_point", chosen=["drag"], angle=1.0, rate=1.8205667230444146e-168)
@given(
    joint=st.sampled_from(["fixed_point", "fixed_axis", "incline", "track"]),
    chosen=st.lists(st.sampled_from(sorted(JOINT_EFFECTS)), max_size=3, unique=True),
    angle=st.floats(0.05, 3.0),
    rate=st.floats(-5.0, 5.0),
)
def test_random_joints_with_random_loads_pass_their_self_checks(joint, chosen, angle, rate) -> None:
    """A body on a fixed point or a fixed axis, or rolling on an incline or in a track,
    under random loads: the run passes its checks (energy where the loads keep it,
    orthonormal attitudes), and the joint's reaction is finite everywhere."""
    body = _box("b")
    if joint == "fixed_point":
        initial = {"theta": angle, "phi_dot": 10.0 * rate}
        jeff = {"type": "fixed_point", "body": "b", "distance": 0.1}
    elif joint == "fixed_axis":
        initial = {"angle": angle, "angular_velocity": rate}
        jeff = {"type": "fixed_axis", "body": "b", "axis": [0.3, 1.0, 0.2], "distance": 0.2}
    else:
        body = _cylinder("b")
        if joint == "incline":
            initial = {"distance": angle, "speed": rate}
            jeff = {"type": "rolling", "body": "b", "surface": "incline", "angle": angle / 4}
        else:
            initial = {"angle": angle, "angular_velocity": rate}
            jeff = {"type": "rolling", "body": "b", "surface": "track", "track_radius": 0.5}
    body = body | {"initial": initial}
    r = run_scene(
        _scene([body], [jeff, *(JOINT_EFFECTS[k] for k in chosen)], duration=0.5, samples=51)
    )
    assert r.passed, r.summary()
    reactions = [v for k, v in r.trajectory.series.items() if k.startswith(("reaction", "bearing"))]
    assert reactions
    assert all(np.all(np.isfinite(v)) for v in reactions)
    # energy is kept by gravity and the joints, and after the push's window ends
    assert ("E" in _conserved(r)) == (set(chosen) <= {"gravity", "push"})


@pytest.mark.parametrize("joint", ["fixed_point", "fixed_axis"])
@pytest.mark.parametrize(
    ("case", "where", "match"),
    [
        ("point", "effects[0].body", "is a point: it cannot"),
        ("fixed", "effects[0].body", "is fixed: it cannot"),
        ("twice", "effects[1].type", "is listed twice"),
        ("thrust", "effects[1].body", "held by a joint: its mass cannot change"),
    ],
)
def test_every_joint_refuses_a_body_it_cannot_hold(joint, case, where, match) -> None:
    spec = {"type": joint, "body": "b", "distance": 0.1}
    body = _box("b")
    effects = [spec]
    if case == "point":
        body = _point("b")
    elif case == "fixed":
        body = _box("b") | {"fixed": True}
    elif case == "twice":
        effects = [spec, dict(spec)]
    else:
        thrust = {
            "type": "thrust",
            "body": "b",
            "mass_flow": 0.1,
            "exhaust_speed": 1.0,
            "fuel_mass": 0.5,
        }
        effects = [spec, thrust]
    with pytest.raises(SceneError, match=match) as info:
        _scene([body], effects)
    assert info.value.field == where


def test_a_hinged_body_takes_only_its_angle_and_rate() -> None:
    hinge = {"type": "fixed_axis", "body": "b", "distance": 0.1}
    with pytest.raises(SceneError, match="takes angle, angular_velocity") as info:
        _scene([_box("b", omega=[0.0, 0.0, 1.0])], [hinge])
    assert info.value.field == "bodies[0].initial.omega"


def test_the_contact_force_of_a_body_rolling_down_an_incline() -> None:
    """m a = m g sin α + F and J a/r² = −F (the moment of F about G) give the friction
    F = −m g sin α J/(J + m r²) up the slope; the normal force is m g cos α (derived by
    hand, not read off the engine)."""
    alpha, g, m, r = 0.4, 9.81, 2.0, 0.1
    J = 0.5 * m * r * r  # a homogeneous cylinder about its axis
    roll = {"type": "rolling", "body": "c", "surface": "incline", "angle": alpha}
    res = run_scene(_scene([_cylinder(mass=m, radius=r)], [{"type": "gravity", "g": g}, roll]))
    assert res.passed, res.summary()
    s = res.trajectory.series
    n = np.array([math.sin(alpha), 0.0, math.cos(alpha)])
    t = np.array([math.cos(alpha), 0.0, -math.sin(alpha)])
    F = np.stack([s["reaction_x"], s["reaction_y"], s["reaction_z"]], -1)
    want = m * g * math.cos(alpha) * n - m * g * math.sin(alpha) * J / (J + m * r * r) * t
    np.testing.assert_allclose(F, np.broadcast_to(want, F.shape), rtol=0, atol=64 * EPS * m * g)
    assert s["v"][-1] == pytest.approx(g * math.sin(alpha) / (1 + J / (m * r * r)), rel=64 * EPS)


@pytest.mark.parametrize(
    ("body", "extra", "where", "match"),
    [
        (_box("c"), {}, "effects[0].body", "only round bodies roll"),
        (_cylinder() | {"fixed": True}, {}, "effects[0].body", "is fixed: it cannot roll"),
        (_cylinder(speed=1.0), {"surface": "track"}, "effects[0].track_radius", "missing"),
        (_cylinder(angle=1.0), {}, "bodies[0].initial.angle", "takes distance, speed"),
        (_cylinder(), {"surface": "ramp"}, "effects[0].surface", "'incline' or 'track'"),
        (_cylinder(), {"angle": 1.6}, "effects[0].angle", r"must lie in \[0, π/2\)"),
    ],
)
def test_rolling_refuses_what_cannot_roll(body, extra, where, match) -> None:
    roll = {"type": "rolling", "body": "c", "surface": "incline", "angle": 0.3} | extra
    with pytest.raises(SceneError, match=match) as info:
        _scene([body], [roll])
    assert info.value.field == where


# ------------------------------------------------------------------ Coulomb friction

#: an event located on a DOP853 run at rtol 1e-12 against its closed form: the
#: integration error, ~1e-11 relative, with a factor of 100 to spare
EVENT_RTOL = 2**22 * EPS


def test_a_ball_rolling_against_a_spring_starts_to_slip_where_friction_gives_out() -> None:
    """Rolling (stick) on a level floor, a spring k x back to the start: x = (v0/ω) sin ωt
    with ω² = k/(m + J/r²); the friction that keeps it rolling is F = J k x/(J + m r²)
    (from m ẍ = −k x + F and J θ̈ = −r F with ẍ = r θ̈), which reaches μ m g at
    x* = μ m g (J + m r²)/(J k).  Derived by hand; after that the ball slips, and the
    friction only takes energy away."""
    m, r, k, mu, g, v0 = 1.0, 0.1, 10.0, 0.1, 9.81, 2.0
    J = 0.4 * m * r * r
    spring = {"type": "spring", "body": "b", "anchor": [0.0, 0.0, r], "stiffness": k}
    fr = {"type": "coulomb_friction", "body": "b", "mu": mu}
    res = run_scene(
        _scene(
            [_ball("b", speed=v0, spin=v0 / r)],
            [{"type": "gravity", "g": g}, spring, fr],
            duration=3.0,
            samples=3001,
        )
    )
    assert res.passed, res.summary()
    ev = res.trajectory.events
    assert ev[0].kind == "slip"
    w = math.sqrt(k / (m + J / r**2))
    x_star = mu * m * g * (J + m * r * r) / (J * k)
    assert ev[0].t == pytest.approx(math.asin(x_star * w / v0) / w, rel=EVENT_RTOL)
    assert {e.kind for e in ev[1:]} <= {"rolling", "slip_zero", "slip"}
    E = res.trajectory.series["E"]
    # (while it rolls E is kept to the integration's error, which wanders both ways)
    assert np.all(np.diff(E) <= INTEGRATED_RTOL * np.abs(E).max()), "friction adds no energy"
    assert E[-1] < E[0] * (1 - 1e-3), "and it has taken some"


def test_a_push_makes_a_rolling_ball_slip_until_friction_rolls_it_again() -> None:
    """A push P at G from t = 0.2 to 0.4 on a ball rolling on a level floor: it slips at
    once (P J/(J + m r²) > μ m g); the slip grows at P/m − μ g (1 + m r²/J) and then
    falls at μ g (1 + m r²/J), so it rolls again at
    t_r = 0.4 + 0.2 (P/m − μ g (1 + m r²/J))/(μ g (1 + m r²/J)) (derived by hand)."""
    m, r, mu, g, P = 1.0, 0.1, 0.2, 9.81, 20.0
    c = 1 + m * r * r / (0.4 * m * r * r)  # 1 + m r²/J = 7/2
    push = {"type": "force", "body": "b", "force": [P, 0.0, 0.0], "start": 0.2, "end": 0.4}
    fr = {"type": "coulomb_friction", "body": "b", "mu": mu}
    res = run_scene(
        _scene(
            [_ball("b", speed=1.0, spin=10.0)],
            [{"type": "gravity", "g": g}, push, fr],
            duration=2.0,
        )
    )
    assert res.passed, res.summary()
    (slip, roll) = res.trajectory.events
    assert (slip.kind, slip.t) == ("slip", 0.2)
    assert roll.kind == "rolling"
    t_r = 0.4 + 0.2 * (P / m - mu * g * c) / (mu * g * c)
    assert roll.t == pytest.approx(t_r, rel=EVENT_RTOL)
    assert "E" in _conserved(res)
    (E,) = [c for c in res.conserved if c.name == "E"]
    assert E.since == pytest.approx(t_r, rel=EVENT_RTOL)


@pytest.mark.parametrize(
    ("body", "effects", "where", "match"),
    [
        (_box("b"), [], "effects[1].body", "only round bodies roll"),
        (_ball("b"), "no gravity", "effects[0].type", "needs a gravity effect"),
        (_ball("b", angle=1.0), [], "bodies[0].initial.angle", "takes distance, speed, spin"),
        (_ball("b"), [{"angle": -0.1}], "effects[1].angle", r"must lie in \[0, π/2\)"),
    ],
)
def test_coulomb_friction_refuses_what_cannot_slide(body, effects, where, match) -> None:
    fr = {"type": "coulomb_friction", "body": "b", "mu": 0.3}
    if effects == "no gravity":
        eff = [fr]
    else:
        eff = [{"type": "gravity", "g": 9.81}, fr | (effects[0] if effects else {})]
    with pytest.raises(SceneError, match=match) as info:
        _scene([body], eff)
    assert info.value.field == where


def test_a_ball_pulled_off_the_floor_stops_the_run_with_the_time() -> None:
    lift = {"type": "force", "body": "b", "force": [0.0, 0.0, 20.0], "start": 0.5}
    fr = {"type": "coulomb_friction", "body": "b", "mu": 0.3}
    sc = _scene([_ball("b", speed=1.0)], [{"type": "gravity", "g": 9.81}, lift, fr])
    with pytest.raises(SceneError, match=r"would leave the plane at t = 0.5 s") as info:
        run_scene(sc)
    assert info.value.field == "effects[2].body"


@settings(max_examples=SCENE_EXAMPLES)
@given(
    speed=st.floats(-3.0, 3.0),
    spin=st.floats(-60.0, 60.0),
    mu=st.floats(0.02, 1.0),
    alpha=st.floats(0.0, 1.2),
)
# a subnormal slip: rate × slip underflowed to −0 and the exact phases never switched
@example(speed=5e-324, spin=0.0, mu=0.03125, alpha=0.0625)
def test_random_sliding_balls_integrate_to_their_exact_phases(speed, spin, mu, alpha) -> None:
    """Any start on any slope under gravity: the integrated run (its switches found on the
    steps' dense output) agrees with the exact phases (switch times in closed form) in
    its events and its state at the end, and friction never adds energy."""
    fr = {"type": "coulomb_friction", "body": "b", "mu": mu, "angle": alpha}
    sc = _scene([_ball("b", speed=speed, spin=spin)], [{"type": "gravity", "g": 9.81}, fr])
    a = run_scene(sc)
    b = run_scene(dataclasses.replace(sc, method="integrate"))
    assert a.method.startswith("exact")
    assert a.passed, a.summary()
    assert b.passed, b.summary()
    assert [e.kind for e in a.trajectory.events] == [e.kind for e in b.trajectory.events]
    for ea, eb in zip(a.trajectory.events, b.trajectory.events, strict=True):
        assert eb.t == pytest.approx(ea.t, rel=EVENT_RTOL, abs=EVENT_RTOL)
    for key in ("s", "v", "omega"):
        x, y = a.trajectory.series[key][-1], b.trajectory.series[key][-1]
        assert y == pytest.approx(x, rel=INTEGRATED_RTOL, abs=INTEGRATED_RTOL * 60)
    E, size = a.trajectory.series["E"], a.trajectory.scales["E"]  # max |T| + max |V|
    assert np.all(np.diff(E) <= 64 * EPS * size)


# ------------------------------------------------------------------ mass flow, tanks


def test_a_pendulum_gaining_mass_on_its_axis_integrates_and_keeps_no_energy_claim() -> None:
    """The carousel's inflow on a pendulum under gravity has no exact flow: integrated,
    J(t) φ̈ = −m g h sin φ − r q v − q R² φ̇ (7.39 with the weight's moment), and no
    bearing reaction is reported (the bullets' momentum is not among the loads)."""
    disc = {
        "name": "d",
        "shape": "disc",
        "mass": 2.0,
        "radius": 0.5,
        "initial": {"angle": 0.5},
    }
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "fixed_axis", "body": "d", "axis": [0.0, 1.0, 0.0], "distance": 0.2},
        {"type": "mass_flow", "body": "d", "rate": 0.1, "speed": 3.0, "offset": 0.1, "radius": 0.5},
    ]
    r = run_scene(_scene([disc], eff, duration=2.0))
    assert r.passed, r.summary()
    assert r.method.startswith("integrated")
    assert "E" not in _conserved(r)
    assert not any(k.startswith("reaction") for k in r.trajectory.series)
    # the same run with the inflow's moment written out by hand
    from scipy.integrate import solve_ivp

    J0, m, h = 0.5 * 2.0 * 0.25 + 2.0 * 0.04, 2.0, 0.2  # m R²/2 about its axis + m h²

    def rhs(t, y):
        J = J0 + 0.1 * 0.25 * t
        return [y[1], (-m * 9.81 * h * math.sin(y[0]) - 0.1 * 0.1 * 3.0 - 0.1 * 0.25 * y[1]) / J]

    ref = solve_ivp(rhs, (0, 2.0), [0.5, 0.0], rtol=1e-12, atol=1e-12, t_eval=[2.0])
    assert r.trajectory.series["phi"][-1] == pytest.approx(ref.y[0, -1], rel=INTEGRATED_RTOL)


def test_a_tank_drains_beside_a_falling_ball() -> None:
    """Two effects that share nothing run side by side: the ball's parabola and the
    tank's Torricelli level, each as in its own scene."""
    tank = {"name": "t", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
    ball = _point("b", velocity=[1.0, 0.0, 2.0])
    eff = [{"type": "gravity", "g": 9.81}, {"type": "tank_outflow", "body": "t", "hole_area": 0.05}]
    both = run_scene(_scene([tank, ball], eff, duration=10.0))
    alone = run_scene(_scene([tank], eff, duration=10.0))
    assert both.passed, both.summary()
    assert both.method.startswith("integrated")
    assert alone.method.startswith("exact")
    (e1,), (e2,) = both.trajectory.events, alone.trajectory.events
    assert e1.kind == e2.kind == "empty"
    assert e1.t == pytest.approx(e2.t, rel=EVENT_RTOL)
    t = both.trajectory.t
    np.testing.assert_allclose(
        both.trajectory.series["b.z"], 2.0 * t - 0.5 * 9.81 * t * t, rtol=0, atol=4096 * EPS * 500
    )
    assert "volume_total" in _conserved(both)


@pytest.mark.parametrize(
    ("effects", "where", "match"),
    [
        ([{"type": "spring", "body": "t", "stiffness": 1.0}], "effects[2].type", "only effect"),
        ([{"type": "tank_outflow", "body": "t", "hole_area": 0.01}], "effects[2].body", "one hole"),
        ("no outflow", "bodies[0].shape", "needs a tank_outflow"),
        (
            [{"type": "mass_flow", "body": "b", "rate": 0.1, "speed": 1, "offset": 0, "radius": 1}],
            "effects[2].type",
            "fixed_axis",
        ),
    ],
)
def test_tanks_and_mass_flow_refuse_what_makes_no_sense(effects, where, match) -> None:
    tank = {"name": "t", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
    base = [
        {"type": "gravity", "g": 9.81},
        {"type": "tank_outflow", "body": "t", "hole_area": 0.05},
    ]
    eff = base[:1] if effects == "no outflow" else base + effects
    with pytest.raises(SceneError, match=match) as info:
        _scene([tank, _box("b")], eff)
    assert info.value.field == where


# ------------------------------------------------------------------ rims on a plane


def test_a_tilted_spinning_cylinder_lands_on_its_lowest_rim_point(monkeypatch) -> None:
    """A cylinder (radius a, height h) tilted by θ and spinning about its axis keeps its
    axis fixed in space (a symmetric body spinning about its symmetry axis), so its
    lowest point is (h/2) cos θ + a sin θ below G, at G + (0, (h/2) sin θ − a cos θ,
    −(h/2) cos θ − a sin θ) for the axis e3 = (0, −sin θ, cos θ): it lands at
    t* = √(2 (z0 − d)/g) there (derived by hand).  The impulse there agrees with
    :func:`mechanics.impact.rigid_impact`."""
    a, h, th, g, z0 = 0.1, 0.3, 0.6, 9.81, 1.0
    seen = _spy_on_impulses(monkeypatch)
    cyl = {
        "name": "c",
        "shape": "cylinder",
        "mass": 1.0,
        "radius": a,
        "height": h,
        "initial": {"position": [0.0, 0.0, z0], "theta": th, "omega": [0.0, 0.0, 5.0]},
    }
    eff = [{"type": "gravity", "g": g}, {"type": "impact", "body": "c", "restitution": 0.5}]
    r = run_scene(_scene([cyl], eff, duration=0.45, samples=451))
    assert r.passed, r.summary()
    d = 0.5 * h * math.cos(th) + a * math.sin(th)
    ev = r.trajectory.events[0]
    assert "rim" in ev.detail["feature"]
    assert ev.t == pytest.approx(math.sqrt(2 * (z0 - d) / g), rel=EVENT_RTOL)
    arm, v, w, ref, _ = seen[0]
    want = [0.0, 0.5 * h * math.sin(th) - a * math.cos(th), -d]
    np.testing.assert_allclose(arm, want, rtol=0, atol=INTEGRATED_RTOL)
    tol = IMPULSE_RTOL * (1.0 + np.abs(ref.omega).max())
    np.testing.assert_allclose(v, ref.v_G, rtol=0, atol=tol)
    np.testing.assert_allclose(w, ref.omega, rtol=0, atol=tol)
    assert min(r.trajectory.gaps.values(), key=np.min).min() >= -64 * EPS


@settings(max_examples=SCENE_EXAMPLES)
@given(
    shape=st.sampled_from(["disc", "ring", "cylinder", "cylindrical_shell"]),
    w=st.tuples(*(st.floats(-8.0, 8.0),) * 3),
    angles=st.tuples(*(st.floats(0.0, 3.0),) * 3),
    e=st.floats(0.0, 1.0),
    mu=st.sampled_from([0.0, 0.3]),
)
# found by hypothesis (29 Nov 2026): a cylinder that lands on one rim almost without a
# bounce (e = 1/128) falls over onto the other while the first still touches, sliding at
# 0.68 m/s: two contacts at once with sliding friction, which the engine refuses naming
# the friction (with friction 0 the same landing comes to rest on its side, refused too)
@example(shape="cylinder", w=(0.0, 4.0, 2.0), angles=(0.0, 1.0, 3.0), e=0.0078125, mu=0.3)
def test_random_tumbling_rims_land_without_sinking_in(shape, w, angles, e, mu) -> None:
    """Any round body that is not a sphere, tumbling onto a floor: the run passes its own
    checks (no interpenetration at any sample, each impulse at a zero gap, the Chapter 6
    energy loss, none gained), or refuses what the engine does not model, saying so: an
    impulse that would gain energy, coming to rest on a rim, or two contacts struck at
    once while sliding with friction.  A face started within NEARLY_FLAT of flat is the
    known loss pinned by test_a_disc_dropped_within_1e_8_of_flat_is_struck_above_the_floor."""
    assume(abs(math.sin(angles[1])) > NEARLY_FLAT)
    body = {"name": "c", "shape": shape, "mass": 1.0, "radius": 0.1}
    if shape.startswith("cylind"):
        body["height"] = 0.2
    body["initial"] = {
        "position": [0.0, 0.0, 0.5],
        "omega": list(w),
        **dict(zip(("psi", "theta", "phi"), angles, strict=True)),
    }
    imp = {"type": "impact", "body": "c", "restitution": e, "friction": mu}
    sc = _scene([body], [{"type": "gravity", "g": 9.81}, imp], duration=0.4, samples=201)
    try:
        r = run_scene(sc)
    except SceneError as exc:  # an honest refusal (above)
        refused = str(exc)
    else:
        refused = None
    if refused is not None:
        said = ("would add", "come to rest", "resting contact", "friction that slides are not")
        assert any(k in refused for k in said), refused
        if "meet at once" in refused:  # only with friction, and only while sliding
            assert mu > 0, refused
            assert float(re.search(r"sliding \(([0-9.e+-]+) m/s", refused).group(1)) > 0
        return
    assert r.passed, r.summary()
    assert any("rim" in ev.detail["feature"] for ev in r.trajectory.events)


#: a face this close to flat (sin θ) at its first landing: the known loss below
NEARLY_FLAT = 1e-7


@pytest.mark.xfail(
    strict=True,
    reason="known loss (found by hypothesis, open): a disc dropped flat to within 2e-8 rad "
    "(e = 1) bounces on one side of its rim, then the other, and its third impulse is "
    "applied 9e-10 m above the floor.  Likely cause (not confirmed): near flat the rim "
    "polynomial q = (w − aρ)(w + aρ) "
    "has a root of slope ~2aρ ẇ ~ 1e-8: its rounding (eps Σ|q_k|) moves the contact by "
    "~1e-10 s; a sin θ of 1e-7 passes",
)
def test_a_disc_dropped_within_1e_8_of_flat_is_struck_above_the_floor() -> None:
    body = {"name": "c", "shape": "disc", "mass": 1.0, "radius": 0.1,
            "initial": {"position": [0.0, 0.0, 0.5], "theta": 2e-8}}  # fmt: skip
    imp = {"type": "impact", "body": "c", "restitution": 1.0, "friction": 0.0}
    sc = _scene([body], [{"type": "gravity", "g": 9.81}, imp], duration=0.4, samples=201)
    r = run_scene(sc)
    assert r.passed, r.summary()


def test_a_rim_meets_only_a_plane() -> None:
    disc = {"name": "d", "shape": "disc", "mass": 1.0, "radius": 0.1}
    ball = _ball("b", position=[0.0, 0.0, 1.0])
    with pytest.raises(SceneError, match="meets only a plane") as info:
        _scene([disc, ball], [{"type": "impact", "body": "d", "other": "b", "restitution": 0.5}])
    assert info.value.field == "effects[0].body"


# ------------------------------------------------------------------ buoyancy


def _floating(z0, rho_ball=500.0, duration=1.0, samples=101):
    a = 0.1
    m = rho_ball * 4.0 / 3.0 * math.pi * a**3
    ball = _ball("b", mass=m, radius=a, position=[0.0, 0.0, z0])
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "buoyancy", "body": "b", "density": 1000.0},
    ]
    return _scene([ball], eff, duration=duration, samples=samples)


def test_a_ball_of_half_the_liquids_density_floats_half_immersed() -> None:
    """Archimedes: the lift ρ g (2/3)π a³ of the half ball equals the weight (ρ/2)(4/3)π
    a³ g, so a ball released at rest with its centre on the level stays there."""
    r = run_scene(_floating(0.0))
    assert r.passed, r.summary()
    # integrated at atol 1e-12 about z = 0: the integration's error, relative to a
    assert np.abs(r.trajectory.series["z"]).max() <= INTEGRATED_RTOL * 0.1
    assert {"E", "p_x", "p_y", "L_z"} <= _conserved(r)


def test_a_floating_ball_bobs_with_the_period_of_its_waterline() -> None:
    """Small oscillations about half immersion: the lift changes by ρ g π a² per unit
    depth (the waterline's area), so ω² = ρ g π a²/m = 3g/(2a) (derived by hand); the
    lift is odd in the displacement x (π(a²x − x³/3)), so the period differs by
    O((x/a)²) = 1e-6 at x = a/1000."""
    a, g = 0.1, 9.81
    T = 2 * math.pi / math.sqrt(1.5 * g / a)
    r = run_scene(_floating(-a / 1000, duration=3 * T, samples=601))
    assert r.passed, r.summary()
    t, z = r.trajectory.t, r.trajectory.series["z"]
    up = [i for i in range(1, len(z)) if z[i - 1] < 0 <= z[i]]
    crossings = [t[i - 1] - z[i - 1] * (t[i] - t[i - 1]) / (z[i] - z[i - 1]) for i in up]
    assert np.mean(np.diff(crossings)) == pytest.approx(T, rel=1e-5)


@pytest.mark.parametrize(
    ("body", "gravity", "where", "match"),
    [
        (_box("b"), {"g": 9.81}, "effects[1].body", "modelled for spheres"),
        (_ball("b"), {"g": 9.81, "direction": [1.0, 0.0, 0.0]}, "effects[1].type", "along −z"),
    ],
)
def test_buoyancy_refuses_what_it_does_not_model(body, gravity, where, match) -> None:
    eff = [{"type": "gravity", **gravity}, {"type": "buoyancy", "body": "b", "density": 1000.0}]
    with pytest.raises(SceneError, match=match) as info:
        _scene([body], eff)
    assert info.value.field == where


def test_a_ball_rolling_into_a_wall_rebounds_rolling() -> None:
    """Rolling on a level floor into a wall, e = 1/2: the floor keeps the contact point at
    rest, so the impulse acts on the rolling coordinate with the effective mass
    M = m + J/r² = 7m/5: it rebounds at e v, losing ½ M (1 − e²) v² (6.41 with the
    guide's mass; derived by hand)."""
    m, v, e = 1.0, 2.0, 0.5
    ball = _ball("b", mass=m, distance=0.0, speed=v)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "rolling", "body": "b", "surface": "incline", "angle": 0.0},
        {
            "type": "impact",
            "body": "b",
            "restitution": e,
            "plane_point": [1.0, 0, 0],
            "plane_normal": [-1.0, 0, 0],
        },
    ]
    r = run_scene(_scene([ball], eff, duration=1.5, samples=151))
    assert r.passed, r.summary()
    (ev,) = r.trajectory.events
    assert ev.t == pytest.approx((1.0 - 0.1) / v, rel=EVENT_RTOL)
    assert ev.detail["normal_speed_after"] == pytest.approx(e * v, rel=IMPULSE_RTOL)
    want = 0.5 * 1.4 * m * (1 - e * e) * v * v
    assert ev.detail["kinetic_energy_before"] - ev.detail["kinetic_energy_after"] == pytest.approx(
        want, rel=IMPULSE_RTOL
    )
    assert r.trajectory.series["v"][-1] == pytest.approx(-e * v, rel=IMPULSE_RTOL)


def _slow_pair():
    """Two bodies on a spring barely stretched: E = 5e-4 J at speeds ~0.02 m/s, below
    the integration's atol/rtol (found by the engine's property tests: its E drifted
    7.6e-10 of E against the 2.3e-10 allowed, the speeds' atol being 5e-11 of them)."""
    return parse_scene(
        {
            "scene": {"name": "slow", "duration": 0.5, "samples": 11},
            "bodies": [
                _ball("b0", position=[0.0, 0.0, 0.75], velocity=[0.0, 0.0, 0.0]),
                {
                    "name": "b1",
                    "shape": "point",
                    "mass": 1.0,
                    "initial": {"position": [1.0, 0.0, 1.0]},
                },
            ],
            "effects": [
                {
                    "type": "spring",
                    "body": "b0",
                    "other": "b1",
                    "stiffness": 1.0,
                    "rest_length": 1.0,
                },
                {"type": "impact", "body": "b0", "other": "b1", "restitution": 1.0},
            ],
        },
        source="slow.toml",
    )


def test_a_slow_scenes_energy_is_held_to_what_the_integrations_atol_allows(monkeypatch) -> None:
    res = run_scene(_slow_pair())
    assert res.method.startswith("integrated: DOP853")
    assert res.passed, res.summary()
    # the check can still fail: a spring whose potential is 0.1 % off its force
    from mechanics.scenes.effects.spring import Spring

    true_potential = Spring.potential
    monkeypatch.setattr(Spring, "potential", lambda self, s: 1.001 * true_potential(self, s))
    bad = run_scene(_slow_pair())
    (e,) = [c for c in bad.conserved if c.name == "E"]
    assert not e.ok
    assert not bad.passed


def test_a_point_reaching_the_floor_in_exact_free_flight_is_struck_at_the_floor() -> None:
    """The exact flow's gap at an impact is rounded relative to the flight's terms (the
    height 0.78 m it fell from), not to its size at the floor (2.2e-16): found by the
    engine's rigid-motion property, where 'impacts at contact' failed at 0.5 of that
    size.  The fall time √(2h/g) and the rebound at e = 1 are closed forms."""
    h, g = 0.78125, 6.9375
    sc = _scene(
        [_point("p", position=[0.0, 0.0, h])],
        [{"type": "gravity", "g": g}, {"type": "impact", "body": "p", "restitution": 1.0}],
        duration=0.5,
        samples=11,
    )
    r = run_scene(sc)
    assert r.passed, r.summary()
    assert r.method.startswith("exact")
    (ev,) = [e for e in r.trajectory.events if e.kind == "impact"]
    assert ev.t == pytest.approx(math.sqrt(2 * h / g), rel=2**4 * EPS)
    assert ev.detail["gap_scale"] >= h  # the height fallen from, not the 2.2e-16 there
