"""The joints of ``mechanics/scenes/effects/`` on their own (rolling, fixed_axis,
fixed_point, mass_flow) and the tank outflow, plus :func:`mechanics.scenes.builtin_path`:
their guides' series and geometry against hand formulas, the fields they read, what they
keep (derived from their reactions), on which bodies they turn, and their refusals word
for word.  Fast: no run."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechanics.scenes
from mechanics._floats import EPS
from mechanics.scenes import builtin_path
from mechanics.scenes.effects import CONSERVED, REGISTRY, Loads
from mechanics.scenes.engine import Engine

from ._effects import build, refusal, scene_of
from .builders import bare_snap

#: a product or quotient of two or three O(1) factors: a few roundings
FORMULA_RTOL = 8 * EPS


def guide_of(bodies, effects, g_vector, which=0):
    """The guide the effect ``which`` makes of its body, given gravity ``g_vector``."""
    sc = scene_of(bodies, effects)
    spec = sc.effects[which]
    return REGISTRY[spec.type].make_guide(spec, sc, np.asarray(g_vector, dtype=float))


def own(spec_dict, bodies, which=0):
    """The effect object built from its fields alone (no scene context)."""
    sc = scene_of(bodies, [spec_dict])
    return REGISTRY[spec_dict["type"]](sc.effects[which])


GRAVITY = {"type": "gravity", "g": 9.81}
# a cylinder of radius 1/8, height 1/2, mass 2: J_z = m a²/2 = 1/64,
# J_x = J_y = m (3a² + h²)/12 = 2 (3/64 + 1/4)/12 = 19/384
CYL = {"name": "c", "shape": "cylinder", "mass": 2.0, "radius": 0.125, "height": 0.5}
BALL = {"name": "a", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5}
BOX = {"name": "b", "shape": "box", "mass": 3.0, "a": 1.0, "b": 0.5, "c": 0.25}
ROD = {"name": "r", "shape": "rod", "mass": 1.0, "length": 2.0}


# ------------------------------------------------------------------ rolling: the track


def track(**extra):
    return {"type": "rolling", "body": "c", "surface": "track", "track_radius": 0.5, **extra}


def test_a_track_reports_psi_psidot_phi_psi_R_over_r_and_g_on_the_circle_of_radius_R_minus_r():
    gd = guide_of([CYL], [track()], [0.0, 0.0, -9.81])
    psi = np.array([0.5, -0.25, 1.0])
    out = gd.series(psi[:, None], np.array([[3.0], [-1.0], [0.0]]))
    np.testing.assert_array_equal(out["psi"], psi)
    np.testing.assert_array_equal(out["psidot"], [3.0, -1.0, 0.0])
    # the body turns by ψ R/r = 4 ψ (R = 1/2, r = 1/8): exact
    np.testing.assert_array_equal(out["phi"], 4.0 * psi)
    # G at distance R − r = 3/8 from the axis, ψ from the lowest line
    np.testing.assert_allclose(out["x_G"], 0.375 * np.sin(psi), rtol=FORMULA_RTOL)
    np.testing.assert_allclose(out["z_G"], -0.375 * np.cos(psi), rtol=FORMULA_RTOL)


def test_a_track_places_g_at_r_minus_r_from_the_axis_and_turns_by_minus_its_ratio():
    gd = guide_of([CYL], [track()], [0.0, 0.0, -9.81])
    np.testing.assert_array_equal(gd.a, [0.0, -1.0, 0.0])
    np.testing.assert_array_equal(gd.u0, [0.0, 0.0, -1.0])  # gravity across the axis
    np.testing.assert_array_equal(gd.u1, [1.0, 0.0, 0.0])  # (−e_y) × (−e_z) = e_x
    assert (gd.r, gd.R, gd.m, gd.k) == (0.125, 0.5, 2.0, 2)
    # ω = −((R − r)/r) ψ̇ a = −3 ψ̇ a
    np.testing.assert_array_equal(gd.W, [[0.0, 3.0, 0.0]])
    G, E, _ = gd.place(np.array([[math.pi / 2]]))
    np.testing.assert_allclose(G[0], [0.375, 0.0, 0.0], rtol=FORMULA_RTOL, atol=FORMULA_RTOL)
    # dG/dψ = (R − r)(cos ψ u1 − sin ψ u0) = 3/8 (0, 0, 1) at ψ = π/2
    np.testing.assert_allclose(E[0, 0], [0.0, 0.0, 0.375], rtol=FORMULA_RTOL, atol=FORMULA_RTOL)
    # the centripetal term −(R − r) ψ̇² ρ̂ at ψ = 0, ψ̇ = 2: −3/8 · 4 (0, 0, −1)
    np.testing.assert_array_equal(gd.bend(np.array([0.0]), np.array([2.0])), [0.0, 0.0, 1.5])
    # M = (m + J_z/r²)(R − r)² = (2 + 1)·9/64
    assert gd.M_eff == 3.0
    np.testing.assert_array_equal(gd.M, [27.0 / 64.0])


@pytest.mark.parametrize(
    ("g", "u0"),
    [
        ([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]),  # no gravity: the lowest line is −e_z
        ([0.0, 5.0, 0.0], [0.0, 0.0, -1.0]),  # gravity along the axis: nothing across it
        ([3.0, 0.0, 0.0], [1.0, 0.0, 0.0]),  # gravity across: its direction
        ([0.0, 2.0, -4.0], [0.0, 0.0, -1.0]),  # only the part across the axis counts
    ],
)
def test_a_track_measures_psi_from_gravity_across_its_axis_else_from_minus_e_z(g, u0):
    gd = guide_of([CYL], [track()], g)
    np.testing.assert_array_equal(gd.u0, u0)
    np.testing.assert_array_equal(gd.u1, np.cross([0.0, -1.0, 0.0], u0))


def test_a_track_with_no_other_effect_rolls_uniformly():
    gd = guide_of([CYL], [track()], [0.0, 0.0, -9.81])
    how, f, ev = gd.exact([], 2.0, np.array([0.5]), np.array([3.0]), 1.0)
    assert how.startswith("exact: uniform rolling")
    assert ev == []
    q, qd = f(np.array(2.0))
    np.testing.assert_array_equal(q, [6.5])
    np.testing.assert_array_equal(qd, [3.0])


def test_a_track_swings_as_a_pendulum_under_the_part_of_gravity_across_its_axis():
    """Gravity g (0, 0.6, −0.8) against the track's axis −e_y: only g⊥ = 0.8 g across it
    drives ψ: (m + J/r²)(R − r)² ψ̈ = −m g⊥ (R − r) sin ψ, i.e. ψ̈ = −(2 · 0.8 g/(3 · 3/8))
    sin ψ, from rest at ψ0 = 0.3; the exact pendulum against DOP853 on that equation."""
    from scipy.integrate import solve_ivp

    sc = scene_of([CYL], [{**GRAVITY, "direction": [0.0, 0.6, -0.8]}, track()])
    eng = Engine(sc)
    gd = eng.layout.guides[0]
    _, f, _ = gd.exact([eng.effects[0]], 2.0, np.array([0.3]), np.array([0.0]), 1.0)
    k = 2.0 * 0.8 * 9.81 / (3.0 * 0.375)
    ts = np.linspace(0.0, 1.0, 5)
    sol = solve_ivp(lambda t, y: [y[1], -k * math.sin(y[0])], (0.0, 1.0), [0.3, 0.0],
                    method="DOP853", rtol=1e-13, atol=1e-15, t_eval=ts)  # fmt: skip
    q, qd = f(ts)
    # DOP853's own error over a swing of O(1): measured 273 eps on ψ, 301 on ψ̇ (of O(1));
    # 2^12 eps leaves a margin of 13
    np.testing.assert_allclose(np.ravel(q), sol.y[0], rtol=0, atol=2**12 * EPS)
    np.testing.assert_allclose(np.ravel(qd), sol.y[1], rtol=0, atol=2**12 * EPS)


# ------------------------------------------------------------------ rolling: the incline


def incline(**extra):
    return {"type": "rolling", "body": "c", "surface": "incline", "angle": math.pi / 6, **extra}


def test_an_incline_reports_s_v_omega_v_over_r_and_the_drop_s_sin_alpha():
    gd = guide_of([CYL], [incline()], [0.0, 0.0, -9.81])
    out = gd.series(np.array([[2.0], [-1.0]]), np.array([[0.5], [-3.0]]))
    np.testing.assert_array_equal(out["s"], [2.0, -1.0])
    np.testing.assert_array_equal(out["v"], [0.5, -3.0])
    np.testing.assert_array_equal(out["omega"], [4.0, -24.0])  # v/r, r = 1/8
    # sin(π/6) = 1/2
    np.testing.assert_allclose(out["drop"], [1.0, -0.5], rtol=FORMULA_RTOL)


def test_an_incline_places_g_at_r_n_plus_s_t_and_spins_about_e_y_by_s_over_r():
    gd = guide_of([CYL], [incline()], [0.0, 0.0, -9.81])
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    np.testing.assert_array_equal(gd.n, [s, 0.0, c])
    np.testing.assert_array_equal(gd.t, [c, 0.0, -s])
    np.testing.assert_array_equal(gd.a, [0.0, 1.0, 0.0])
    np.testing.assert_array_equal(gd.W, [[0.0, 8.0, 0.0]])  # a/r
    G, E, _ = gd.place(np.array([[2.0]]))
    np.testing.assert_allclose(G[0], [0.125 * s + 2 * c, 0.0, 0.125 * c - 2 * s], rtol=FORMULA_RTOL)
    np.testing.assert_array_equal(E[0, 0], [c, 0.0, -s])
    # M = m + J_z/r² = 2 + (1/64)·64 = 3
    np.testing.assert_array_equal(gd.M, [3.0])
    assert gd.alpha == math.pi / 6


def test_an_incline_with_no_angle_given_is_level():
    gd = guide_of([CYL], [{"type": "rolling", "body": "c", "surface": "incline"}], [0, 0, -9.81])
    assert gd.alpha == 0.0
    np.testing.assert_array_equal(gd.n, [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(gd.t, [1.0, 0.0, 0.0])


def test_an_incline_under_gravity_alone_accelerates_by_m_g_sin_alpha_over_m_plus_j_over_r2():
    """3.80: a = m g sin α / (m + J/r²) = 2·9.81·½/3 = 3.27."""
    sc = scene_of([CYL], [GRAVITY, incline()])
    eng = Engine(sc)
    gravity = eng.effects[0]
    gd = eng.layout.guides[0]
    how, f, _ = gd.exact([gravity], 2.0, np.array([0.0]), np.array([1.0]), 1.0)
    assert "3.80" in how
    q, qd = f(np.array(2.0))
    acc = 2.0 * 9.81 * 0.5 / 3.0
    np.testing.assert_allclose(qd, [1.0 + 2.0 * acc], rtol=FORMULA_RTOL)
    np.testing.assert_allclose(q, [2.0 + 2.0 * acc], rtol=FORMULA_RTOL)
    assert gd.exact([gravity, eng.effects[1]], 2.0, np.array([0.0]), np.array([1.0]), 1.0) is None


def test_rolling_reads_its_body_axis_and_uses_the_moment_about_it():
    """About x: J_x = 19/384 for the cylinder; m + J_x/r² = 2 + 19/6 = 31/6."""
    e = own(incline(body_axis="x"), [CYL])
    assert e.body_axis == 0
    J_G = np.diag([19.0 / 384.0, 19.0 / 384.0, 1.0 / 64.0])
    assert abs(e.effective_mass(2.0, J_G, 0.125) - 31.0 / 6.0) <= FORMULA_RTOL * 31.0 / 6.0
    assert own(incline(), [CYL]).body_axis == 2  # z by default
    gd = guide_of([CYL], [incline(body_axis="x")], [0.0, 0.0, -9.81])
    assert gd.k == 0
    assert abs(gd.M[0] - 31.0 / 6.0) <= FORMULA_RTOL * 31.0 / 6.0
    assert guide_of([CYL], [track(body_axis="y")], [0.0, 0.0, -1.0]).k == 1


def test_rolling_keeps_only_the_energy_and_turns_only_its_body():
    """The contact point is at rest: the contact force does no work (E), but it changes
    the momentum and the angular momentum (friction and normal force)."""
    (_, e), _ = build([BALL, CYL], [GRAVITY, {**incline(), "body": "c"}])
    assert [q for q in CONSERVED if e.keeps(q)] == ["E"]
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)
    assert own(incline(), [CYL]).exerts_moment(5)  # no scene: every body


def test_rolling_refuses_a_body_that_is_not_round_with_its_name_and_shape():
    err = refusal([BOX], [{"type": "rolling", "body": "b", "surface": "incline"}])
    assert err.field == "effects[0].body"
    assert err.reason == (
        "only round bodies roll (ring, disc, cylinder, cylindrical_shell, solid_sphere, "
        "hollow_sphere); 'b' is a box"
    )


@pytest.mark.parametrize(
    ("spec", "field", "reason"),
    [
        (incline(angle=math.pi / 2), "effects[0].angle", f"must lie in [0, π/2); got {math.pi / 2!r}"),
        (incline(angle=-0.5), "effects[0].angle", "must lie in [0, π/2); got -0.5"),
        (track(track_radius=0.125), "effects[0].track_radius",
         "must exceed the body's radius 0.125 (R > r); got 0.125"),
        ({"type": "rolling", "body": "c", "surface": "track"}, "effects[0].track_radius",
         "missing required field for a track"),
        ({"type": "rolling", "body": "c", "surface": "floor"}, "effects[0].surface",
         "expected 'incline' or 'track'; got 'floor'"),
    ],
)  # fmt: skip
def test_rolling_refuses_a_bad_slope_track_or_surface_word_for_word(spec, field, reason):
    err = refusal([CYL], [spec])
    assert (err.field, err.reason) == (field, reason)


def test_rolling_on_an_incline_takes_angle_zero_and_a_track_any_angle():
    scene_of([CYL], [incline(angle=0.0)])
    scene_of([CYL], [track(angle=2.0)])  # a track's "angle" field is no slope


@pytest.mark.parametrize(
    ("spec", "key", "keys"),
    [(incline(), "angle", "distance, speed"), (track(), "speed", "angle, angular_velocity")],
)
def test_rolling_takes_only_its_own_initial_keys(spec, key, keys):
    err = refusal([{**CYL, "initial": {key: 1.0}}], [spec])
    assert (err.field, err.reason) == (
        "bodies[0].initial." + key,
        f"a body on a rolling takes {keys}",
    )


def test_rolling_starts_from_its_initial_keys_or_zero():
    gd = guide_of([CYL], [incline()], [0.0, 0.0, -1.0])
    assert [x.tolist() for x in gd.start({"distance": 2.0, "speed": 3.0})] == [[2.0], [3.0]]
    assert [x.tolist() for x in gd.start({})] == [[0.0], [0.0]]
    gt = guide_of([CYL], [track()], [0.0, 0.0, -1.0])
    assert [x.tolist() for x in gt.start({"angle": 0.5, "angular_velocity": -1.0})] == [
        [0.5],
        [-1.0],
    ]
    assert [x.tolist() for x in gt.start({})] == [[0.0], [0.0]]


# ------------------------------------------------------------------ fixed axis


def hinge(**extra):
    return {"type": "fixed_axis", "body": "b", **extra}


@pytest.mark.parametrize(
    ("axis", "point", "kept"),
    [
        # the bearings' force acts on the axis (points λ a through C = O): its moment
        # λ a × F ⟂ a, and their couple is ⟂ a too; so L·a is kept, and L_k = ±L·a only
        # when a = ±e_k.  The other components change (the couple across a).
        ([0.0, 0.0, 1.0], None, ["L_z", "E"]),
        ([0.0, 0.0, -2.0], None, ["L_z", "E"]),
        ([1.0, 0.0, 0.0], None, ["L_x", "E"]),
        ([0.0, 3.0, 0.0], None, ["L_y", "E"]),
        # a slanted axis: L·a is no single component
        ([0.0, 0.6, 0.8], None, ["E"]),
        # an axis off the origin: C × F has a component along a, L_z about O changes
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], ["E"]),
        ([0.0, 0.0, 1.0], [0.0, 0.0, 2.0], ["E"]),
    ],
)
def test_a_fixed_axis_keeps_the_energy_and_l_along_it_only_through_the_origin(axis, point, kept):
    spec = hinge(axis=axis) if point is None else hinge(axis=axis, point=point)
    e = own(spec, [{**BOX, "initial": {"angle": 0.5}}])
    assert [q for q in CONSERVED if e.keeps(q)] == kept


def test_a_fixed_axis_turns_only_its_own_body():
    (e,), _ = build([BALL, {**BOX, "initial": {"angle": 0.5}}], [hinge()])
    assert e.i == 1
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)


def test_a_fixed_axis_reads_its_fields_and_defaults_to_the_z_axis_through_the_origin():
    e = own(hinge(axis=[0.0, 0.0, -2.0], distance=0.5, body_axis="y", point=[1.0, 2.0, 3.0]), [BOX])
    np.testing.assert_array_equal(e.axis, [0.0, 0.0, -1.0])
    assert (e.h, e.body_axis) == (0.5, 1)
    np.testing.assert_array_equal(e.point, [1.0, 2.0, 3.0])
    d = own(hinge(), [BOX])
    np.testing.assert_array_equal(d.axis, [0.0, 0.0, 1.0])
    assert (d.h, d.body_axis) == (0.0, 2)
    np.testing.assert_array_equal(d.point, [0.0, 0.0, 0.0])


def test_the_moment_about_a_fixed_axis_is_j_about_the_body_axis_plus_m_h_squared():
    """4.54: J_a = J_G,kk + m h²; about y with h = 1/2, m = 3: 2 + 3/4."""
    e = own(hinge(distance=0.5, body_axis="y"), [BOX])
    assert e.moment_of_inertia(3.0, np.diag([1.0, 2.0, 4.0])) == 2.75
    assert own(hinge(body_axis="x"), [BOX]).moment_of_inertia(3.0, np.diag([1.0, 2.0, 4.0])) == 1.0


@pytest.mark.parametrize(
    ("axis", "g", "u0"),
    [
        ([0.0, 0.0, 1.0], [3.0, 4.0, -5.0], [0.6, 0.8, 0.0]),  # gravity across the axis
        ([0.0, 1.0, 0.0], [0.0, 0.0, -9.81], [0.0, 0.0, -1.0]),
        ([0.0, 0.0, 1.0], [0.0, 0.0, -9.81], [1.0, 0.0, 0.0]),  # along it: e_x
        ([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),  # no gravity: e_x
        ([1.0, 0.0, 0.0], [-2.0, 0.0, 0.0], [0.0, 1.0, 0.0]),  # e_x along the axis: e_y
        ([1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        # a part across the axis below 1e-8 of gravity counts as along it; above, not
        ([0.0, 0.0, 1.0], [0.0, 1e-9, -1.0], [1.0, 0.0, 0.0]),
        ([0.0, 0.0, 1.0], [0.0, 1e-7, -1.0], [0.0, 1.0, 0.0]),
        # relative to gravity's own size: a weak one (0.01) tilted by 5e-7 rad still counts
        ([0.0, 0.0, 1.0], [0.0, 5e-9, -0.01], [0.0, 1.0, 0.0]),
    ],
)
def test_a_fixed_axis_measures_phi_from_gravity_across_it_else_from_e_x_then_e_y(axis, g, u0):
    e = own(hinge(axis=axis), [BOX])
    np.testing.assert_allclose(e.reference(g), u0, rtol=0, atol=2 * EPS)


@pytest.mark.parametrize("tilt", [2e-8, 1.5e-8, 3e-8, 1e-7, 1e-6])
@pytest.mark.parametrize("g", [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
def test_a_fixed_axis_reference_is_across_it_to_rounding_when_e_x_or_gravity_nearly_lie_along_it(
    tilt, g
):
    """The axis tilted from e_x by ``tilt`` rad, gravity absent or along e_x: u0 is e_x's
    (or gravity's) small part across the axis, a unit vector at right angles to the axis
    within a few eps. One projection left 2.2e-9 of it along the axis at 2e-8 rad (the
    hinge's attitude then drifted from orthogonal by as much: found by hypothesis)."""
    a = np.array([1.0, 0.0, tilt]) / math.hypot(1.0, tilt)
    u0 = own(hinge(axis=[0.5, 0.0, 0.5 * tilt]), [BOX]).reference(g)
    assert abs(u0 @ a) <= 4 * EPS
    assert abs(float(np.linalg.norm(u0)) - 1.0) <= 4 * EPS
    assert u0[2] < -0.99  # e_x's part across the axis points down the tilt


def test_a_fixed_axis_makes_a_hinge_with_its_point_axis_reference_body_axes_and_inertia():
    """Box 3 kg, a = 1, b = 1/2, c = 1/4: J_y = m (a² + c²)/12 = 17/64; + m h² = 3/4."""
    sc = scene_of(
        [{**BOX, "initial": {"angle": 0.5}}],
        [hinge(axis=[0.0, 0.0, 1.0], distance=0.5, body_axis="y", point=[0.0, 0.0, 1.0])],
    )
    gd = REGISTRY["fixed_axis"].make_guide(sc.effects[0], sc, np.array([0.0, -2.0, 0.0]))
    np.testing.assert_array_equal(gd.C, [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(gd.a, [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(gd.u0, [0.0, -1.0, 0.0])
    np.testing.assert_array_equal(gd.u1, [1.0, 0.0, 0.0])  # e_z × (−e_y) = e_x
    assert (gd.k, gd.j, gd.l, gd.h) == (1, 2, 0, 0.5)
    assert abs(gd.J_a - (17.0 / 64.0 + 0.75)) <= FORMULA_RTOL


def test_a_fixed_axis_refuses_an_axis_with_no_moment_of_inertia_word_for_word():
    """A thin rod about its own (z) axis through G has J = 0; off the axis, m h² > 0."""
    err = refusal([{**ROD, "name": "b"}], [hinge()])
    assert (err.field, err.reason) == (
        "effects[0].body_axis",
        "the moment of inertia about this axis is zero for a rod",
    )
    scene_of([{**ROD, "name": "b"}], [hinge(distance=0.5)])
    scene_of([{**ROD, "name": "b"}], [hinge(body_axis="x")])


def test_a_fixed_axis_refuses_a_point_and_initial_keys_other_than_its_angle():
    err = refusal([{"name": "b", "shape": "point", "mass": 1.0}], [hinge()])
    assert (err.field, err.reason) == (
        "effects[0].body",
        "body 'b' is a point: it cannot turn on an axis",
    )
    err = refusal([BALL, {**BOX, "initial": {"velocity": [1.0, 0.0, 0.0]}}], [hinge()])
    assert (err.field, err.reason) == (
        "bodies[1].initial.velocity",
        "a body on a fixed_axis takes angle, angular_velocity",
    )


# ------------------------------------------------------------------ fixed point


def pivot(**extra):
    return {"type": "fixed_point", "body": "b", "distance": 0.25, **extra}


@pytest.mark.parametrize("key", ["position", "velocity"])
def test_a_fixed_point_refuses_a_position_or_velocity_of_g_word_for_word(key):
    err = refusal([BALL, {**BOX, "initial": {key: [1.0, 0.0, 0.0]}}], [pivot()])
    assert err.field == f"bodies[1].initial.{key}"
    assert err.reason == "a pinned body's centre follows from its attitude: give psi, theta, phi"


def test_a_fixed_point_takes_the_attitude_and_the_spin():
    sc = scene_of(
        [{**BOX, "initial": {"psi": 0.1, "theta": 0.2, "phi": 0.3, "omega": [0, 0, 1.0]}}],
        [pivot()],
    )
    assert sc.effects[0].type == "fixed_point"


def test_a_fixed_point_refuses_a_point_body():
    err = refusal([{"name": "b", "shape": "point", "mass": 1.0}], [pivot()])
    assert (err.field, err.reason) == (
        "effects[0].body",
        "body 'b' is a point: it cannot be pinned",
    )


@pytest.mark.parametrize(
    ("point", "kept"),
    [
        # the pivot's force acts at C = O: no moment about O, every L component kept
        (None, ["L_x", "L_y", "L_z", "E"]),
        # elsewhere, C × F about O is a general vector
        ([0.0, 0.0, 1.0], ["E"]),
    ],
)
def test_a_fixed_point_keeps_the_energy_and_l_about_it_only_at_the_origin(point, kept):
    e = own(pivot() if point is None else pivot(point=point), [BOX])
    assert [q for q in CONSERVED if e.keeps(q)] == kept


def test_a_fixed_point_pins_c_with_g_at_distance_ell_up_the_body_axis_and_turns_its_body():
    e = own(pivot(point=[1.0, 2.0, 3.0]), [BOX])
    C, g_A = e.pin()
    np.testing.assert_array_equal(C, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(g_A, [0.0, 0.0, 0.25])
    np.testing.assert_array_equal(own(pivot(), [BOX]).pin()[0], [0.0, 0.0, 0.0])
    (e,), _ = build([BALL, BOX], [pivot()])
    assert e.i == 1
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)


# ------------------------------------------------------------------ mass flow

SPUN = [BALL, {**BOX, "initial": {"angle": 0.5, "angular_velocity": 2.0}}]
#: q = 1/4 kg/s at v = 8 m/s along a line r = 1/2 from the axis, stuck at R = 2
FLOW = {"type": "mass_flow", "body": "b", "rate": 0.25, "speed": 8.0, "offset": 0.5, "radius": 2.0}
SLANT = hinge(axis=[0.0, 0.6, 0.8])


def test_mass_flow_adds_q_r_squared_t_to_its_own_body_and_nothing_to_another():
    (_, e), _ = build(SPUN, [SLANT, FLOW])
    assert e.i == 1
    t = np.array([0.0, 2.0, 3.0])
    # q R² t = ¼·4·t = t, on a trailing axis of one coordinate
    np.testing.assert_array_equal(e.inertia_added(t, 1), [[0.0], [2.0], [3.0]])
    assert e.inertia_added(t, 0) == 0.0
    assert e.inertia_added(2.0, 0) == 0.0
    np.testing.assert_array_equal(e.inertia_added(2.0, 1), [2.0])


def test_mass_flow_turns_its_body_by_minus_r_q_v_minus_q_r2_phidot_about_the_axis():
    """7.36–7.39: (−r q v − q R² φ̇) a = (−½·¼·8 − ¼·4·2)(0, 0.6, 0.8) = −3 (0, 0.6, 0.8)."""
    (_, e), eng = build(SPUN, [SLANT, FLOW])
    assert e.hinge is eng.layout.guides[1]
    s = eng.snapshot(0.0, eng.y0)
    assert float(s.coords[1][1][0]) == 2.0
    out = Loads(2, s)
    e.loads(0.0, s, out)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A[0], [0.0, 0.0, 0.0])
    M_O = s.R[1].T @ out.M_A[1]
    np.testing.assert_allclose(M_O, [0.0, -1.8, -2.4], rtol=FORMULA_RTOL, atol=4 * EPS)
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)


def test_mass_flow_alone_keeps_j_phidot_plus_r_q_v_t_and_with_another_load_nothing():
    (_, e), _ = build(SPUN, [SLANT, FLOW])
    s = bare_snap(np.ones((2, 2)), t=np.array([0.0, 2.0]))
    # J(t) = 1 + t (a J_a of 1 and q R² = 1), φ̇ = 3, then 1 (J φ̇: 3, then 3)
    s.inertia = {1: np.array([[1.0], [3.0]])}
    s.coords = {1: (np.zeros((2, 1)), np.array([[3.0], [1.0]]))}
    ((name, (value, size)),) = e.conserved(s).items()
    assert name == "L_axis + r q v t"
    # + r q v t = ½·¼·8 t = t: 3 + 0, 3 + 2
    np.testing.assert_array_equal(value, [3.0, 5.0])
    assert size == 3.0 + 2.0  # max |J φ̇| + max |r q v t|
    (_, _, e2), _ = build(SPUN, [GRAVITY, SLANT, FLOW])
    assert e2.conserved(s) == {}


def test_mass_flow_needs_a_fixed_axis_for_its_body_word_for_word():
    err = refusal([BALL, BOX], [hinge(body="a"), FLOW])
    assert (err.field, err.reason) == (
        "effects[1].type",
        "mass flows onto a body turning on a fixed axis: list a fixed_axis for 'b'",
    )


# ------------------------------------------------------------------ tank outflow

TANK = {"name": "tank", "shape": "tank", "area": 1.0, "initial": {"level": 2.0}}
#: a = A/2, g = 3, h0 = 2: 1 − (a/A)² = 3/4, u0 = √(2·3·2/(3/4)) = 4,
#: c = −d√h/dt = ½ √(3/(3/2)) = √2/2, T = √h0/c = 2
DRAIN = [{"type": "gravity", "g": 3.0}, {"type": "tank_outflow", "body": "tank", "hole_area": 0.5}]


def tank_snap(w, vout):
    s = bare_snap(np.ones((*np.shape(w), 1)))
    s.fluid = {0: np.stack([np.asarray(w, float), np.asarray(vout, float)], axis=-1)}
    return s


def test_torricelli_speed_and_the_constant_rate_of_the_root_of_the_level():
    (_, e), _ = build([TANK], DRAIN)
    assert (e.a, e.A, e.h0, e.g, e.i) == (0.5, 1.0, 2.0, 3.0, 0)
    np.testing.assert_array_equal(
        e.outflow_speed(np.array([2.0, 0.0, -1.0]), 3.0, 1.0), [4.0, 0.0, 0.0]
    )
    assert abs(e.sqrt_level_rate(3.0, 1.0) + math.sqrt(2.0) / 2) <= FORMULA_RTOL
    np.testing.assert_allclose(e.start(), [math.sqrt(2.0), 0.0], rtol=0)


def test_the_tank_drains_at_its_rates_until_empty_then_stops():
    (_, e), _ = build([TANK], DRAIN)
    s = tank_snap(math.sqrt(2.0), 0.0)
    out = Loads(1, s)
    e.begin(0.0, s, out)
    assert e.empty is False
    e.loads(0.0, s, out)
    # (d√h/dt, a u) = (−√2/2, ½·4)
    np.testing.assert_allclose(out.rates[0], [-math.sqrt(2.0) / 2, 2.0], rtol=FORMULA_RTOL)
    assert e.switch_function(0.0, s, out) == (math.sqrt(2.0), math.sqrt(2.0))
    ev = e.switch(1.5, s, out)
    assert (ev.t, ev.kind, ev.detail) == (1.5, "empty", {"body": "tank"})
    assert e.empty is True
    assert s.fluid[0][0] == 0.0
    e.loads(2.0, s, out)
    np.testing.assert_array_equal(out.rates[0], [0.0, 0.0])
    assert e.switch_function(2.0, s, out) == (1.0, 1.0)
    e.begin(0.0, tank_snap(0.5, 0.0), out)
    assert e.empty is False
    e.begin(0.0, tank_snap(0.0, 0.0), out)
    assert e.empty is True


def test_the_tanks_exact_flow_empties_at_t_2_and_its_volume_is_kept():
    """√h = √2 − (√2/2) t; volume out a k c (T t − t²/2) = 2t − t²/2 (a k c = ½·2√2·√2/2
    = 1), which is A (h0 − h): 3/2 at t = 1, 2 from T = 2 on."""
    (_, e), _ = build([TANK], DRAIN)
    how, f, events = e.exact(2.0)
    assert "8.37" in how
    assert [(ev.t, ev.kind, ev.detail) for ev in events] == [(2.0, "empty", {"body": "tank"})]
    assert e.exact(1.9)[2] == []
    y = f(np.array([0.0, 1.0, 2.0, 3.0]))
    r2 = math.sqrt(2.0)
    np.testing.assert_allclose(y[:, 0], [r2, r2 / 2, 0.0, 0.0], rtol=FORMULA_RTOL, atol=4 * EPS)
    np.testing.assert_allclose(y[:, 1], [0.0, 1.5, 2.0, 2.0], rtol=FORMULA_RTOL, atol=4 * EPS)


def test_a_wider_tanks_exact_flow_drains_at_its_own_area_ratio():
    """A = 2, a = ½ (a/A = ¼), g = 3, h0 = 2: A ḣ = −a u with u = √(2 g h/(1 − 1/16)) gives
    d√h/dt = −(a/A) √(2g/(15/16))/2 = −√6.4/8 = −c, so T = √2/c = √20; the volume out is
    A (h0 − h) = 2 (2 − (√2 − c t)²) (the water is kept)."""
    (_, e), _ = build([{**TANK, "area": 2.0}], DRAIN)
    _, f, events = e.exact(5.0)
    c, T = math.sqrt(6.4) / 8, math.sqrt(20.0)
    assert [(ev.t, ev.kind) for ev in events] == [(pytest.approx(T, rel=FORMULA_RTOL), "empty")]
    t = np.array([0.0, 1.0, 3.0, T, 5.0])
    w = np.maximum(math.sqrt(2.0) - c * np.minimum(t, T), 0.0)
    y = f(t)
    np.testing.assert_allclose(y[:, 0], w, rtol=FORMULA_RTOL, atol=8 * EPS)
    np.testing.assert_allclose(y[:, 1], 2.0 * (2.0 - w * w), rtol=FORMULA_RTOL, atol=8 * EPS)


def test_the_tank_reports_h_u_the_volume_out_and_the_kept_total():
    """A tank of area A = 2 with the hole a = 1/2: 1 − (a/A)² = 15/16, u = √(2·3·h·16/15)
    = √(6.4 h); the total A h + volume out."""
    (_, e), _ = build([{**TANK, "area": 2.0}], DRAIN)
    s = tank_snap([2.0, 1.0], [0.5, 3.0])
    x = e.series(s)
    np.testing.assert_array_equal(x["h"], [4.0, 1.0])
    np.testing.assert_allclose(x["u"], [math.sqrt(25.6), math.sqrt(6.4)], rtol=FORMULA_RTOL)
    np.testing.assert_array_equal(x["volume_out"], [0.5, 3.0])
    np.testing.assert_array_equal(x["volume_total"], [8.5, 5.0])
    ((name, (value, size)),) = e.conserved(s).items()
    assert name == "volume_total"
    np.testing.assert_array_equal(value, [8.5, 5.0])
    assert size == 2.0 * 4.0 + 3.0  # A max h + max |volume out|
    assert all(e.keeps(q) for q in CONSERVED)
    assert not e.exerts_moment(0)


def test_a_tank_outflow_built_without_a_scene_reads_only_its_hole():
    e = REGISTRY["tank_outflow"](scene_of([TANK], DRAIN).effects[1])
    assert e.a == 0.5
    assert not hasattr(e, "A")


@pytest.mark.parametrize(
    ("bodies", "effects", "field", "reason"),
    [
        ([BOX], [GRAVITY, {"type": "tank_outflow", "body": "b", "hole_area": 0.5}],
         "effects[1].body", "tank_outflow needs a tank body; got a box"),
        ([TANK], [GRAVITY, {"type": "tank_outflow", "body": "tank", "hole_area": 1.0}],
         "effects[1].hole_area", "must be smaller than the tank's area 1.0; got 1.0"),
        ([TANK], [{"type": "tank_outflow", "body": "tank", "hole_area": 0.5}],
         "effects[0].type", "tank_outflow is driven by gravity: list a gravity effect"),
        ([TANK], [{"type": "gravity", "g": 1.0, "direction": [1.0, 0.0, 0.0]}, DRAIN[1]],
         "effects", "gravity must point down (−z) to drain the tank"),
        ([{**TANK, "initial": {}}], DRAIN, "bodies[0].initial.level", "missing required field for a tank"),
        ([{**TANK, "initial": {"level": 1.0, "speed": 2.0}}], DRAIN,
         "bodies[0].initial.speed", "a tank takes only level"),
        ([TANK], [*DRAIN, DRAIN[1]], "effects[2].body", "tank 'tank' has one hole: list one outflow"),
    ],
)  # fmt: skip
def test_a_tank_outflow_refuses_word_for_word(bodies, effects, field, reason):
    err = refusal(bodies, effects)
    assert (err.field, err.reason) == (field, reason)


def test_a_tank_with_a_hole_just_smaller_than_it_and_gravity_partly_down_is_fine():
    scene_of([TANK], [{"type": "gravity", "g": 1.0, "direction": [1.0, 0.0, -1e-3]},
                      {"type": "tank_outflow", "body": "tank", "hole_area": 0.999}])  # fmt: skip


# ------------------------------------------------------------------ builtin_path


def test_builtin_path_finds_a_scene_file_by_its_stem():
    p = builtin_path("carousel")
    assert p.name == "carousel.toml"
    assert p.is_file()


def test_builtin_path_names_the_unknown_scene_and_lists_the_known_ones():
    folder = Path(mechanics.scenes.__file__).parent / "builtin"
    known = sorted(q.stem for q in folder.glob("*.toml"))
    assert "carousel" in known
    with pytest.raises(KeyError) as info:
        builtin_path("no_such_scene")
    assert info.value.args == (
        f"unknown built-in scene 'no_such_scene' (known: {', '.join(known)})",
    )


#: the pendulum's amplitude ψ0 = 1e-6 shifts its frequency by ψ0²/16 ~ 6e-14 relative;
#: the elliptic functions round to a few eps: 2^20 eps = 2.3e-10 of ψ0 leaves a wide margin
SMALL_ANGLE_RTOL = 2**20 * EPS


def test_a_track_under_gravity_released_from_rest_swings_as_its_equivalent_pendulum():
    """4.64: T = ½ M_eff (R − r)² ψ̇², U = −m g (R − r) cos ψ: ω² = m g/(M_eff (R − r))
    = 2·9.81/(3·3/8) for the cylinder (M_eff = 3/2 m); small ψ0: ψ0 cos ω t."""
    eng = Engine(scene_of([CYL], [GRAVITY, track()]))
    gravity, gd = eng.effects[0], eng.layout.guides[0]
    psi0 = 1e-6
    how, f, ev = gd.exact([gravity], 2.0, np.array([psi0]), np.array([0.0]), 1.0)
    assert "4.64" in how
    assert ev == []
    w = math.sqrt(2.0 * 9.81 / (3.0 * 0.375))
    t = np.array([0.25, 0.5, 1.0])
    q, qd = f(t)
    np.testing.assert_allclose(
        q[..., 0], psi0 * np.cos(w * t), rtol=0, atol=SMALL_ANGLE_RTOL * psi0
    )
    np.testing.assert_allclose(
        qd[..., 0], -psi0 * w * np.sin(w * t), rtol=0, atol=SMALL_ANGLE_RTOL * psi0 * w
    )
    # released at the top itself, |ψ0| = π, still (4.64 covers |ψ0| ≤ π)
    assert "4.64" in gd.exact([gravity], 2.0, np.array([math.pi]), np.array([0.0]), 1.0)[0]
    # moving, beyond the top, or under two loads: no closed form here
    assert gd.exact([gravity], 2.0, np.array([psi0]), np.array([0.5]), 1.0) is None
    assert gd.exact([gravity], 2.0, np.array([3.5]), np.array([0.0]), 1.0) is None
    assert gd.exact([gravity, gravity], 2.0, np.array([psi0]), np.array([0.0]), 1.0) is None
