"""API, validation and edge cases of :mod:`mechanics.particles`."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from mechanics import particles as mp
from mechanics._floats import EPS
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    ZeroAxisError,
    ZeroTotalMassError,
)

from ._naming import cases, check_refusal, entries_of, valid_kwargs

M3 = np.array([1.0, 2.0, 0.5])
R3 = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 1.0], [-1.0, 1.0, 3.0]])
V3 = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, -1.0], [2.0, 2.0, 0.0]])
O = np.zeros(3)


# ----------------------------------------------------------- book examples


@pytest.mark.parametrize("t", [0.0, 0.3, 1.7])
def test_example_1_1_angular_momentum_and_moment_match_the_book(t):
    # Example 1.1, (1.34)–(1.38): two balls m at ±r_1 on a rod of length 2R
    # at angle ϑ to the z-axis, turning at ω.
    m, R, th, w = 0.7, 1.3, 0.4, 2.1
    c, s = math.cos(w * t), math.sin(w * t)
    r1 = np.array([R * math.sin(th) * c, R * math.sin(th) * s, R * math.cos(th)])
    v1 = R * math.sin(th) * w * np.array([-s, c, 0.0])
    a1 = -(w**2) * np.array([r1[0], r1[1], 0.0])
    r, v, a = np.stack([r1, -r1]), np.stack([v1, -v1]), np.stack([a1, -a1])
    masses = [m, m]
    assert np.abs(mp.momentum(masses, v)).max() == 0.0  # (1.36)
    L = mp.angular_momentum(masses, r, v, about=O)
    book_L = (
        2
        * m
        * R**2
        * math.sin(th)
        * w
        * np.array([-math.cos(th) * c, -math.cos(th) * s, math.sin(th)])
    )  # (1.37)
    np.testing.assert_allclose(L, book_L, rtol=0, atol=8 * EPS * np.abs(book_L).max())
    Ldot = mp.angular_momentum_rate(masses, r, v, a, about=O, about_velocity=O)
    book_M = 2 * m * R**2 * w**2 * math.sin(th) * math.cos(th) * np.array([s, -c, 0.0])  # (1.38)
    np.testing.assert_allclose(Ldot, book_M, rtol=0, atol=8 * EPS * np.abs(book_M).max() + 1e-300)


def test_example_1_2_platform_relation_conserves_axial_angular_momentum():
    # (1.78)–(1.80): with α̇ = −m ρ² ϕ̇/(J_z + m ρ²), the platform (a ring of
    # particles of total moment J_z) and the walker have L_z = 0.
    Jz, m, rho, phidot = 4.0, 1.5, 0.8, 0.9
    alphadot = -m * rho**2 * phidot / (Jz + m * rho**2)
    ring_angles = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    ring = np.stack([np.cos(ring_angles), np.sin(ring_angles), 0 * ring_angles], -1)
    ring_m = np.full(8, Jz / 8)
    walker = np.array([[rho, 0.0, 0.0]])
    r = np.concatenate([ring, walker])
    ez = np.array([0.0, 0.0, 1.0])
    v = np.concatenate([np.cross(alphadot * ez, ring), np.cross((alphadot + phidot) * ez, walker)])
    L = mp.angular_momentum(np.concatenate([ring_m, [m]]), r, v, about=O)
    assert abs(L[2]) <= 8 * EPS * (Jz + m) * abs(phidot)


# -------------------------------------------------------------------- API


def test_total_mass_and_centre_of_mass_of_a_simple_system():
    assert mp.total_mass(M3) == 3.5
    np.testing.assert_array_equal(mp.centre_of_mass(M3, R3), (M3 @ R3) / 3.5)


def test_batches_broadcast_one_mass_vector_over_many_configurations():
    rng = np.random.default_rng(0)
    r = rng.normal(size=(4, 5, 3))
    v = rng.normal(size=(4, 5, 3))
    m = rng.uniform(1, 2, 5)
    rG = mp.centre_of_mass(m, r)
    assert rG.shape == (4, 3)
    L = mp.angular_momentum(m, r, v, about=np.zeros((4, 3)))
    assert L.shape == (4, 3)
    for b in range(4):
        np.testing.assert_allclose(rG[b], mp.centre_of_mass(m, r[b]), rtol=4 * EPS)
        np.testing.assert_allclose(L[b], mp.angular_momentum(m, r[b], v[b], about=O), rtol=1e-15)
    T = mp.kinetic_energy(m, v)
    assert T.shape == (4,)
    T_G, T_cm = mp.kinetic_energy_decomposition(m, v)
    assert T_G.shape == T_cm.shape == (4,)


def test_single_particle_has_no_internal_angular_momentum_or_energy():
    L_G, L_ext = mp.angular_momentum_decomposition([2.0], [[1.0, 2.0, 3.0]], [[0, 1, 0]], about=O)
    assert not L_G.any()
    np.testing.assert_array_equal(L_ext, np.cross([1.0, 2.0, 3.0], [0.0, 2.0, 0.0]))
    T_G, T_cm = mp.kinetic_energy_decomposition([2.0], [[0.0, 3.0, 0.0]])
    assert T_G == 0.0
    assert T_cm == 9.0


def test_zero_masses_are_allowed_when_some_mass_remains():
    rG = mp.centre_of_mass([0.0, 2.0], [[1e300, 0, 0], [1.0, 2.0, 3.0]])
    np.testing.assert_array_equal(rG, [1.0, 2.0, 3.0])


def test_relative_velocity_angular_momentum_about_G_is_L_G():
    rG, vG = mp.centre_of_mass(M3, R3), mp.centre_of_mass_velocity(M3, V3)
    L_rel = mp.angular_momentum(M3, R3, V3, about=rG, about_velocity=vG)
    L_G, _ = mp.angular_momentum_decomposition(M3, R3, V3, about=O)
    np.testing.assert_allclose(L_rel, L_G, rtol=0, atol=16 * EPS * 10)


def test_internal_forces_and_moment_of_a_non_central_pair():
    f = np.zeros((3, 3, 3))
    f[0, 2] = [0.0, 0.0, 1.0]
    f[2, 0] = -f[0, 2]
    F = mp.internal_forces(f)
    np.testing.assert_array_equal(F, [[0, 0, 1], [0, 0, 0], [0, 0, -1]])
    # M^i = r_02 × f_02 = (2, -1, -3) × (0, 0, 1)
    np.testing.assert_array_equal(mp.internal_moment(R3, f), np.cross(R3[0] - R3[2], f[0, 2]))


def test_cylindrical_components_of_a_point_on_the_x_axis():
    c = mp.cylindrical_components([2.0, 0.0, 1.0], [1.0, 4.0, -1.0], about=O, axis=[0, 0, 1])
    assert (float(c.rho), float(c.phi), float(c.z)) == (2.0, 0.0, 1.0)
    assert (float(c.rhodot), float(c.phidot), float(c.zdot)) == (1.0, 2.0, -1.0)


def test_cylindrical_components_about_a_general_axis_are_consistent():
    e = np.array([1.0, 2.0, 2.0]) / 3
    A = np.array([0.5, -1.0, 2.0])
    r, v = np.array([3.0, 1.0, -2.0]), np.array([0.3, -0.4, 1.1])
    c = mp.cylindrical_components(r, v, about=A, axis=3 * e)
    # ρ² + z² = |r − A|², ρ ρ̇ + z ż = (r − A)·v and ρ² ϕ̇ = ((r − A) × v)·e (1.68).
    d = r - A
    assert c.rho**2 + c.z**2 == pytest.approx(d @ d, rel=1e-14)
    assert c.rho * c.rhodot + c.z * c.zdot == pytest.approx(d @ v, rel=1e-14)
    assert c.rho**2 * c.phidot == pytest.approx(np.cross(d, v) @ e, rel=1e-14)


def test_continuous_rod_by_the_midpoint_rule_converges_at_second_order():
    errs = []
    for n in (100, 200):
        x = (np.arange(n) + 0.5) * (2.0 / n)
        pts = np.stack([x, 0 * x, 0 * x], -1)
        errs.append(abs(mp.continuous_centre_of_mass(x, pts, cell_volume=2.0 / n)[0] - 4 / 3))
    assert 3.9 < errs[0] / errs[1] < 4.1


# -------------------------------------------------------------- validation


@pytest.mark.parametrize(
    ("func", "args", "kwargs"),
    [
        (mp.total_mass, ([1.0, -0.5],), {}),
        (mp.centre_of_mass, ([1.0, -0.5], R3[:2]), {}),
        (mp.momentum, ([1.0, -1.0], V3[:2]), {}),
        (mp.angular_momentum, ([1.0, -1e-300], R3[:2], V3[:2]), {"about": O}),
        (mp.kinetic_energy, ([1.0, -2.0], V3[:2]), {}),
    ],
)
def test_negative_masses_are_rejected_naming_the_value(func, args, kwargs):
    with pytest.raises(NegativeMassError, match=r"m must be >= 0; found -.* at index \(1,\)"):
        func(*args, **kwargs)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_masses_and_positions_are_rejected(bad):
    with pytest.raises(NonFiniteError, match="m must be finite"):
        mp.total_mass([1.0, bad])
    r = R3.copy()
    r[1, 2] = bad
    with pytest.raises(NonFiniteError, match=r"r must be finite; found .* at index \(1, 2\)"):
        mp.centre_of_mass(M3, r)


def test_zero_total_mass_is_rejected():
    with pytest.raises(ZeroTotalMassError, match="total mass of m is 0"):
        mp.centre_of_mass([0.0, 0.0], R3[:2])
    with pytest.raises(ZeroTotalMassError):
        mp.angular_momentum_decomposition([0.0], R3[:1], V3[:1], about=O)


@pytest.mark.parametrize(
    ("m", "r"),
    [
        (M3, R3[:2]),  # N differs
        (M3, R3[:, :2]),  # not 3-vectors
        (2.0, R3[:1]),  # scalar mass: no particle axis
        (np.ones((2, 3)), np.ones((3, 3, 3))),  # batch axes 2 vs 3
        ([], np.zeros((0, 3))),  # no particle
    ],
)
def test_mismatched_shapes_are_rejected_naming_them(m, r):
    with pytest.raises(ShapeError, match=r"shape|\(2, 3\)"):
        mp.centre_of_mass(m, r)


def test_base_point_is_required():
    with pytest.raises(TypeError):
        mp.angular_momentum(M3, R3, V3)  # type: ignore[call-arg]
    with pytest.raises(ShapeError, match="about"):
        mp.angular_momentum(M3, R3, V3, about=[0.0, 0.0])


def test_pair_forces_must_be_square():
    with pytest.raises(ShapeError, match=r"\(\.\.\., N, N, 3\)"):
        mp.internal_forces(np.zeros((2, 3, 3)))


def test_axis_problems_are_rejected():
    with pytest.raises(ZeroAxisError):
        mp.axial_component([1.0, 2.0, 3.0], axis=[0.0, 0.0, 0.0])
    with pytest.raises(OutOfDomainError, match="on the axis"):
        mp.cylindrical_components([0.0, 0.0, 5.0], [1, 0, 0], about=O, axis=[0, 0, 1])
    with pytest.raises(OutOfDomainError, match="J_z = 0"):
        mp.average_angular_velocity(
            [1.0], [[0.0, 0.0, 1.0]], [[1.0, 0, 0]], about=O, axis=[0, 0, 1]
        )


def test_density_validation():
    with pytest.raises(NegativeMassError, match="rho"):
        mp.masses_from_density([1.0, -1.0], cell_volume=1.0)
    with pytest.raises(NonPositiveParameterError, match="cell_volume"):
        mp.masses_from_density([1.0], cell_volume=0.0)


# ----------------------------------------------------------- extreme scales


def test_centre_of_mass_is_found_where_the_weighted_sum_overflows():
    # Σ m r = 1e300 × 1e100 is beyond float64, r_G = 1e100 is not.
    rG = mp.centre_of_mass([1e300, 1e300], [[1e100, 0, 0], [1e100, 2.0, 0]])
    np.testing.assert_allclose(rG, [1e100, 1.0, 0.0], rtol=2 * EPS)


def test_centre_of_mass_of_tiny_masses_does_not_underflow():
    rG = mp.centre_of_mass([1e-300, 3e-300], [[0.0, 0, 0], [4.0, 0, 0]])
    np.testing.assert_allclose(rG, [3.0, 0.0, 0.0], rtol=2 * EPS)


def test_an_overflowing_result_raises_instead_of_returning_inf():
    with pytest.raises(ResultOverflowError, match="momentum"):
        mp.momentum([1e300, 1e300], [[1e10, 0, 0], [1e10, 0, 0]])
    with pytest.raises(ResultOverflowError):
        mp.kinetic_energy([1.0], [[1e200, 0, 0]])


def test_compensated_sums_are_exact_where_plain_sums_lose_everything():
    # 1 + 1e100 − 1e100 cancels: the compensated momentum keeps the 1.
    p = mp.momentum([1.0, 1.0, 1.0], [[1.0, 0, 0], [1e100, 0, 0], [-1e100, 0, 0]])
    assert p[0] == 1.0
    assert (np.array([1.0, 1e100, -1e100])).sum() == 0.0  # the plain sum loses it


def test_koenig_parts_of_T_at_a_speed_of_1e8():
    T_G, T_cm = mp.kinetic_energy_decomposition([1.0, 1.0], [[1e8 + 1, 0, 0], [1e8 - 1, 0, 0]])
    assert T_G == 1.0
    assert T_cm == 1e16


# ------------------------------------------- every parameter named, every overflow named
_M_COND = (
    r"m must be >= 0; found -2\.0 at index \(1,\)"
    r"|the total mass of m is 0 \(index \(\)\): the centre of mass of a massless system is "
    r"undefined"
)
_RHO_COND = (
    r"rho must be >= 0; found -2\.0 at index \(1,\)"
    r"|^rho is zero everywhere: the total mass is 0 and the centre of mass of a massless body "
    r"is undefined$"
)
#: the condition an unphysical value of each parameter violates (tests.fuzz.entries)
_BY_PARAM = {
    "m": _M_COND,
    "rho": _RHO_COND,
    "axis": r"axis = \[0\.0, 0\.0, 0\.0\] has zero length",
    "cell_volume": r"cell_volume = (0\.0|-1\.0) must be > 0",
}
_CONDITIONS = {
    (fname, p): _BY_PARAM[p] for fname, e in entries_of("particles").items() for p in e.bad
}
#: masses and densities are 1-D of any length N: their wrong shape is a scalar (below)
_SKIP = frozenset((fname, p, "shape") for fname in entries_of("particles") for p in ("m", "rho"))


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"),
    list(cases("particles", _CONDITIONS, skip=_SKIP)),
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("particles", fname) | {param: value}
    check_refusal(getattr(mp, fname), kw, param, error, condition)


_B = 1e300  # a product of two is beyond float64
_H = 1.7e308  # a difference of two of opposite signs is beyond float64
_Z3 = [0.0, 0.0, 0.0]


@pytest.mark.parametrize(
    ("call", "what"),
    [
        pytest.param(lambda: mp.total_mass([1e308, 1e308]), "the total mass", id="total_mass"),
        pytest.param(lambda: mp.momentum([_B, _B], [[_B, 0, 0]] * 2), "the momentum", id="p"),
        pytest.param(
            lambda: mp.angular_momentum([1.0], [[_H, 0, 0]], [[0, 1, 0]], about=[-_H, 0, 0]),
            "the offsets r - about",
            id="L-offsets",
        ),
        pytest.param(
            lambda: mp.angular_momentum(
                [1.0], [[1, 0, 0]], [[_H, 0, 0]], about=_Z3, about_velocity=[-_H, 0, 0]
            ),
            "the offsets r - about_velocity",
            id="L-about_velocity",
        ),
        pytest.param(
            lambda: mp.angular_momentum([_B], [[_B, 0, 0]], [[0, 1, 0]], about=_Z3),
            "m_j AP_j",
            id="L-m_AP",
        ),
        pytest.param(
            lambda: mp.moment_of_forces([[_H, 0, 0]], [[0, 1, 0]], about=[-_H, 0, 0]),
            "the offsets r - about",
            id="M-offsets",
        ),
        pytest.param(
            lambda: mp.moment_of_inertia_about_axis(
                [1.0], [[_H, 0, 0]], about=[-_H, 0, 0], axis=[0, 0, 1]
            ),
            "the offsets r - about",
            id="J_z-offsets",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                [1.0], [_Z3], [[_H, 0, 0]], [_Z3], about=_Z3, about_velocity=[-_H, 0, 0]
            ),
            "the offsets r - about_velocity",
            id="Ldot-about_velocity",
        ),
        pytest.param(
            lambda: mp.angular_momentum([1.0], [[_B, 0, 0]], [[0, _B, 0]], about=_Z3),
            "the angular momentum",
            id="L",
        ),
        pytest.param(
            lambda: mp.angular_momentum_decomposition(
                [1.0, 1e-300], [[_H, 0, 0], [-_H, 0, 0]], [[0, 1, 0]] * 2, about=_Z3
            ),
            "the offsets r - r_G",
            id="decomposition-r_G",
        ),
        pytest.param(
            lambda: mp.angular_momentum_decomposition(
                [1.0, 1e-300], [[1, 0, 0], [-1, 0, 0]], [[_H, 0, 0], [-_H, 0, 0]], about=_Z3
            ),
            "the offsets r - v_G",
            id="decomposition-v_G",
        ),
        pytest.param(
            lambda: mp.angular_momentum_decomposition(
                [_B, _B], [[1, 0, 0], [-1, 0, 0]], [[_B, 0, 0]] * 2, about=_Z3
            ),
            "the momentum",
            id="decomposition-p",
        ),
        pytest.param(
            lambda: mp.angular_momentum_decomposition(
                [1.0, 1.0], [[_B, 0, 0], [-_B, 0, 0]], [[0, _B, 0], [0, -_B, 0]], about=_Z3
            ),
            "L_G",
            id="decomposition-L_G",
        ),
        pytest.param(
            lambda: mp.angular_momentum_decomposition(
                [1.0, 1.0], [[_B, 0, 0]] * 2, [[0, _B, 0]] * 2, about=_Z3
            ),
            "AG x p",
            id="decomposition-AG_x_p",
        ),
        pytest.param(
            lambda: mp.moving_base_point_term([1.0], [[0, _B, 0]], about_velocity=[_B, 0, 0]),
            "v_B x p",
            id="moving_base_point_term",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                [_B], [_Z3], [_Z3], [[_B, 0, 0]], about=_Z3, about_velocity=_Z3
            ),
            "m_j a_j",
            id="rate-m_a",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                [_B], [_Z3], [[_B, 0, 0]], [_Z3], about=_Z3, about_velocity=_Z3
            ),
            "m_j v_j",
            id="rate-m_v",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                [1.0], [[_B, 0, 0]], [_Z3], [[0, _B, 0]], about=_Z3, about_velocity=_Z3
            ),
            "dL_B/dt",
            id="rate",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                [1.0], [[_H, 0, 0]], [_Z3], [_Z3], about=[-_H, 0, 0], about_velocity=_Z3
            ),
            "the offsets r - about",
            id="rate-offsets",
        ),
        pytest.param(
            lambda: mp.moment_of_forces([[_B, 0, 0]], [[0, _B, 0]], about=_Z3),
            "the moment",
            id="moment_of_forces",
        ),
        pytest.param(
            lambda: mp.internal_forces(
                np.array([[[0, 0, 0], [_H, 0, 0], [_H, 0, 0]], [_Z3] * 3, [_Z3] * 3])
            ),
            "the internal forces",
            id="internal_forces",
        ),
        pytest.param(
            lambda: mp.internal_moment(
                [[_B, 0, 0], _Z3], np.array([[_Z3, [0, _B, 0]], [[0, -_B, 0], _Z3]])
            ),
            "the internal moment",
            id="internal_moment",
        ),
        pytest.param(
            lambda: mp.internal_moment(
                [[_H, 0, 0], [-_H, 0, 0]], np.array([[_Z3, [0, 1, 0]], [[0, -1, 0], _Z3]])
            ),
            "r_jk",
            id="internal_moment-r_jk",
        ),
        pytest.param(lambda: mp.kinetic_energy([1.0], [[_B, 0, 0]]), "v_j^2", id="T-v2"),
        pytest.param(
            lambda: mp.kinetic_energy([1e308, 1e308], [[1.5, 0, 0]] * 2),
            "the kinetic energy",
            id="T",
        ),
        pytest.param(
            lambda: mp.kinetic_energy_decomposition([_B], [[_B, 0, 0]]),
            "1/2 m v_G^2",
            id="T-decomposition",
        ),
        pytest.param(
            lambda: mp.moment_of_inertia_about_axis([_B], [[_B, 0, 0]], about=_Z3, axis=[0, 0, 1]),
            "J_z",
            id="J_z",
        ),
    ],
)
def test_a_result_beyond_float64_is_an_overflow_error_naming_what_overflowed(call, what):
    with pytest.raises(ResultOverflowError) as info:
        call()
    msg = str(info.value)
    assert msg.startswith(f"{what} is beyond float64 (index "), msg
    assert msg.endswith("the exact result exceeds 1.8e308 in magnitude"), msg


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: mp.total_mass(5.0), "m"),
        (lambda: mp.check_masses(5.0, "masses"), "masses"),
        (lambda: mp.masses_from_density(5.0, cell_volume=1.0), "rho"),
        (lambda: mp.continuous_momentum(5.0, [[1.0, 0, 0]], cell_volume=1.0), "rho"),
    ],
)
def test_a_scalar_for_the_masses_is_refused_naming_them_and_the_shape_wanted(call, name):
    with pytest.raises(ShapeError) as info:
        call()
    msg = str(info.value)
    assert msg == f"{name} has shape (); expected (..., N) with N >= 1 particles", msg


def test_a_unit_axis_is_normalised_row_by_row_in_a_batch():
    # two axes of different lengths along the same batch: each row is normalised by its
    # own length (2 and 3), so x · e reads off x_z and x_x
    x = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    out = mp.axial_component(x, axis=[[0.0, 0.0, 2.0], [3.0, 0.0, 0.0]])
    np.testing.assert_array_equal(out, [3.0, 4.0])


def test_a_system_of_no_particles_has_no_internal_forces():
    # the sum over no partners is an empty (0, 3) array, not an error
    out = mp.internal_forces(np.zeros((0, 0, 3)))
    assert out.shape == (0, 3)


# ------------------------------------- batches against exact rational arithmetic (Fraction)
#
# Leading axes of different lengths (2 and 5 particles, or a (3, 1) batch broadcast against
# (2,)), so that a sum over the wrong axis, a slice of the wrong axis or a transposed batch
# gives a different number or shape.  The oracle is exact: each float is a binary rational,
# the sums of products are formed in fractions.Fraction and compared with the result.
#
# The sums of the module are compensated (Sum2/Dot2, Ogita, Rump & Oishi 2005): within one
# rounding of the exact sum, plus (4 N eps)² Σ|terms| for the compensation's own rounding
# (N terms, a tree of depth log₂N ≤ N).  One ulp of the exact value bounds the first.

RNG_SEED = 20261126


def _F(x) -> Fraction:
    return Fraction(float(x))


def _assert_exact_sum(got, exact, size, n_terms, what=""):
    """|got − exact| ≤ ulp(exact) + (4 N eps)² size, elementwise (exact: nested lists)."""
    got = np.asarray(got, dtype=float)
    ex = np.empty(got.shape, dtype=object)
    ex[...] = exact if got.shape == () else _nested_to_array(exact, got.shape)
    sz = np.broadcast_to(np.asarray(size, dtype=object), got.shape)
    for i in np.ndindex(got.shape):
        e = ex[i]
        tol = Fraction(math.ulp(float(e))) + Fraction((4 * n_terms * EPS) ** 2) * sz[i]
        assert abs(_F(got[i]) - e) <= tol, (what, i, float(got[i]), float(e))


def _nested_to_array(nested, shape):
    out = np.empty(shape, dtype=object)
    for i in np.ndindex(shape):
        x = nested
        for k in i:
            x = x[k]
        out[i] = x
    return out


def _vec(x):
    return [_F(c) for c in x]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _system_data(lead=(2,), n=5, per_batch_masses=True):
    """Masses (lead, n) or (n,), positions and velocities (lead, n, 3): full-width floats."""
    rng = np.random.default_rng(RNG_SEED)
    m = rng.uniform(0.1, 3.0, (*lead, n) if per_batch_masses else (n,))
    r = rng.normal(size=(*lead, n, 3)) * 10.0 ** rng.integers(-3, 4, size=(*lead, n, 1))
    v = rng.normal(size=(*lead, n, 3))
    return m, r, v


def _masses_of(m, b):
    return m[b] if m.ndim > 1 else m


@pytest.mark.parametrize("per_batch_masses", [True, False])
def test_batched_mass_centre_and_momentum_are_each_rows_exact_sums(per_batch_masses):
    m, r, v = _system_data(per_batch_masses=per_batch_masses)
    M, rG, vG, p = (
        mp.total_mass(m),
        mp.centre_of_mass(m, r),
        mp.centre_of_mass_velocity(m, v),
        mp.momentum(m, v),
    )
    assert rG.shape == vG.shape == p.shape == (2, 3)
    assert M.shape == ((2,) if per_batch_masses else ())
    for b in range(2):
        mb = [_F(x) for x in _masses_of(m, b)]
        Mx = sum(mb)
        Sr = [sum(mj * _F(r[b, j, c]) for j, mj in enumerate(mb)) for c in range(3)]
        Sv = [sum(mj * _F(v[b, j, c]) for j, mj in enumerate(mb)) for c in range(3)]
        size_r = [sum(mj * abs(_F(r[b, j, c])) for j, mj in enumerate(mb)) for c in range(3)]
        size_v = [sum(mj * abs(_F(v[b, j, c])) for j, mj in enumerate(mb)) for c in range(3)]
        _assert_exact_sum(M[b] if per_batch_masses else M, Mx, Mx, 5, "M")
        _assert_exact_sum(p[b], Sv, size_v, 5, "p")
        # r_G = S/M: two sums within an ulp each and a division, 3 ulps (2 roundings + ½)
        for got, S, size in ((rG[b], Sr, size_r), (vG[b], Sv, size_v)):
            for c in range(3):
                want = S[c] / Mx
                tol = 3 * Fraction(math.ulp(float(want))) + Fraction((20 * EPS) ** 2) * size[c] / Mx
                assert abs(_F(got[c]) - want) <= tol, (b, c, float(got[c]), float(want))


def test_batched_angular_momentum_about_each_rows_point_is_the_exact_sum():
    m, r, v = _system_data()
    A = np.array([[0.5, -1.0, 2.0], [3.0, 0.25, -4.0]])
    vA = np.array([[0.1, 0.2, -0.3], [-1.5, 0.0, 2.0]])
    L = mp.angular_momentum(m, r, v, about=A)
    L_rel = mp.angular_momentum(m, r, v, about=A, about_velocity=vA)
    assert L.shape == L_rel.shape == (2, 3)
    for b in range(2):
        for got, vel_ref in ((L[b], [0, 0, 0]), (L_rel[b], vA[b])):
            terms = [
                [
                    _F(m[b, j]) * t
                    for t in _cross(
                        [_F(r[b, j, c]) - _F(A[b, c]) for c in range(3)],
                        [_F(v[b, j, c]) - _F(vel_ref[c]) for c in range(3)],
                    )
                ]
                for j in range(5)
            ]
            exact = [sum(t[c] for t in terms) for c in range(3)]
            # the offsets r − A and v − v_A are rounded once each (½ ulp of each factor)
            size = [
                sum(
                    _F(m[b, j])
                    * (abs(_F(r[b, j, k]) - _F(A[b, k])) + abs(_F(r[b, j, k2]) - _F(A[b, k2])))
                    * (
                        abs(_F(v[b, j, k]) - _F(vel_ref[k]))
                        + abs(_F(v[b, j, k2]) - _F(vel_ref[k2]))
                    )
                    for j in range(5)
                )
                for k, k2 in ((1, 2), (2, 0), (0, 1))
            ]
            for c in range(3):
                tol = Fraction(math.ulp(float(exact[c]))) + Fraction(2 * EPS) * size[c]
                assert abs(_F(got[c]) - exact[c]) <= tol, (b, c, float(got[c]), float(exact[c]))


def test_batched_kinetic_energy_and_its_koenig_parts_are_each_rows_exact_values():
    m, _, v = _system_data()
    T = mp.kinetic_energy(m, v)
    T_G, T_cm = mp.kinetic_energy_decomposition(m, v)
    assert T.shape == T_G.shape == T_cm.shape == (2,)
    for b in range(2):
        mb = [_F(x) for x in m[b]]
        vb = [_vec(x) for x in v[b]]
        exact = sum(mj * sum(c * c for c in vj) for mj, vj in zip(mb, vb, strict=True)) / 2
        _assert_exact_sum(T[b], exact, exact, 15, "T")
        M = sum(mb)
        vG = [sum(mj * vj[c] for mj, vj in zip(mb, vb, strict=True)) / M for c in range(3)]
        T_cm_exact = M * sum(c * c for c in vG) / 2
        # T = T' + ½ M v_G² (Koenig, 3.7), each part ≥ 0: T' and T_cm within 8 eps of T
        # (T' from offsets v − v_G with v_G rounded, T_cm from the rounded M and v_G)
        tol = Fraction(8 * EPS) * exact
        assert abs(_F(T_cm[b]) - T_cm_exact) <= tol
        assert abs(_F(T_G[b]) - (exact - T_cm_exact)) <= tol


def test_batched_forces_moments_and_rates_are_each_rows_exact_values():
    m, r, v = _system_data()
    a = np.random.default_rng(RNG_SEED + 1).normal(size=(2, 5, 3))
    B = np.array([[0.0, 1.0, 0.0], [2.0, 0.0, -1.0]])
    vB = np.array([[1.0, 0.0, 0.5], [0.0, -2.0, 0.0]])
    F = m[..., None] * a
    M_B = mp.moment_of_forces(r, F, about=B)
    Ldot = mp.angular_momentum_rate(m, r, v, a, about=B, about_velocity=vB)
    vxp = mp.moving_base_point_term(m, v, about_velocity=vB)
    assert M_B.shape == Ldot.shape == vxp.shape == (2, 3)
    for b in range(2):
        d = [[_F(r[b, j, c]) - _F(B[b, c]) for c in range(3)] for j in range(5)]
        moment = [sum(_cross(d[j], _vec(F[b, j]))[c] for j in range(5)) for c in range(3)]
        p = [sum(_F(m[b, j]) * _F(v[b, j, c]) for j in range(5)) for c in range(3)]
        # (1.47)–(1.50): dL_B/dt = Σ BP_j × m_j a_j − v_B × p
        rate = [
            sum(_cross(d[j], [_F(m[b, j]) * _F(a[b, j, c]) for c in range(3)])[c] for j in range(5))
            - _cross(_vec(vB[b]), p)[c]
            for c in range(3)
        ]
        vb_x_p = _cross(_vec(vB[b]), p)
        # scale of the terms: Σ |BP| |m a| (+ |v_B| Σ m |v|); offsets rounded once each
        s_f = sum(
            sum(abs(x) for x in d[j]) * sum(abs(_F(F[b, j, c])) for c in range(3)) for j in range(5)
        )
        s_p = sum(abs(_F(vB[b, c])) for c in range(3)) * sum(
            _F(m[b, j]) * sum(abs(_F(v[b, j, c])) for c in range(3)) for j in range(5)
        )
        for c in range(3):
            assert abs(_F(M_B[b, c]) - moment[c]) <= 4 * EPS * s_f
            assert abs(_F(Ldot[b, c]) - rate[c]) <= 4 * EPS * (s_f + s_p)
            assert abs(_F(vxp[b, c]) - vb_x_p[c]) <= 4 * EPS * s_p


def test_batched_pair_forces_give_each_rows_internal_forces_and_moment():
    rng = np.random.default_rng(RNG_SEED + 2)
    r = rng.normal(size=(2, 5, 3))
    f = rng.normal(size=(2, 5, 5, 3))
    Fi = mp.internal_forces(f)
    Mi = mp.internal_moment(r, f)
    assert Fi.shape == (2, 5, 3)
    assert Mi.shape == (2, 3)
    for b in range(2):
        for k in range(5):
            exact = [sum(_F(f[b, k, j, c]) for j in range(5)) for c in range(3)]
            size = [sum(abs(_F(f[b, k, j, c])) for j in range(5)) for c in range(3)]
            _assert_exact_sum(Fi[b, k], exact, size, 5, "F^i")
        # (1.31): M^i = ½ Σ_jk r_jk × f_jk, r_jk = r_j − r_k rounded once
        pairs = [(j, k) for j in range(5) for k in range(5)]
        rjk = {(j, k): [_F(r[b, j, c]) - _F(r[b, k, c]) for c in range(3)] for j, k in pairs}
        exact = [sum(_cross(rjk[jk], _vec(f[b][jk]))[c] for jk in pairs) / 2 for c in range(3)]
        size = sum(sum(abs(x) for x in rjk[jk]) * sum(abs(_F(x)) for x in f[b][jk]) for jk in pairs)
        for c in range(3):
            assert abs(_F(Mi[b, c]) - exact[c]) <= 4 * EPS * size


def test_a_batch_of_3_by_1_broadcast_against_2_gives_each_pair_its_own_result():
    # m (3, 1, 5) against r (2, 5, 3): the leading axes broadcast to (3, 2)
    rng = np.random.default_rng(RNG_SEED + 3)
    m = rng.uniform(0.5, 2.0, (3, 1, 5))
    r = rng.normal(size=(2, 5, 3))
    rG = mp.centre_of_mass(m, r)
    assert rG.shape == (3, 2, 3)
    for i in range(3):
        for b in range(2):
            mb = [_F(x) for x in m[i, 0]]
            for c in range(3):
                want = sum(mj * _F(r[b, j, c]) for j, mj in enumerate(mb)) / sum(mb)
                size = sum(mj * abs(_F(r[b, j, c])) for j, mj in enumerate(mb)) / sum(mb)
                assert abs(_F(rG[i, b, c]) - want) <= 3 * math.ulp(float(want)) + 4 * EPS**2 * size


def test_rows_of_very_different_magnitude_are_each_scaled_by_their_own_exponent():
    # one batch row near 1e300 and one near 1e-300: each is scaled by a power of two of
    # its own before the products, so neither overflows nor underflows; m r exact rationals
    m = np.array([[1e300, 3e300], [1e-300, 3e-300]])
    r = np.array([[[1e8, 0.0, -4.0], [5e7, 2.0, 4.0]], [[-8.0, 1e-8, 0.0], [4.0, 3e-8, 1.0]]])
    v = r[..., ::-1].copy()
    rG = mp.centre_of_mass(m, r)
    for b in range(2):
        mb = [_F(x) for x in m[b]]
        for c in range(3):
            want = sum(mj * _F(r[b, j, c]) for j, mj in enumerate(mb)) / sum(mb)
            assert abs(_F(rG[b, c]) - want) <= 3 * Fraction(math.ulp(float(want))), (b, c)
    M = mp.total_mass(m)
    assert M.tolist() == [4e300, 4e-300]
    p = mp.momentum(m[1:], v[1:])
    for c in range(3):
        exact = sum(_F(m[1, j]) * _F(v[1, j, c]) for j in range(2))
        _assert_exact_sum(p[0, c], exact, abs(exact), 2, "p at 1e-300")
    # the moment of inertia about the z axis: Σ m (x² + y²), row 0 near 1e316 overflows
    J = mp.moment_of_inertia_about_axis(m[1:], r[1:], about=[0.0, 0.0, 0.0], axis=[0, 0, 3.0])
    exact = sum(_F(m[1, j]) * (_F(r[1, j, 0]) ** 2 + _F(r[1, j, 1]) ** 2) for j in range(2))
    assert abs(_F(J[0]) - exact) <= 4 * EPS * exact


def test_batched_axis_quantities_use_each_rows_axis_and_point():
    # axes along coordinate directions with lengths 2 and 3 (normalised exactly), two
    # different base points: ρ, z, J_z and ω_av by hand
    r = np.array([[[1.0, 2.0, 3.0], [0.0, -1.0, 2.0]], [[4.0, 0.0, 1.0], [-2.0, 2.0, 5.0]]])
    v = np.array([[[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]], [[0.0, 0.0, 2.0], [1.0, 1.0, 0.0]]])
    m = np.array([2.0, 1.0])
    axis = np.array([[0.0, 0.0, 2.0], [3.0, 0.0, 0.0]])
    A = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    J = mp.moment_of_inertia_about_axis(m, r, about=A, axis=axis)
    # row 0, axis z through O: ρ² = x² + y² = 5, 1 → J = 2·5 + 1·1 = 11
    # row 1, axis x through (0, 1, 1): ρ² = (y − 1)² + (z − 1)² = 1 + 0 = 1, 1 + 16 = 17 → 2 + 17
    assert J.tolist() == [11.0, 19.0]
    w = mp.average_angular_velocity(m, r, v, about=A, axis=axis)
    # L_Az = Σ m ((r − A) × v)·e: row 0: 2·(1·1 − 2·0) + 1·(0·0 − (−1)·1) = 3 → 3/11
    # row 1 (e = x): 2·((−1)·2 − 0·0) + 1·(1·0 − 4·1) = −8 → −8/19
    np.testing.assert_allclose(w, [3 / 11, -8 / 19], rtol=2 * EPS, atol=0)
    x = mp.axial_component(v[:, 0], axis=axis)
    assert x.tolist() == [0.0, 0.0]
    c = mp.cylindrical_components(r[:, 0], v[:, 0], about=A, axis=axis)
    # row 0: (1, 2, 3) about z: ρ = √5, z = 3; row 1: d = (4, −1, 0) about x: ρ = 1, z = 4
    np.testing.assert_allclose(c.rho, [math.sqrt(5.0), 1.0], rtol=EPS, atol=0)
    assert c.z.tolist() == [3.0, 4.0]
    assert c.zdot.tolist() == [0.0, 0.0]


# ------------------------------------------- every shape guard, one argument wrong at a time

_O = np.zeros(3)
_M4, _R4, _V4 = np.ones(4), np.ones((4, 3)), np.ones((4, 3))


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        pytest.param(
            lambda: mp.centre_of_mass(_M4, np.ones((3, 3))),
            ShapeError,
            "r has shape (3, 3) but m has shape (4,): expected r of shape (..., N, 3) with "
            "N = 4 particles",
            id="r-N",
        ),
        pytest.param(
            lambda: mp.centre_of_mass(np.ones(3), np.ones(3)),
            ShapeError,
            "r has shape (3,) but m has shape (3,): expected r of shape (..., N, 3) with "
            "N = 3 particles",
            id="r-no-particle-axis",
        ),
        pytest.param(
            lambda: mp.kinetic_energy(_M4, np.ones((5, 3))),
            ShapeError,
            "v has shape (5, 3) but m has shape (4,): expected v of shape (..., N, 3) with "
            "N = 4 particles",
            id="T-v-N",
        ),
        pytest.param(
            lambda: mp.angular_momentum(_M4, _R4, np.ones((3, 3)), about=_O),
            ShapeError,
            "v has shape (3, 3) but m has shape (4,): expected v of shape (..., N, 3) with "
            "N = 4 particles",
            id="L-v-N",
        ),
        pytest.param(
            lambda: mp.angular_momentum_rate(
                _M4, _R4, _V4, np.ones((2, 3)), about=_O, about_velocity=_O
            ),
            ShapeError,
            "a has shape (2, 3) but m has shape (4,): expected a of shape (..., N, 3) with "
            "N = 4 particles",
            id="rate-a-N",
        ),
        pytest.param(
            lambda: mp.angular_momentum(
                np.ones((2, 4)), np.ones((3, 4, 3)), np.ones((4, 3)), about=_O
            ),
            ShapeError,
            "leading (batch) axes do not broadcast: m (2, 4), r (3, 4, 3), v (4, 3)",
            id="L-batch",
        ),
        pytest.param(
            lambda: mp.angular_momentum(_M4, np.ones((2, 4, 3)), _V4, about=np.zeros((5, 3))),
            ShapeError,
            "about has shape (5, 3); its leading axes do not broadcast against the system's (2,)",
            id="L-about-batch",
        ),
        pytest.param(
            lambda: mp.angular_momentum(
                _M4, np.ones((2, 4, 3)), _V4, about=_O, about_velocity=np.zeros((5, 3))
            ),
            ShapeError,
            "about_velocity has shape (5, 3); its leading axes do not broadcast against the "
            "system's (2,)",
            id="L-about_velocity-batch",
        ),
        pytest.param(
            lambda: mp.moving_base_point_term(
                np.ones((2, 4)), np.ones((2, 4, 3)), about_velocity=np.zeros((3, 3))
            ),
            ShapeError,
            "about_velocity has shape (3, 3); its leading axes do not broadcast against the "
            "system's (2,)",
            id="vB-batch",
        ),
        pytest.param(
            lambda: mp.moment_of_forces(np.ones(3), np.ones((1, 3)), about=_O),
            ShapeError,
            "r and F must both have shape (..., N, 3) with the same N; got (3,) and (1, 3)",
            id="M-r-no-particle-axis",
        ),
        pytest.param(
            lambda: mp.moment_of_forces(np.ones((1, 3)), np.ones(3), about=_O),
            ShapeError,
            "r and F must both have shape (..., N, 3) with the same N; got (1, 3) and (3,)",
            id="M-F-no-particle-axis",
        ),
        pytest.param(
            lambda: mp.moment_of_forces(np.ones((2, 3)), np.ones((3, 3)), about=_O),
            ShapeError,
            "r and F must both have shape (..., N, 3) with the same N; got (2, 3) and (3, 3)",
            id="M-N",
        ),
        pytest.param(
            lambda: mp.moment_of_forces(np.ones((2, 1, 3)), np.ones((3, 1, 3)), about=_O),
            ShapeError,
            "leading axes of r (2, 1, 3) and F (3, 1, 3) do not broadcast",
            id="M-batch",
        ),
        pytest.param(
            lambda: mp.internal_moment(np.ones(3), np.zeros((1, 1, 3))),
            ShapeError,
            "r has shape (3,) but f has shape (1, 1, 3): N must agree",
            id="Mi-r-no-particle-axis",
        ),
        pytest.param(
            lambda: mp.internal_moment(np.ones((2, 3)), np.zeros((3, 3, 3))),
            ShapeError,
            "r has shape (2, 3) but f has shape (3, 3, 3): N must agree",
            id="Mi-N",
        ),
        pytest.param(
            lambda: mp.internal_forces(np.zeros((3, 3))),
            ShapeError,
            "f has shape (3, 3); expected (..., N, N, 3) (f[k, j] = f_kj)",
            id="f-no-pair-axes",
        ),
        pytest.param(
            lambda: mp.internal_forces(np.zeros((2, 3, 3))),
            ShapeError,
            "f has shape (2, 3, 3); expected (..., N, N, 3) (f[k, j] = f_kj)",
            id="f-not-square",
        ),
        pytest.param(
            lambda: mp.cylindrical_components(
                np.ones((2, 3)), np.ones((3, 3)), about=_O, axis=[0, 0, 1]
            ),
            ShapeError,
            "r (2, 3) and v (3, 3) do not broadcast",
            id="cyl-r-v",
        ),
        pytest.param(
            lambda: mp.cylindrical_components(
                np.ones((2, 3)), np.ones((2, 3)), about=_O, axis=np.ones((3, 3))
            ),
            ShapeError,
            "axis has shape (3, 3); its leading axes do not broadcast against the system's (2,)",
            id="cyl-axis-batch",
        ),
        pytest.param(
            lambda: mp.masses_from_density([1.0], cell_volume=[1.0, 2.0]),
            ShapeError,
            "cell_volume must be a scalar; got shape (2,)",
            id="cell_volume-shape",
        ),
        pytest.param(
            lambda: mp.masses_from_density([1.0], cell_volume=-2.5),
            NonPositiveParameterError,
            "cell_volume = -2.5 must be > 0",
            id="cell_volume-negative",
        ),
        pytest.param(
            lambda: mp.total_mass(np.zeros((2, 0))),
            ShapeError,
            "m has shape (2, 0); expected (..., N) with N >= 1 particles",
            id="m-no-particles",
        ),
        pytest.param(
            lambda: mp.total_mass([[1.0, 2.0, 0.5], [3.0, 0.0, -1.0]]),
            NegativeMassError,
            "m must be >= 0; found -1.0 at index (1, 2)",
            id="m-negative-in-a-batch",
        ),
        pytest.param(
            lambda: mp.centre_of_mass([[1.0, 2.0, 1.0], [0.0, 0.0, 0.0]], np.ones((2, 3, 3))),
            ZeroTotalMassError,
            "the total mass of m is 0 (index (1,)): the centre of mass of a massless system "
            "is undefined",
            id="m-massless-row",
        ),
        pytest.param(
            lambda: mp.continuous_centre_of_mass(
                [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]], np.ones((2, 3, 3)), cell_volume=1.0
            ),
            ZeroTotalMassError,
            "rho is zero everywhere: the total mass is 0 and the centre of mass of a massless "
            "body is undefined",
            id="rho-zero-row",
        ),
        pytest.param(
            lambda: mp.axial_component(np.ones((2, 3)), axis=[[0, 0, 1], [0, 0, 0]]),
            ZeroAxisError,
            "axis = [0.0, 0.0, 0.0] has zero length",
            id="axis-zero-row",
        ),
        pytest.param(
            lambda: mp.cylindrical_components(
                [[1.0, 0, 0], [0, 0, 2.0]], [[1.0, 0, 0], [0, 0, 1.0]], about=_O, axis=[0, 0, 1]
            ),
            OutOfDomainError,
            "point [0.0, 0.0, 2.0] lies on the axis (rho = 0): phi and phidot are undefined there",
            id="on-axis-row",
        ),
        pytest.param(
            lambda: mp.average_angular_velocity(
                [1.0],
                [[[1.0, 0, 0]], [[0, 0, 2.0]], [[0, 1.0, 0]]],
                [[[0, 1.0, 0]], [[1.0, 0, 0]], [[1.0, 0, 0]]],
                about=_O,
                axis=[0, 0, 1],
            ),
            OutOfDomainError,
            "J_z = 0 at index (1,): all mass is on the axis, omega_av is undefined",
            id="Jz-zero-row",
        ),
    ],
)
def test_each_guard_refuses_its_own_argument_with_the_exact_message(call, error, message):
    with pytest.raises(error) as info:
        call()
    assert str(info.value) == message


def test_batched_koenig_parts_of_L_are_each_rows_exact_values():
    # L_A = L_G + AG × p (1.12), with r_G, v_G, p exact rationals: L_G = Σ m (r − r_G) × (v − v_G)
    # (the rounding of r_G, v_G enters only at second order: Σ m r' = Σ m v' = 0), and
    # AG × p from r_G within 3 ulps and p within 1: 8 eps of |AG| |p| per component
    m, r, v = _system_data()
    A = np.array([[1.0, 2.0, -3.0], [-0.5, 0.0, 4.0]])
    L_G, L_ext = mp.angular_momentum_decomposition(m, r, v, about=A)
    assert L_G.shape == L_ext.shape == (2, 3)
    for b in range(2):
        mb = [_F(x) for x in m[b]]
        M = sum(mb)
        rG = [sum(mj * _F(r[b, j, c]) for j, mj in enumerate(mb)) / M for c in range(3)]
        vG = [sum(mj * _F(v[b, j, c]) for j, mj in enumerate(mb)) / M for c in range(3)]
        p = [M * x for x in vG]
        d = [[_F(r[b, j, c]) - rG[c] for c in range(3)] for j in range(5)]
        w = [[_F(v[b, j, c]) - vG[c] for c in range(3)] for j in range(5)]
        LG = [sum(mb[j] * _cross(d[j], w[j])[c] for j in range(5)) for c in range(3)]
        size = sum(mb[j] * sum(map(abs, d[j])) * sum(map(abs, w[j])) for j in range(5))
        AG = [rG[c] - _F(A[b, c]) for c in range(3)]
        ext = _cross(AG, p)
        size_ext = sum(map(abs, AG)) * sum(map(abs, p))
        for c in range(3):
            assert abs(_F(L_G[b, c]) - LG[c]) <= 16 * EPS * size, (b, c)
            assert abs(_F(L_ext[b, c]) - ext[c]) <= 8 * EPS * size_ext, (b, c)


def test_batched_cylindrical_components_measure_phi_from_each_rows_own_reference():
    # row 0: axis e_z, ϕ from e_x; row 1: axis e_x, ϕ from e_y (the coordinate axis least
    # aligned with e, the first of the two), e_y × ... right-handed about e_x: ϕ from e_y to e_z
    r = np.array([[1.0, 2.0, 3.0], [4.0, 0.0, 1.0]])
    v = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 2.0]])
    axis = np.array([[0.0, 0.0, 2.0], [3.0, 0.0, 0.0]])
    A = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    c = mp.cylindrical_components(r, v, about=A, axis=axis)
    # row 0: (x, y) = (1, 2): ρ̇ = (x ẋ + y ẏ)/ρ = 2/√5, ϕ̇ = (x ẏ − y ẋ)/ρ² = 1/5
    # row 1: d = (4, −1, 0): (x, y) = (d·e_y, d·e_z) = (−1, 0), (ẋ, ẏ) = (0, 2): ϕ = π,
    #        ρ̇ = 0, ϕ̇ = −2
    np.testing.assert_allclose(c.phi, [math.atan2(2.0, 1.0), math.pi], rtol=EPS, atol=0)
    np.testing.assert_allclose(c.rhodot, [2 / math.sqrt(5.0), 0.0], rtol=2 * EPS, atol=0)
    np.testing.assert_allclose(c.phidot, [0.2, -2.0], rtol=2 * EPS, atol=0)


def test_the_compensated_sums_run_block_by_block_over_a_long_particle_axis_of_a_batch():
    # 100 configurations of 600 particles: momentum's rows are 3 × 100, so the blocks are 256
    # particles long (3 blocks, the last of 88); integer-valued data, so every partial sum
    # is exact and the exact totals are numpy's int64 sums
    rng = np.random.default_rng(RNG_SEED + 4)
    m = rng.integers(1, 10, size=(100, 600))
    v = rng.integers(-1000, 1001, size=(100, 600, 3))
    p = mp.momentum(m.astype(float), v.astype(float))
    np.testing.assert_array_equal(p, np.einsum("bj,bjc->bc", m, v).astype(float))
    T = mp.kinetic_energy(m.astype(float), v.astype(float))
    np.testing.assert_array_equal(T, 0.5 * np.einsum("bj,bjc->b", m, v * v).astype(float))
    np.testing.assert_array_equal(mp.total_mass(m.astype(float)), m.sum(axis=-1).astype(float))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        pytest.param(
            lambda: mp.momentum(
                [[1.0, 1.0], [1e300, 1e300]], [[[1.0, 0, 0]] * 2, [[1e10, 1, 0]] * 2]
            ),
            "the momentum is beyond float64 (index (1, 0)): the exact result exceeds 1.8e308 "
            "in magnitude",
            id="p-row-1-x",
        ),
        pytest.param(
            lambda: mp.total_mass([1e308, 1e308]),
            "the total mass is beyond float64 (index ()): the exact result exceeds 1.8e308 in "
            "magnitude",
            id="M-scalar",
        ),
        pytest.param(
            lambda: mp.kinetic_energy([[1.0], [1.0]], [[[1.0, 0, 0]], [[0, 0, 1e200]]]),
            "v_j^2 is beyond float64 (index (1, 0, 2)): the exact result exceeds 1.8e308 in "
            "magnitude",
            id="v2-element",
        ),
        pytest.param(
            lambda: mp.kinetic_energy_decomposition(
                [1.0, 1e-300], [[1.7e308, 0, 0], [-1.7e308, 0, 0]]
            ),
            "the offsets r - v_G is beyond float64 (index (1, 0)): the exact result exceeds "
            "1.8e308 in magnitude",
            id="T-decomposition-v_G",
        ),
        pytest.param(
            # the helper on its own (every public caller also masks numpy's warnings): it
            # names the offset and raises, without a RuntimeWarning of its own
            lambda: mp._offsets(
                np.array([[1.0, 0, 0], [1.7e308, 0, 0]]), np.array([-1.7e308, 0, 0]), "about"
            ),
            "the offsets r - about is beyond float64 (index (1, 0)): the exact result exceeds "
            "1.8e308 in magnitude",
            id="offsets-helper",
        ),
    ],
)
def test_an_overflow_message_points_at_the_first_element_beyond_float64(call, message):
    with pytest.raises(ResultOverflowError) as info:
        call()
    assert str(info.value) == message


def test_an_axis_of_any_magnitude_is_normalised_by_its_own_power_of_two():
    # (3, 0, 4)·s has length 5 s for any s: x · e = (3 x + 4 z)/5 = (3 + 12)/5 = 3; a
    # squared norm of 1e-600 or 1e616 would underflow or overflow without the scaling
    x = [1.0, 2.0, 3.0]
    for s in (1e-300, 1.0, 1e300):
        assert float(mp.axial_component(x, axis=[3.0 * s, 0.0, 4.0 * s])) == pytest.approx(
            3.0, rel=4 * EPS, abs=0
        )
    # a batch: a subnormal axis along z, and one of 1e308 along x + y: x_z and (x + y)/√2
    out = mp.axial_component(x, axis=[[0.0, 0.0, 1e-320], [1e308, 1e308, 0.0]])
    np.testing.assert_allclose(out, [3.0, 3.0 / math.sqrt(2.0)], rtol=4 * EPS, atol=0)


def test_the_centre_of_mass_lies_within_the_range_of_the_positions_to_the_last_bit():
    # a mean with weights ≥ 0 lies between the smallest and largest position in each
    # component: particles all at the largest float have r_G there (the ratio of the
    # compensated sums used to round above it, to inf: a false overflow error), and
    # coincident particles have r_G exactly at their common position
    big = np.finfo(float).max
    rng = np.random.default_rng(RNG_SEED + 5)
    m = rng.uniform(0.01, 1.0, (20, 4))
    at_max = np.broadcast_to([big, -big, np.nextafter(big, 0.0)], (20, 4, 3))
    np.testing.assert_array_equal(
        mp.centre_of_mass(m, at_max), np.broadcast_to(at_max[:, 0], (20, 3))
    )
    x = rng.normal(size=(20, 1, 3)) * 10.0 ** rng.integers(-5, 5, size=(20, 1, 1))
    coincident = np.broadcast_to(x, (20, 4, 3))
    np.testing.assert_array_equal(mp.centre_of_mass(m, coincident), x[:, 0])
    np.testing.assert_array_equal(mp.centre_of_mass_velocity(m, coincident), x[:, 0])


def test_one_point_about_two_axes_gives_two_sets_of_cylindrical_coordinates():
    # the axes' batch (2,) against a single point: (1, 2, 3) about e_z is ρ = √5, z = 3, and
    # about e_x is ρ = √13, z = 1
    c = mp.cylindrical_components(
        [1.0, 2.0, 3.0], [0.0, 1.0, 0.0], about=[0.0, 0.0, 0.0], axis=[[0, 0, 1.0], [1.0, 0, 0]]
    )
    np.testing.assert_allclose(c.rho, [math.sqrt(5.0), math.sqrt(13.0)], rtol=EPS, atol=0)
    assert c.z.tolist() == [3.0, 1.0]
    assert c.zdot.tolist() == [0.0, 0.0]


def test_masses_from_density_are_density_times_cell_volume():
    # m_j = rho_j dV (the midpoint rule of (1.3)); dV = 0.25 is a power of two, so the
    # products are exact: 1 * 0.25 and 3 * 0.25
    assert mp.masses_from_density([1.0, 3.0], cell_volume=0.25).tolist() == [0.25, 0.75]


# a system batched over (2, 3) with N = 4 particles, and a base point, velocity of the
# base point and axis per element of the *inner* batch axis (shape (3, 3)): they broadcast
# against the system's leading axes (2, 3) as the module's conventions say, so element
# [i, j] is the unbatched result for configuration [i, j] with the point and axis j
_BR = np.arange(2 * 3 * 4 * 3, dtype=float).reshape(2, 3, 4, 3) % 7 - 3.0
_BV = np.arange(2 * 3 * 4 * 3, dtype=float).reshape(2, 3, 4, 3) % 5 - 2.0
_BA = np.arange(2 * 3 * 4 * 3, dtype=float).reshape(2, 3, 4, 3) % 3 - 1.0
_BM = np.array([1.0, 2.0, 0.5, 3.0])
_PTS = np.array([[0.5, -1.0, 2.0], [1.0, 1.0, 1.0], [-2.0, 0.0, 3.0]])
_PVS = np.array([[1.0, 0.0, -1.0], [0.0, 2.0, 0.0], [3.0, 1.0, 1.0]])
_AXES = np.array([[0.0, 0.0, 1.0], [1.0, 2.0, 2.0], [0.0, 3.0, 4.0]])


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(lambda r, v, a, A, vA, e: mp.angular_momentum(_BM, r, v, about=A), id="L"),
        pytest.param(
            lambda r, v, a, A, vA, e: mp.angular_momentum(_BM, r, v, about=A, about_velocity=vA),
            id="L-relative",
        ),
        pytest.param(
            lambda r, v, a, A, vA, e: np.stack(
                mp.angular_momentum_decomposition(_BM, r, v, about=A)
            ),
            id="L-decomposition",
        ),
        pytest.param(
            lambda r, v, a, A, vA, e: mp.angular_momentum_rate(
                _BM, r, v, a, about=A, about_velocity=vA
            ),
            id="Ldot",
        ),
        pytest.param(
            lambda r, v, a, A, vA, e: mp.moving_base_point_term(_BM, v, about_velocity=vA),
            id="v_B x p",
        ),
        pytest.param(
            lambda r, v, a, A, vA, e: mp.moment_of_inertia_about_axis(_BM, r, about=A, axis=e),
            id="J_z",
        ),
        pytest.param(
            lambda r, v, a, A, vA, e: mp.average_angular_velocity(_BM, r, v, about=A, axis=e),
            id="omega_av",
        ),
        pytest.param(lambda r, v, a, A, vA, e: mp.axial_component(r[..., 0, :], axis=e), id="x.e"),
    ],
)
def test_a_point_and_axis_per_inner_batch_element_broadcast_against_the_system(call):
    got = call(_BR, _BV, _BA, _PTS, _PVS, _AXES)
    for i in range(2):
        for j in range(3):
            one = call(_BR[i, j], _BV[i, j], _BA[i, j], _PTS[j], _PVS[j], _AXES[j])
            np.testing.assert_array_equal(got[..., i, j, :] if got.ndim == 4 else got[i, j], one)


def test_one_system_about_a_batch_of_base_points_gives_one_result_per_point():
    # an unbatched system (N = 4) about 3 points: the points' batch (3,) is the result's;
    # L_A = L_O − OA × p (the connection formula (1.46)), here exact in integers
    r, v = _BR[0, 0], _BV[0, 0]
    L = mp.angular_momentum(_BM, r, v, about=_PTS)
    p = (_BM[:, None] * v).sum(axis=0)
    L_O = (_BM[:, None] * np.cross(r, v)).sum(axis=0)
    np.testing.assert_array_equal(L, L_O - np.cross(_PTS, p))


def test_a_particle_axis_longer_than_one_block_sums_every_block():
    # one row of 2**16 + 3 particles: more than one block of _BLOCK_ELEMENTS (2**16), so
    # the blocks' sums are added; unit masses with velocities 1 sum to N exactly
    n = 2**16 + 3
    assert mp.total_mass(np.ones(n)) == float(n)
    v = np.zeros((n, 3))
    v[:, 0] = 1.0
    v[-1, 1] = 2.0  # only in the last (second) block
    assert mp.momentum(np.ones(n), v).tolist() == [float(n), 2.0, 0.0]


def test_the_compensated_helpers_return_inf_beyond_float64_whatever_the_callers_errstate():
    # _dot (shared with mechanics.energy) and _sum promise inf where the exact sum is beyond
    # float64 (1e200 * 1e200 = 1e400; 2 * 1.5e308 = 3e308), not a FloatingPointError
    # under a caller's errstate(over="raise")
    with np.errstate(over="raise"):
        assert mp._dot(np.array([1e200, 1e200]), np.array([1e200, 1e200])) == math.inf
        assert mp._sum(np.array([1.5e308, 1.5e308])) == math.inf
