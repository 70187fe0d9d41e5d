"""Several contacts of one body at one instant are one impact problem (issue 27, item 1).

A body landing flat touches the plane at several corners at once; Newton's law must hold
at every one of them together (:meth:`mechanics.scenes.impacts.Resolver.together`): by
symmetry the body leaves with v_z = e v and no spin.  Resolving the corners one at a
time (the sequential model, right for a chain of distinct bodies) gives a spin and a
smaller v_z; the negative controls below show the checks catch it.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.scenes import SceneError, impacts, run_scene
from mechanics.scenes.engine import Engine
from mechanics.scenes.impacts import LAW_RTOL, solve_lcp

from .builders import box, scene

G = 9.81
#: the issue's bound for a body landing flat: v_z = e v and no spin to 1e-12 relative
FLAT_RTOL = 1e-12


_scene = functools.partial(scene, name="flat", samples=11, method="auto")


def _box(z=1.0, velocity=(0.0, 0.0, 0.0), omega=(0.0, 0.0, 0.0), **dims):
    """A box on the z axis at height z (edges 0.2, 0.4, 0.6 unless ``dims`` say)."""
    return box("box", (0.0, 0.0, z), velocity, omega=omega, **dims)


def _floor(e=0.5, friction=None):
    out = {"type": "impact", "body": "box", "restitution": e}
    if friction is not None:
        out["friction"] = friction
    return out


def _first_impact(result):
    (first, *_) = [ev for ev in result.trajectory.events if ev.kind == "impact"]
    return first.detail


@pytest.mark.parametrize("friction", [None, 0.8])
def test_the_issues_box_lands_flat_and_leaves_with_e_v_and_no_spin(friction) -> None:
    """The issue's box: 0.2 × 0.4 × 0.6 m, 1 kg, centre at z = 1.0, onto a smooth (and a
    rough, μ = 0.8) floor with e = 0.5: it falls 0.7 m, so v_z = e √(2 g 0.7) =
    1.85297 m/s after, no spin, no sliding (the old engine: 1.67154 m/s, 1.74 rad/s)."""
    drop = 0.7
    v = math.sqrt(2.0 * G * drop)
    t1 = math.sqrt(2.0 * drop / G)
    # to the top of the first rebound (the next landing is after 2 e v/g more)
    r = run_scene(
        _scene([_box()], [{"type": "gravity", "g": G}, _floor(0.5, friction)], duration=t1 + 0.1)
    )
    assert r.passed, r.summary()
    d = _first_impact(r)
    assert d["impact_model"] == "simultaneous"
    assert len(d["features"]) == 4  # the four corners of the 0.2 × 0.4 face
    (after,) = d["bodies_after"]
    np.testing.assert_allclose(after["v_G"], [0.0, 0.0, 0.5 * v], rtol=0, atol=FLAT_RTOL * v)
    # no spin: relative to v over the body's half-size
    np.testing.assert_allclose(after["omega"], np.zeros(3), rtol=0, atol=FLAT_RTOL * v / 0.1)
    assert 0.5 * v == pytest.approx(1.85297, abs=5e-6)  # the issue's figure
    assert d["law_residual"] <= LAW_RTOL


def test_a_plate_lands_flat_and_leaves_with_e_v_and_no_spin() -> None:
    plate = {
        "name": "box",
        "shape": "rectangular_plate",
        "mass": 2.0,
        "a": 0.3,
        "b": 0.5,
        "initial": {"position": [0.0, 0.0, 0.5]},
    }
    v, e = math.sqrt(2.0 * G * 0.5), 0.8
    r = run_scene(
        _scene(
            [plate],
            [{"type": "gravity", "g": G}, _floor(e)],
            duration=math.sqrt(1.0 / G) + 0.1,
        )
    )
    assert r.passed, r.summary()
    d = _first_impact(r)
    assert (d["impact_model"], len(d["features"])) == ("simultaneous", 4)
    (after,) = d["bodies_after"]
    np.testing.assert_allclose(after["v_G"], [0.0, 0.0, e * v], rtol=0, atol=FLAT_RTOL * v)
    np.testing.assert_allclose(after["omega"], np.zeros(3), rtol=0, atol=FLAT_RTOL * v / 0.15)


def test_a_cylinder_lands_flat_on_its_face_and_leaves_with_e_v_and_no_spin() -> None:
    """A cylinder's face is one rim feature whose support point, lying flat and not
    turning, is the face's centre: a single impulse through G."""
    cyl = {
        "name": "box",
        "shape": "cylinder",
        "mass": 1.5,
        "radius": 0.2,
        "height": 0.4,
        "initial": {"position": [0.0, 0.0, 0.7]},
    }
    v, e = math.sqrt(2.0 * G * 0.5), 0.6
    r = run_scene(
        _scene([cyl], [{"type": "gravity", "g": G}, _floor(e)], duration=math.sqrt(1.0 / G) + 0.1)
    )
    assert r.passed, r.summary()
    (after,) = _first_impact(r)["bodies_after"]
    np.testing.assert_allclose(after["v_G"], [0.0, 0.0, e * v], rtol=0, atol=FLAT_RTOL * v)
    np.testing.assert_allclose(after["omega"], np.zeros(3), rtol=0, atol=FLAT_RTOL * v / 0.2)


def test_a_box_sliding_as_it_lands_flat_on_a_rough_floor_is_refused_in_one_line() -> None:
    scene = _scene(
        [_box(velocity=(1.0, 0.0, 0.0))],
        [{"type": "gravity", "g": G}, _floor(0.5, 0.3)],
        duration=0.5,
    )
    with pytest.raises(SceneError) as info:
        run_scene(scene)
    assert info.value.field == "effects[1].friction"
    assert "4 contacts of body 'box' and the plane meet at once at t = 0.377" in info.value.reason
    assert "friction that slides are not modelled" in info.value.reason


def _at_contact(box, e, friction=None):
    """An engine with ``box`` resting on the floor z = 0 (its lowest corners at z = 0),
    and its floor impact."""
    eng = Engine(_scene([box], [_floor(e, friction)], duration=1.0))
    (imp,) = eng.impacts
    return eng, imp


@given(
    dims=st.tuples(*[st.floats(0.05, 2.0)] * 3),
    mass=st.floats(0.1, 10.0),
    e=st.floats(0.0, 1.0),
    v=st.floats(0.1, 10.0),
    slide=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)),
    spin=st.floats(-5.0, 5.0),
)
def test_any_smooth_box_landing_flat_keeps_its_slide_and_spin_and_leaves_with_e_v(
    dims, mass, e, v, slide, spin
) -> None:
    """On a smooth floor a box landing flat, sliding (v_x, v_y) and spinning about the
    vertical (ω_z), keeps them; its normal velocity reverses to e v; it gains no
    rocking spin.  Every corner's normal velocity is the same, so no corner is struck
    harder: the answer of one impulse e v m through G (independent of the LCP)."""
    a, b, c = dims
    box = _box(z=c / 2, velocity=(*slide, -v), omega=(0.0, 0.0, spin), a=a, b=b, c=c)
    box["mass"] = mass
    eng, imp = _at_contact(box, e)
    events: list = []
    (ft, *_) = [f for f in imp.features if f.at[2] < 0]
    eng.resolver.resolve(0.0, eng.y0.copy(), imp, ft, events)
    (ev,) = events
    d = ev.detail
    assert d["impact_model"] == "simultaneous"
    (after,) = d["bodies_after"]
    # velocities of O(v + |slide| + |spin| × size): the bound is relative to that
    size = v + abs(slide[0]) + abs(slide[1]) + abs(spin) * (a + b)
    np.testing.assert_allclose(after["v_G"], [*slide, e * v], rtol=0, atol=FLAT_RTOL * size)
    w = np.asarray(after["omega"])
    assert np.abs(w[:2]).max() <= FLAT_RTOL * size / min(a, b)
    assert w[2] == pytest.approx(spin, abs=FLAT_RTOL * size / min(a, b))
    assert d["law_residual"] <= LAW_RTOL
    assert d["energy_loss"] >= -64 * EPS * d["kinetic_energy_before"]


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_box_landing_on_an_edge_is_the_single_impulse_at_the_edges_middle(e) -> None:
    """A box tilted by θ about x lands on one edge: two corners at once, symmetric about
    x = 0, so the answer is the single impulse (6.36) at the edge's midpoint ρ = (0, y,
    z) from G: μ = 1/(1/m + y²/J_x... ) with the arm's moment about x, an independent
    closed form."""
    theta, m, v = 0.3, 1.0, 2.0
    a, b, c = 0.2, 0.4, 0.6
    box = _box(velocity=(0.0, 0.0, -v), a=a, b=b, c=c)
    box["initial"]["theta"] = theta
    # the lowest edge: body corners (±a/2, y0, z0) with the smallest height
    R = Engine(_scene([box], [_floor(e)], duration=1.0)).R0[0]
    corners = [np.array([0.0, sy * b / 2, sz * c / 2]) for sy in (-1, 1) for sz in (-1, 1)]
    mid = min(corners, key=lambda p: (R.T @ p)[2])
    rho = R.T @ mid  # from G, space components
    box["initial"]["position"] = [0.0, 0.0, -rho[2]]
    eng, imp = _at_contact(box, e)
    (ft, *_) = [f for f in imp.features if np.allclose(f.at[1:], mid[1:])]
    events: list = []
    eng.resolver.resolve(0.0, eng.y0.copy(), imp, ft, events)
    (ev,) = events
    d = ev.detail
    assert (d["impact_model"], len(d["features"])) == ("simultaneous", 2)
    J_x = m * (b * b + c * c) / 12.0  # about the body's (and space's) x axis
    mu = 1.0 / (1.0 / m + rho[1] ** 2 / J_x)
    P = (1.0 + e) * mu * v
    (after,) = d["bodies_after"]
    np.testing.assert_allclose(after["v_G"], [0.0, 0.0, -v + P / m], rtol=0, atol=64 * EPS * v)
    np.testing.assert_allclose(
        after["omega"], [rho[1] * P / J_x, 0.0, 0.0], rtol=0, atol=64 * EPS * v / 0.1
    )


def test_the_sequential_model_fails_the_flat_box_and_the_law_check_sees_it(monkeypatch) -> None:
    """Negative control: with the corners resolved one at a time (the old engine), the
    box leaves spinning, and the impact-law self-check fails the run."""
    monkeypatch.setattr(impacts.Resolver, "closing_with", lambda self, s, imp, ft, floor: [ft])
    drop = 0.7
    t1 = math.sqrt(2.0 * drop / G)
    r = run_scene(_scene([_box()], [{"type": "gravity", "g": G}, _floor(0.5)], duration=t1 + 0.1))
    assert not r.passed
    (bad,) = [c for c in r.self_checks if not c.ok]
    assert bad.name.startswith("impact law at every contact")
    d = _first_impact(r)
    (after,) = d["bodies_after"]
    assert abs(after["omega"][0]) + abs(after["omega"][1]) > 0.1  # the old spin


def test_newtons_cradle_stays_sequential_and_textbook() -> None:
    """A chain of distinct bodies meeting at an instant propagates as a sequence: a at
    1 m/s onto b touching c: a stops, b stops, c leaves at 1 m/s."""
    balls = [
        {"name": n, "shape": "solid_sphere", "mass": 1.0, "radius": 0.1,
         "initial": {"position": [x, 0.0, 0.0], "velocity": [vx, 0.0, 0.0]}}
        for n, x, vx in (("a", 0.0, 1.0), ("b", 0.7, 0.0), ("c", 0.9, 0.0))
    ]  # fmt: skip
    pairs = [
        {"type": "impact", "body": "a", "other": "b", "restitution": 1.0},
        {"type": "impact", "body": "b", "other": "c", "restitution": 1.0},
    ]
    r = run_scene(_scene(balls, pairs, duration=1.0))
    assert r.passed, r.summary()
    models = [ev.detail["impact_model"] for ev in r.trajectory.events]
    assert models == ["single", "sequential"]
    s = r.trajectory.series
    assert s["a.vx"][-1] == pytest.approx(0.0, abs=4 * EPS)
    assert s["b.vx"][-1] == pytest.approx(0.0, abs=4 * EPS)
    assert s["c.vx"][-1] == pytest.approx(1.0, abs=4 * EPS)


@given(
    G=st.lists(st.lists(st.floats(-2.0, 2.0), min_size=6, max_size=6), min_size=1, max_size=5),
    u=st.lists(st.floats(-3.0, 3.0), min_size=5, max_size=5),
)
def test_solve_lcp_gives_a_complementary_solution_of_a_psd_problem(G, u) -> None:
    """W = G Gᵀ (contact rows G of a 6-dof body: PSD, singular beyond 6 contacts or
    dependent rows) with q = G v (a velocity's normal components, so a solution exists
    for normals that cannot cancel; otherwise None is allowed): P ≥ 0, w = W P + q ≥ 0,
    P·w = 0, each within the rounding the solver allows (2^6 eps m × its terms)."""
    Gm = np.array(G)
    m = len(Gm)
    W = Gm @ Gm.T
    v = np.concatenate([u, [0.0]])
    q = Gm @ v
    P = solve_lcp(W, q)
    if P is None:  # no complementary basis within the rounding: allowed, never a wrong P
        return
    w = W @ P + q
    size = float(np.abs(W).max()) * float(np.abs(P).max(initial=0.0)) + float(np.abs(q).max())
    rnd = 2**6 * EPS * m * max(size, 1e-300)
    assert np.all(P >= 0.0)
    assert np.all(w >= -rnd)
    assert abs(float(P @ w)) <= rnd * (1.0 + float(np.abs(P).sum()))


def test_solve_lcp_negative_control_an_infeasible_problem_gives_none() -> None:
    """w = −1 + 0·P can never be ≥ 0: no basis passes, the solver says None."""
    assert solve_lcp(np.zeros((1, 1)), np.array([-1.0])) is None
    # and a feasible one with one contact: P = −q/W
    np.testing.assert_allclose(solve_lcp(np.array([[2.0]]), np.array([-3.0])), [1.5])


def test_a_scene_may_choose_the_sequential_model_and_the_result_says_so() -> None:
    """``model = "sequential"`` on the impact: the flat box's corners one at a time (the
    model chosen explicitly, each impulse obeying the law at its own contact); the
    events say "single" then "sequential", and the box leaves turning, unlike the
    default's one simultaneous event."""
    drop = 0.7
    t1 = math.sqrt(2.0 * drop / G)
    floor = {**_floor(0.5), "model": "sequential"}
    r = run_scene(_scene([_box()], [{"type": "gravity", "g": G}, floor], duration=t1 + 0.1))
    assert r.passed, r.summary()
    models = [ev.detail["impact_model"] for ev in r.trajectory.events]
    assert models[0] == "single"
    assert set(models[1:]) == {"sequential"}
    (after,) = r.trajectory.events[-1].detail["bodies_after"]
    assert abs(after["omega"][0]) + abs(after["omega"][1]) > 0.1
    auto = run_scene(
        _scene([_box()], [{"type": "gravity", "g": G}, _floor(0.5)], duration=t1 + 0.1)
    )
    assert [ev.detail["impact_model"] for ev in auto.trajectory.events] == ["simultaneous"]


def test_an_unknown_impact_model_is_refused_by_name() -> None:
    with pytest.raises(SceneError) as info:
        _scene([_box()], [{**_floor(0.5), "model": "simultaneous"}], duration=1.0)
    assert info.value.field == "effects[0].model"
    assert "expected 'auto' or 'sequential'; got 'simultaneous'" in info.value.reason
