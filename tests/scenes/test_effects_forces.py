"""Each load effect of ``mechanics/scenes/effects/`` on its own, on a hand-made snapshot:
its forces and moments against hand-derived values, its potential against its closed
form and as the negative work of its loads, what it keeps (every quantity of CONSERVED)
against the rates its loads give, its switch times and its refusals.  Fast: no run."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.scenes.effects import CONSERVED, REGISTRY, Loads, Snapshot
from mechanics.scenes.effects.capabilities import HasPotential
from mechanics.scenes.effects.newton_gravity import G_NEWTON

from ._effects import assert_says, build, refusal, scene_of
from .builders import bare_snap, snap, snapshots

#: a force of a few O(1) factors, each rounded once, and a unit vector (a norm, a
#: division): a handful of roundings of O(1) values
FORCE_RTOL = 16 * EPS
#: a rate summed over bodies of O(1) terms that cancel when the quantity is kept: the
#: roundings of those terms, relative to their size
KEPT_RTOL = 64 * EPS
#: a central difference at h = 2^-16 of a smooth O(1) potential: truncation h²/6 |U'''|
#: ~ 1e-10 on O(1) data, rounding eps |U|/h ~ 2e-11: 2^26 eps = 1.5e-8 leaves a factor 100
FD_RTOL = 2**26 * EPS
FD_STEP = 2.0**-16


# ------------------------------------------------------------------ set-up


SPHERE = {"name": "a", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5}
BOX = {"name": "b", "shape": "box", "mass": 3.0, "a": 1.0, "b": 0.5, "c": 0.25}
POINT = {"name": "p", "shape": "point", "mass": 1.5}

#: the body's axes are the space axes y, z, x (rows of R_A_O: e_1 = e_y, e_2 = e_z,
#: e_3 = e_x), exact in floats
R_CYCLIC = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])


def rotation(rng) -> np.ndarray:
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.linalg.det(q))


def random_snap(rng, n, *, phase=0.5) -> Snapshot:
    return snap(
        rng.normal(size=(n, 3)),
        rng.normal(size=(n, 3)),
        [rotation(rng) for _ in range(n)],
        rng.normal(size=(n, 3)),
        rng.uniform(0.5, 2.0, n),
        rng.uniform(0.5, 2.0, (n, 3)),
        t=phase,
        phase=phase,
    )


def loads_of(e, s, n) -> Loads:
    out = Loads(n, s)
    e.loads(s.t, s, out)
    return out


def _active(w_O, h):
    """The active rotation by the angle |w_O| h about w_O (Rodrigues)."""
    th = float(np.linalg.norm(w_O)) * h
    k = w_O / np.linalg.norm(w_O)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(th) * K + (1 - math.cos(th)) * K @ K


def moved(s, h) -> Snapshot:
    """The snapshot a time h later along the free motion: r + h v, the basis turned by
    ω h (R(t + h) = R(t) Q(h)ᵀ, Q the active rotation about ω_O)."""
    R = np.array(
        [s.R[k] @ _active(s.R[k].T @ s.omega[k], h).T for k in range(len(s.m))]
    )  # fmt: skip
    return snap(s.r + h * s.v, s.v, R, s.omega, s.m, s.J, t=s.t, phase=s.phase)


def rates(e, s, n) -> dict[str, tuple[float, float]]:
    """Each quantity of CONSERVED: (its rate under e's loads at s, the size of its terms).
    p: Σ F; L about the origin: Σ r × F + Rᵀ M_A; E: the power Σ F·v + M_A·ω plus dU/dt
    (a central difference along the motion)."""
    out = loads_of(e, s, n)
    dp = out.F.sum(0)
    turn = np.einsum("kji,kj->ki", s.R, out.M_A)
    dL = (np.cross(s.r, out.F) + turn).sum(0)
    norm = np.linalg.norm
    L_size = float((norm(s.r, axis=1) * norm(out.F, axis=1) + norm(out.M_A, axis=1)).sum())
    power = np.einsum("ki,ki->k", out.F, s.v) + np.einsum("ki,ki->k", out.M_A, s.omega)
    dE = power.sum()
    E_size = float((norm(out.F, axis=1) * norm(s.v, axis=1)).sum())
    E_size += float((norm(out.M_A, axis=1) * norm(s.omega, axis=1)).sum())
    if isinstance(e, HasPotential):
        U1, U0 = e.potential(moved(s, FD_STEP)), e.potential(moved(s, -FD_STEP))
        dU = (U1 - U0) / (2 * FD_STEP)
        dE, E_size = dE + dU, E_size + abs(dU) + abs(U1)
    F_size = float(norm(out.F, axis=1).sum())
    out_rates = {f"p_{a}": (dp[k], F_size) for k, a in enumerate("xyz")}
    out_rates |= {f"L_{a}": (dL[k], L_size) for k, a in enumerate("xyz")}
    out_rates["E"] = (dE, E_size)
    return out_rates


def assert_keeps_what_its_rates_keep(e, n, *, states=6, seed=16, snaps=None, complete=True) -> None:
    """keeps(q) is True exactly when q's rate vanishes at every random state (within the
    roundings of its terms: KEPT_RTOL, FD_RTOL for E through the potential), and
    exerts_moment(k) exactly when some state gives body k a moment about G.  Where the
    effect claims less than it could (``complete=False``: a zero force, a drag on the
    spin only), only that each claim holds."""
    rng = np.random.default_rng(seed)
    snaps = snaps or [random_snap(rng, n) for _ in range(states)]
    kept = dict.fromkeys(CONSERVED, True)
    moment = [False] * n
    for s in snaps:
        for q, (rate, size) in rates(e, s, n).items():
            tol = (FD_RTOL if q == "E" and isinstance(e, HasPotential) else KEPT_RTOL) * size
            assert size > 0 or rate == 0
            kept[q] &= bool(abs(rate) <= tol)
        M_A = loads_of(e, s, n).M_A
        moment = [moment[k] or bool(M_A[k].any()) for k in range(n)]
    claims = {q: bool(e.keeps(q)) for q in CONSERVED}
    turns = [bool(e.exerts_moment(k)) for k in range(n)]
    if complete:
        assert claims == kept
        assert turns == moment
    else:
        assert all(kept[q] for q in CONSERVED if claims[q]), (claims, kept)
        assert all(turns[k] for k in range(n) if moment[k]), (turns, moment)


def assert_potential_is_minus_the_work(e, s, n, *, seed=7) -> None:
    """dU along a random displacement of each centre of mass is −Σ F·δr (moments: by the
    rates test, which turns the bodies)."""
    rng = np.random.default_rng(seed)
    F = loads_of(e, s, n).F
    for _ in range(3):
        dr = rng.normal(size=(n, 3))

        def shifted(h, dr=dr):
            return snap(s.r + h * dr, s.v, s.R, s.omega, s.m, s.J, t=s.t, phase=s.phase)

        dU = (e.potential(shifted(FD_STEP)) - e.potential(shifted(-FD_STEP))) / (2 * FD_STEP)
        work = float((F * dr).sum())
        scale = float(np.abs(F * dr).sum()) + abs(float(e.potential(s)))
        assert abs(dU + work) <= FD_RTOL * scale, (dU, work)


def two_at_rest():
    """Sphere a at (1, 2, 0) with the identity attitude, box b at (-1, 0, 0) turned by
    R_CYCLIC."""
    return snap(
        [[1.0, 2.0, 0.0], [-1.0, 0.0, 0.0]],
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        [np.eye(3), R_CYCLIC],
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        [2.0, 3.0],
        [[0.2, 0.2, 0.2], [0.08, 0.26, 0.31]],
    )


# ------------------------------------------------------------------ gravity

GRAVITY_CASES = [
    {"type": "gravity", "g": 2.0},
    {"type": "gravity", "g": 9.81, "direction": [0.0, 3.0, -4.0]},
    {"type": "gravity", "g": 1.0, "direction": [5.0, 0.0, 0.0]},
    {"type": "gravity", "g": 1.5, "direction": [1.0, -2.0, 2.0]},
]


@pytest.mark.parametrize("spec", GRAVITY_CASES)
def test_gravity_keeps_what_its_weight_along_d_keeps(spec) -> None:
    (e,), _ = build([SPHERE, BOX], [spec])
    assert_keeps_what_its_rates_keep(e, 2)


def test_gravity_pulls_each_body_with_m_g_along_the_unit_direction() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "gravity", "g": 2.0, "direction": [0, 3, -4]}])
    s = two_at_rest()
    out = loads_of(e, s, 2)
    # d = (0, 0.6, -0.8): m g d = 2·2 d and 3·2 d
    np.testing.assert_allclose(out.F, [[0, 2.4, -3.2], [0, 3.6, -4.8]], rtol=FORCE_RTOL)
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    out.F[:] = 1.0  # adds to what is there
    e.loads(0.0, s, out)
    np.testing.assert_allclose(out.F, [[1, 3.4, -2.2], [1, 4.6, -3.8]], rtol=FORCE_RTOL)


def test_gravity_points_down_by_default_and_its_potential_is_m_g_z() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "gravity", "g": 2.0}])
    assert e.ctx.index == {"a": 0, "b": 1}  # it knows its scene
    np.testing.assert_array_equal(e.vector, [0.0, 0.0, -2.0])
    s = snap(
        [[1.0, 2.0, 0.5], [-1.0, 0.0, -2.0]], np.zeros((2, 3)), [np.eye(3)] * 2,
        np.zeros((2, 3)), [2.0, 3.0], np.ones((2, 3)),
    )  # fmt: skip
    np.testing.assert_array_equal(loads_of(e, s, 2).F, [[0, 0, -4.0], [0, 0, -6.0]])
    # U = Σ m g z = 2·2·0.5 + 3·2·(−2) = −10
    assert e.potential(s) == -10.0
    # over a time axis: one value per instant
    batch = snap(np.stack([s.r, 2 * s.r]), np.zeros((2, 2, 3)), np.stack([s.R] * 2),
                 np.zeros((2, 2, 3)), [[2.0, 3.0]] * 2, np.ones((2, 2, 3)))  # fmt: skip
    np.testing.assert_array_equal(e.potential(batch), [-10.0, -20.0])
    deep = snap(np.stack([batch.r] * 3), np.zeros((3, 2, 2, 3)), np.stack([batch.R] * 3),
                np.zeros((3, 2, 2, 3)), np.stack([batch.m] * 3), np.ones((3, 2, 2, 3)))  # fmt: skip
    np.testing.assert_array_equal(e.potential(deep), [[-10.0, -20.0]] * 3)
    assert_potential_is_minus_the_work(e, s, 2)


def test_gravity_across_a_fixed_axis_is_its_component_perpendicular_to_it() -> None:
    (e,), _ = build([SPHERE], [{"type": "gravity", "g": 10.0}])
    assert e.axis_g_perp(np.array([1.0, 0.0, 0.0])) == 10.0
    assert e.axis_g_perp(np.array([0.0, 0.0, 1.0])) == 0.0
    # an axis at cos = 0.8 to the vertical: g sin = 10 · 0.6
    assert math.isclose(e.axis_g_perp(np.array([0.0, 0.6, 0.8])), 6.0, rel_tol=FORCE_RTOL)
    assert isinstance(e.axis_g_perp(np.array([1.0, 0.0, 0.0])), float)


# ------------------------------------------------------------------ newton gravity

THREE = [SPHERE, BOX, {**POINT, "name": "c", "mass": 4.0}]


def test_newton_gravity_pulls_each_pair_with_g_m1_m2_over_r_squared_equal_and_opposite() -> None:
    (e,), _ = build(THREE, [{"type": "newton_gravity", "G": 1.5, "bodies": ["a", "c"]}])
    s = snap(
        [[0.0, 0.0, 0.0], [7.0, 7.0, 7.0], [0.0, 3.0, 4.0]], np.zeros((3, 3)),
        [np.eye(3)] * 3, np.zeros((3, 3)), [2.0, 3.0, 4.0], np.ones((3, 3)),
    )  # fmt: skip
    out = loads_of(e, s, 3)
    # |r_c − r_a| = 5: G m_a m_c / 25 = 1.5·2·4/25 = 0.48 toward each other, along
    # (0, 0.6, 0.8); b is not listed
    pull = 0.48 * np.array([0.0, 0.6, 0.8])
    np.testing.assert_allclose(out.F, [pull, [0, 0, 0], -pull], rtol=FORCE_RTOL, atol=0)
    np.testing.assert_array_equal(out.M_A, np.zeros((3, 3)))
    # U = −G m_a m_c/5 = −2.4
    assert math.isclose(e.potential(s), -2.4, rel_tol=FORCE_RTOL)
    assert_potential_is_minus_the_work(e, s, 3)


def test_newton_gravity_acts_between_every_pair_by_default_with_codata_g() -> None:
    """On one seeded snapshot: the sum is compared component by component at FORCE_RTOL,
    which needs no component of a body's two pulls to cancel (and of three bodies one is
    between the others in each coordinate: no bound on the positions excludes it)."""
    assert G_NEWTON == 6.67430e-11  # CODATA 2018
    (e,), _ = build(THREE, [{"type": "newton_gravity"}])
    assert e.G == G_NEWTON
    assert sorted(map(tuple, e.pairs.tolist())) == [(0, 1), (0, 2), (1, 2)]
    rng = np.random.default_rng(3)
    s = random_snap(rng, 3)
    F = loads_of(e, s, 3).F
    for i in range(3):  # the sum of the pair forces on each body, by hand
        want = sum(
            -G_NEWTON * s.m[i] * s.m[j] * (s.r[i] - s.r[j]) / np.linalg.norm(s.r[i] - s.r[j]) ** 3
            for j in range(3)
            if j != i
        )
        np.testing.assert_allclose(F[i], want, rtol=FORCE_RTOL * 4)
    U = -sum(
        G_NEWTON * s.m[i] * s.m[j] / np.linalg.norm(s.r[i] - s.r[j])
        for i in range(3)
        for j in range(i + 1, 3)
    )
    assert math.isclose(e.potential(s), U, rel_tol=FORCE_RTOL)
    batch = snap(np.stack([s.r, 2 * s.r]), np.zeros((2, 3, 3)), np.stack([s.R] * 2),
                 np.zeros((2, 3, 3)), np.stack([s.m] * 2), np.ones((2, 3, 3)))  # fmt: skip
    np.testing.assert_allclose(e.potential(batch), [U, U / 2], rtol=FORCE_RTOL)


#: three bodies at the corners of a right triangle, each within 0.5 of its corner per
#: component: 3 apart or more (a smooth potential on the difference's step)
APART = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 8.0, 0.0]]


@settings(max_examples=5)
@given(snaps=st.lists(snapshots(3, centres=APART, spread=0.5), min_size=4, max_size=4))
def test_newton_gravity_keeps_everything(snaps) -> None:
    (e,), _ = build(THREE, [{"type": "newton_gravity", "G": 2.0}])
    assert_keeps_what_its_rates_keep(e, 3, snaps=snaps)


@pytest.mark.parametrize(
    ("bodies", "names", "reason"),
    [
        ([SPHERE], None, "needs at least two bodies; got ['a']"),
        ([SPHERE, BOX], ["a", "a"], "needs at least two bodies; got ['a', 'a']"),
        ([SPHERE, BOX], ["a", "b", "a"], "a body is listed twice: ['a', 'b', 'a']"),
    ],
)
def test_newton_gravity_refuses_fewer_than_two_bodies_or_a_repeated_one(
    bodies, names, reason
) -> None:
    spec = {"type": "newton_gravity"} | ({"bodies": names} if names else {})
    err = refusal(bodies, [{"type": "gravity", "g": 1.0}, spec])
    assert err.field == "effects[1].bodies"
    assert err.reason == reason


# ------------------------------------------------------------------ springs and dampers


def spring_pair(**extra):
    spec = {
        "type": "spring", "body": "a", "other": "b", "at": [2.0, 2.0, 0.0],
        "other_at": [0.0, 0.0, 1.0], "stiffness": 2.0, "rest_length": 1.5, **extra,
    }  # fmt: skip
    (e,), _ = build([SPHERE, BOX], [spec])
    return e


def test_a_spring_pulls_its_ends_with_k_stretch_plus_c_closing_speed_along_the_line() -> None:
    e = spring_pair(damping=0.5)
    s = two_at_rest()
    s.v[0] = [1.0, 0.0, 0.0]
    s.v[1] = [0.0, 1.0, 0.0]
    s.omega[1] = [2.0, 0.0, 0.0]
    # P = (1, 2, 0) + (2, 2, 0) = (3, 4, 0); Q = (−1, 0, 0) + Rᵀ(0, 0, 1) = (0, 0, 0):
    # PQ = 5 along u = (0.6, 0.8, 0), stretch 5 − 1.5: k·3.5 = 7.
    # v_P = (1, 0, 0); ω_b about the body x = space y, (0, 2, 0) × (1, 0, 0) = (0, 0, −2):
    # v_Q = (0, 1, −2); (v_P − v_Q)·u = 0.6 − 0.8 = −0.2, damping 0.5·(−0.2) = −0.1:
    # F_P = −6.9 u
    out = loads_of(e, s, 2)
    F = -6.9 * np.array([0.6, 0.8, 0.0])
    np.testing.assert_allclose(out.F, [F, -F], rtol=FORCE_RTOL)
    # moments: (2, 2, 0) × F_P (identity attitude) = (0, 0, 2 F_y − 2 F_x); on b the
    # lever is space (1, 0, 0): (1, 0, 0) × (−F) = (0, 0, −F_y) in space, body (0, −F_y, 0)
    np.testing.assert_allclose(out.M_A[0], [0, 0, 2 * F[1] - 2 * F[0]], rtol=FORCE_RTOL)
    np.testing.assert_allclose(out.M_A[1], [0, -F[1], 0], rtol=FORCE_RTOL)
    # U = ½ k (5 − 1.5)² = 12.25 (the damper has none)
    assert math.isclose(float(e.potential(s)), 12.25, rel_tol=FORCE_RTOL)


def test_a_spring_of_zero_length_pulls_with_minus_k_d_and_damps_the_whole_velocity() -> None:
    (e,), _ = build(
        [SPHERE, BOX],
        [{"type": "spring", "body": "a", "other": "b", "stiffness": 2.0, "damping": 0.5,
          "rest_length": 1.0}],
    )  # fmt: skip
    s = two_at_rest()
    s.r[1] = s.r[0]
    s.v[0], s.v[1] = [1.0, -2.0, 4.0], [0.0, 0.0, 2.0]
    out = loads_of(e, s, 2)
    # d = 0: F = −k·0 − c (v_P − v_Q) = −0.5 (1, −2, 2)
    np.testing.assert_array_equal(out.F, [[-0.5, 1.0, -1.0], [0.5, -1.0, 1.0]])
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    # U = ½ k ℓ0² at zero length
    assert float(e.potential(s)) == 1.0


def test_a_damper_opposes_the_closing_speed_along_the_line_and_nothing_at_zero_length() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "damper", "body": "a", "anchor": [1, 2, 5],
                                      "damping": 0.5}])  # fmt: skip
    s = two_at_rest()
    s.v[0] = [3.0, 1.0, 2.0]
    # the line from the anchor to P: (0, 0, −5), u = (0, 0, −1); (v_P·u) = −2:
    # F = −c (v·u) u = −0.5·(−2)·(0, 0, −1) = (0, 0, −1)
    out = loads_of(e, s, 2)
    np.testing.assert_array_equal(out.F, [[0, 0, -1.0], [0, 0, 0]])
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    s.r[0] = [1.0, 2.0, 5.0]
    np.testing.assert_array_equal(loads_of(e, s, 2).F, np.zeros((2, 3)))
    assert not isinstance(e, HasPotential)  # a damper dissipates


def test_a_spring_to_the_ground_anchor_pulls_its_body_point_toward_it() -> None:
    (e,), _ = build(
        [SPHERE, BOX],
        [{"type": "spring", "body": "b", "at": [0.0, 0.0, 1.0], "anchor": [0.0, 4.0, 0.0],
          "stiffness": 3.0, "rest_length": 1.0}],
    )  # fmt: skip
    s = two_at_rest()
    # P = (−1, 0, 0) + Rᵀ(0, 0, 1) = (0, 0, 0); P − a = (0, −4, 0): F = −3·3 (0, −1, 0)
    out = loads_of(e, s, 2)
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [0, 9.0, 0]])
    # lever space (1, 0, 0) × (0, 9, 0) = (0, 0, 9) space, body (0, 9, 0)
    np.testing.assert_array_equal(out.M_A, [[0, 0, 0], [0, 9.0, 0]])
    assert float(e.potential(s)) == 13.5  # ½·3·3²


SPRING_CASES = [
    {"type": "spring", "body": "a", "other": "b", "stiffness": 2.0},
    {"type": "spring", "body": "a", "other": "b", "at": [0.1, 0.2, 0.3],
     "other_at": [0.3, -0.1, 0.2], "stiffness": 5.0, "rest_length": 0.3},
    {"type": "spring", "body": "a", "other": "b", "at": [0.1, 0.2, 0.3],
     "stiffness": 5.0, "rest_length": 0.3, "damping": 0.2},
    {"type": "spring", "body": "b", "other": "a", "other_at": [0.1, 0.2, 0.3],
     "stiffness": 5.0, "rest_length": 0.3},
    {"type": "spring", "body": "b", "at": [0.3, 0.0, -0.2], "stiffness": 4.0,
     "rest_length": 0.5},
    {"type": "spring", "body": "b", "at": [0.3, 0.0, -0.2], "anchor": [0.5, -1.0, 2.0],
     "stiffness": 4.0},
    {"type": "spring", "body": "a", "anchor": [0.0, 0.0, 0.0], "stiffness": 4.0,
     "damping": 1.0},
    {"type": "damper", "body": "a", "other": "b", "at": [0.1, 0.2, 0.3], "damping": 0.7},
    {"type": "damper", "body": "b", "at": [0.1, 0.2, 0.3], "damping": 0.7},
    {"type": "damper", "body": "a", "anchor": [1.0, 2.0, -0.5], "other_at": None,
     "damping": 0.7},
]  # fmt: skip


@pytest.mark.parametrize("spec", SPRING_CASES)
def test_a_spring_or_damper_keeps_what_its_rates_keep(spec) -> None:
    spec = {k: v for k, v in spec.items() if v is not None}
    (e,), _ = build([SPHERE, BOX], [spec])
    assert_keeps_what_its_rates_keep(e, 2)


def test_the_spring_potential_is_minus_the_work_of_its_force() -> None:
    e = spring_pair()
    assert_potential_is_minus_the_work(e, random_snap(np.random.default_rng(5), 2), 2)


def test_the_spring_potential_broadcasts_over_time() -> None:
    e = spring_pair()
    s = two_at_rest()
    # P − Q = (3, 4, 0): L = 5, U = ½·2·3.5² = 12.25; moved by (0, 0, 12): L = 13, U = 132.25
    r = np.stack([s.r, s.r + np.array([[0, 0, 12.0], [0, 0, 0]])])
    batch = snap(r, np.zeros((2, 2, 3)), np.stack([s.R] * 2), np.zeros((2, 2, 3)),
                 np.stack([s.m] * 2), np.stack([s.J] * 2))  # fmt: skip
    np.testing.assert_allclose(e.potential(batch), [12.25, 132.25], rtol=FORCE_RTOL)


@pytest.mark.parametrize(
    ("spec", "field", "reason"),
    [
        ({"other": "p", "anchor": [0, 0, 1]}, "anchor",
         "give either another body or a ground anchor, not both"),
        ({"other": "a"}, "other", "a spring needs two different ends"),
        ({"other_at": [0, 0, 1]}, "other_at", "needs an 'other' body"),
        ({"body": "p", "at": [0.0, 0.0, 1.0]}, "at",
         "body 'p' is a point: it has no points off its centre; got [0.0, 0.0, 1.0]"),
        ({"other": "p", "other_at": [1.0, 0.0, 0.0]}, "other_at",
         "body 'p' is a point: it has no points off its centre; got [1.0, 0.0, 0.0]"),
    ],
)  # fmt: skip
def test_a_spring_refuses_ambiguous_or_impossible_ends(spec, field, reason) -> None:
    spring = {"type": "spring", "body": "a", "stiffness": 1.0, **spec}
    err = refusal([SPHERE, POINT], [spring])
    assert err.field == f"effects[0].{field}"
    assert err.reason == reason


def test_a_damper_names_itself_when_its_ends_are_one_body() -> None:
    err = refusal([SPHERE], [{"type": "damper", "body": "a", "other": "a", "damping": 1.0}])
    assert_says(err, "effects[0].other", "a damper needs two different ends")


def test_a_point_may_hang_from_its_centre() -> None:
    (e,), _ = build([POINT, SPHERE], [{"type": "spring", "body": "p", "other": "a",
                                       "at": [0.0, 0.0, 0.0], "other_at": [0.0, 0.0, 0.0],
                                       "stiffness": 1.0}])  # fmt: skip
    assert e.at is None
    assert e.other_at is None
    assert not e.exerts_moment(0)
    assert not e.exerts_moment(1)


# ------------------------------------------------------------------ drag


def test_drag_is_linear_plus_quadratic_in_the_speed_and_the_spin() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "drag", "body": "b", "linear": 0.5, "quadratic": 0.25,
                                     "angular_linear": 0.1, "angular_quadratic": 0.2}])  # fmt: skip
    s = two_at_rest()
    s.v[1] = [3.0, 0.0, 4.0]
    s.v[0] = [1.0, 1.0, 1.0]  # another body: no drag
    s.omega[1] = [0.0, 2.0, 0.0]
    out = loads_of(e, s, 2)
    # F = −(0.5 + 0.25·5) (3, 0, 4) = −1.75 (3, 0, 4)
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [-5.25, 0, -7.0]])
    # M = −(0.1 + 0.2·2) ω: body components −0.5 (0, 2, 0)
    np.testing.assert_allclose(out.M_A, [[0, 0, 0], [0, -1.0, 0]], rtol=FORCE_RTOL)


def test_drag_without_angular_terms_exerts_no_moment() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "drag", "body": "b", "quadratic": 0.25}])
    s = two_at_rest()
    s.v[1] = [0.0, 3.0, 4.0]
    s.omega[1] = [1.0, 2.0, 3.0]
    out = loads_of(e, s, 2)
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [0, -3.75, -5.0]])
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    assert not e.exerts_moment(1)


@pytest.mark.parametrize(
    "coefficients",
    [{"linear": 0.5}, {"quadratic": 0.3}, {"angular_linear": 0.2}, {"angular_quadratic": 0.4},
     {"linear": 0.1, "quadratic": 0.2, "angular_linear": 0.3, "angular_quadratic": 0.4}],
)  # fmt: skip
def test_drag_keeps_nothing_and_turns_only_with_an_angular_term(coefficients) -> None:
    """(A drag on the spin only pushes nothing: it keeps p but does not claim it.)"""
    (e,), _ = build([SPHERE, BOX], [{"type": "drag", "body": "b", **coefficients}])
    translates = bool(coefficients.get("linear") or coefficients.get("quadratic"))
    assert_keeps_what_its_rates_keep(e, 2, complete=translates)
    assert not any(e.keeps(q) for q in CONSERVED)


def test_drag_refuses_all_coefficients_zero_and_a_spin_drag_on_a_point() -> None:
    err = refusal([SPHERE], [{"type": "drag", "body": "a", "linear": 0.0}])
    assert err.field == "effects[0]"
    assert err.reason == (
        "a drag needs one of ('linear', 'quadratic', 'angular_linear', 'angular_quadratic') > 0"
    )
    for k in ("angular_linear", "angular_quadratic"):
        err = refusal([POINT], [{"type": "drag", "body": "p", "linear": 1.0, k: 0.5}])
        assert err.field == f"effects[0].{k}"
        assert err.reason == "body 'p' is a point: it has no rotation"
    scene_of([POINT], [{"type": "drag", "body": "p", "linear": 1.0, "angular_linear": 0.0}])


# ------------------------------------------------------------------ applied force and torque


def test_a_space_fixed_force_acts_in_its_window_at_its_point() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "force", "body": "b", "force": [0, 0, 3.0],
                                     "at": [1.0, 0.0, 0.0], "start": 0.5, "end": 2.0}])  # fmt: skip
    s = two_at_rest()
    for phase, on in ((0.25, False), (0.5, True), (1.0, True), (2.0, False), (3.0, False)):
        s.phase = phase
        out = loads_of(e, s, 2)
        np.testing.assert_array_equal(out.F, [[0, 0, 0], [0, 0, 3.0 * on]])
        # the body point (1, 0, 0) is space (0, 1, 0) from G: moment (0, 1, 0) × (0, 0, 3)
        # = (3, 0, 0) in space, (0, 0, 3) in body components (space x is the body z)
        np.testing.assert_array_equal(out.M_A, [[0, 0, 0], [0, 0, 3.0 * on]])
    assert e.switch_times() == [0.5, 2.0]
    assert e.acts_until() == 2.0


def test_a_force_off_g_turns_its_body_and_a_body_fixed_force_turns_with_it() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "force", "body": "b", "force": [1.0, 0.0, 0.0],
                                     "at": [0.0, 2.0, 0.0], "frame": "body"}])  # fmt: skip
    s = two_at_rest()
    out = loads_of(e, s, 2)
    # body x is space y: F = (0, 1, 0); the lever body (0, 2, 0) is space (0, 0, 2);
    # moment (0, 0, 2) × (0, 1, 0) = (−2, 0, 0) space = body (0, 0, −2)
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [0, 1.0, 0]])
    np.testing.assert_array_equal(out.M_A, [[0, 0, 0], [0, 0, -2.0]])
    assert e.switch_times() == []  # from 0 to the end
    assert e.acts_until() == math.inf


def test_a_torque_is_a_couple_in_space_or_body_components() -> None:
    (space, body), _ = build(
        [SPHERE, BOX],
        [{"type": "torque", "body": "b", "torque": [2.0, 0.0, 0.0], "end": 1.0},
         {"type": "torque", "body": "b", "torque": [2.0, 0.0, 0.0], "frame": "body",
          "start": 0.5}],
    )  # fmt: skip
    s = two_at_rest()
    s.phase = 0.75
    out = loads_of(space, s, 2)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A, [[0, 0, 0], [0, 0, 2.0]])  # space x: body z
    out = loads_of(body, s, 2)
    np.testing.assert_array_equal(out.M_A, [[0, 0, 0], [2.0, 0, 0]])
    s.phase = 1.0
    np.testing.assert_array_equal(loads_of(space, s, 2).M_A, np.zeros((2, 3)))
    s.phase = 0.25
    np.testing.assert_array_equal(loads_of(body, s, 2).M_A, np.zeros((2, 3)))
    assert space.switch_times() == [1.0]
    assert body.switch_times() == [0.5]


APPLIED_CASES = [
    {"type": "force", "body": "b", "force": [0.0, 0.0, 2.0]},
    {"type": "force", "body": "b", "force": [0.0, 1.0, 0.0], "at": [0.2, 0.3, -0.1]},
    {"type": "force", "body": "b", "force": [1.0, 1.0, 0.0], "at": [0.2, 0.3, -0.1]},
    {"type": "force", "body": "b", "force": [0.0, 0.0, 2.0], "frame": "body"},
    {"type": "force", "body": "a", "force": [0.0, 0.0, 0.0], "at": [0.2, 0.0, 0.0]},
    {"type": "torque", "body": "b", "torque": [0.0, 0.0, 2.0]},
    {"type": "torque", "body": "b", "torque": [1.0, 0.0, 2.0], "frame": "body"},
]


@pytest.mark.parametrize("spec", APPLIED_CASES)
def test_an_applied_load_keeps_what_its_rates_keep(spec) -> None:
    (e,), _ = build([SPHERE, BOX], [spec])
    # a zero force at a point off G claims a moment it never exerts; a couple fixed in
    # space along e_z keeps L_x and L_y, but the torque claims only p
    in_space = spec["type"] == "torque" and spec.get("frame") != "body"
    complete = any(spec.get("force", [1])) and not in_space
    assert_keeps_what_its_rates_keep(e, 2, complete=complete)


@pytest.mark.parametrize(
    ("spec", "field", "reason"),
    [
        ({"type": "force", "body": "a", "force": [1, 0, 0], "start": 0.5, "end": 0.5}, "end",
         "must be after start 0.5; got 0.5"),
        ({"type": "torque", "body": "a", "torque": [1, 0, 0], "end": 0.25, "start": 0.5}, "end",
         "must be after start 0.5; got 0.25"),
        ({"type": "force", "body": "p", "force": [1, 0, 0], "at": [0, 0, 1.0]}, "at",
         "body 'p' is a point: it has no rotation (no points off G, no couple)"),
        ({"type": "torque", "body": "p", "torque": [1, 0, 0]}, "type",
         "body 'p' is a point: it has no rotation (no points off G, no couple)"),
    ],
)  # fmt: skip
def test_an_applied_load_refuses_an_empty_window_or_a_turn_of_a_point(spec, field, reason) -> None:
    err = refusal([SPHERE, POINT], [spec])
    assert err.field == f"effects[0].{field}"
    assert err.reason == reason


def test_an_applied_force_at_the_centre_of_a_point_is_fine() -> None:
    (e,), _ = build([POINT], [{"type": "force", "body": "p", "force": [1, 0, 0],
                              "at": [0.0, 0.0, 0.0], "end": 1.0}])  # fmt: skip
    assert e.at is None
    assert e.switch_times() == [1.0]
    scene_of([POINT], [{"type": "force", "body": "p", "force": [1.0, 0.0, 0.0]}])  # no at


@settings(max_examples=10)
@given(s=snapshots(1))
def test_a_zero_force_keeps_everything(s) -> None:
    (e,), _ = build([SPHERE], [{"type": "force", "body": "a", "force": [0.0, 0.0, 0.0]}])
    np.testing.assert_array_equal(loads_of(e, s, 1).F, np.zeros((1, 3)))
    assert all(e.keeps(q) for q in CONSERVED)


# ------------------------------------------------------------------ thrust

THRUST = {"type": "thrust", "body": "b", "mass_flow": 0.5, "exhaust_speed": 6.0, "fuel_mass": 1.0}


def test_thrust_pushes_with_q_u_along_d_until_burn_out_and_then_stops() -> None:
    (e,), _ = build([SPHERE, BOX], [{**THRUST, "direction": [0.0, 3.0, 4.0]}])
    assert e.burn_out == 2.0  # m_f / q
    s = two_at_rest()
    for phase, on in ((0.0, True), (1.999, True), (2.0, False), (5.0, False)):
        s.phase = phase
        out = loads_of(e, s, 2)
        # q u = 3 along (0, 0.6, 0.8)
        np.testing.assert_allclose(out.F, [[0, 0, 0], [0, 1.8 * on, 2.4 * on]], rtol=FORCE_RTOL)
        np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    assert e.switch_times() == [2.0]
    assert e.acts_until() == 2.0


def test_thrust_points_up_in_space_by_default_and_along_a_body_axis_in_the_body_frame() -> None:
    (up, along), _ = build(
        [SPHERE, BOX],
        [{**THRUST, "body": "a"}, {**THRUST, "direction": [1.0, 0.0, 0.0], "frame": "body"}],
    )
    s = two_at_rest()
    np.testing.assert_array_equal(loads_of(up, s, 2).F, [[0, 0, 3.0], [0, 0, 0]])
    # the body x of b is space y
    np.testing.assert_array_equal(loads_of(along, s, 2).F, [[0, 0, 0], [0, 3.0, 0]])


def test_thrust_burns_the_mass_q_t_until_the_fuel_is_gone() -> None:
    (e,), _ = build([SPHERE, BOX], [THRUST])
    np.testing.assert_array_equal(e.mass_loss(1.0), [0.0, 0.5])
    t = np.array([[0.0, 0.5], [2.0, 7.0]])
    loss = e.mass_loss(t)
    assert loss.shape == (2, 2, 2)
    np.testing.assert_array_equal(loss[..., 1], [[0.0, 0.25], [1.0, 1.0]])
    np.testing.assert_array_equal(loss[..., 0], np.zeros((2, 2)))


def test_thrust_keeps_nothing_the_gas_carries_momentum_and_energy_away() -> None:
    """d(m v)/dt = q u d − q v (7.24): with v across d, every momentum component and the
    angular momentum change; the kinetic energy changes by q u d·v − ½ q v² ≠ 0."""
    (e,), _ = build([SPHERE, BOX], [THRUST])
    s = two_at_rest()
    s.r[1] = [-1.0, 0.5, 2.0]
    s.v[1] = [1.0, 2.0, 0.5]
    q, u, d = 0.5, 6.0, np.array([0.0, 0.0, 1.0])
    F = loads_of(e, s, 2).F[1]
    dp = F - q * s.v[1]  # the body's momentum rate with its mass rate −q
    assert np.all(dp != 0)
    dL = np.cross(s.r[1], dp)
    assert np.all(dL != 0)
    dT = F @ s.v[1] - 0.5 * q * s.v[1] @ s.v[1]
    assert dT != 0
    np.testing.assert_allclose(F, q * u * d, rtol=FORCE_RTOL)
    assert not any(e.keeps(x) for x in CONSERVED)
    assert not e.exerts_moment(0)
    assert not e.exerts_moment(1)


@pytest.mark.parametrize(
    ("bodies", "effects", "field", "reason"),
    [
        ([SPHERE, BOX], [THRUST, THRUST], "effects[1].body", "body 'b' already has a thrust"),
        ([BOX], [{**THRUST, "fuel_mass": 3.0}], "effects[0].fuel_mass",
         "the fuel mass must be less than the body's mass 3.0 (the mass after burn-out must "
         "stay > 0); got 3.0"),
        ([POINT], [{**THRUST, "body": "p", "frame": "body"}], "effects[0].frame",
         "body 'p' is a point: it has no body frame"),
    ],
)  # fmt: skip
def test_thrust_refuses_a_second_motor_too_much_fuel_or_a_body_frame_on_a_point(
    bodies, effects, field, reason
) -> None:
    err = refusal(bodies, effects)
    assert err.field == field
    assert err.reason == reason


def test_thrust_takes_a_fuel_just_below_the_mass_and_a_space_frame_on_a_point() -> None:
    scene_of([BOX], [{**THRUST, "fuel_mass": 2.5}])
    scene_of([POINT], [{**THRUST, "body": "p", "frame": "space", "fuel_mass": 1.0}])
    scene_of([SPHERE, BOX], [{**THRUST, "body": "a"}, THRUST])  # one motor on each body


# ------------------------------------------------------------------ buoyancy

WATER = [{"type": "gravity", "g": 2.0}, {"type": "buoyancy", "body": "a", "density": 3.0,
                                         "level": 1.0}]  # fmt: skip


def floating(z):
    s = two_at_rest()
    s.r[0] = [0.25, -0.5, z]
    return s


def test_buoyancy_lifts_with_rho_g_times_the_immersed_cap_volume() -> None:
    """The sphere a = 0.5 under the level 1: immersed depth d = 1 − (z − 0.5); the cap
    V(d) = ∫ π (a² − x²) dx from −a to d − a: 0 at d = 0, half the ball 2π a³/3 at d = a,
    the whole ball 4π a³/3 from d = 2a on; the lift ρ g V = 6 V upward at G."""
    (_, e), _ = build([SPHERE, BOX], WATER)
    a = 0.5

    def cap(d):  # the integral of the cross-sections, by hand
        x = d - a
        return math.pi * ((a * a * x - x**3 / 3) - (-(a**3) + a**3 / 3))

    for z, V in ((2.0, 0.0), (1.5, 0.0), (1.0, 2 * math.pi * a**3 / 3),
                 (0.5, 4 * math.pi * a**3 / 3), (-3.0, 4 * math.pi * a**3 / 3),
                 (1.2, cap(0.3)), (0.7, cap(0.8))):  # fmt: skip
        out = loads_of(e, floating(z), 2)
        np.testing.assert_allclose(out.F, [[0, 0, 6.0 * V], [0, 0, 0]], rtol=FORCE_RTOL, atol=0)
        np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))


def test_buoyancy_potential_is_its_closed_form_and_minus_the_work_of_the_lift() -> None:
    (_, e), _ = build([SPHERE, BOX], WATER)
    a = 0.5
    # W(2a) = π (a (2a)³/3 − (2a)⁴/12) = π a⁴ (8/3 − 4/3) = 4π a⁴/3; beyond, + (4πa³/3) δ
    full = 4 * math.pi * a**4 / 3
    assert float(e.potential(floating(2.0))) == 0.0
    assert math.isclose(float(e.potential(floating(0.5))), 6.0 * full, rel_tol=FORCE_RTOL)
    deep = 6.0 * (full + 4 * math.pi * a**3 / 3 * 2.0)
    assert math.isclose(float(e.potential(floating(-1.5))), deep, rel_tol=FORCE_RTOL)
    for z in (1.3, 0.9, 0.6, -0.4):
        assert_potential_is_minus_the_work(e, floating(z), 2)
    zs = np.array([2.0, 0.5])
    batch = snap(np.stack([floating(z).r for z in zs]), np.zeros((2, 2, 3)),
                 np.stack([np.stack([np.eye(3), R_CYCLIC])] * 2), np.zeros((2, 2, 3)),
                 [[2.0, 3.0]] * 2, np.ones((2, 2, 3)))  # fmt: skip
    np.testing.assert_allclose(e.potential(batch), [0.0, 6.0 * full], rtol=FORCE_RTOL)


def test_buoyancy_keeps_the_energy_and_what_a_vertical_force_keeps() -> None:
    (_, e), _ = build([SPHERE, BOX], WATER)
    rng = np.random.default_rng(11)
    snaps = []
    for _ in range(5):
        s = random_snap(rng, 2)
        s.r[0, 2] = rng.uniform(0.6, 1.4)  # partly immersed: a lift that varies
        snaps.append(s)
    assert_keeps_what_its_rates_keep(e, 2, snaps=snaps)


def test_buoyancy_reads_the_level_zero_by_default_and_gravitys_size() -> None:
    (_, e), _ = build([SPHERE], [{"type": "gravity", "g": 4.0},
                                 {"type": "buoyancy", "body": "a", "density": 1.0}])  # fmt: skip
    assert e.level == 0.0
    assert e.g == 4.0
    assert e.a == 0.5
    assert e.rho == 1.0
    s = snap([[0, 0, 0.0]], [[0, 0, 0]], [np.eye(3)], [[0, 0, 0]], [2.0], [[1, 1, 1]])
    # G on the level: half the ball, 2π/3 · 0.125
    F = loads_of(e, s, 1).F
    np.testing.assert_allclose(F, [[0, 0, 4.0 * 2 * math.pi / 3 * 0.125]], rtol=FORCE_RTOL)


@pytest.mark.parametrize(
    ("bodies", "effects", "field", "reason"),
    [
        ([BOX], [{"type": "gravity", "g": 1.0}], "effects[1].body",
         "buoyancy is modelled for spheres (solid_sphere, hollow_sphere); 'b' is a box"),
        ([POINT], [{"type": "gravity", "g": 1.0}], "effects[1].body",
         "buoyancy is modelled for spheres (solid_sphere, hollow_sphere); 'p' is a point"),
        ([{**SPHERE, "fixed": True}], [{"type": "gravity", "g": 1.0}], "effects[1].body",
         "body 'a' is fixed: it cannot float"),
        ([SPHERE], [{"type": "gravity", "g": 1.0, "direction": [1.0, 0.0, -1.0]}],
         "effects[1].type", "buoyancy needs gravity along −z (the liquid's level is "
         "horizontal); the listed gravity is [0.7071067811865475, 0.0, -0.7071067811865475]"),
        ([SPHERE], [{"type": "gravity", "g": 1.0, "direction": [0.0, 1.0, -1.0]}],
         "effects[1].type", None),
        ([SPHERE], [{"type": "gravity", "g": 1.0, "direction": [0.0, 0.0, 1.0]}],
         "effects[1].type", None),
        ([SPHERE], [{"type": "drag", "body": "a", "linear": 1.0}], "effects[1].type",
         "buoyancy needs gravity along −z (the liquid's level is horizontal); the listed "
         "gravity is [0.0, 0.0, 0.0]"),
    ],
)  # fmt: skip
def test_buoyancy_refuses_a_body_that_is_no_free_sphere_or_a_gravity_off_vertical(
    bodies, effects, field, reason
) -> None:
    name = bodies[0]["name"]
    err = refusal(bodies, [*effects, {"type": "buoyancy", "body": name, "density": 1.0}])
    assert err.field == field
    if reason is not None:
        assert err.reason == reason
    else:
        assert err.reason.startswith("buoyancy needs gravity along −z")


def test_buoyancy_takes_a_hollow_sphere() -> None:
    hollow = {**SPHERE, "shape": "hollow_sphere"}
    scene_of([hollow], [{"type": "gravity", "g": 1.0}, {"type": "buoyancy", "body": "a",
                                                       "density": 1.0}])  # fmt: skip


# ------------------------------------------------------------------ torsion

HINGED = [SPHERE, {**BOX, "initial": {"angle": 0.5}}]
TWIST = [{"type": "fixed_axis", "body": "b", "axis": [0.0, 0.6, 0.8]},
         {"type": "torsion", "body": "b", "stiffness": 3.0}]  # fmt: skip


def test_torsion_twists_back_with_minus_tau0_phi_about_the_axis() -> None:
    (_, e), eng = build(HINGED, TWIST)
    s = eng.snapshot(0.0, eng.y0)
    assert s.angle[1] == 0.5
    out = loads_of(e, s, 2)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    M_O = s.R[1].T @ out.M_A[1]
    # −τ0 φ a = −3·0.5 (0, 0.6, 0.8)
    np.testing.assert_allclose(M_O, [0.0, -0.9, -1.2], rtol=FORCE_RTOL, atol=4 * EPS)
    np.testing.assert_array_equal(out.M_A[0], [0, 0, 0])
    # U = ½ τ0 φ² = 0.375, over a time axis too
    assert float(e.potential(s)) == 0.375
    angles = np.array([[0.0, 0.5], [7.0, -2.0]])
    batch = bare_snap(np.ones((2, 2)), angle=angles)
    np.testing.assert_array_equal(e.potential(batch), [0.375, 6.0])


def test_torsion_potential_is_minus_the_work_of_its_couple() -> None:
    (_, e), eng = build(HINGED, TWIST)
    for phi in (0.5, -1.25, 2.0):
        s = eng.snapshot(0.0, eng.y0)
        s.angle = np.array([0.0, phi])
        M = float(s.R[1].T @ loads_of(e, s, 2).M_A[1] @ np.array([0.0, 0.6, 0.8]))
        up, down = (bare_snap(s.m, angle=np.array([0.0, phi + h])) for h in (FD_STEP, -FD_STEP))
        dU = (e.potential(up) - e.potential(down)) / (2 * FD_STEP)
        assert abs(dU + M) <= FD_RTOL * abs(M)


def test_torsion_keeps_the_energy_and_the_momentum_and_turns_its_body_only() -> None:
    """A couple: no force (p kept); its potential makes E kept; its moment about the axis
    changes L (L not kept)."""
    (_, e), _ = build(HINGED, TWIST)
    assert [q for q in CONSERVED if e.keeps(q)] == ["p_x", "p_y", "p_z", "E"]
    assert e.exerts_moment(1)
    assert not e.exerts_moment(0)


def test_a_torsion_spring_acts_on_the_body_it_names() -> None:
    (_, _, e), eng = build(
        [{**SPHERE, "initial": {"angle": 0.0}}, {**BOX, "initial": {"angle": 0.5}}],
        [{"type": "fixed_axis", "body": "a"}, {"type": "fixed_axis", "body": "b"},
         {"type": "torsion", "body": "b", "stiffness": 2.0}],
    )  # fmt: skip
    assert e.i == 1
    assert e.hinge is eng.layout.guides[1]
    assert e.tau_0 == 2.0


def test_effects_built_without_a_scene_read_their_own_fields() -> None:
    """(``ctx=None``: no body index, no guide; the fields alone.)"""
    sc = scene_of(
        [{**SPHERE, "initial": {"angle": 0.5}}],
        [
            {"type": "gravity", "g": 2.0, "direction": [0.0, 0.0, -4.0]},
            {"type": "fixed_axis", "body": "a", "axis": [1.0, 0.0, 0.0]},
            {"type": "torsion", "body": "a", "stiffness": 3.0},
            {"type": "buoyancy", "body": "a", "density": 5.0, "level": -1.0},
        ],
    )
    gravity, _, torsion, buoyancy = (REGISTRY[e.type](e) for e in sc.effects)
    assert gravity.g == 2.0
    np.testing.assert_array_equal(gravity.vector, [0.0, 0.0, -2.0])
    assert torsion.tau_0 == 3.0
    assert torsion.i == 0  # no scene: no body index but the first
    assert torsion.hinge is None
    assert torsion.ctx is None
    assert (buoyancy.rho, buoyancy.level) == (5.0, -1.0)
    assert not hasattr(buoyancy, "a")  # the radius comes from the scene


def test_torsion_and_gravity_know_their_scene() -> None:
    (gravity, _, torsion), eng = build(HINGED, [{"type": "gravity", "g": 1.0}, *TWIST])
    assert gravity.ctx.index == torsion.ctx.index == {"a": 0, "b": 1}
    assert torsion.ctx.guides is eng.layout.guides


def test_a_linear_drag_alone_is_minus_b_v_and_a_linear_spin_drag_alone_minus_c_omega() -> None:
    (lin, spin), _ = build(
        [SPHERE, BOX],
        [
            {"type": "drag", "body": "b", "linear": 0.5},
            {"type": "drag", "body": "a", "angular_linear": 0.25},
        ],
    )
    s = two_at_rest()
    s.v[1] = [3.0, 0.0, 4.0]
    s.v[0] = [1.0, 2.0, 2.0]
    s.omega[0] = [0.0, 2.0, -4.0]
    s.omega[1] = [1.0, 1.0, 1.0]
    out = loads_of(lin, s, 2)
    np.testing.assert_array_equal(out.F, [[0, 0, 0], [-1.5, 0.0, -2.0]])
    np.testing.assert_array_equal(out.M_A, np.zeros((2, 3)))
    out = loads_of(spin, s, 2)
    np.testing.assert_array_equal(out.F, np.zeros((2, 3)))
    np.testing.assert_array_equal(out.M_A, [[0.0, -0.5, 1.0], [0, 0, 0]])


LISTED = [
    {"type": "gravity", "g": 1.0},
    {"type": "newton_gravity", "G": 1.0},
    {"type": "spring", "body": "a", "other": "b", "stiffness": 1.0},
    {"type": "damper", "body": "a", "other": "b", "damping": 1.0},
    {"type": "drag", "body": "a", "linear": 1.0},
    {"type": "force", "body": "a", "force": [1.0, 0.0, 0.0]},
    {"type": "torque", "body": "a", "torque": [1.0, 0.0, 0.0]},
    {"type": "thrust", "body": "a", "mass_flow": 0.1, "exhaust_speed": 1.0, "fuel_mass": 0.5},
    {"type": "buoyancy", "body": "a", "density": 1.0},
]


def test_each_effect_holds_its_spec_and_its_scene() -> None:
    effects, eng = build([SPHERE, BOX], LISTED)
    for e, spec in zip(effects, eng.scene.effects, strict=True):
        assert e.spec is spec
        assert e.fields is spec.fields
        assert e.ctx.index == {"a": 0, "b": 1}
        assert e.ctx.scene is eng.scene


def test_buoyancy_adds_its_lift_to_the_other_loads() -> None:
    (gravity, e), _ = build([SPHERE, BOX], WATER)
    s = floating(0.5)  # wholly immersed: lift ρ g 4π a³/3 = 6 π/6 = π
    out = loads_of(gravity, s, 2)  # the weight m g = 4 down
    e.loads(0.0, s, out)
    np.testing.assert_allclose(out.F, [[0, 0, math.pi - 4.0], [0, 0, -6.0]], rtol=FORCE_RTOL)


@pytest.mark.parametrize("kind", ["damper", "spring"])
@pytest.mark.parametrize("scale", [1.0, 0.1])
def test_the_damping_force_is_minus_c_times_the_rate_of_the_length(kind, scale) -> None:
    """The closing speed (v_P − v_Q)·u is d|PQ|/dt: a central difference of the length
    along the motion (both bodies moving and turning, P and Q off their centres; at
    scale 0.1 the ends are closer than 1).  A spring with ℓ0 = |PQ| pulls with its
    damping alone."""
    rng = np.random.default_rng(21)
    at, other_at = np.array([0.3, -0.2, 0.4]), np.array([-0.1, 0.5, 0.2])
    for _ in range(3):
        s = random_snap(rng, 2)
        s.r *= scale
        s.r[1] = s.r[0] + scale * (rng.normal(size=3) + 0.5)
        P = s.point(0, at * scale)
        Q = s.point(1, other_at * scale)
        length = float(np.linalg.norm(P - Q))
        spec = {"type": kind, "body": "a", "other": "b", "at": list(at * scale),
                "other_at": list(other_at * scale), "damping": 0.7}  # fmt: skip
        if kind == "spring":
            spec |= {"stiffness": 5.0, "rest_length": length}
        (e,), _ = build([SPHERE, BOX], [spec])

        def length_at(h, s=s):
            m = moved(s, h)
            return float(np.linalg.norm(m.point(0, at * scale) - m.point(1, other_at * scale)))

        rate = (length_at(FD_STEP) - length_at(-FD_STEP)) / (2 * FD_STEP)
        u = (P - Q) / length
        F = loads_of(e, s, 2).F
        want = -0.7 * rate * u
        size = 0.7 * float(np.linalg.norm(s.v).sum() + np.linalg.norm(s.omega).sum())
        np.testing.assert_allclose(F[0], want, rtol=0, atol=FD_RTOL * size)
        np.testing.assert_allclose(F[1], -want, rtol=0, atol=FD_RTOL * size)


def test_a_spring_without_rest_length_pulls_with_minus_k_times_the_whole_length() -> None:
    (e,), _ = build([SPHERE, BOX], [{"type": "spring", "body": "a", "anchor": [1.0, 0.0, 0.0],
                                     "stiffness": 3.0}])  # fmt: skip
    s = two_at_rest()  # a at (1, 2, 0): P − anchor = (0, 2, 0)
    np.testing.assert_array_equal(loads_of(e, s, 2).F, [[0, -6.0, 0], [0, 0, 0]])
    assert float(e.potential(s)) == 6.0  # ½·3·2²


def test_a_spring_shorter_than_the_float_resolution_still_pulls_with_minus_k_d() -> None:
    """|d|² underflows to 0 for |d| = 1e-170: the length reads 0, the zero-length branch
    pulls with −k d (and the damping of the whole relative velocity)."""
    (e,), _ = build([SPHERE, BOX], [{"type": "spring", "body": "a", "other": "b",
                                     "stiffness": 3.0}])  # fmt: skip
    s = two_at_rest()
    s.r[1] = [0.0, 0.0, 0.0]
    s.r[0] = [1e-170, 0.0, 0.0]
    F = loads_of(e, s, 2).F
    np.testing.assert_allclose(F, [[-3e-170, 0.0, 0.0], [3e-170, 0.0, 0.0]], rtol=FORCE_RTOL)
