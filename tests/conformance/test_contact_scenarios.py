"""The battery's contact scenarios (issue 29, item 4): a box landing flat, a box sliding
to a stop, a ball rolling down an incline, Newton's cradle.

Each closed form is confirmed here by a route of its own: the laws it must obey
(friction's work and impulse, the energy of rolling, the momentum and energy of the
elastic row), and the scene engine, whose contacts were derived independently (issue
27; tests/scenes), meeting every one at the exact profile
(tests/conformance/test_thresholds.py).  Each law's wrong version fails, naming the
figure it spoils; a variant outside a reference's range is refused with the reason.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.conformance import get_scenario, reference, run_battery
from mechanics.conformance.adapters import ExactAdapter
from mechanics.conformance.protocol import Ground
from mechanics.conformance.scenarios import check_scenario, invariants, measure
from mechanics.errors import MechanicsValueError

from .toys import Wrapped

#: a closed form against a law that restates it: a few roundings of O(1) quantities
LAW_RTOL = 2**6 * EPS


def _ref(name):
    s = get_scenario(name)
    return s, reference(s)


# -- the closed forms obey the laws --------------------------------------------------


def test_the_sliding_box_stops_where_friction_has_taken_its_energy_and_its_momentum():
    s, ref = _ref("sliding_stop")
    b, gr = s.bodies[0], s.ground
    m, v0 = b.mass, float(np.linalg.norm(b.velocity))
    friction = gr.friction * m * -s.gravity[2]  # μ N, N = m g on flat ground
    # work: friction × distance = the kinetic energy; impulse: friction × time = p
    assert abs(friction * ref.figures["stop_distance"] - 0.5 * m * v0**2) <= LAW_RTOL * m * v0**2
    assert abs(friction * ref.figures["stop_time"] - m * v0) <= LAW_RTOL * m * v0
    tr = ref.trajectory
    assert np.all(np.diff(np.linalg.norm(tr.velocity[:, 0], axis=-1)) <= 0)  # never speeds up
    assert np.all(tr.velocity[tr.t > ref.figures["stop_time"], 0] == 0)  # then rests
    assert not np.any(tr.omega)


def test_the_rolling_ball_keeps_its_energy_and_rolls_at_every_sample():
    s, ref = _ref("incline_rolling")
    tr = ref.trajectory
    r = s.bodies[0].shape.dims[0]
    E, scale = invariants(s, tr)["E"]
    assert np.max(np.abs(E - E[0])) <= LAW_RTOL * scale
    # the contact point is at rest: v + ω × (−r n) = 0, ω in space
    w_space = np.einsum("tji,tj->ti", tr.R_A_O[:, 0], tr.omega[:, 0])
    slip = tr.velocity[:, 0] - r * np.cross(w_space, [0.0, 0.0, 1.0])
    assert np.max(np.linalg.norm(slip, axis=-1)) <= LAW_RTOL * np.max(np.abs(tr.velocity))
    # a = g sin α / (1 + J/(m r²)) = 5/7 g sin α for a solid ball
    g_t = math.hypot(s.gravity[0], s.gravity[1])
    assert abs(ref.figures["acceleration"] - 5.0 / 7.0 * g_t) <= LAW_RTOL * g_t
    # the attitude turns by the distance rolled over r: its rotation angle
    along = tr.position[:, 0, 0] - tr.position[0, 0, 0]
    cos_turn = (np.trace(tr.R_A_O[:, 0], axis1=-2, axis2=-1) - 1.0) / 2.0
    np.testing.assert_allclose(cos_turn, np.cos(along / r), rtol=0, atol=2**8 * EPS)


def test_the_cradle_passes_the_momentum_down_the_row_keeping_p_and_e():
    s, ref = _ref("newtons_cradle")
    inv = invariants(s, ref.trajectory)
    for name in ("E", "p", "L"):
        q, scale = inv[name]
        assert np.max(np.abs(np.asarray(q) - q[0])) <= LAW_RTOL * scale, name
    # equal masses, e = 1: each pair exchanges velocities (6.36)-(6.38), so the last leaves
    from mechanics.impact import direct_impact

    v = [1.0, 0.0, 0.0]
    for i in range(2):
        v[i], v[i + 1] = (float(x) for x in direct_impact(1.0, 1.0, v[i], v[i + 1], 1.0))
    np.testing.assert_array_equal(ref.figures["velocities_after"], v)


def test_the_box_lands_flat_as_a_ball_would_bounce():
    s, ref = _ref("box_landing_flat")
    tr = ref.trajectory
    assert not np.any(tr.omega)
    assert not np.any(tr.velocity[:, 0, :2])
    h0 = s.bodies[0].position[2] - s.bodies[0].shape.dims[2]
    e = s.ground.restitution
    np.testing.assert_allclose(
        ref.figures["apex_heights"], h0 * e ** (2.0 * np.arange(1, 4)), rtol=LAW_RTOL
    )
    lowest = tr.position[:, 0, 2] - s.bodies[0].shape.dims[2]
    assert np.min(lowest) >= -LAW_RTOL * h0  # never below the ground


@pytest.mark.parametrize(
    "name",
    [
        "box_landing_flat",
        "sliding_stop",
        "incline_rolling",
        "newtons_cradle",
        "bounce_to_rest",
        "oblique_impact_sticks",
        "oblique_impact_slips",
    ],
)
def test_each_figure_reads_back_off_the_exact_samples(name):
    s, ref = _ref(name)
    got = measure(s, ref.trajectory)
    for k, want in ref.figures.items():
        np.testing.assert_allclose(got[k], want, rtol=2**10 * EPS, atol=2**10 * EPS, err_msg=k)
    check_scenario(s)


# -- a wrong law fails, naming its figure --------------------------------------------


def _slides_with(mu_factor):
    def spoil(s):
        g = dataclasses.replace(s.ground, friction=mu_factor * s.ground.friction)
        return dataclasses.replace(s, ground=g)

    return Wrapped(f"friction x{mu_factor}", scenario=spoil, only={"sliding_stop"})


def test_friction_taken_twice_stops_the_box_at_half_the_distance_and_fails():
    r = run_battery(_slides_with(2.0), scenarios=["sliding_stop"], profile="first-order")
    res = r["sliding_stop"]
    assert res.status == "fail"
    assert res.figure("stop_distance").value == pytest.approx(0.5, rel=LAW_RTOL)
    assert "stop_distance 0.5 violates" in res.message
    ok = run_battery(_slides_with(1.0), scenarios=["sliding_stop"], profile="exact")
    assert ok.passed


def _sliding_down(s, tr):
    """A ball that slides down the incline without turning (the friction dropped):
    a = g sin α, no spin."""
    g_t = np.array([s.gravity[0], s.gravity[1], 0.0])
    t = tr.t[:, None]
    pos = tr.position.copy()
    pos[:, 0] = np.asarray(s.bodies[0].position) + 0.5 * t**2 * g_t
    vel = (t * g_t)[:, None, :]
    R = np.broadcast_to(np.asarray(s.bodies[0].R_A_O), tr.R_A_O.shape).copy()
    return dataclasses.replace(
        tr, position=pos, velocity=vel, R_A_O=R, omega=np.zeros_like(tr.omega)
    )


def test_a_ball_that_slides_instead_of_rolling_fails_on_the_acceleration_and_the_spin():
    bad = Wrapped("no rolling", answer=_sliding_down, only={"incline_rolling"})
    res = run_battery(bad, scenarios=["incline_rolling"], profile="first-order")["incline_rolling"]
    assert res.status == "fail"
    # a = g sin α against 5/7 g sin α: 2/5 too large
    assert res.figure("acceleration").value == pytest.approx(0.4, rel=2**20 * EPS)
    assert res.figure("roll_speed").value == pytest.approx(1.0, rel=LAW_RTOL)
    assert "acceleration 0.4 violates" in res.message


def _simultaneous(s, tr):
    """The three balls' velocities after, as a simultaneous LCP gives them (Siconos's
    (−1/3, 2/3, 2/3)): momentum and energy kept alike (−1/3 + 2/3 + 2/3 = 1, 1/9 + 4/9 +
    4/9 = 1), so only the velocities tell it from the textbook's sequence of pairs."""
    ref = reference(s)
    tc = ref.figures["impact_time"]
    after = np.array([-1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0])
    pos, vel = tr.position.copy(), tr.velocity.copy()
    late = tr.t > tc
    for i in range(3):
        x_c = np.asarray(s.bodies[i].position) + (tc if i == 0 else 0.0) * np.array([1.0, 0, 0])
        pos[late, i] = x_c + (tr.t[late] - tc)[:, None] * np.array([after[i], 0.0, 0.0])
        vel[late, i] = [after[i], 0.0, 0.0]
    return dataclasses.replace(tr, position=pos, velocity=vel)


def test_the_simultaneous_answer_to_the_cradle_fails_on_the_velocities_alone():
    bad = Wrapped("simultaneous", answer=_simultaneous, only={"newtons_cradle"})
    res = run_battery(bad, scenarios=["newtons_cradle"], profile="default")["newtons_cradle"]
    assert res.status == "fail"
    # the middle ball at 2/3 against 0, relative to the largest exact velocity, 1
    assert res.figure("velocities_after").value == pytest.approx(2.0 / 3.0, rel=LAW_RTOL)
    assert res.figure("E_drift").value <= LAW_RTOL
    assert res.figure("p_drift").value <= LAW_RTOL
    ok = run_battery(ExactAdapter(), scenarios=["newtons_cradle"], profile="exact")
    assert ok.passed


def _spins(s, tr):
    w = tr.omega.copy()
    w[tr.t > 0.4, 0] = [0.0, 0.0, 0.1]  # a spurious spin after the first landing
    return dataclasses.replace(tr, omega=w)


def test_a_landing_that_sets_the_box_spinning_fails_on_omega():
    bad = Wrapped("spins", answer=_spins, only={"box_landing_flat"})
    res = run_battery(bad, scenarios=["box_landing_flat"], profile="exact")["box_landing_flat"]
    assert res.status == "fail"
    assert res.figure("omega").passed is False
    assert f"omega {res.figure('omega').value:.3g} violates" in res.message


# -- outside the references' range: refused with the reason ---------------------------


def _with_body(name, **changes):
    s = get_scenario(name)
    return dataclasses.replace(s, bodies=(dataclasses.replace(s.bodies[0], **changes),))


@pytest.mark.parametrize(
    ("scenario", "match"),
    [
        # a box that tips: μ h ≥ its half length along the motion
        (
            dataclasses.replace(
                get_scenario("sliding_stop"), ground=Ground(0.5, friction=4.0)
            ),
            r"the box tips over \(μ h = 0\.4 m is not under its half length 0\.3 m",
        ),
        # a ball that slips on the incline: rolling needs μ ≥ 2/7 tan α = 0.088
        (
            dataclasses.replace(
                get_scenario("incline_rolling"), ground=Ground(0.5, friction=0.05)
            ),
            r"the ball slips: rolling needs friction 0\.08\d+",
        ),
        # a ball that is not rolling at the start
        (
            _with_body("incline_rolling", velocity=(1.0, 0.0, 0.0)),
            r"starts rolling downhill, ω = n × v / r",
        ),
        # a ball above the incline
        (
            _with_body("incline_rolling", position=(0.0, 0.0, 0.5)),
            r"starts with the body resting on the ground; its lowest point is 0\.4 m",
        ),
        # the box turned off its face
        (
            _with_body(
                "box_landing_flat",
                R_A_O=((1.0, 0.0, 0.0), (0.0, math.cos(0.1), math.sin(0.1)),
                       (0.0, -math.sin(0.1), math.cos(0.1))),
            ),
            r"a box lands as a bounce only lying flat on a face",
        ),
        # a landing box sliding over rough ground
        (
            _with_body("box_landing_flat", velocity=(0.5, 0.0, 0.0)),
            r"on rough ground \(friction 0\.5\) a bounce's reference needs no sliding",
        ),
        # a cradle whose row does not touch
        (
            dataclasses.replace(
                get_scenario("newtons_cradle"),
                bodies=(
                    *get_scenario("newtons_cradle").bodies[:2],
                    dataclasses.replace(
                        get_scenario("newtons_cradle").bodies[2], position=(0.45, 0.0, 0.0)
                    ),
                ),
            ),
            r"the others touch; got offsets \[0\.0, 0\.0, 0\.0\] m from the line, gaps",
        ),
        # a cradle with an inelastic pair
        (
            dataclasses.replace(
                get_scenario("newtons_cradle"), pair_restitution=((0, 1, 1.0), (1, 2, 0.9))
            ),
            r"each pair of neighbours elastic",
        ),
    ],
)  # fmt: skip
def test_a_variant_outside_its_reference_is_refused_with_the_reason(scenario, match):
    with pytest.raises(MechanicsValueError, match=match):
        reference(scenario)


def test_a_box_that_never_stops_or_stops_at_once_says_so():
    s, ref = _ref("sliding_stop")
    tr = ref.trajectory
    never = dataclasses.replace(tr, velocity=np.broadcast_to(tr.velocity[:1], tr.velocity.shape))
    assert measure(s, never)["stop_time"] == "the box does not stop within the samples"
    at_once = dataclasses.replace(tr, velocity=np.zeros_like(tr.velocity))
    assert measure(s, at_once)["stop_time"] == (
        "the box stops before the second sample: no deceleration to read"
    )


# -- oblique impacts on rough ground, and a ball bouncing to rest ---------------------


def _impact_states(name):
    """(scenario, the states just before and just after the impact, whether it sticks)."""
    from mechanics.conformance.scenarios import _oblique_numbers

    s = get_scenario(name)
    b, r, n, _, v1, w1, v2, w2, sticks = _oblique_numbers(s)
    return s, b, r, np.asarray(n), (v1, w1), (v2, w2), sticks


@pytest.mark.parametrize("name", ["oblique_impact_sticks", "oblique_impact_slips"])
def test_an_oblique_impact_keeps_the_angular_momentum_about_the_contact_point(name):
    s, b, r, n, (v1, w1), (v2, w2), _ = _impact_states(name)
    m, J = b.mass, b.inertia[0]
    # every impulse acts at the contact point C = G − r n: L about C is kept (Section 6.2)
    L1 = m * np.cross(r * n, v1) + J * w1
    L2 = m * np.cross(r * n, v2) + J * w2
    np.testing.assert_allclose(L2, L1, rtol=0, atol=LAW_RTOL * np.linalg.norm(L1))
    # Newton's e on the normal part (6.6), and no energy gained
    assert abs(v2 @ n + s.ground.restitution * (v1 @ n)) <= LAW_RTOL * abs(v1 @ n)
    T = lambda v, w: 0.5 * m * v @ v + 0.5 * J * w @ w  # noqa: E731
    assert T(v2, w2) <= T(v1, w1)


def test_the_sticking_impact_leaves_rolling_and_the_slipping_one_at_coulombs_bound():
    s, b, r, n, (v1, w1), (v2, w2), sticks = _impact_states("oblique_impact_sticks")
    assert sticks
    slip_after = v2 - (v2 @ n) * n + np.cross(w2, -r * n)
    assert np.linalg.norm(slip_after) <= LAW_RTOL * np.linalg.norm(v1)
    # a solid ball from a slide with no spin leaves at 5/7 of its tangential speed
    np.testing.assert_allclose(v2 - (v2 @ n) * n, 5 / 7 * (v1 - (v1 @ n) * n), rtol=LAW_RTOL)
    s, b, r, n, (v1, w1), (v2, w2), sticks = _impact_states("oblique_impact_slips")
    assert not sticks
    m = b.mass
    P = m * (v2 - v1)
    P_n, P_t = P @ n, P - (P @ n) * n
    assert abs(np.linalg.norm(P_t) - s.ground.friction * P_n) <= LAW_RTOL * P_n
    slip_before = v1 - (v1 @ n) * n + np.cross(w1, -r * n)
    slip_after = v2 - (v2 @ n) * n + np.cross(w2, -r * n)
    # still slipping the same way, more slowly
    assert slip_after @ slip_before > 0
    assert np.linalg.norm(slip_after) < np.linalg.norm(slip_before)


def test_an_impact_without_friction_fails_on_the_tangential_velocity_and_the_spin():
    def smooth(s):
        return dataclasses.replace(s, ground=dataclasses.replace(s.ground, friction=2.0**-60))

    for name in ("oblique_impact_sticks", "oblique_impact_slips"):
        bad = Wrapped("friction ignored", scenario=smooth, only={name})
        res = run_battery(bad, scenarios=[name], profile="second-order")[name]
        assert res.status == "fail", name
        assert res.figure("omega_after").passed is False
        assert res.figure("v_tangential_after").passed is False
        assert res.figure("apex_height_after").passed is True  # the normal law holds


def test_the_ball_rests_at_the_sum_of_its_flights():
    from mechanics.conformance.scenarios import REST_FRACTION, _rest_numbers

    s, ref = _ref("bounce_to_rest")
    v1, k, t_k, t_rest = _rest_numbers(s)
    e, g = s.ground.restitution, -s.gravity[2]
    # the flights one by one (rebound e^j v1 flies 2 e^j v1 / g) against the closed sums
    t, j = v1 / g, 0
    while e ** (j + 1) > REST_FRACTION:
        j += 1
        t += 2 * e**j * v1 / g
    assert j + 1 == k
    assert abs(t - t_k) <= LAW_RTOL * t_rest
    assert abs(v1 / g * (1 + e) / (1 - e) - t_rest) <= LAW_RTOL * t_rest
    tr = ref.trajectory
    rest = tr.t >= t_rest
    assert rest.any()
    assert not np.any(tr.velocity[rest])
    np.testing.assert_allclose(tr.position[rest, 0, 2], s.bodies[0].shape.dims[0], rtol=LAW_RTOL)
    # the rest time read is the first sample after impact k
    samples = np.asarray(s.sample_times)
    assert ref.figures["rest_time"] == samples[samples >= t_k][0]


def _jitters(s, tr):
    v = tr.velocity.copy()
    v[tr.t > 1.0, 0, 2] = 0.01  # a ball that never settles: 1 cm/s at the end
    return dataclasses.replace(tr, velocity=v)


def test_a_ball_that_never_settles_fails_on_the_rest_time_saying_so():
    bad = Wrapped("jitters", answer=_jitters, only={"bounce_to_rest"})
    res = run_battery(bad, scenarios=["bounce_to_rest"], profile="first-order")["bounce_to_rest"]
    assert res.status == "fail"
    assert res.figure("rest_time").value == math.inf
    assert "the ball does not come to rest within the samples" in res.message


@pytest.mark.parametrize(
    ("scenario", "match"),
    [
        (
            _with_body("oblique_impact_sticks", inertia=(0.004, 0.004, 0.005)),
            r"the ball's principal moments must be equal",
        ),
        (
            _with_body("incline_rolling", inertia=(0.004, 0.005, 0.004)),
            r"the ball's principal moments must be equal",
        ),
        (
            _with_body("oblique_impact_sticks", velocity=(1.0, 0.0, 0.5)),
            r"the ball starts falling or at rest along the normal",
        ),
        (
            dataclasses.replace(get_scenario("oblique_impact_sticks"), duration=1.0,
                                sample_times=tuple(k / 32 for k in range(33))),
            r"the run must end between the rebound's apex \(0\.45\d* s\) and the second "
            r"impact \(0\.6\d* s\)",
        ),
        (
            dataclasses.replace(get_scenario("bounce_to_rest"), duration=0.75,
                                sample_times=tuple(k / 32 for k in range(25))),
            r"rebounds fall below 0\.000976562 of its first impact speed at 0\.866\d s",
        ),
        (
            dataclasses.replace(get_scenario("bounce_to_rest"), ground=Ground(1.0)),
            r"a ball with e = 1 never comes to rest",
        ),
        (
            dataclasses.replace(get_scenario("free_top_axis1"),
                                sample_times=tuple(k / 4 for k in range(33))),
            r"the figure 'omega_period' read off its exact samples is 4\.27e-08 off "
            r"\(relative\), above the exact profile's 3\.73e-09: its samples are too sparse",
        ),
    ],
)  # fmt: skip
def test_a_variant_outside_the_range_its_figures_hold_for_is_refused(scenario, match):
    with pytest.raises(MechanicsValueError, match=match):
        check_scenario(scenario)


def test_the_reading_floor_is_the_exact_profiles_bound():
    from mechanics.conformance.scenarios import READ_RTOL
    from mechanics.conformance.thresholds import PROFILES

    assert PROFILES["exact"].rtol == READ_RTOL
