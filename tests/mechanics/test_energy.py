"""API, validation and edge cases of :mod:`mechanics.energy`."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechanics import energy as me
from mechanics import particles as mp
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ShapeError,
)

EPS = np.finfo(float).eps


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
