"""The effects' common interface (``mechanics/scenes/effects/base.py``), unit by unit: the
snapshot's frames (passive R_A_O: body components R x, space components Rᵀ x), body
points and their velocities (2.66), the loads' moments about G, what a force along one
fixed direction keeps, the gravity of a scene, the checks shared by the joints, and
what the base class contributes (nothing)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import SceneError
from mechanics.scenes.effects import base
from mechanics.scenes.effects.capabilities import CAPABILITIES

from ._effects import assert_says, refusal, scene_of
from .builders import snap

#: a product of a rotation matrix and a vector, summed over 3 terms, of O(1) values: a few
#: roundings each
ROTATE_ATOL = 8 * EPS


def _r3(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _r1(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


#: a rotation with no zero entry (passive R3(ψ) R1(θ) R3(φ) of ψ = 0.3, θ = 1.1, φ = -0.7)
R_GENERAL = _r3(0.3) @ _r1(1.1) @ _r3(-0.7)
#: the body's axes are the space axes y, z, x (rows of R_A_O: e_1 = e_y, e_2 = e_z,
#: e_3 = e_x; a proper rotation, exact in floats)
R_CYCLIC = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])


def two_bodies(**kw) -> base.Snapshot:
    """Body 0 at rest at the origin (identity attitude), body 1 moving and turning."""
    return snap(
        r=[[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]],
        v=[[0.0, 0.0, 0.0], [0.5, -1.0, 2.0]],
        R=[np.eye(3), R_CYCLIC],
        omega=[[0.0, 0.0, 0.0], [0.0, 0.0, 2.0]],
        m=[1.0, 2.0],
        J=[[1.0, 1.0, 1.0], [1.0, 2.0, 2.0]],
        **kw,
    )


ROD = {"name": "rod", "shape": "box", "mass": 1.0, "a": 1.0, "b": 0.5, "c": 0.25}
POINT = {"name": "p", "shape": "point", "mass": 1.0}


# ------------------------------------------------------------------ the snapshot


def test_to_space_is_r_transposed_and_to_body_is_r_for_a_passive_attitude() -> None:
    s = two_bodies()
    # the body's x axis is the space y axis (first row of R_CYCLIC): body (1, 0, 0) is
    # space (0, 1, 0); a space x is the body's z (third row)
    np.testing.assert_array_equal(s.to_space(1, [1.0, 0.0, 0.0]), [0.0, 1.0, 0.0])
    np.testing.assert_array_equal(s.to_space(1, [0.0, 0.0, 5.0]), [5.0, 0.0, 0.0])
    np.testing.assert_array_equal(s.to_body(1, [1.0, 0.0, 0.0]), [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(s.to_body(1, [0.0, 3.0, 0.0]), [3.0, 0.0, 0.0])
    # body 0 has the identity attitude: both leave a vector as it is
    np.testing.assert_array_equal(s.to_space(0, [1, 2, 3]), [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(s.to_body(0, [1, 2, 3]), [1.0, 2.0, 3.0])


def test_to_body_and_to_space_are_inverse_and_match_the_matrix_products() -> None:
    s = snap([[0.0] * 3], [[0.0] * 3], [R_GENERAL], [[0.0] * 3], [1.0], [[1.0] * 3])
    x = np.array([0.3, -1.2, 2.5])
    np.testing.assert_allclose(s.to_body(0, x), R_GENERAL @ x, rtol=0, atol=ROTATE_ATOL * 3)
    np.testing.assert_allclose(s.to_space(0, x), R_GENERAL.T @ x, rtol=0, atol=ROTATE_ATOL * 3)
    np.testing.assert_allclose(s.to_space(0, s.to_body(0, x)), x, rtol=0, atol=ROTATE_ATOL * 3)


def test_to_space_and_to_body_broadcast_over_leading_time_axes() -> None:
    # two instants: attitude identity then R_CYCLIC, of one body
    R = np.stack([np.eye(3), R_CYCLIC])[:, None]  # (2, 1, 3, 3)
    s = base.Snapshot(
        np.array([0.0, 1.0]),
        np.zeros((2, 1, 3)),
        np.zeros((2, 1, 3)),
        np.zeros((2, 1, 3)),
        R,
        np.zeros((2, 1, 3)),
        np.ones((2, 1)),
        np.ones((2, 1, 3)),
    )
    np.testing.assert_array_equal(s.to_space(0, [1.0, 0.0, 0.0]), [[1, 0, 0], [0, 1, 0]])
    np.testing.assert_array_equal(s.to_body(0, [1.0, 0.0, 0.0]), [[1, 0, 0], [0, 0, 1]])
    assert s.angle.shape == (2, 1)
    np.testing.assert_array_equal(s.angle, np.zeros((2, 1)))


def test_a_body_point_is_g_plus_its_offset_turned_into_space() -> None:
    s = two_bodies()
    np.testing.assert_array_equal(s.point(1), [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(s.point(0), [0.0, 0.0, 0.0])
    # body (1, 0, 2) is space (0, 1, 0) + 2 (1, 0, 0) = (2, 1, 0), about G = (1, 2, 3)
    np.testing.assert_array_equal(s.point(1, [1.0, 0.0, 2.0]), [3.0, 3.0, 3.0])


def test_a_body_point_moves_with_v_plus_omega_cross_its_offset() -> None:
    s = two_bodies()
    np.testing.assert_array_equal(s.point_velocity(1), [0.5, -1.0, 2.0])
    # ω = 2 about the body z, which is space x: ω_O = (2, 0, 0); the body point (1, 0, 0)
    # is at space (0, 1, 0) from G; ω_O × (0, 1, 0) = (0, 0, 2)
    np.testing.assert_array_equal(s.point_velocity(1, [1.0, 0.0, 0.0]), [0.5, -1.0, 4.0])
    # a point on the spin axis moves with G
    np.testing.assert_array_equal(s.point_velocity(1, [0.0, 0.0, 3.0]), [0.5, -1.0, 2.0])
    # body 0 is at rest and does not turn
    np.testing.assert_array_equal(s.point_velocity(0, [1.0, 1.0, 1.0]), [0.0, 0.0, 0.0])


def test_point_velocity_is_the_time_derivative_of_the_point() -> None:
    """A central difference of the point over the exact rotation by ω_O h (the basis
    turns: R(t + h) = R(t) Q(h)ᵀ with Q the active rotation about ω_O)."""
    w_A = np.array([0.4, -0.3, 1.2])
    s = snap([[0.1, 0.2, 0.3]], [[1.0, -2.0, 0.5]], [R_GENERAL], [w_A], [1.0], [[1.0] * 3])
    at = np.array([0.5, -0.7, 0.9])
    w_O = R_GENERAL.T @ w_A

    def active(h):
        th = np.linalg.norm(w_O) * h
        k = w_O / np.linalg.norm(w_O)
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        return np.eye(3) + math.sin(th) * K + (1 - math.cos(th)) * K @ K

    h = 2.0**-12
    pts = []
    for sign in (1, -1):
        moved = snap(
            s.r + sign * h * s.v, s.v, [R_GENERAL @ active(sign * h).T], [w_A], [1.0], [[1.0] * 3]
        )
        pts.append(moved.point(0, at))
    fd = (pts[0] - pts[1]) / (2 * h)
    # truncation |ω|² |at| h²/6 ≈ 1e-8 at h = 2^-12; 2^28 eps = 6e-8
    np.testing.assert_allclose(s.point_velocity(0, at), fd, rtol=0, atol=2**28 * EPS)


def test_a_snapshot_starts_with_no_guides_no_tanks_and_its_phase_is_its_time() -> None:
    s = base.Snapshot(
        0.25, np.zeros((2, 3)), np.zeros((2, 3)), np.zeros((2, 3)),
        np.stack([np.eye(3)] * 2), np.zeros((2, 3)), np.ones(2), np.ones((2, 3)),
    )  # fmt: skip
    assert s.phase == 0.25
    assert s.t == 0.25
    assert s.coords == {}
    assert s.inertia == {}
    assert s.fluid == {}
    assert s.angle.shape == (2,)
    np.testing.assert_array_equal(s.angle, [0.0, 0.0])
    given = base.Snapshot(
        0.25, s.r, s.v, s.L_A, s.R, s.omega, s.m, s.J, phase=0.125, angle=np.array([0.5, 1.5])
    )
    assert given.phase == 0.125
    np.testing.assert_array_equal(given.angle, [0.5, 1.5])
    for name in ("r", "v", "L_A", "R", "omega", "m", "J"):
        assert getattr(given, name) is getattr(s, name)


# ------------------------------------------------------------------ the loads


def test_loads_start_at_zero_and_hold_their_snapshot() -> None:
    s = two_bodies()
    out = base.Loads(2, s)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    assert out.snap is s
    assert out.rates == {}


def test_a_force_at_g_has_no_moment_and_forces_add_up() -> None:
    out = base.Loads(2, two_bodies())
    out.force(1, [1, 2, 3])
    out.force(1, [0.5, 0.0, -1.0])
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [1.5, 2.0, 2.0]])
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))


def test_a_force_off_g_has_the_moment_of_its_lever_in_body_components() -> None:
    out = base.Loads(2, two_bodies())
    # F = (0, 0, 3) in space at the body point (1, 0, 0), which is space (0, 1, 0) from
    # G: moment (0, 1, 0) × (0, 0, 3) = (3, 0, 0) in space, (0, 0, 3) in body components
    out.force(1, [0.0, 0.0, 3.0], np.array([1.0, 0.0, 0.0]))
    np.testing.assert_array_equal(out.F[1], [0.0, 0.0, 3.0])
    np.testing.assert_array_equal(out.M_A[1], [0.0, 0.0, 3.0])
    out.force(1, [0.0, 0.0, 3.0], np.array([1.0, 0.0, 0.0]))  # adds, does not replace
    np.testing.assert_array_equal(out.M_A[1], [0.0, 0.0, 6.0])
    np.testing.assert_array_equal(out.M_A[0], [0.0, 0.0, 0.0])


def test_the_moment_of_a_force_off_g_is_the_lever_cross_force_in_space() -> None:
    s = snap([[0.0] * 3], [[0.0] * 3], [R_GENERAL], [[0.0] * 3], [1.0], [[1.0] * 3])
    out = base.Loads(1, s)
    at, F = np.array([0.3, -0.4, 1.2]), np.array([2.0, 0.5, -1.0])
    out.force(0, F, at)
    M_O = np.cross(R_GENERAL.T @ at, F)
    np.testing.assert_allclose(R_GENERAL.T @ out.M_A[0], M_O, rtol=0, atol=16 * ROTATE_ATOL)


def test_a_couple_in_space_components_is_stored_in_body_components() -> None:
    out = base.Loads(2, two_bodies())
    out.moment(1, [2.0, 0.0, 0.0])  # space x is the body's z
    np.testing.assert_array_equal(out.M_A[1], [0.0, 0.0, 2.0])
    out.moment(1, [0.0, 1.0, 0.0])  # space y is the body's x: adds
    np.testing.assert_array_equal(out.M_A[1], [1.0, 0.0, 2.0])
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A[0], [0.0, 0.0, 0.0])


def test_a_couple_in_body_components_is_added_as_it_is() -> None:
    out = base.Loads(2, two_bodies())
    out.moment_body(1, [2, 0, 0])
    out.moment_body(1, [0.0, 1.0, 0.0])
    np.testing.assert_array_equal(out.M_A[1], [2.0, 1.0, 0.0])
    np.testing.assert_array_equal(out.M_A[0], [0.0, 0.0, 0.0])
    assert out.M_A.dtype == np.float64


# ------------------------------------------------------------------ the helpers


def test_unit_divides_by_the_length() -> None:
    np.testing.assert_array_equal(base.unit([3, 0, 4]), [0.6, 0.0, 0.8])
    np.testing.assert_array_equal(base.unit([0.0, -2.0, 0.0]), [0.0, -1.0, 0.0])
    assert base.unit([3, 0, 4]).dtype == np.float64


@pytest.mark.parametrize("scale", [1e154, 3e200 / 3, 1e307])
def test_unit_of_a_huge_direction_is_exact_and_warns_nothing(scale) -> None:
    # |v| = 5 scale overflows the squares of numpy's norm beyond ~1e154: the vector is scaled
    # by its largest component first, (3/4, 0, 1) of norm 5/4, each quotient rounded once.
    # A RuntimeWarning would fail here (pytest: filterwarnings = error).
    np.testing.assert_array_equal(base.unit([3 * scale, 0.0, 4 * scale]), [0.6, 0.0, 0.8])
    top = np.finfo(np.float64).max
    np.testing.assert_array_equal(base.unit([top, 0.0, -top]), np.array([1, 0, -1]) / np.sqrt(2))


DIRECTIONS = [
    (0.0, 0.0, -1.0),
    (0.0, 2.0, 0.0),
    (-3.0, 0.0, 0.0),
    (1.0, 1.0, 0.0),
    (0.0, 1.0, -1.0),
    (1.0, -2.0, 3.0),
    (1e-300, 0.0, 1.0),
]


@pytest.mark.parametrize("d", DIRECTIONS)
def test_what_a_force_along_a_fixed_direction_keeps_follows_from_its_rates(d) -> None:
    """A force F d (any size, at any point r) changes the momentum by F d: p_k is kept
    iff d_k = 0; it changes the angular momentum about the origin by F r × d, whose k-th
    component vanishes for every r iff d is along e_k; it does work F d·v (E: not by
    this rule).  The rates are computed at random points."""
    rng = np.random.default_rng(7)
    dv = np.array(d)
    lever = np.cross(rng.normal(size=(50, 3)), dv)
    for k, axis in enumerate("xyz"):
        assert base.keeps_for_force_along(d, f"p_{axis}") == (dv[k] == 0)
        assert base.keeps_for_force_along(d, f"L_{axis}") == np.all(lever[:, k] == 0)
    assert not base.keeps_for_force_along(d, "E")


def test_gravity_vector_sums_the_listed_gravities_along_their_unit_directions() -> None:
    g = base.gravity_vector(
        scene_of(
            [POINT],
            [
                {"type": "gravity", "g": 2.0},  # default direction: down, (0, 0, -2)
                {"type": "gravity", "g": 5.0, "direction": [3.0, 0.0, 4.0]},  # (3, 0, 4)
                {"type": "gravity", "g": 1.0, "direction": [0.0, -7.0, 0.0]},  # (0, -1, 0)
            ],
        )
    )
    np.testing.assert_allclose(g, [3.0, -1.0, 2.0], rtol=0, atol=8 * EPS)
    assert g.shape == (3,)
    none = base.gravity_vector(scene_of([POINT], []))
    np.testing.assert_array_equal(none, np.zeros(3))
    assert none.shape == (3,)


def test_gravity_vector_of_one_default_gravity_points_down() -> None:
    g = base.gravity_vector(scene_of([POINT], [{"type": "gravity", "g": 9.5}]))
    np.testing.assert_array_equal(g, [0.0, 0.0, -9.5])


@pytest.mark.parametrize(
    ("body", "kind"),
    [(POINT, "a point"), ({**ROD, "name": "p", "fixed": True}, "fixed")],
)
def test_a_joint_refuses_a_point_or_a_fixed_body(body, kind) -> None:
    err = refusal([body], [{"type": "fixed_axis", "body": "p"}])
    assert_says(err, "effects[0].body", "body", "'p'", f"is {kind}:", "it cannot turn on an axis")
    assert err.reason == f"body 'p' is {kind}: it cannot turn on an axis"


def test_a_joint_refuses_a_tank() -> None:
    # the engine refuses any effect on a tank first; the joint's own check says it too
    tank = {"name": "t", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
    scene = scene_of(
        [tank],
        [{"type": "gravity", "g": 9.81}, {"type": "tank_outflow", "body": "t", "hole_area": 0.01}],
    )
    spec = type("Spec", (), {"fields": {"body": "t"}, "where": "effects[3]", "type": "x"})()
    with pytest.raises(SceneError) as info:
        base.check_joint_body(spec, scene, {"t": 0}, what="it cannot roll", keys=None)
    assert info.value.field == "effects[3].body"
    assert info.value.reason == "body 't' is a tank: it cannot roll"


def test_a_joint_refuses_a_thrust_on_its_body_but_not_on_another() -> None:
    thrust = {"type": "thrust", "mass_flow": 0.1, "exhaust_speed": 1.0, "fuel_mass": 0.1}
    err = refusal(
        [ROD, {**ROD, "name": "other"}],
        [
            {**thrust, "body": "other"},
            {"type": "fixed_axis", "body": "rod"},
            {**thrust, "body": "rod"},
        ],
    )
    assert_says(err, "effects[2].body", "body 'rod' is held by a joint:", "its mass cannot change")
    assert err.reason == "body 'rod' is held by a joint: its mass cannot change"
    scene_of(  # a thrust on another body is fine, and so is another effect on this one
        [ROD, {**ROD, "name": "other"}],
        [{**thrust, "body": "other"}, {"type": "fixed_axis", "body": "rod"}],
    )


def test_a_joint_refuses_an_initial_key_it_does_not_take_naming_the_ones_it_does() -> None:
    err = refusal(
        [POINT, {**ROD, "initial": {"angle": 0.1, "velocity": [1.0, 0.0, 0.0]}}],
        [{"type": "fixed_axis", "body": "rod"}],
    )
    assert err.field == "bodies[1].initial.velocity"
    assert err.reason == "a body on a fixed_axis takes angle, angular_velocity"
    # the keys it takes pass
    scene_of([{**ROD, "initial": {"angle": 0.1, "angular_velocity": 2.0}}], [
        {"type": "fixed_axis", "body": "rod"}
    ])  # fmt: skip


def test_check_joint_body_without_keys_accepts_any_initial_key() -> None:
    scene = scene_of([{**ROD, "initial": {"velocity": [1.0, 0.0, 0.0]}}], [])
    spec = type("Spec", (), {"fields": {"body": "rod"}, "where": "effects[0]", "type": "x"})()
    base.check_joint_body(spec, scene, {"rod": 0}, what="w", keys=None)  # no error
    with pytest.raises(SceneError) as info:
        base.check_joint_body(spec, scene, {"rod": 0}, what="w", keys=("angle",))
    assert info.value.field == "bodies[0].initial.velocity"
    assert info.value.reason == "a body on a x takes angle"


def test_a_torsion_spring_needs_a_fixed_axis_for_its_own_body() -> None:
    torsion = {"type": "torsion", "body": "rod", "stiffness": 1.0}
    err = refusal([ROD], [torsion])
    assert_says(err, "effects[0].type", "a torsion spring twists a body about its axis:")
    assert err.reason == (
        "a torsion spring twists a body about its axis: list a fixed_axis for 'rod'"
    )
    err = refusal(  # a fixed axis for another body does not do
        [ROD, {**ROD, "name": "b"}], [{"type": "fixed_axis", "body": "b"}, torsion]
    )
    assert err.field == "effects[1].type"
    assert err.reason.endswith("list a fixed_axis for 'rod'")
    scene_of([ROD, {**ROD, "name": "b"}], [  # its own axis, listed after another's: fine
        {"type": "fixed_axis", "body": "b"}, {"type": "fixed_axis", "body": "rod"}, torsion
    ])  # fmt: skip


# ------------------------------------------------------------------ the base class


def test_the_base_effect_contributes_nothing_and_claims_nothing() -> None:
    spec = scene_of([POINT], [{"type": "gravity", "g": 1.0}]).effects[0]
    ctx = object()
    e = base.Effect(spec, ctx)
    assert e.spec is spec
    assert e.fields is spec.fields
    assert e.ctx is ctx
    assert e.where == "effects[0]"
    assert repr(e) == "Effect({'g': 1.0})"
    s = two_bodies()
    out = base.Loads(2, s)
    e.loads(0.0, s, out)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    assert not any(isinstance(e, c) for c in CAPABILITIES)  # no potential, modes, ...
    assert e.series(s) == {}
    assert e.conserved(s) == {}
    assert not any(e.keeps(q) for q in base.CONSERVED)
    assert e.exerts_moment(0) is True
    assert e.exerts_moment(1) is True
    assert e.switch_times() == []
    assert e.acts_until() == math.inf
    assert e.after_loads is False
    assert base.Effect(spec).ctx is None


def test_register_makes_a_type_known_by_name_and_refuses_it_twice(monkeypatch) -> None:
    monkeypatch.setattr(base, "REGISTRY", {})

    class Made(base.Effect):
        type = "made_up"

    assert base.register(Made) is Made
    assert {"made_up": Made} == base.REGISTRY
    with pytest.raises(RuntimeError, match=r"effect type 'made_up' registered twice"):
        base.register(Made)
