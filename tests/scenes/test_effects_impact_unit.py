"""The impact effect (``mechanics/scenes/effects/impact.py``) on its own, on snapshots of
tiny scenes: its refusals word for word, its features and gaps, what it keeps and on
which bodies it exerts a moment (with and without friction), and the impulse against
hand-worked cases (Chapter 6: a ball on a plane, a box struck at a corner, a direct
impact of two balls, a sliding ball that slips or sticks).  Fast: no run."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.errors import SeparatingContactError
from mechanics.scenes.effects import CONSERVED

from ._effects import build, refusal, scene_of

#: an impulse of a few O(1) products and one 3×3 solve: a few dozen roundings
IMPULSE_RTOL = 32 * EPS


#: where each body starts unless a test says: apart, and 2 m above the floor
APART = {"a": 0.0, "c": 5.0, "f": 10.0, "b": 20.0, "r": 30.0, "d": 40.0, "y": 50.0, "p": 60.0}


def at(name):
    return {"position": [APART[name], 0.0, 2.0]}


def ball(name="a", m=2.0, radius=0.5, **initial):
    initial = initial or at(name)
    return {"name": name, "shape": "solid_sphere", "mass": m, "radius": radius, "initial": initial}


BOX = {"name": "b", "shape": "box", "mass": 3.0, "a": 1.0, "b": 0.5, "c": 0.25, "initial": at("b")}
ROD = {"name": "r", "shape": "rod", "mass": 1.0, "length": 2.0, "initial": at("r")}
DISC = {"name": "d", "shape": "disc", "mass": 1.0, "radius": 0.5, "initial": at("d")}
CYLINDER = {
    "name": "y", "shape": "cylinder", "mass": 1.0, "radius": 0.5, "height": 1.0, "initial": at("y")
}  # fmt: skip
POINT = {"name": "p", "shape": "point", "mass": 1.0, "initial": at("p")}
CUSTOM = {"name": "x", "shape": "custom", "mass": 1.0, "inertia": [1.0, 1.0, 1.0]}


def hit(body="a", **extra):
    return {"type": "impact", "body": body, "restitution": 0.5, **extra}


# ------------------------------------------------------------------ refusals

MODELLED = (
    "point, solid_sphere, hollow_sphere, box, rectangular_plate, rod, disc, ring, cylinder, "
    "cylindrical_shell"
)


@pytest.mark.parametrize(
    ("bodies", "spec", "field", "reason"),
    [
        ([ball()], hit(other="a"), "effects[0].other", "a body cannot hit itself"),
        ([ball(), ball("c")], hit(other="c", plane_point=[0.0, 0.0, 0.0]), "effects[0].other",
         "give either another body or a plane, not both"),
        ([ball(), ball("c")], hit(other="c", plane_normal=[0.0, 0.0, 1.0]), "effects[0].other",
         "give either another body or a plane, not both"),
        ([CUSTOM], hit("x"), "effects[0].body",
         f"contacts of a custom are not modelled (only {MODELLED}); body 'x'"),
        ([ball(), CUSTOM], hit(other="x"), "effects[0].other",
         f"contacts of a custom are not modelled (only {MODELLED}); body 'x'"),
        ([DISC, ball()], hit("d", other="a"), "effects[0].body",
         "the rim of a disc ('d') meets only a plane, not a body"),
        ([ball(), CYLINDER], hit(other="y"), "effects[0].other",
         "the rim of a cylinder ('y') meets only a plane, not a body"),
        ([BOX, ROD], hit("b", other="r"), "effects[0].other",
         "contacts between two polyhedral bodies (box, rod) are not modelled: one of the "
         "pair must be a sphere or a point"),
        ([{**ball(), "fixed": True}], hit(), "effects[0].body", "a fixed body cannot hit a plane"),
        ([{**ball(), "fixed": True}, {**ball("c"), "fixed": True}], hit(other="c"),
         "effects[0].other", "two fixed bodies never meet"),
    ],
)  # fmt: skip
def test_an_impact_refuses_word_for_word(bodies, spec, field, reason):
    err = refusal(bodies, [spec])
    assert (err.field, err.reason) == (field, reason)


@pytest.mark.parametrize(
    ("bodies", "spec"),
    [
        ([{**ball(), "fixed": True}, ball("c")], hit(other="c")),  # one fixed: it can be hit
        ([ball(), {**ball("c"), "fixed": True}], hit(other="c")),
        ([BOX, ball()], hit("b", other="a")),  # a corner against a sphere
        ([POINT, ROD], hit("p", other="r")),
        ([DISC], hit("d", plane_point=[0.0, 0.0, -1.0])),
    ],
)
def test_an_impact_takes_a_fixed_partner_a_sphere_and_a_corner_or_a_rim_and_a_plane(bodies, spec):
    assert scene_of(bodies, [spec]).effects[0].type == "impact"


# ------------------------------------------------------------------ features, keeps


def test_an_impact_reads_its_fields_and_defaults_to_the_floor_z_0_smooth():
    (e,), _ = build([ball()], [hit()])
    assert (e.i, e.j, e.e, e.mu_f) == (0, None, 0.5, 0.0)
    np.testing.assert_array_equal(e.point, [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(e.normal, [0.0, 0.0, 1.0])
    (e,), _ = build(
        [ball(), ball("c")],
        [hit("c", plane_point=[1.0, 2.0, 3.0], plane_normal=[0.0, -2.0, 0.0], friction=0.25)],
    )
    assert (e.i, e.j, e.mu_f) == (1, None, 0.25)
    np.testing.assert_array_equal(e.point, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(e.normal, [0.0, -1.0, 0.0])


def test_a_sphere_touches_with_its_centre_a_box_with_its_corners_a_rim_with_its_circles():
    (e,), _ = build([ball()], [hit()])
    assert [(f.body, f.at, f.a, f.sphere, f.flip) for f in e.features] == [
        (0, None, 0.5, None, False)
    ]
    assert e.features[0].label == "body 'a' and the plane"
    (e,), _ = build([BOX], [hit("b")])
    assert len(e.features) == 8
    np.testing.assert_array_equal(e.features[0].at, [-0.5, -0.25, -0.125])
    np.testing.assert_array_equal(e.features[7].at, [0.5, 0.25, 0.125])
    assert e.features[3].label == "body 'b' and the plane (corner 3 of 'b')"
    (e,), _ = build([DISC], [hit("d")])
    assert [(f.support, f.label) for f in e.features] == [
        ((0.5, 0.0), "body 'd' and the plane (the rim of 'd')")
    ]
    (e,), _ = build([CYLINDER], [hit("y")])
    assert [f.support for f in e.features] == [(0.5, 0.5), (0.5, -0.5)]
    assert e.features[0].label.endswith("(the rim of 'y', its +e3 end)")
    assert e.features[1].label.endswith("(the rim of 'y', its −e3 end)")


def test_a_pair_takes_the_sphere_as_the_sphere_and_the_other_bodys_corners_flipped():
    (e,), _ = build([ball(), ball("c", radius=0.25)], [hit(other="c")])
    assert e.label == "bodies 'a' and 'c'"
    assert [(f.body, f.a, f.sphere, f.a_s, f.flip) for f in e.features] == [
        (0, 0.5, 1, 0.25, False)
    ]
    (e,), _ = build([ball(), ROD], [hit(other="r")])
    # the rod's two ends against the ball: the feature belongs to ``other``, flipped
    assert [(f.body, f.a, f.sphere, f.a_s, f.flip) for f in e.features] == [
        (1, 0.0, 0, 0.5, True)
    ] * 2
    assert e.features[1].label == "bodies 'a' and 'r' (corner 1 of 'r')"
    (e,), _ = build([ROD, ball()], [hit("r", other="a")])
    assert [(f.body, f.sphere, f.flip) for f in e.features] == [(0, 1, False)] * 2


@pytest.mark.parametrize(
    ("normal", "kept"),
    [
        # a smooth impulse along the plane's normal n: p across n, L_O along n
        ([0.0, 0.0, 1.0], ["p_x", "p_y", "L_z"]),
        ([-3.0, 0.0, 0.0], ["p_y", "p_z", "L_x"]),
        ([0.0, 0.6, 0.8], ["p_x"]),
    ],
)
def test_a_smooth_impact_on_a_plane_keeps_what_a_force_along_its_normal_keeps(normal, kept):
    (e,), _ = build([ball()], [hit(plane_point=[5.0, 0.0, 0.0], plane_normal=normal)])
    assert [q for q in CONSERVED if e.keeps(q)] == kept


def test_a_rough_impact_on_a_plane_keeps_nothing():
    (e,), _ = build([ball()], [hit(friction=0.5)])
    assert [q for q in CONSERVED if e.keeps(q)] == []


@pytest.mark.parametrize(
    ("extra", "kept"),
    [
        # two free bodies: internal impulses keep p and L; E only if elastic and smooth
        ({"restitution": 0.5}, ["p_x", "p_y", "p_z", "L_x", "L_y", "L_z"]),
        ({"restitution": 1.0}, list(CONSERVED)),
        ({"restitution": 1.0, "friction": 0.5}, ["p_x", "p_y", "p_z", "L_x", "L_y", "L_z"]),
    ],
)
def test_an_impact_of_two_free_bodies_keeps_p_and_l_and_e_only_when_elastic_and_smooth(extra, kept):
    (e,), _ = build([ball(), ball("c")], [{**hit(other="c"), **extra}])
    assert [q for q in CONSERVED if e.keeps(q)] == kept


def test_an_impact_with_a_fixed_body_keeps_nothing():
    (e,), _ = build([ball(), {**ball("c"), "fixed": True}], [hit(other="c", restitution=1.0)])
    assert e.fixed == {1}
    assert e.bodies() == [0]
    assert [q for q in CONSERVED if e.keeps(q)] == []


def test_a_smooth_impact_turns_a_body_struck_at_a_corner_or_rim_never_a_sphere():
    """A smooth impulse is along n: through a sphere's centre (no moment); at a corner or
    a rim point off G's line it turns the body."""
    (e,), _ = build([ball()], [hit()])
    assert not e.exerts_moment(0)
    (e,), _ = build([BOX, ball()], [hit("b")])
    assert e.exerts_moment(0)
    assert not e.exerts_moment(1)
    (e,), _ = build([ball(), DISC], [hit("d")])
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)
    (e,), _ = build([ball(), ROD, ball("c")], [hit(other="r")])
    assert [e.exerts_moment(k) for k in range(3)] == [False, True, False]
    (e,), _ = build([ball(), ball("c")], [hit(other="c")])
    assert [e.exerts_moment(k) for k in range(2)] == [False, False]


def test_a_rough_impact_turns_every_moving_body_it_strikes():
    """With friction the impulse has a part across n: a moment about every centre."""
    (e,), _ = build([ball(), ball("c"), ball("f")], [hit(other="c", friction=0.5)])
    assert [e.exerts_moment(k) for k in range(3)] == [True, True, False]
    (e,), _ = build([ball(), {**ball("c"), "fixed": True}], [hit(other="c", friction=0.5)])
    assert [e.exerts_moment(k) for k in range(2)] == [True, False]
    (e,), _ = build([ball("f"), ball()], [hit(friction=0.5)])
    assert [e.exerts_moment(k) for k in range(2)] == [False, True]


# ------------------------------------------------------------------ gaps


def test_a_plane_gap_is_the_height_along_n_minus_the_radius_and_a_pair_gap_the_distance_minus_radii():
    (e,), eng = build(
        [ball(position=[1.0, 2.0, 0.75])],
        [hit(plane_point=[5.0, 5.0, 0.125], plane_normal=[0.0, 0.0, 4.0])],
    )
    s = eng.snapshot(0.0, eng.y0)
    # (0.75 − 0.125) − 0.5
    assert e.gap(s, e.features[0]) == 0.125
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 0.0]), ball("c", radius=0.25, position=[3.0, 4.0, 0.0])],
        [hit(other="c")],
    )
    s = eng.snapshot(0.0, eng.y0)
    assert e.gap(s, e.features[0]) == 5.0 - 0.5 - 0.25


# ------------------------------------------------------------------ impulses


def test_a_smooth_ball_rebounds_from_the_floor_with_minus_e_v_n_losing_half_mu_1_minus_e2_v_n2():
    """m = 2, v = (1, 0, −3), e = ½: v' = (1, 0, 3/2); loss ½·2·(3/4)·9 = 27/4."""
    (e,), eng = build([ball(position=[0.0, 0.0, 0.5], velocity=[1.0, 0.0, -3.0])], [hit()])
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[0]
    assert e.approach(s, ft) == 3.0
    S, n = e.contact(s, ft)
    np.testing.assert_array_equal(S, [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(n, [0.0, 0.0, 1.0])
    d = e.apply(s, ft)
    np.testing.assert_array_equal(s.v[0], [1.0, 0.0, 1.5])
    np.testing.assert_array_equal(s.omega[0], [0.0, 0.0, 0.0])
    assert d["energy_loss"] == 6.75
    assert (d["normal_speed_before"], d["normal_speed_after"]) == (3.0, 1.5)
    assert (d["kinetic_energy_before"], d["kinetic_energy_after"]) == (10.0, 3.25)
    assert d["body"] == "a"
    assert d["friction"] == "smooth"
    assert d["feature"] == "body 'a' and the plane"
    assert d["gap"] == 0.0
    assert "external_impulse" not in d


def test_an_impact_refuses_to_resolve_a_separating_contact():
    (e,), eng = build([ball(position=[0.0, 0.0, 0.5], velocity=[0.0, 0.0, 3.0])], [hit()])
    s = eng.snapshot(0.0, eng.y0)
    with pytest.raises(SeparatingContactError, match=r"the contact separates \(v_n = 3\.0 ≥ 0\)"):
        e.apply(s, e.features[0])


def test_a_box_struck_at_a_corner_turns_with_the_impulse_of_its_effective_mass():
    """Box m = 3, edges 1, ½, ¼: J = m (b²+c², a²+c², a²+b²)/12 = (5/64, 17/64, 5/16).
    Falling at 1 onto its corner ρ = (−½, −¼, −⅛): ρ × n = (−¼, ½, 0),
    1/μ = 1/3 + (1/16)/(5/64) + (1/4)/(17/64) = 1/3 + 4/5 + 16/17, P = (1 + e) μ;
    v_z = −1 + P/3, ω = P J⁻¹ (ρ × n) = P (−16/5, 32/17, 0)."""
    (e,), eng = build(
        [{**BOX, "initial": {"position": [0.0, 0.0, 0.125], "velocity": [0.0, 0.0, -1.0]}}],
        [hit("b", restitution=0.25)],
    )
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[0]
    inv_mu = Fraction(1, 3) + Fraction(4, 5) + Fraction(16, 17)
    P = Fraction(5, 4) / inv_mu
    d = e.apply(s, ft)
    np.testing.assert_allclose(
        s.v[0], [0.0, 0.0, float(-1 + P / 3)], rtol=IMPULSE_RTOL, atol=4 * EPS
    )
    # the size the corner's gap rounds relative to: its position G + ρ is made of
    # Σ|S| = ½ + ¼, Σ|G| = ⅛ and the arm Σ|ρ| = ⅞ (all exact in binary)
    np.testing.assert_array_equal(d["contact_point"], [-0.5, -0.25, 0.0])
    assert d["gap_scale"] == 1.75
    np.testing.assert_allclose(
        s.omega[0],
        [float(-P * Fraction(16, 5)), float(P * Fraction(32, 17)), 0.0],
        rtol=IMPULSE_RTOL,
        atol=4 * EPS,
    )
    # Newton's law at the corner: it leaves at e·1
    assert abs(-e.approach(s, ft) - 0.25) <= IMPULSE_RTOL


def test_an_impulse_adds_the_speeds_it_changed_to_the_contacts_rounding_scale():
    """The box of the test above, struck at its corner: the impulse P changes v_G by P/3
    and ω by P (−16/5, 32/17, 0), so the body's velocities now carry the rounding of
    P/3 + P |(−16/5, 32/17, 0)| |ρ|, |ρ| = √21/8 (Context.carried); the contacts' speed
    scale adds it to the speeds at the contact, and a run starts from none."""
    (e,), eng = build(
        [{**BOX, "initial": {"position": [0.0, 0.0, 0.125], "velocity": [0.0, 0.0, -1.0]}}],
        [hit("b", restitution=0.25)],
    )
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[0]
    assert e.carried[0] == 0.0
    P = float(Fraction(5, 4) / (Fraction(1, 3) + Fraction(4, 5) + Fraction(16, 17)))
    e.apply(s, ft)
    dw = P * np.hypot(16 / 5, 32 / 17)
    carried = P / 3 + dw * np.sqrt(21) / 8
    assert e.carried[0] == pytest.approx(carried, rel=IMPULSE_RTOL)
    S, _ = e.contact(s, ft)
    w_O = s.to_space(0, s.omega[0])
    at_contact = np.linalg.norm(s.v[0]) + np.linalg.norm(np.cross(w_O, S - s.r[0]))
    assert e.speed_scale(s, ft) == pytest.approx(at_contact + carried, rel=IMPULSE_RTOL)
    eng.model.carried[:] = 5.0  # as if from an earlier run: a run starts from none
    eng.run()
    _, fresh = build(
        [{**BOX, "initial": {"position": [0.0, 0.0, 0.125], "velocity": [0.0, 0.0, -1.0]}}],
        [hit("b", restitution=0.25)],
    )
    fresh.run()
    assert fresh.model.carried[0] > 0.0
    assert eng.model.carried[0] == fresh.model.carried[0]


def test_two_balls_meet_head_on_with_the_direct_impact_velocities():
    """m_a = 2 at 1, m_c = 1 at −1 along x, e = ½: centre-of-mass speed 1/3; v_a' = 0,
    v_c' = 1 (relative −1 = −e·2); loss ½ (2/3)(3/4)·4 = 1."""
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 0.0], velocity=[1.0, 0.0, 0.0]),
         ball("c", m=1.0, radius=0.25, position=[0.75, 0.0, 0.0], velocity=[-1.0, 0.0, 0.0])],
        [hit(other="c")],
    )  # fmt: skip
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[0]
    S, n = e.contact(s, ft)
    np.testing.assert_array_equal(S, [0.5, 0.0, 0.0])
    np.testing.assert_array_equal(n, [-1.0, 0.0, 0.0])  # into ``body`` from ``other``
    assert e.approach(s, ft) == 2.0
    assert e.speed_scale(s, ft) == 2.0
    d = e.apply(s, ft)
    np.testing.assert_array_equal(s.v, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    assert abs(d["energy_loss"] - 1.0) <= IMPULSE_RTOL
    assert d["bodies"] == ["a", "c"]
    assert d["momentum_before"] == d["momentum_after"] == [1.0, 0.0, 0.0]


@pytest.mark.parametrize(
    ("mu", "mode", "v_x", "omega_y"),
    [
        # slip: P = P_n (n − μ t̂), P_n = m v = 2 (e = 0, n·K·(n − μ t̂) = 1/m):
        # v_x = 1 − μ P_n/m, ω_y = (a μ P_n)/J with J = 2/5 m a² = 1/5
        (0.1, "slip", 0.9, 0.5),
        # stick: the contact stops, K_tt = 1/m + a²/J = 7/4, P_t = −4/7: v_x = 5/7, ω_y = 10/7
        (1.0, "stick", 5.0 / 7.0, 10.0 / 7.0),
    ],
)
def test_a_sliding_ball_on_a_rough_floor_slips_or_sticks(mu, mode, v_x, omega_y):
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 0.5], velocity=[1.0, 0.0, -1.0])],
        [hit(restitution=0.0, friction=mu)],
    )
    s = eng.snapshot(0.0, eng.y0)
    d = e.apply(s, e.features[0])
    assert d["friction"] == mode
    np.testing.assert_allclose(s.v[0], [v_x, 0.0, 0.0], rtol=IMPULSE_RTOL, atol=4 * EPS)
    np.testing.assert_allclose(s.omega[0], [0.0, omega_y, 0.0], rtol=IMPULSE_RTOL, atol=4 * EPS)
    # the loss is the kinetic energy's drop: 2 − (v_x² + ½·(1/5) ω_y²)
    lost = 2.0 - (v_x**2 + 0.1 * omega_y**2)
    assert abs(d["energy_loss"] - lost) <= IMPULSE_RTOL * 2.0


def test_a_ball_sticks_at_the_edge_of_the_friction_cone():
    """v = (7/4, 0, −1), e = 0: sticking needs P_t = −(7/4)/K_tt = −1 (K_tt = 7/4) and
    P_n = 2, on the cone's edge for μ = ½: it sticks (|P_t| ≤ μ P_n) and rolls off,
    v_x = 7/4 − ½ = 5/4, ω_y = (½·1)/(1/5) = 5/2, the contact at rest."""
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 0.5], velocity=[1.75, 0.0, -1.0])],
        [hit(restitution=0.0, friction=0.5)],
    )
    s = eng.snapshot(0.0, eng.y0)
    d = e.apply(s, e.features[0])
    assert d["friction"] == "stick"
    np.testing.assert_allclose(s.v[0], [1.25, 0.0, 0.0], rtol=IMPULSE_RTOL, atol=4 * EPS)
    np.testing.assert_allclose(s.omega[0], [0.0, 2.5, 0.0], rtol=IMPULSE_RTOL, atol=4 * EPS)


def test_the_speed_scale_adds_the_spins_part_of_the_contact_velocity():
    """Spin ω = 2 e_y, arm (0, 0, −½): ω × ρ = (−1, 0, 0); |v| = √2: scale √2 + 1; the
    spin does not change the approach speed 1."""
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 0.5], velocity=[1.0, 0.0, -1.0], omega=[0.0, 2.0, 0.0])], [hit()]
    )
    s = eng.snapshot(0.0, eng.y0)
    assert e.approach(s, e.features[0]) == 1.0
    assert abs(e.speed_scale(s, e.features[0]) - (2.0**0.5 + 1.0)) <= 4 * EPS
    # the kinetic energy ½ m v² + ½ J ω² = 2 + ½·(1/5)·4 = 12/5; the angular momentum's
    # scale |ρ| m |v| + |J ω| = ½·2·√2 + 2/5 (a smooth impulse leaves the spin)
    d = e.apply(s, e.features[0])
    assert abs(d["kinetic_energy_before"] - 2.4) <= 4 * EPS
    assert abs(d["angular_momentum_scale"] - (2.0**0.5 + 0.4)) <= 4 * EPS
    np.testing.assert_allclose(s.omega[0], [0.0, 2.0, 0.0], rtol=4 * EPS)


def test_a_rod_end_strikes_a_ball_above_it_along_the_normal_into_the_ball():
    """The ball 'a' (2 kg, radius ½, at z = 2) is ``body``; the rod's upper end, at
    z = 3/2, is the feature (flipped): n = +e_z into the ball.  The rod (1 kg) rising at
    1 hits the ball at rest, e = ½: common speed 1/3, ball 1/3 + ½·(1/3)·1 = ½, rod 0."""
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 2.0]),
         {**ROD, "initial": {"position": [0.0, 0.0, 0.5], "velocity": [0.0, 0.0, 1.0]}}],
        [hit(other="r")],
    )  # fmt: skip
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[1]
    np.testing.assert_array_equal(e.feature_point(s, ft), [0.0, 0.0, 1.5])
    S, n = e.contact(s, ft)
    np.testing.assert_array_equal(S, [0.0, 0.0, 1.5])
    np.testing.assert_array_equal(n, [0.0, 0.0, 1.0])
    assert e.approach(s, ft) == 1.0
    e.apply(s, ft)
    np.testing.assert_array_equal(s.v, [[0.0, 0.0, 0.5], [0.0, 0.0, 0.0]])


def test_a_hinged_rod_struck_at_its_end_rebounds_with_its_moment_about_the_axis():
    """A rod (1 kg, length 2) on the y axis, G 1 from it: J_a = 1/3 + 1 = 4/3.  With no
    gravity φ is measured from e_x: the rod lies along +x, its free end at (2, 0, 0);
    u1 = e_y × e_x = −e_z, so φ̇ = 1 drives that end down at 2 into the floor z = 0.
    μ = J_a/2² = 1/3, P = (1 + e) μ 2 = 1 with e = ½: φ̇' = 1 − 2 P/J_a = −½ (the end
    leaves at e·2); loss ½ μ (1 − e²) 2² = ½; the axis takes an impulse too."""
    (_, e), eng = build(
        [{**ROD, "initial": {"angle": 0.0, "angular_velocity": 1.0}}],
        [{"type": "fixed_axis", "body": "r", "axis": [0.0, 1.0, 0.0], "distance": 1.0,
          "body_axis": "y"},
         hit("r")],
    )  # fmt: skip
    s = eng.snapshot(0.0, eng.y0)
    (ft,) = [f for f in e.features if e.feature_point(s, f)[0] > 1.0]
    np.testing.assert_allclose(e.feature_point(s, ft), [2.0, 0.0, 0.0], rtol=0, atol=4 * EPS)
    assert abs(e.approach(s, ft) - 2.0) <= IMPULSE_RTOL
    d = e.apply(s, ft)
    assert abs(float(s.coords[0][1][0]) + 0.5) <= IMPULSE_RTOL
    assert abs(d["energy_loss"] - 0.5) <= IMPULSE_RTOL
    assert d["external_impulse"] == "the pivot, bearings or track of a joint"


@pytest.mark.parametrize(("friction", "mode"), [(0.0, "smooth"), (0.5, "stick")])
def test_a_rod_end_striking_a_ball_off_its_centre_line_turns_the_rod_and_pushes_both_apart(
    friction, mode
):
    """The rod (1 kg, length 2, J = 1/3 across it) upright at G = (0, 0, ½) moving at 1
    along x; its upper end (0, 0, 3/2) touches the ball (2 kg) at (½, 0, 3/2): n = e_x
    into the ball, the rod's arm ρ = e_z, ρ × n = e_y.  1/μ = ½ + 1 + 3 = 9/2, e = ½:
    P = (3/2)(2/9) = 1/3.  Ball: 1/6; rod: 1 − 1/3 = 2/3 and ω = 3 (e_z × (−P e_x))
    = −e_y; its end then moves at −1/3, half the approach speed 1 behind the ball.
    With friction: no sliding at the contact, K = diag(9/2, 9/2, 3/2) has no coupling of
    n to the tangent, the sticking impulse is the same P n."""
    (e,), eng = build(
        [ball(position=[0.5, 0.0, 1.5]),
         {**ROD, "initial": {"position": [0.0, 0.0, 0.5], "velocity": [1.0, 0.0, 0.0]}}],
        [hit(other="r", friction=friction)],
    )  # fmt: skip
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[1]
    assert e.approach(s, ft) == 1.0
    d = e.apply(s, ft)
    np.testing.assert_allclose(
        s.v, [[1 / 6, 0.0, 0.0], [2 / 3, 0.0, 0.0]], rtol=IMPULSE_RTOL, atol=4 * EPS
    )
    np.testing.assert_allclose(s.omega[1], [0.0, -1.0, 0.0], rtol=IMPULSE_RTOL, atol=4 * EPS)
    np.testing.assert_array_equal(s.omega[0], [0.0, 0.0, 0.0])
    assert abs(-e.approach(s, ft) - 0.5) <= IMPULSE_RTOL
    # loss ½ μ (1 − e²) v_n² = ½ (2/9)(3/4) = 1/12
    assert abs(d["energy_loss"] - 1 / 12) <= IMPULSE_RTOL


def test_a_box_corner_slipping_on_a_rough_floor_stops_along_the_normal_for_e_0():
    """The box of the corner test falls at 1 and slides at 1 along x, e = 0, μ = 1/8.
    Slip (sticking would need |P_t| ~ 1/K_tt ~ 1.7 ≫ μ P_n): P = P_n (n − μ e_x) with
    n·K·(n − μ e_x) = 1/μ_n − μ (ρ × n)·J⁻¹(ρ × e_x), ρ × e_x = (0, −1/8, 1/4):
    (ρ × n)·J⁻¹(ρ × e_x) = ½·(64/17)·(−1/8) = −4/17, so P_n = 1/(1/μ_n + 1/34);
    v' = (1 − μ P_n/3, 0, −1 + P_n/3) and the corner no longer approaches."""
    (e,), eng = build(
        [{**BOX, "initial": {"position": [0.0, 0.0, 0.125], "velocity": [1.0, 0.0, -1.0]}}],
        [hit("b", restitution=0.0, friction=0.125)],
    )
    s = eng.snapshot(0.0, eng.y0)
    ft = e.features[0]
    P_n = 1 / (Fraction(1, 3) + Fraction(4, 5) + Fraction(16, 17) + Fraction(1, 34))
    d = e.apply(s, ft)
    assert d["friction"] == "slip"
    np.testing.assert_allclose(
        s.v[0], [float(1 - P_n / 24), 0.0, float(-1 + P_n / 3)], rtol=IMPULSE_RTOL, atol=4 * EPS
    )
    assert abs(e.approach(s, ft)) <= IMPULSE_RTOL


def test_a_rim_touches_the_floor_at_its_lowest_point_or_flat_where_it_turns_down():
    """A disc on its edge (θ = π/2: e3 along −e_y) touches with the rim point a below G.
    Lying flat every rim point is lowest: the one that approaches fastest, along
    ω × n: with ω = e_x that is −a e_y (its velocity e_x × (−a e_y) = −a e_z); with no
    spin, the face's centre.  A flat cylinder's two circles sit at ±h/2 on e3."""
    (e,), eng = build(
        [{**DISC, "initial": {"position": [0.0, 0.0, 2.0], "theta": np.pi / 2}}], [hit("d")]
    )
    s = eng.snapshot(0.0, eng.y0)
    np.testing.assert_allclose(
        e.feature_point(s, e.features[0]), [0.0, 0.0, 1.5], rtol=0, atol=4 * EPS
    )
    assert abs(e.gap(s, e.features[0]) - 1.5) <= 4 * EPS
    (e,), eng = build([{**DISC, "initial": {"position": [0.0, 0.0, 2.0]}}], [hit("d")])
    s = eng.snapshot(0.0, eng.y0)
    np.testing.assert_array_equal(e.feature_point(s, e.features[0]), [0.0, 0.0, 2.0])
    (e,), eng = build(
        [{**DISC, "initial": {"position": [0.0, 0.0, 2.0], "omega": [1.0, 0.0, 0.0]}}], [hit("d")]
    )
    s = eng.snapshot(0.0, eng.y0)
    np.testing.assert_array_equal(e.feature_point(s, e.features[0]), [0.0, -0.5, 2.0])
    (e,), eng = build([{**CYLINDER, "initial": {"position": [0.0, 0.0, 2.0]}}], [hit("y")])
    s = eng.snapshot(0.0, eng.y0)
    np.testing.assert_array_equal(e.feature_point(s, e.features[0]), [0.0, 0.0, 2.5])
    np.testing.assert_array_equal(e.feature_point(s, e.features[1]), [0.0, 0.0, 1.5])


def test_an_impacts_details_report_the_gap_its_scale_and_the_totals_before_and_after():
    """The ball (2 kg, radius ½) 1/4 above the plane z = ½ through p = (1, −2, ½)
    (apply does not look at the gap): gap (5/4 − ½) − ½ = ¼, its scale
    |x|₁ + |r_G|₁ + |p|₁ + a = 5/4 + 5/4 + 7/2 + ½ = 13/2; S = (0, 0, ¾); the momentum (2, 0, −6) → (2, 0, 3), its scale m|v| = 2√10; about S
    the angular momentum (0, 0, ½) × m v = (0, 1, 0) before and after (the impulse
    passes through S), its scale ½·2·√10."""
    (e,), eng = build(
        [ball(position=[0.0, 0.0, 1.25], velocity=[1.0, 0.0, -3.0])],
        [hit(plane_point=[1.0, -2.0, 0.5])],
    )
    s = eng.snapshot(0.0, eng.y0)
    d = e.apply(s, e.features[0])
    assert d["gap"] == 0.25
    assert d["gap_scale"] == 6.5
    assert (d["contact_point"], d["normal"]) == ([0.0, 0.0, 0.75], [0.0, 0.0, 1.0])
    assert (d["momentum_before"], d["momentum_after"]) == ([2.0, 0.0, -6.0], [2.0, 0.0, 3.0])
    assert abs(d["momentum_scale"] - 2 * 10**0.5) <= 4 * EPS
    assert d["angular_momentum_before"] == d["angular_momentum_after"] == [0.0, 1.0, 0.0]
    assert abs(d["angular_momentum_scale"] - 10**0.5) <= 4 * EPS
    assert d["attitude_defect"] == 0.0
    (b0,) = d["bodies_before"]
    assert (b0["index"], b0["m"], b0["r_G"], b0["v_G"], b0["omega"]) == (
        0, 2.0, [0.0, 0.0, 1.25], [1.0, 0.0, -3.0], [0.0, 0.0, 0.0]
    )  # fmt: skip
    # J = 2/5 m a² = 1/5 about every axis
    np.testing.assert_allclose(b0["J_G"], 0.2 * np.eye(3), rtol=4 * EPS, atol=0)
    assert d["bodies_after"][0]["v_G"] == [1.0, 0.0, 1.5]


def test_a_ball_pinned_off_the_origin_swings_back_with_its_centre_moving_about_the_pivot():
    """A ball (2 kg, radius ½, J_G = 2/5·2·¼ = 1/5) on a fixed point C = (10, 0, 3) one
    metre below G (θ = 0: G = (10, 0, 4)), turning at ω = e_y, so G moves at
    ω × (G − C) = e_x into the wall x = 10.5 (normal −e_x).  The contact S = (10.5, 0, 4),
    S − C = (½, 0, 1): approach ω × (S − C) · e_x = 1, (S − C) × n = −e_y, J_C = 1/5 + 2·1²
    = 11/5 about e_y: 1/μ = 5/11, P = (1 + ½)·1·11/5 = 33/10, Δω = −P/J_C e_y = −3/2 e_y.
    After: ω = −½ e_y, G moves at −½ e_x about C, the point S at −½ = −e · 1."""
    pinned = {**ball(), "initial": {"theta": 0.0, "omega": [0.0, 1.0, 0.0]}}
    (_, e), eng = build(
        [pinned],
        [{"type": "fixed_point", "body": "a", "distance": 1.0, "point": [10.0, 0.0, 3.0]},
         hit(plane_point=[10.5, 0.0, 0.0], plane_normal=[-1.0, 0.0, 0.0])],
    )  # fmt: skip
    s = eng.snapshot(0.0, eng.y0)
    np.testing.assert_allclose(s.r[0], [10.0, 0.0, 4.0], rtol=0, atol=16 * EPS)
    np.testing.assert_allclose(s.v[0], [1.0, 0.0, 0.0], rtol=0, atol=16 * EPS)
    (ft,) = e.features
    assert abs(e.approach(s, ft) - 1.0) <= IMPULSE_RTOL
    d = e.apply(s, ft)
    np.testing.assert_allclose(s.omega[0], [0.0, -0.5, 0.0], rtol=0, atol=IMPULSE_RTOL)
    # G's velocity about the pivot C, not about the origin nor −C
    np.testing.assert_allclose(s.v[0], [-0.5, 0.0, 0.0], rtol=0, atol=IMPULSE_RTOL)
    assert abs(d["normal_speed_after"] - 0.5) <= IMPULSE_RTOL
    # loss ½ μ (1 − e²) v_n² = ½ (11/5)(3/4) = 33/40
    assert abs(d["energy_loss"] - 33 / 40) <= IMPULSE_RTOL
    assert d["external_impulse"] == "the pivot, bearings or track of a joint"


def test_a_face_lying_flat_offers_the_rim_point_that_approaches_fastest():
    """A cylinder (radius ½, height 1) lying flat on the floor, tipping at ω = 2 e_x: every
    point of its lower rim is lowest; the one chosen moves down fastest, along
    ω × e3 = (0, −2, 0): the rim point at −a e_y of the lower face, (50, −½, 0), which
    moves at ω × (0, −½, −½) = (0, 1, −1): down at 2a = 1."""
    flat = {**CYLINDER, "initial": {"position": [50.0, 0.0, 0.5], "omega": [2.0, 0.0, 0.0]}}
    (e,), eng = build([flat], [hit("y")])
    s = eng.snapshot(0.0, eng.y0)
    (lower,) = [ft for ft in e.features if ft.support[1] < 0]
    np.testing.assert_allclose(e.feature_point(s, lower), [50.0, -0.5, 0.0], rtol=0, atol=4 * EPS)
    assert abs(e.approach(s, lower) - 1.0) <= IMPULSE_RTOL
