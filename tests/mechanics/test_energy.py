"""API, validation and edge cases of :mod:`mechanics.energy`."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from mechanics import energy as me
from mechanics import particles as mp
from mechanics._floats import EPS, ulps
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
)

from ._naming import cases, check_refusal, valid_kwargs, word

# ------------------------------------------------------------ book examples


def test_example_3_5_torsion_pendulum_energy_is_conserved_and_period_matches():
    # (3.72)–(3.76): E = ½ J φ̇² + ½ τ0 φ² along φ = φ0 cos(ω0 t), ω0 = √(τ0/J),
    # J = ½ m R² for the disc.
    m, R, tau0, phi0 = 2.0, 0.3, 0.45, 0.7
    J = 0.5 * m * R**2
    w0 = math.sqrt(tau0 / J)
    t = np.linspace(0.0, 3.0, 31)
    phi, phidot = phi0 * np.cos(w0 * t), -phi0 * w0 * np.sin(w0 * t)
    E = me.kinetic_energy_fixed_axis(J, phidot) + me.torsion_potential(tau0, phi)
    np.testing.assert_allclose(E, 0.5 * tau0 * phi0**2, rtol=8 * EPS)
    # The period 2π/ω0 = 2π √(J/τ0) = 2π √(m R²/(2 τ0)).  (The printed (3.76)
    # reads 2π √(τ0/J_z) = 2π √(2τ0/(m R²)), the ratio inverted: that has the
    # dimension of 1/time; the identities check of E3.5 owns that erratum.)
    assert 2 * math.pi / w0 == pytest.approx(2 * math.pi * math.sqrt(m * R**2 / (2 * tau0)))


def test_example_3_6_rolling_cylinder_speed_from_energy():
    # (3.77)–(3.80): energy with the rolling constraint gives ẋ = √(4 g h/3).
    m, r, g, h = 3.0, 0.25, 9.81, 1.7
    xdot = math.sqrt(4 * g * h / 3)
    J_G = np.diag([0.25 * m * r**2, 0.25 * m * r**2, 0.5 * m * r**2])  # cylinder axis e_z
    T = me.kinetic_energy_rigid(m, [xdot, 0.0, 0.0], [0.0, 0.0, -xdot / r], J_G)
    assert float(T) == pytest.approx(m * g * h, rel=4 * EPS)
    # The contact point is at rest, so the contact force does no work (3.2.2):
    assert (
        float(me.rolling_contact_power([5.0, 20.0, 0], [xdot, 0, 0], [0, 0, -xdot / r], [0, -r, 0]))
        == 0.0
    )


def test_example_3_3_rubber_band_only_stores_energy_when_stretched():
    k, ell0 = 40.0, 0.5
    assert me.spring_potential(k, ell0, [0, 0, 0], [0.7, 0, 0], tension_only=True) == pytest.approx(
        0.5 * k * 0.2**2
    )
    assert me.spring_potential(k, ell0, [0, 0, 0], [0.3, 0, 0], tension_only=True) == 0.0
    assert me.spring_potential(k, ell0, [0, 0, 0], [0.3, 0, 0]) == pytest.approx(0.5 * k * 0.2**2)
    np.testing.assert_array_equal(
        me.spring_force(k, ell0, [0, 0, 0], [0.3, 0, 0], tension_only=True), [0.0, 0.0, 0.0]
    )


# -------------------------------------------------------------------- API


def test_rigid_kinetic_energy_agrees_with_the_particles_it_is_made_of():
    rng = np.random.default_rng(3)
    m = rng.uniform(0.5, 2.0, 7)
    r = rng.normal(size=(7, 3))
    rG = mp.centre_of_mass(m, r)
    d = r - rG
    J = np.einsum("n,ij->ij", m * (d * d).sum(-1), np.eye(3)) - np.einsum("n,ni,nj->ij", m, d, d)
    vG, w = np.array([0.3, -1.0, 2.0]), np.array([1.5, 0.2, -0.7])
    T = me.kinetic_energy_rigid(m.sum(), vG, w, J)
    assert float(T) == pytest.approx(float(mp.kinetic_energy(m, vG + np.cross(w, d))), rel=1e-14)


def test_power_and_work_shapes_broadcast_over_batches():
    F = np.ones((4, 2, 3))
    v = np.arange(6.0).reshape(2, 3)
    P = me.power(F, v)
    assert P.shape == (4,)
    assert np.all(P == 15.0)
    s = np.linspace(0, 1, 11)
    path = np.stack([s, 2 * s, 0 * s], -1)
    W = me.work_along_path(np.broadcast_to([1.0, 1.0, 1.0], (3, 11, 3)), path)
    np.testing.assert_allclose(W, 3.0, rtol=4 * EPS)


def test_work_from_power_is_simpson_accurate():
    t = np.linspace(0.0, 2.0, 101)
    W = me.work_from_power(np.cos(t), t)
    assert abs(float(W) - math.sin(2.0)) < 1e-8  # O(h⁴): h = 0.02 gives ~1e-9


def test_gravity_potential_is_minus_m_g_dot_r_G_at_large_offsets():
    m = np.array([1.0, 2.0, 3.0])
    r = 1e8 + np.array([[0.0, 0, 0.5], [0.0, 0, -0.25], [0.0, 0, 0.125]])
    g = [0.0, 0.0, -9.81]
    Phi = me.gravity_potential(m, r, g=g)
    exact = 9.81 * math.fsum([1e8 * 6, 0.5 * 1, -0.25 * 2, 0.125 * 3])
    assert float(Phi) == pytest.approx(exact, rel=2 * EPS)


def test_forces_that_do_no_work():
    assert float(me.pair_power([0.0, 0.0, 2.0], [1.0, 3.0, 0.5], [-4.0, 9.0, 0.5])) == 0.0
    assert float(me.contact_power([1.0, 1.0, 0.0], [2.0, 0.0, 0.0], [0, 0, 0], [0, -1, 0])) == 2.0
    np.testing.assert_array_equal(
        me.contact_point_velocity([2.0, 0.0, 0.0], [0.0, 0.0, -2.0], [0.0, -1.0, 0.0]), [0, 0, 0]
    )


# -------------------------------------------------------------- validation


def test_gravity_vector_is_required():
    with pytest.raises(TypeError):
        me.gravity_potential([1.0], [[0.0, 0.0, 1.0]])  # type: ignore[call-arg]


@pytest.mark.parametrize(
    ("func", "args", "error", "match"),
    [
        (
            me.kinetic_energy_rigid,
            (-1.0, [0, 0, 0], [0, 0, 1], np.eye(3)),
            NegativeMassError,
            "m must",
        ),
        (
            me.kinetic_energy_rigid,
            (1.0, [0, 0, 0], [0, 0, 1], [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]),
            NonPhysicalInertiaError,
            "not symmetric",
        ),
        (
            me.kinetic_energy_rigid,
            (1.0, [0, 0, 0], [0, 0, 1], np.diag([1.0, 1.0, -1.0])),
            NonPhysicalInertiaError,
            "positive semidefinite",
        ),
        (me.kinetic_energy_fixed_axis, (-2.0, 1.0), NonPhysicalInertiaError, "J_axis"),
        (me.kinetic_energy_fixed_axis, (2.0, math.nan), NonFiniteError, "omega"),
        (me.gravity_potential, ([-1.0], [[0, 0, 0]]), NegativeMassError, "m must"),
        (me.spring_potential, (-1.0, 1.0, [0, 0, 0], [1, 0, 0]), OutOfDomainError, "k = -1.0"),
        (me.spring_potential, (1.0, -1.0, [0, 0, 0], [1, 0, 0]), OutOfDomainError, "ell_0"),
        (me.spring_force, (1.0, 1.0, [1, 2, 3], [1, 2, 3]), NonPositiveParameterError, "coincide"),
        (me.torsion_potential, (-0.5, 1.0), OutOfDomainError, "tau_0"),
        (me.power, ([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]), ShapeError, r"\(1, 3\)"),
        (me.power, (np.ones((2, 3)), np.ones((3, 3))), ShapeError, "broadcast"),
        (me.work_along_path, (np.ones((1, 3)), np.ones((1, 3))), ShapeError, "K >= 2"),
        (me.work_from_power, ([1.0, 2.0], [0.0, 0.0]), NonPositiveParameterError, "increasing"),
        (me.work_from_power, ([1.0, 2.0, 3.0], [0.0, 1.0]), ShapeError, "K"),
    ],
)
def test_bad_input_raises_a_specific_error_naming_the_value(func, args, error, match):
    kwargs = {"g": [0.0, 0.0, -9.81]} if func is me.gravity_potential else {}
    with pytest.raises(error, match=match):
        func(*args, **kwargs)


# ------------------------------------------- every parameter named, every overflow named
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("gravity_potential", "m"): r"must be >= 0; found -1\.0",
    ("kinetic_energy_fixed_axis", "J_axis"): r"must be >= 0; found -1\.0",
    ("kinetic_energy_rigid", "m"): r"must be >= 0; found -1\.0",
    ("spring_force", "k"): r"k = -1\.0 must be >= 0",
    ("spring_potential", "k"): r"k = -1\.0 must be >= 0",
    ("spring_force", "ell_0"): r"ell_0 = -1\.0 must be >= 0",
    ("spring_potential", "ell_0"): r"ell_0 = -1\.0 must be >= 0",
    ("torsion_moment", "tau_0"): r"tau_0 = -1\.0 must be >= 0",
    ("torsion_potential", "tau_0"): r"tau_0 = -1\.0 must be >= 0",
    ("work_from_power", "t"): r"strictly increasing",
}
_OTHER = {
    ("gravity_potential", "m", "shape"): r"r has shape \(1, 3\) but m has shape \(2,\)",
    (
        "work_from_power",
        "P",
        "shape",
    ): r"must be \(K,\) with K >= 2 and P \(\.\.\., K\); got t \(4,\), P \(3,\)",
    (
        "work_from_power",
        "t",
        "shape",
    ): r"must be \(K,\) with K >= 2 and P \(\.\.\., K\); got t \(3,\), P \(4,\)",
}


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"),
    list(cases("energy", _CONDITIONS, other=_OTHER)),
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("energy", fname) | {param: value}
    check_refusal(getattr(me, fname), kw, param, error, condition)


_BIG = 1e300  # squared or multiplied by another 1e300: beyond float64's 1.8e308
_X = [_BIG, 0.0, 0.0]


@pytest.mark.parametrize(
    ("call", "what"),
    [
        pytest.param(
            lambda: me.kinetic_energy_rigid(_BIG, _X, [0, 0, 0], np.eye(3)),
            "the kinetic energy",
            id="kinetic_energy_rigid",
        ),
        pytest.param(
            lambda: me.kinetic_energy_fixed_axis(_BIG, _BIG),
            "the kinetic energy",
            id="kinetic_energy_fixed_axis",
        ),
        pytest.param(lambda: me.power([_X], [_X]), "the power", id="power"),
        pytest.param(
            lambda: me.work_from_power([1e308, 1e308, 1e308], [0.0, 1e10, 2e10]),
            "the work",
            id="work_from_power",
        ),
        pytest.param(
            lambda: me.work_along_path([_X, _X], [[0, 0, 0], _X]), "the work", id="work_along_path"
        ),
        pytest.param(lambda: me.work_of_couple(_X, _X), "the work", id="work_of_couple"),
        pytest.param(
            lambda: me.rigid_body_power(_X, [0, 0, 0], _X, [0, 0, 0]),
            "the power",
            id="rigid_body_power",
        ),
        pytest.param(
            lambda: me.gravity_potential([1e308], [[0, 0, 1.0]], g=[0, 0, -10.0]),
            "m g",
            id="gravity_potential-m_g",
        ),
        pytest.param(
            lambda: me.gravity_potential([_BIG], [[0, 0, _BIG]], g=[0, 0, -10.0]),
            "the potential energy",
            id="gravity_potential",
        ),
        pytest.param(
            lambda: me.spring_potential(_BIG, 0.0, [0, 0, 0], _X),
            "the spring energy",
            id="spring_potential",
        ),
        pytest.param(
            lambda: me.spring_force(_BIG, 0.0, [0, 0, 0], _X), "the spring force", id="spring_force"
        ),
        pytest.param(
            lambda: me.torsion_potential(_BIG, _BIG), "the torsion energy", id="torsion_potential"
        ),
        pytest.param(lambda: me.torsion_moment(_BIG, _BIG), "torsion_moment", id="torsion_moment"),
        pytest.param(
            lambda: me.contact_point_velocity([1e308, 0, 0], [0, 0, 1e308], [0, 1e308, 0]),
            "contact_point_velocity",
            id="contact_point_velocity",
        ),
        pytest.param(
            lambda: me.contact_power(_X, _X, [0, 0, 0], [0, 0, 0]), "the power", id="contact_power"
        ),
        pytest.param(
            lambda: me.rolling_contact_power(_X, _X, [0, 0, 0], [0, 0, 0]),
            "the power",
            id="rolling_contact_power",
        ),
        pytest.param(lambda: me.pair_power(_X, _X, [0, 0, 0]), "the power", id="pair_power"),
    ],
)
def test_a_result_beyond_float64_is_an_overflow_error_naming_what_overflowed(call, what):
    with pytest.raises(ResultOverflowError) as info:
        call()
    msg = str(info.value)
    assert re.search(rf"^{re.escape(what)}\b", msg), msg
    assert re.search(r"beyond float64|exceeds float64", msg), msg


@pytest.mark.parametrize(
    ("call", "first", "second"),
    [
        pytest.param(lambda a, b: me.power(a, b), "F", "v", id="power"),
        pytest.param(lambda a, b: me.work_along_path(a, b), "F", "r", id="work_along_path"),
        pytest.param(
            lambda a, b: me.rigid_body_power(a, [0, 0, 1.0], b, [1.0, 0, 0]),
            "F",
            "v_A",
            id="rigid_body_power-F",
        ),
        pytest.param(
            lambda a, b: me.rigid_body_power([0, 0, 1.0], a, [1.0, 0, 0], b),
            "M_A",
            "omega",
            id="rigid_body_power-M_A",
        ),
        pytest.param(
            lambda a, b: me.contact_point_velocity(a, b, [0, 0, 1.0]),
            "v_G",
            "omega",
            id="contact_point_velocity",
        ),
        pytest.param(lambda a, b: me.pair_power([0, 0, 1.0], a, b), "v_1", "v_2", id="pair_power"),
    ],
)
def test_batches_that_do_not_broadcast_name_each_argument_with_its_own_shape(call, first, second):
    # 2 and 3 rows along a leading axis: the message pairs each name with its own shape
    a, b = np.ones((2, 2, 3)), np.ones((3, 2, 3))
    with pytest.raises(ShapeError) as info:
        call(a, b)
    msg = str(info.value)
    assert re.search(
        rf"{word(first)} \(2, 2, 3\) and {word(second)} \(3, 2, 3\) do not broadcast", msg
    ), msg


# ------------------------------------------- boundaries of the domains, signs, batches


def test_a_negative_mass_or_moment_is_reported_with_its_value_and_its_own_index():
    # The first negative entry in C order, with its value and its full index: (2,) in a
    # vector, (1, 0) in a (2, 2) batch, never the whole array or an empty index.
    with pytest.raises(
        NonPhysicalInertiaError, match=r"J_axis must be >= 0; found -0\.5 at index \(2,\)$"
    ):
        me.kinetic_energy_fixed_axis([1.0, 2.0, -0.5, -3.0], 1.0)
    with pytest.raises(NegativeMassError, match=r"m must be >= 0; found -2\.0 at index \(1, 0\)$"):
        me.kinetic_energy_rigid([[1.0, 0.0], [-2.0, 4.0]], [1.0, 0, 0], [0, 0, 1.0], np.eye(3))


def test_zero_and_small_spring_and_torsion_constants_are_in_the_domain():
    # k >= 0 and tau_0 >= 0 (3.53), (3.72): zero stiffness is a spring that stores nothing
    # and pulls with nothing; a constant below 1 is as valid as any other.
    assert float(me.spring_potential(0.0, 1.0, [0, 0, 0], [3.0, 4.0, 0.0])) == 0.0
    np.testing.assert_array_equal(me.spring_force(0.0, 1.0, [0, 0, 0], [3.0, 4.0, 0.0]), 0.0)
    # ½ · 0.5 · (5 − 1)² = 4 and −0.5 · (5 − 1) · (−3, −4, 0)/5 = (1.2, 1.6, 0)
    assert float(me.spring_potential(0.5, 1.0, [0, 0, 0], [3.0, 4.0, 0.0])) == 4.0
    np.testing.assert_allclose(
        me.spring_force(0.5, 1.0, [0, 0, 0], [3.0, 4.0, 0.0]), [1.2, 1.6, 0.0], rtol=2 * EPS
    )  # rounded once in ext/dist = 4/5 and once in the product
    assert float(me.torsion_potential(0.0, 3.0)) == 0.0
    assert float(me.torsion_moment(0.0, 3.0)) == 0.0
    assert float(me.torsion_potential(0.5, 2.0)) == 1.0  # ½ · 0.5 · 2² (3.72)
    assert float(me.torsion_moment(0.5, 2.0)) == -1.0  # −0.5 · 2


def test_the_torsion_moment_restores_minus_tau_0_phi():
    # M = −τ_0 φ (3.71): opposite to the twist, on both sides; products exact in binary.
    assert float(me.torsion_moment(2.5, 0.5)) == -1.25
    assert float(me.torsion_moment(2.0, -0.75)) == 1.5
    np.testing.assert_array_equal(me.torsion_moment([1.0, 4.0], [0.25, -0.5]), [-0.25, 2.0])
    # and M = −dΦ/dφ: Φ(φ) = ½ τ_0 φ² has the central difference τ_0 φ exactly for a parabola
    tau0, phi, h = 3.0, 0.625, 0.125
    dPhi = (me.torsion_potential(tau0, phi + h) - me.torsion_potential(tau0, phi - h)) / (2 * h)
    assert float(me.torsion_moment(tau0, phi)) == -float(dPhi) == -1.875


def test_coincident_spring_ends_are_reported_at_their_index():
    r1 = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [5.0, 0.0, 0.0]])
    r2 = np.array([[1.0, 0.0, 0.0], [1.0, 2.0, 3.0], [5.0, 0.0, 0.0]])
    with pytest.raises(NonPositiveParameterError) as info:
        me.spring_force(1.0, 0.5, r1, r2)
    assert str(info.value) == (
        "the spring's end points coincide (index (1,)): |r_1 - r_2| = 0, its direction is undefined"
    )


@pytest.mark.parametrize(
    ("call", "message"),
    [
        pytest.param(
            lambda: me.power([1.0, 2.0, 3.0], [[1.0, 0.0, 0.0]]),
            r"F \(3,\) and v \(1, 3\) must be \(\.\.\., N, 3\); one force is \(1, 3\)",
            id="power-F",
        ),
        pytest.param(
            lambda: me.power([[1.0, 2.0, 3.0]], [1.0, 0.0, 0.0]),
            r"F \(1, 3\) and v \(3,\) must be \(\.\.\., N, 3\); one force is \(1, 3\)",
            id="power-v",
        ),
        pytest.param(
            lambda: me.work_along_path([0.0, 0.0, 1.0], [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
            r"F \(3,\) and r \(2, 3\) must be \(\.\.\., K, 3\) with K >= 2 samples",
            id="work_along_path-F",
        ),
        pytest.param(
            lambda: me.work_along_path([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]], [0.0, 0.0, 1.0]),
            r"F \(2, 3\) and r \(3,\) must be \(\.\.\., K, 3\) with K >= 2 samples",
            id="work_along_path-r",
        ),
        pytest.param(
            lambda: me.work_from_power([1.0], [0.0]),
            r"K >= 2 and P \(\.\.\., K\); got t \(1,\), P \(1,\)",
            id="work_from_power-one-sample",
        ),
        pytest.param(
            lambda: me.work_from_power(1.0, [0.0, 1.0]),
            r"K >= 2 and P \(\.\.\., K\); got t \(2,\), P \(\)",
            id="work_from_power-scalar-P",
        ),
        pytest.param(
            lambda: me.work_from_power([1.0, 2.0], [[0.0, 1.0], [2.0, 3.0]]),
            r"K >= 2 and P \(\.\.\., K\); got t \(2, 2\), P \(2,\)",
            id="work_from_power-2d-t",
        ),
        pytest.param(
            lambda: me.work_from_power([1.0, 2.0], 2.0),
            r"K >= 2 and P \(\.\.\., K\); got t \(\), P \(2,\)",
            id="work_from_power-scalar-t",
        ),
    ],
)
def test_each_argument_of_the_wrong_rank_is_refused_alone(call, message):
    # One argument of the right rank does not excuse the other: a bare (3,) force is
    # not a system of forces even when the velocities are (1, 3), and t must be (K,)
    # with K >= 2 whatever P is.
    with pytest.raises(ShapeError, match=message):
        call()


def test_gravity_potential_of_a_batch_of_systems():
    # Two systems of two particles, each with its own gravity vector; Φ = −Σ m_k g · r_k:
    # system 0: g = −10 e_z, Φ = 10 (1 · 2 + 3 · 6) = 200 (Example 3.2's numbers);
    # system 1: g = −2 e_y, Φ = 2 (2 · 3 + 0.5 · 4) = 16.
    m = [[1.0, 3.0], [2.0, 0.5]]
    r = [[[0.0, 0.0, 2.0], [5.0, 1.0, 6.0]], [[1.0, 3.0, 1.0], [0.0, 4.0, 8.0]]]
    g = [[0.0, 0.0, -10.0], [0.0, -2.0, 0.0]]
    np.testing.assert_array_equal(me.gravity_potential(m, r, g=g), [200.0, 16.0])
    # one system's masses and one g, three configurations of it: Φ = 10 Σ m_k z_k
    z = np.array([[2.0, 6.0], [0.0, 1.0], [-1.0, 0.5]])
    rs = np.zeros((3, 2, 3))
    rs[..., 2] = z
    np.testing.assert_array_equal(
        me.gravity_potential([1.0, 3.0], rs, g=[0.0, 0.0, -10.0]), [200.0, 30.0, 5.0]
    )


# ----------------------------------------- springs at any scale (the hunt, 29 Nov 2026)

#: the scaled norm (√ of a sum of 3 squares: ~2 ulps), ext, ext/|d| and the products
SPRING_ULPS = 4


@pytest.mark.parametrize(
    ("r_1", "ell_0"),
    [
        # |d| = 1e160: its square overflowed in the plain norm (ResultOverflowError for a force
        # of 1e160, a float)
        pytest.param([1e160, 0.0, 0.0], 0.0, id="1e160"),
        # |d| = 5e-170 and subnormal ends: the squares underflowed to 0 and distinct ends were
        # refused as coincident (NonPositiveParameterError)
        pytest.param([3e-170, 4e-170, 0.0], 1e-170, id="1e-170"),
        pytest.param([3e-310, 4e-310, 0.0], 0.0, id="subnormal"),
        pytest.param([5e-324, 0.0, 0.0], 0.0, id="smallest-subnormal"),
    ],
)
def test_spring_force_and_energy_hold_at_any_length(r_1, ell_0):
    """Against mpmath at 60 digits: |d|, the
    force k (|d| − ℓ_0) d/|d| and the energy ½ k (|d| − ℓ_0)².  A few roundings (the scaled
    norm, ext, the quotient, the product): within 4 ulps."""
    import mpmath

    k = 3.0
    with mpmath.workdps(60):
        d = [mpmath.mpf(x) for x in r_1]
        dist = mpmath.sqrt(sum(x * x for x in d))
        ext = dist - mpmath.mpf(ell_0)
        F = [-mpmath.mpf(k) * ext * x / dist for x in d]
        Phi = mpmath.mpf(k) * ext * ext / 2
        got_F = me.spring_force(k, ell_0, r_1, [0.0, 0.0, 0.0]).tolist()
        assert max(ulps(g, w) for g, w in zip(got_F, F, strict=True)) <= SPRING_ULPS, got_F
        if Phi > mpmath.mpf(np.finfo(float).max):  # 1.5e320: refused, as documented
            with pytest.raises(ResultOverflowError, match=r"^the spring energy is beyond"):
                me.spring_potential(k, ell_0, r_1, [0.0, 0.0, 0.0])
        elif Phi > mpmath.mpf(2.0**-1022):  # a normal energy (not 3.75e-647, rounded to 0)
            got_Phi = float(me.spring_potential(k, ell_0, r_1, [0.0, 0.0, 0.0]))
            assert ulps(got_Phi, Phi) <= SPRING_ULPS, got_Phi


@pytest.mark.parametrize(
    "f", [me.spring_potential, me.torsion_potential], ids=["spring", "torsion"]
)
def test_half_k_x_squared_does_not_round_a_subnormal_half_k_first(f):
    """½ k x² = 3 · 2**-995 exactly for k = 3 · 2**-1074 (subnormal) and x = 2**40: the plain
    (½ k) x x rounded ½ k = 1.5 · 2**-1074 to 2 · 2**-1074 and gave 4 · 2**-995 (33 % off)."""
    k, x = 3.0 * 2.0**-1074, 2.0**40
    got = f(k, 0.0, [x, 0.0, 0.0], [0.0, 0.0, 0.0]) if f is me.spring_potential else f(k, x)
    assert float(got) == 3.0 * 2.0**-995
